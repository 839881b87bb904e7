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
#include <unistd.h>

#include "golden/tdc_content.h"
#include "tdc_gamma.h"
#include "tdc_panels.h"
#include "tdc_png.h"
#include "tdc_run.h"
#include "tdc_trm.h"
#include "tdc_trm_gaze.h"
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
    "      --gaze FILE        gaze-aware TRM (tdc_trm_gaze.h, the simulator's trm50g): the eye\n"
    "                         tracker's gaze velocity per frame, lines frame,gx,gy (px/frame)\n"
    "      --mv FILE          with --gaze: the renderer's motion per 16-px tile and frame,\n"
    "                         lines frame,tx,ty,dx,dy (px/frame); every full frame needs all\n"
    "                         its tiles and its gaze line (docs/tools.md)\n"
    "      --kernels K        TRM row kernels: auto (AVX2 when this CPU has it), c (the\n"
    "                         portable kernels boards run) or avx2 (error without AVX2);\n"
    "                         all give the same bytes (default auto)\n"
    "  -q, --quiet            no per-frame lines on stderr\n"
    "  -h, --help             this text\n"
    "\n"
    "exit codes (docs/tools.md): 0 OK, 1 ARGS, 7 FILE, 13 INPUT, 14 REFUSED, 17 NOMEM\n";

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
    const char *gaze, *mv; /* gaze-aware TRM inputs (run_gaze.c) */
} opts_t;

static const tdc_panel_t *find_panel(const char *name)
{
#define MATCH(sym)                 \
    if (!strcmp(sym.name, name)) { \
        return &sym;               \
    }
    TDC_PANEL_LIST(MATCH)
#undef MATCH
    return NULL;
}

static void panel_names(char *buf, size_t n)
{
    buf[0] = 0;
#define NAME(sym) snprintf(buf + strlen(buf), n - strlen(buf), "%s%s", buf[0] ? ", " : "", sym.name);
    TDC_PANEL_LIST(NAME)
#undef NAME
}

static int usage_error(const char *fmt, const char *arg)
{
    char what[512];
    snprintf(what, sizeof what, fmt, arg);
    return tdc_fail(TDC_EXIT_ARGS, NULL, what, "try 'tdc-run --help'");
}

/* N/D with 1 <= N, D <= 1000 (the range check against 1/4..1 is the caller's). */
static int parse_ratio(const char *s, int *num, int *den)
{
    uint64_t n, d;
    const char *e;
    if (tdc_parse_u64_field(s, &e, 1000, &n) != 0 || *e != '/' || tdc_parse_u64_field(e + 1, &e, 1000, &d) != 0 ||
        *e != '\0' || n < 1 || d < 1) {
        return -1;
    }
    *num = (int)n;
    *den = (int)d;
    return 0;
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
    tdc_trm_gaze_t gaze;
    void *gmem;
} eye_t;

/* The gaze stage on an open eye (16-px tiles, default ramp). */
static int eye_gaze(eye_t *e, uint16_t w, uint16_t h)
{
    tdc_trm_gaze_config_t gc;
    tdc_trm_gaze_default_config(&gc, w, h);
    gc.tile = TDC_RUN_GAZE_TILE;
    size_t n = tdc_trm_gaze_get_size(&gc);
    e->gmem = n ? malloc(n) : NULL;
    if (!e->gmem) {
        return tdc_fail(TDC_EXIT_NOMEM, NULL, "gaze stage", "cannot allocate %zu bytes", n);
    }
    tdc_status_t st = tdc_trm_gaze_init(&e->gaze, &gc, e->gmem, n);
    if (st == TDC_OK) {
        st = tdc_trm_set_gaze(&e->trm, &e->gaze);
    }
    return st == TDC_OK ? TDC_EXIT_OK : tdc_fail(TDC_EXIT_REFUSED, NULL, "gaze stage", "%s", tdc_status_name(st));
}

static int eye_open(eye_t *e, const tdc_trm_config_t *cfg, const tdc_panel_t *panel, int kernels)
{
    size_t n = tdc_trm_get_size(cfg);
    e->mem = n ? malloc(n) : NULL;
    if (!e->mem) {
        return n ? tdc_fail(TDC_EXIT_NOMEM, NULL, "TRM state", "cannot allocate %zu bytes", n)
                 : tdc_fail(TDC_EXIT_REFUSED, NULL, "TRM configuration", "refused by the firmware (size 0)");
    }
    tdc_status_t st = tdc_trm_init(&e->trm, cfg, panel, e->mem, n);
    if (st == TDC_ERR_REFRESH_LOW) {
        return tdc_fail(TDC_EXIT_REFUSED, NULL, "TRM refused",
                        "refresh %u Hz is below the minimum %u Hz (paper §9); use --ratio 1 for no TRM",
                        cfg->refresh_hz, cfg->min_refresh_hz);
    }
    if (st != TDC_OK) {
        return tdc_fail(TDC_EXIT_REFUSED, NULL, "TRM init", "%s", tdc_status_name(st));
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
        if (!img->data) {
            return tdc_fail(TDC_EXIT_NOMEM, NULL, o->builtin, "cannot allocate a %dx%d frame", o->bw, o->bh);
        }
        tdc_content_frame(c, (uint32_t)i, 1u, img->data, o->bw, o->bh, o->bw * 3);
        return 0;
    }
    if (tdc_png_read(files[i], img, err, sizeof err) != 0) {
        /* tdc_png_read's message names the file and why; a file it cannot open is FILE */
        return tdc_fail(tdc_in_check(files[i]) != 0 ? TDC_EXIT_FILE : TDC_EXIT_INPUT, NULL, NULL, "%s", err);
    }
    tdc_png_to8(img);
    return 0;
}

static int run_trm(const opts_t *po, char **files, int nframes);

static int write_png(const opts_t *o, const char *prefix, int i, const uint8_t *rgb, int w, int h)
{
    char path[4096], err[512];
    snprintf(path, sizeof path, "%s/%s_%05d.png", o->out, prefix, i);
    if (tdc_png_write(path, rgb, w, h, 8, (size_t)w * 3, err, sizeof err) != 0) {
        return tdc_fail(TDC_EXIT_FILE, NULL, NULL, "%s", err);
    }
    return 0;
}

int tdc_run_trm_main(int argc, char **argv)
{
    opts_t o = {NULL, &tdc_panel_htc_vive, 1, 2, 10.0, 2.5, 0, "alternate", 0, 0, 0, 0, NULL, 8, 160, 120, -1, NULL, NULL};
    static const struct option longopts[] = {{"out", required_argument, 0, 'o'},
                                             {"panel", required_argument, 0, 'p'},
                                             {"ratio", required_argument, 0, 'r'},
                                             {"sensitivity", required_argument, 0, 's'},
                                             {"sigma", required_argument, 0, 1},
                                             {"refresh", required_argument, 0, 2},
                                             {"frames", required_argument, 0, 'f'},
                                             {"stereo", no_argument, 0, 3},
                                             {"perceived", no_argument, 0, 4},
                                             {"builtin", required_argument, 0, 5},
                                             {"count", required_argument, 0, 6},
                                             {"size", required_argument, 0, 7},
                                             {"quiet", no_argument, 0, 'q'},
                                             {"help", no_argument, 0, 'h'},
                                             {"save-input", no_argument, 0, 8},
                                             {"kernels", required_argument, 0, 9},
                                             {"gaze", required_argument, 0, 10},
                                             {"mv", required_argument, 0, 11},
                                             {0, 0, 0, 0}};
    int c;
    opterr = 0;
    while ((c = getopt_long(argc, argv, ":o:p:r:s:f:qh", longopts, NULL)) != -1) {
        switch (c) {
        case 'o': o.out = optarg; break;
        case 'p':
            o.panel = find_panel(optarg);
            if (!o.panel) {
                char names[512];
                panel_names(names, sizeof names);
                char what[300];
                snprintf(what, sizeof what, "unknown panel '%s'", optarg);
                return tdc_fail(TDC_EXIT_ARGS, NULL, what, "known panels: %s", names);
            }
            break;
        case 'r':
            if (!strcmp(optarg, "1")) {
                o.r_num = o.r_den = 1;
            } else if (parse_ratio(optarg, &o.r_num, &o.r_den) != 0 || o.r_num > o.r_den || 4 * o.r_num < o.r_den) {
                return usage_error("--ratio must be N/D with 1/4 <= N/D <= 1, got '%s'", optarg);
            }
            break;
        case 's':
            if (tdc_parse_double(optarg, 0.0, 1e6, &o.s) != 0) {
                return usage_error("--sensitivity must be a number in [0, 1e6], got '%s'", optarg);
            }
            break;
        case 1:
            if (tdc_parse_double(optarg, 0.25, 3.5, &o.sigma) != 0) {
                return usage_error("--sigma must be in [0.25, 3.5] pixels, got '%s'", optarg);
            }
            break;
        case 2:
            if (tdc_parse_int(optarg, 1, 1000, &o.refresh) != 0) {
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
        case 3: o.stereo = 1; break;
        case 4: o.perceived = 1; break;
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
            if (tdc_parse_int(optarg, 1, 1000000, &o.count) != 0) {
                return usage_error("--count must be 1..1000000, got '%s'", optarg);
            }
            break;
        case 7: {
            unsigned bw, bh;
            if (tdc_parse_size(optarg, 8192, &bw, &bh) != 0) {
                return usage_error("--size must be WxH within 1..8192, got '%s'", optarg);
            }
            o.bw = (int)bw;
            o.bh = (int)bh;
            break;
        }
        case 'q': o.quiet = 1; break;
        case 8: o.save_input = 1; break;
        case 9:
            if (!strcmp(optarg, "auto")) {
                o.kernels = -1;
            } else if (!strcmp(optarg, "c")) {
                o.kernels = 0;
            } else if (!strcmp(optarg, "avx2")) {
                if (!tdc_trm_avx2_available()) {
                    return tdc_fail(TDC_EXIT_ARGS, NULL, "--kernels avx2", "this build or CPU has no AVX2 kernels");
                }
                o.kernels = 1;
            } else {
                return usage_error("--kernels must be auto, c or avx2, got '%s'", optarg);
            }
            break;
        case 10: o.gaze = optarg; break;
        case 11: o.mv = optarg; break;
        case 'h': {
            char names[512];
            panel_names(names, sizeof names);
            printf(k_usage, names);
            return TDC_EXIT_OK;
        }
        case ':': return usage_error("option '%s' needs a value", argv[optind - 1]);
        default: return usage_error("unknown option '%s'", argv[optind - 1]);
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
    if (!o.gaze != !o.mv) {
        return usage_error("%s", "--gaze and --mv go together (retinal motion = motion - gaze)");
    }
    if (o.gaze && o.stereo) {
        return usage_error("%s", "--gaze is for one eye (no --stereo)");
    }
    if (o.stereo && strcmp(o.frames, "auto")) {
        return usage_error("%s", "--stereo needs --frames auto");
    }
    char **files = argv + optind;
    if (mkdir_p(o.out) != 0) {
        return tdc_fail(TDC_EXIT_FILE, NULL, o.out, "cannot create the output folder: %s", strerror(errno));
    }
    return run_trm(&o, files, nframes);
}

/* The frames through TRM; every error path frees what was allocated. */
static int run_trm(const opts_t *po, char **files, int nframes)
{
    const opts_t o = *po;
    eye_t eye[2] = {{.mem = NULL}, {.mem = NULL}};
    uint8_t *out = NULL, *prev_out = NULL, *red = NULL, *perc = NULL;
    FILE *csv = NULL;
    tdc_run_gaze_t gz = {0};
    int rc = TDC_EXIT_OK, eyes = o.stereo ? 2 : 1;

    /* The first frame decides the size; it must be full-res. */
    tdc_image_t first;
    rc = load_frame(&o, files, 0, &first);
    if (rc != TDC_EXIT_OK) {
        return rc;
    }
    const int W = first.width, H = first.height;
    tdc_png_free(&first);
    if (o.stereo && (W & 1)) {
        return tdc_fail(TDC_EXIT_INPUT, NULL, files[0],
                        "stereo frames need an even width (two eyes side by side), got %d", W);
    }
    const int EW = W / eyes;
    if (EW > 8192 || H > 8192) {
        return tdc_fail(TDC_EXIT_INPUT, NULL, o.builtin ? o.builtin : files[0], "frames of %dx%d exceed 8192x8192", W,
                        H);
    }
    tdc_trm_config_t cfg;
    tdc_trm_default_config(&cfg, (uint16_t)EW, (uint16_t)H, (uint16_t)(o.refresh ? o.refresh : o.panel->refresh_hz));
    cfg.r_num = (uint16_t)o.r_num;
    cfg.r_den = (uint16_t)o.r_den;
    cfg.s_q8 = (uint32_t)(o.s * 256.0 + 0.5);
    cfg.sigma_q8 = (uint16_t)(o.sigma * 256.0 + 0.5);
    cfg.reduced_in_stream = (uint8_t)(o.r_num != o.r_den);
    for (int e = 0; e < eyes && rc == TDC_EXIT_OK; e++) {
        rc = eye_open(&eye[e], &cfg, o.panel, o.kernels);
    }
    if (rc == TDC_EXIT_OK && o.gaze && !eye[0].trm.passthrough) {
        rc = tdc_run_gaze_load(&gz, o.gaze, o.mv, nframes, EW, H);
        if (rc == TDC_EXIT_OK) {
            rc = eye_gaze(&eye[0], (uint16_t)EW, (uint16_t)H);
        }
    }
    if (rc != TDC_EXIT_OK) {
        goto done;
    }
    const int rw = eye[0].trm.rw, rh = eye[0].trm.rh;
    out = calloc((size_t)W * H * 3, 1);
    prev_out = calloc((size_t)W * H * 3, 1);
    red = calloc((size_t)rw * rh * 3, 1);
    perc = calloc((size_t)W * H * 3, 1);
    if (!out || !prev_out || !red || !perc) {
        rc = tdc_fail(TDC_EXIT_NOMEM, NULL, "frame buffers", "cannot allocate 4 buffers of %dx%d", W, H);
        goto done;
    }
    char path[4096];
    snprintf(path, sizeof path, "%s/stats.csv", o.out);
    csv = fopen(path, "w");
    if (!csv) {
        rc = tdc_fail(TDC_EXIT_FILE, NULL, path, "cannot write: %s", strerror(errno));
        goto done;
    }
    fprintf(csv, "frame,eye,kind,clamped_high,clamped_low,weights_computed,weights_skipped,"
                 "no_residual,firmware_us\n");
    for (int i = 0; i < nframes && rc == TDC_EXIT_OK; i++) {
        tdc_image_t img;
        rc = load_frame(&o, files, i, &img);
        if (rc != TDC_EXIT_OK) {
            break;
        }
        const char *name = o.builtin ? o.builtin : files[i];
        if (o.save_input && (rc = write_png(&o, "input", i, img.data, img.width, img.height)) != 0) {
            tdc_png_free(&img);
            break;
        }
        for (int e = 0; e < eyes && rc == TDC_EXIT_OK; e++) {
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
                    rc = tdc_fail(TDC_EXIT_INPUT, NULL, name, "full-res frame is %dx%d, expected %dx%d", img.width,
                                  img.height, W, H);
                    break;
                }
                if (gz.mv) {
                    /* the map for this full frame, as a board computes it from the FULL packet's MOTION */
                    const int16_t *mv;
                    int16_t gx, gy;
                    if ((rc = tdc_run_gaze_frame(&gz, i, o.gaze, o.mv, &mv, &gx, &gy)) != TDC_EXIT_OK) {
                        break;
                    }
                    st = tdc_trm_gaze_update(&eye[e].gaze, mv, gz.tx * gz.ty, gx, gy);
                    if (st != TDC_OK) {
                        rc = tdc_fail(TDC_EXIT_REFUSED, NULL, o.mv, "gaze stage refused frame %d: %s", i,
                                      tdc_status_name(st));
                        break;
                    }
                }
                st = tdc_trm_full(t, (uint8_t *)img.data + (size_t)e * EW * 3, (uint32_t)W * 3, eye_out,
                                  (uint32_t)W * 3);
            } else {
                const uint8_t *rsrc;
                uint32_t rstride;
                if (!strcmp(o.frames, "auto")) {
                    if (img.width != W || img.height != H) {
                        rc = tdc_fail(TDC_EXIT_INPUT, NULL, name, "frame is %dx%d, expected %dx%d (--frames auto)",
                                      img.width, img.height, W, H);
                        break;
                    }
                    st = tdc_trm_downsample(t, (uint8_t *)img.data + (size_t)e * EW * 3, (uint32_t)W * 3, red,
                                            (uint32_t)rw * 3);
                    if (st != TDC_OK) {
                        rc = tdc_fail(TDC_EXIT_REFUSED, NULL, name, "firmware could not reduce frame %d: %s", i,
                                      tdc_status_name(st));
                        break;
                    }
                    rsrc = red;
                    rstride = (uint32_t)rw * 3;
                } else {
                    if (img.width != rw || img.height != rh) {
                        rc = tdc_fail(TDC_EXIT_INPUT, NULL, name,
                                      "reduced frame is %dx%d, expected %dx%d (r = %d/%d of %dx%d)", img.width,
                                      img.height, rw, rh, o.r_num, o.r_den, W, H);
                        break;
                    }
                    rsrc = img.data;
                    rstride = (uint32_t)rw * 3;
                }
                st = tdc_trm_reduced(t, rsrc, rstride, eye_out, (uint32_t)W * 3);
            }
            double us = (now_s() - t0) * 1e6;
            if (st != TDC_OK) {
                rc = tdc_fail(TDC_EXIT_REFUSED, NULL, name, "firmware rejected frame %d: %s", i, tdc_status_name(st));
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
        if (rc != TDC_EXIT_OK || (rc = write_png(&o, "drive", i, out, W, H)) != TDC_EXIT_OK) {
            break;
        }
        if (o.perceived && i > 0) {
            /* Talbot-Plateau: mean of this frame and the previous in linear light */
            for (size_t k = 0; k < (size_t)W * H * 3; k++) {
                const tdc_gamma_table_t *gt = &o.panel->gamma[k % 3];
                int64_t sum = (int64_t)tdc_gamma_decode(gt, out[k]) + tdc_gamma_decode(gt, prev_out[k]);
                perc[k] = (uint8_t)tdc_gamma_encode(gt, (tdc_lin_t)(sum / 2), 255u);
            }
            if ((rc = write_png(&o, "perceived", i, perc, W, H)) != TDC_EXIT_OK) {
                break;
            }
        }
        memcpy(prev_out, out, (size_t)W * H * 3);
    }
done:
    if (csv && fclose(csv) != 0 && rc == TDC_EXIT_OK) {
        rc = tdc_fail(TDC_EXIT_FILE, NULL, "stats.csv", "write failed: %s", strerror(errno));
    }
    for (int e = 0; e < eyes; e++) {
        free(eye[e].mem);
        free(eye[e].gmem);
    }
    tdc_run_gaze_free(&gz);
    free(out);
    free(prev_out);
    free(red);
    free(perc);
    return rc;
}

int main(int argc, char **argv)
{
    tdc_tool_set_name("tdc-run");
    if (argc > 1 && !strcmp(argv[1], "assemble")) {
#ifdef TDC_RUN_WITH_ASSEMBLE
        return tdc_run_assemble_main(argc - 1, argv + 1);
#else
        return tdc_fail(TDC_EXIT_ARGS, "assemble", NULL, "this build has no tile-assembly mode");
#endif
    }
    return tdc_run_trm_main(argc, argv);
}
