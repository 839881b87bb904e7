/*
 * tdc-run - runs the firmware pipeline on anyone's frames, exactly as a
 * board runs it: PNG frames in, panel drive frames out as PNG, plus a CSV of
 * per-frame statistics.  Modes: TRM (default) and `assemble` (tile-ordered
 * subframes, see run_assemble.c).
 */
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "golden/tdc_content.h"
#include "tdc_gamma.h"
#include "tdc_panels.h"
#include "tdc_png.h"
#include "tdc_run.h"
#include "tdc_trm.h"
#include "tdc_trm_kernels.h"

static const char k_usage[] =
    "usage: tdc-run [options] -o OUTDIR FRAME.png...\n"
    "       tdc-run [options] -o OUTDIR --builtin CONTENT --count N --size WxH\n"
    "       tdc-run assemble --help        (tile-ordered subframe assembly)\n"
    "\n"
    "Feeds frames through the firmware TRM stage as a board runs it and writes the\n"
    "panel drive frames (OUTDIR/drive_NNNNN.png) and per-frame statistics\n"
    "(OUTDIR/stats.csv).  PNG input may be 8- or 16-bit (16-bit is rounded to 8).\n"
    "\n"
    "options:\n"
    "  -o, --out DIR          output folder (created if missing)            [required]\n"
    "  -p, --panel NAME       panel profile: %s (default htc-vive)\n"
    "  -r, --ratio N/D        reduction ratio r, 1/4 <= r <= 1 (default 1/2; 1 = no TRM)\n"
    "  -s, --sensitivity S    motion sensitivity s of w = exp(-s c) (default 10)\n"
    "      --sigma PX         Gaussian sigma of D in full-res pixels (default 2.5, max 3.5)\n"
    "      --refresh HZ       refresh rate (default: the panel's); TRM refuses < 90 Hz\n"
    "  -f, --frames MODE      which inputs are full and which reduced:\n"
    "                           alternate  even frames full-res, odd frames reduced-size images\n"
    "                           auto       every input full-res; odd ones are reduced by the\n"
    "                                      firmware's own D (the renderer's prefilter)\n"
    "                           a string of F and R, e.g. FRFRFF (repeats if shorter)\n"
    "                         default: alternate\n"
    "      --stereo           inputs are side-by-side stereo (2W x H); eye 0 full on even\n"
    "                         frames, eye 1 on odd (needs --frames auto)\n"
    "      --perceived        also write OUTDIR/perceived_NNNNN.png: the Talbot-Plateau mean\n"
    "                         of each frame and the one before it, in linear light\n"
    "      --builtin NAME     use a built-in test content instead of files:\n"
    "                         edge text noise black white primaries checker flash gradient\n"
    "      --count N          frames of built-in content (default 8)\n"
    "      --size WxH         size of built-in content (default 160x120)\n"
    "      --save-input       also write the input frames as OUTDIR/input_NNNNN.png\n"
    "      --kernels K        TRM row kernels: auto (AVX2 when this CPU has it), c (the\n"
    "                         portable kernels boards run) or avx2 (error without AVX2);\n"
    "                         all give the same bytes (default auto)\n"
    "  -q, --quiet            no per-frame lines on stderr\n"
    "  -h, --help             this text\n"
    "\n"
    "exit status: 0 ok, 1 bad input or firmware refused, 2 usage error\n";

typedef struct {
    const char *out;
    const tdc_panel_t *panel;
    int r_num, r_den;
    double s, sigma;
    int refresh;
    const char *frames;
    int stereo, perceived, quiet, save_input;
    const char *builtin;
    int count, bw, bh;
    int kernels; /* -1 auto, 0 C, 1 AVX2 */
} opts_t;

static const tdc_panel_t *find_panel(const char *name)
{
#define MATCH(sym)                   \
    if (!strcmp(sym.name, name)) {   \
        return &sym;                 \
    }
    TDC_PANEL_LIST(MATCH)
#undef MATCH
    return NULL;
}

static void panel_names(char *buf, size_t n)
{
    buf[0] = 0;
#define NAME(sym)                                                         \
    snprintf(buf + strlen(buf), n - strlen(buf), "%s%s", buf[0] ? ", " : "", sym.name);
    TDC_PANEL_LIST(NAME)
#undef NAME
}

static int usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "tdc-run: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, "\ntry 'tdc-run --help'\n");
    return TDC_RUN_EXIT_USAGE;
}

static char frame_kind(const opts_t *o, int i)
{
    if (!strcmp(o->frames, "alternate") || !strcmp(o->frames, "auto")) {
        return (i & 1) ? 'R' : 'F';
    }
    return o->frames[i % (int)strlen(o->frames)];
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* mkdir -p */
static int mkdir_p(const char *path)
{
    char buf[4096];
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf) {
        errno = ENAMETOOLONG;
        return -1;
    }
    for (char *p = buf + 1; *p; p++) {
        if (*p == '/') {
            *p = 0;
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) {
                return -1;
            }
            *p = '/';
        }
    }
    return (mkdir(buf, 0777) != 0 && errno != EEXIST) ? -1 : 0;
}

typedef struct {
    tdc_trm_t trm;
    void *mem;
} eye_t;

static int eye_open(eye_t *e, const tdc_trm_config_t *cfg, const tdc_panel_t *panel, int kernels)
{
    size_t n = tdc_trm_get_size(cfg);
    e->mem = n ? malloc(n) : NULL;
    if (!e->mem) {
        fprintf(stderr, "tdc-run: invalid TRM configuration\n");
        return -1;
    }
    tdc_status_t st = tdc_trm_init(&e->trm, cfg, panel, e->mem, n);
    if (st == TDC_ERR_REFRESH_LOW) {
        fprintf(stderr, "tdc-run: TRM refused: refresh %u Hz is below the minimum %u Hz (paper §9); "
                        "use --ratio 1 for no TRM\n", cfg->refresh_hz, cfg->min_refresh_hz);
        return -1;
    }
    if (st != TDC_OK) {
        fprintf(stderr, "tdc-run: TRM init failed: %s\n", tdc_status_name(st));
        return -1;
    }
    if (kernels >= 0) {
        tdc_trm_set_simd(&e->trm, kernels);
    }
    return 0;
}

/* Load input i as 8-bit RGB (file or built-in). */
static int load_frame(const opts_t *o, char **files, int i, tdc_image_t *img)
{
    char err[512];
    if (o->builtin) {
        tdc_content_t c = TDC_CONTENT_COUNT;
        for (int k = 0; k < TDC_CONTENT_COUNT; k++) {
            if (!strcmp(tdc_content_name((tdc_content_t)k), o->builtin)) {
                c = (tdc_content_t)k;
            }
        }
        img->width = o->bw;
        img->height = o->bh;
        img->bits = 8;
        img->data = malloc((size_t)o->bw * o->bh * 3);
        tdc_content_frame(c, (uint32_t)i, 1u, img->data, o->bw, o->bh, o->bw * 3);
        return 0;
    }
    if (tdc_png_read(files[i], img, err, sizeof err) != 0) {
        fprintf(stderr, "tdc-run: %s\n", err);
        return -1;
    }
    tdc_png_to8(img);
    return 0;
}

static int write_png(const opts_t *o, const char *prefix, int i, const uint8_t *rgb, int w, int h)
{
    char path[4096], err[512];
    snprintf(path, sizeof path, "%s/%s_%05d.png", o->out, prefix, i);
    if (tdc_png_write(path, rgb, w, h, 8, (size_t)w * 3, err, sizeof err) != 0) {
        fprintf(stderr, "tdc-run: %s\n", err);
        return -1;
    }
    return 0;
}

int tdc_run_trm_main(int argc, char **argv)
{
    opts_t o = {NULL, &tdc_panel_htc_vive, 1, 2, 10.0, 2.5, 0, "alternate", 0, 0, 0, 0, NULL, 8, 160, 120, -1};
    static const struct option longopts[] = {
        {"out", required_argument, 0, 'o'},   {"panel", required_argument, 0, 'p'},
        {"ratio", required_argument, 0, 'r'}, {"sensitivity", required_argument, 0, 's'},
        {"sigma", required_argument, 0, 1},   {"refresh", required_argument, 0, 2},
        {"frames", required_argument, 0, 'f'}, {"stereo", no_argument, 0, 3},
        {"perceived", no_argument, 0, 4},     {"builtin", required_argument, 0, 5},
        {"count", required_argument, 0, 6},   {"size", required_argument, 0, 7},
        {"quiet", no_argument, 0, 'q'},       {"help", no_argument, 0, 'h'},
        {"save-input", no_argument, 0, 8},    {"kernels", required_argument, 0, 9},
        {0, 0, 0, 0}};
    int c;
    char *end;
    opterr = 0;
    while ((c = getopt_long(argc, argv, ":o:p:r:s:f:qh", longopts, NULL)) != -1) {
        switch (c) {
        case 'o':
            o.out = optarg;
            break;
        case 'p':
            o.panel = find_panel(optarg);
            if (!o.panel) {
                char names[512];
                panel_names(names, sizeof names);
                fprintf(stderr, "tdc-run: unknown panel '%s'; known panels: %s\n", optarg, names);
                return TDC_RUN_EXIT_USAGE;
            }
            break;
        case 'r':
            if (!strcmp(optarg, "1")) {
                o.r_num = o.r_den = 1;
            } else if (sscanf(optarg, "%d/%d", &o.r_num, &o.r_den) != 2 || o.r_den <= 0 || o.r_num <= 0 ||
                       o.r_num > o.r_den || 4 * o.r_num < o.r_den || o.r_den > 1000) {
                return usage_error("--ratio must be N/D with 1/4 <= N/D <= 1, got '%s'", optarg);
            }
            break;
        case 's':
            o.s = strtod(optarg, &end);
            if (*end || !(o.s >= 0.0 && o.s <= 1e6)) {
                return usage_error("--sensitivity must be a number in [0, 1e6], got '%s'", optarg);
            }
            break;
        case 1:
            o.sigma = strtod(optarg, &end);
            if (*end || !(o.sigma >= 0.25 && o.sigma <= 3.5)) {
                return usage_error("--sigma must be in [0.25, 3.5] pixels, got '%s'", optarg);
            }
            break;
        case 2:
            o.refresh = (int)strtol(optarg, &end, 10);
            if (*end || o.refresh < 1 || o.refresh > 1000) {
                return usage_error("--refresh must be 1..1000 Hz, got '%s'", optarg);
            }
            break;
        case 'f':
            o.frames = optarg;
            if (strcmp(optarg, "alternate") && strcmp(optarg, "auto")) {
                if (!*optarg || strspn(optarg, "FR") != strlen(optarg) || optarg[0] != 'F') {
                    return usage_error("--frames must be alternate, auto or F/R letters starting with F, got '%s'",
                                       optarg);
                }
            }
            break;
        case 3:
            o.stereo = 1;
            break;
        case 4:
            o.perceived = 1;
            break;
        case 5: {
            int ok = 0;
            for (int k = 0; k < TDC_CONTENT_COUNT; k++) {
                ok |= !strcmp(tdc_content_name((tdc_content_t)k), optarg);
            }
            if (!ok) {
                return usage_error("unknown built-in content '%s'", optarg);
            }
            o.builtin = optarg;
            break;
        }
        case 6:
            o.count = (int)strtol(optarg, &end, 10);
            if (*end || o.count < 1 || o.count > 1000000) {
                return usage_error("--count must be 1..1000000, got '%s'", optarg);
            }
            break;
        case 7:
            if (sscanf(optarg, "%dx%d", &o.bw, &o.bh) != 2 || o.bw < 1 || o.bh < 1 || o.bw > 8192 ||
                o.bh > 8192) {
                return usage_error("--size must be WxH within 1..8192, got '%s'", optarg);
            }
            break;
        case 'q':
            o.quiet = 1;
            break;
        case 8:
            o.save_input = 1;
            break;
        case 9:
            if (!strcmp(optarg, "auto")) {
                o.kernels = -1;
            } else if (!strcmp(optarg, "c")) {
                o.kernels = 0;
            } else if (!strcmp(optarg, "avx2")) {
                if (!tdc_trm_avx2_available()) {
                    fprintf(stderr, "tdc-run: --kernels avx2: this build or CPU has no AVX2 kernels\n");
                    return TDC_RUN_EXIT_FAILED;
                }
                o.kernels = 1;
            } else {
                return usage_error("--kernels must be auto, c or avx2, got '%s'", optarg);
            }
            break;
        case 'h': {
            char names[512];
            panel_names(names, sizeof names);
            printf(k_usage, names);
            return TDC_RUN_EXIT_OK;
        }
        case ':':
            return usage_error("option '%s' needs a value", argv[optind - 1]);
        default:
            return usage_error("unknown option '%s'", argv[optind - 1]);
        }
    }
    if (!o.out) {
        return usage_error("%s", "no output folder: give -o DIR");
    }
    int nframes = o.builtin ? o.count : argc - optind;
    if (nframes < 1) {
        return usage_error("%s", "no input frames");
    }
    if (o.builtin && argc > optind) {
        return usage_error("--builtin takes no frame files (got '%s')", argv[optind]);
    }
    if (o.stereo && strcmp(o.frames, "auto")) {
        return usage_error("%s", "--stereo needs --frames auto");
    }
    char **files = argv + optind;
    if (mkdir_p(o.out) != 0) {
        fprintf(stderr, "tdc-run: cannot create %s: %s\n", o.out, strerror(errno));
        return TDC_RUN_EXIT_FAILED;
    }

    /* The first frame decides the size; it must be full-res. */
    tdc_image_t first;
    if (load_frame(&o, files, 0, &first) != 0) {
        return TDC_RUN_EXIT_FAILED;
    }
    const int W = first.width, H = first.height;
    tdc_png_free(&first);
    const int eyes = o.stereo ? 2 : 1;
    if (o.stereo && (W & 1)) {
        fprintf(stderr, "tdc-run: stereo frames need an even width (two eyes side by side), got %d\n", W);
        return TDC_RUN_EXIT_FAILED;
    }
    const int EW = W / eyes;
    if (EW > 8192 || H > 8192) {
        fprintf(stderr, "tdc-run: frames of %dx%d exceed 8192x8192\n", W, H);
        return TDC_RUN_EXIT_FAILED;
    }
    tdc_trm_config_t cfg;
    tdc_trm_default_config(&cfg, (uint16_t)EW, (uint16_t)H, (uint16_t)(o.refresh ? o.refresh : o.panel->refresh_hz));
    cfg.r_num = (uint16_t)o.r_num;
    cfg.r_den = (uint16_t)o.r_den;
    cfg.s_q8 = (uint32_t)(o.s * 256.0 + 0.5);
    cfg.sigma_q8 = (uint16_t)(o.sigma * 256.0 + 0.5);
    cfg.reduced_in_stream = (uint8_t)(o.r_num != o.r_den);
    eye_t eye[2];
    for (int e = 0; e < eyes; e++) {
        if (eye_open(&eye[e], &cfg, o.panel, o.kernels) != 0) {
            return TDC_RUN_EXIT_FAILED;
        }
    }
    const int rw = eye[0].trm.rw, rh = eye[0].trm.rh;
    uint8_t *out = calloc((size_t)W * H * 3, 1), *prev_out = calloc((size_t)W * H * 3, 1);
    uint8_t *red = calloc((size_t)rw * rh * 3, 1), *perc = calloc((size_t)W * H * 3, 1);
    char path[4096];
    snprintf(path, sizeof path, "%s/stats.csv", o.out);
    FILE *csv = fopen(path, "w");
    if (!csv || !out || !prev_out || !red || !perc) {
        fprintf(stderr, "tdc-run: cannot write %s: %s\n", path, strerror(errno));
        return TDC_RUN_EXIT_FAILED;
    }
    fprintf(csv, "frame,eye,kind,clamped_high,clamped_low,weights_computed,weights_skipped,"
                 "no_residual,firmware_us\n");
    int rc = TDC_RUN_EXIT_OK;
    for (int i = 0; i < nframes && rc == TDC_RUN_EXIT_OK; i++) {
        tdc_image_t img;
        if (load_frame(&o, files, i, &img) != 0) {
            rc = TDC_RUN_EXIT_FAILED;
            break;
        }
        const char *name = o.builtin ? o.builtin : files[i];
        if (o.save_input && write_png(&o, "input", i, img.data, img.width, img.height) != 0) {
            tdc_png_free(&img);
            rc = TDC_RUN_EXIT_FAILED;
            break;
        }
        for (int e = 0; e < eyes && rc == TDC_RUN_EXIT_OK; e++) {
            tdc_trm_t *t = &eye[e].trm;
            char kind = o.stereo ? (tdc_trm_stereo_eye_is_full((uint32_t)i, e) ? 'F' : 'R') : frame_kind(&o, i);
            if (t->passthrough) {
                kind = 'F';
            }
            if (i == 0 && kind != 'F') {
                /* the first frame of eye 1 in stereo: nothing before it, show it as full */
                kind = 'F';
            }
            tdc_trm_stats_t before = t->stats;
            double t0 = now_s();
            tdc_status_t st;
            uint8_t *eye_out = out + (size_t)e * EW * 3;
            if (kind == 'F') {
                if (img.width != W || img.height != H) {
                    fprintf(stderr, "tdc-run: %s: full-res frame is %dx%d, expected %dx%d\n", name, img.width,
                            img.height, W, H);
                    rc = TDC_RUN_EXIT_FAILED;
                    break;
                }
                st = tdc_trm_full(t, (uint8_t *)img.data + (size_t)e * EW * 3, (uint32_t)W * 3, eye_out,
                                  (uint32_t)W * 3);
            } else {
                const uint8_t *rsrc;
                uint32_t rstride;
                if (!strcmp(o.frames, "auto")) {
                    if (img.width != W || img.height != H) {
                        fprintf(stderr, "tdc-run: %s: frame is %dx%d, expected %dx%d (--frames auto)\n", name,
                                img.width, img.height, W, H);
                        rc = TDC_RUN_EXIT_FAILED;
                        break;
                    }
                    st = tdc_trm_downsample(t, (uint8_t *)img.data + (size_t)e * EW * 3, (uint32_t)W * 3, red,
                                            (uint32_t)rw * 3);
                    if (st != TDC_OK) {
                        fprintf(stderr, "tdc-run: %s: firmware could not reduce frame %d: %s\n", name, i,
                                tdc_status_name(st));
                        rc = TDC_RUN_EXIT_FAILED;
                        break;
                    }
                    rsrc = red;
                    rstride = (uint32_t)rw * 3;
                } else {
                    if (img.width != rw || img.height != rh) {
                        fprintf(stderr, "tdc-run: %s: reduced frame is %dx%d, expected %dx%d (r = %d/%d of %dx%d)\n",
                                name, img.width, img.height, rw, rh, o.r_num, o.r_den, W, H);
                        rc = TDC_RUN_EXIT_FAILED;
                        break;
                    }
                    rsrc = img.data;
                    rstride = (uint32_t)rw * 3;
                }
                st = tdc_trm_reduced(t, rsrc, rstride, eye_out, (uint32_t)W * 3);
            }
            double us = (now_s() - t0) * 1e6;
            if (st != TDC_OK) {
                fprintf(stderr, "tdc-run: %s: firmware rejected frame %d: %s\n", name, i, tdc_status_name(st));
                rc = TDC_RUN_EXIT_FAILED;
                break;
            }
            fprintf(csv, "%d,%d,%s,%llu,%llu,%llu,%llu,%llu,%.1f\n", i, e,
                    t->passthrough ? "pass" : (kind == 'F' ? "full" : "reduced"),
                    (unsigned long long)(t->stats.clamped_high - before.clamped_high),
                    (unsigned long long)(t->stats.clamped_low - before.clamped_low),
                    (unsigned long long)(t->stats.weight_computed - before.weight_computed),
                    (unsigned long long)(t->stats.weight_skipped - before.weight_skipped),
                    (unsigned long long)(t->stats.residual_skipped - before.residual_skipped), us);
            if (!o.quiet) {
                fprintf(stderr, "frame %5d eye %d %-7s %8.0f us\n", i, e, kind == 'F' ? "full" : "reduced", us);
            }
        }
        tdc_png_free(&img);
        if (rc != TDC_RUN_EXIT_OK) {
            break;
        }
        if (write_png(&o, "drive", i, out, W, H) != 0) {
            rc = TDC_RUN_EXIT_FAILED;
            break;
        }
        if (o.perceived && i > 0) {
            /* Talbot-Plateau: mean of this frame and the previous in linear light */
            for (size_t k = 0; k < (size_t)W * H * 3; k++) {
                const tdc_gamma_table_t *gt = &o.panel->gamma[k % 3];
                int64_t sum = (int64_t)tdc_gamma_decode(gt, out[k]) + tdc_gamma_decode(gt, prev_out[k]);
                perc[k] = (uint8_t)tdc_gamma_encode(gt, (tdc_lin_t)(sum / 2), 255u);
            }
            if (write_png(&o, "perceived", i, perc, W, H) != 0) {
                rc = TDC_RUN_EXIT_FAILED;
                break;
            }
        }
        memcpy(prev_out, out, (size_t)W * H * 3);
    }
    fclose(csv);
    for (int e = 0; e < eyes; e++) {
        free(eye[e].mem);
    }
    free(out);
    free(prev_out);
    free(red);
    free(perc);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc > 1 && !strcmp(argv[1], "assemble")) {
#ifdef TDC_RUN_WITH_ASSEMBLE
        return tdc_run_assemble_main(argc - 1, argv + 1);
#else
        fprintf(stderr, "tdc-run: this build has no tile-assembly mode\n");
        return TDC_RUN_EXIT_USAGE;
#endif
    }
    return tdc_run_trm_main(argc, argv);
}
