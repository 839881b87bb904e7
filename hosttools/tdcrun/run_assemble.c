/*
 * run_assemble.c - `tdc-run assemble`: tile-ordered frame assembly (the
 * firmware stage tdc_assemble) on any renderer's subframe stream.
 *
 * Input, one entry per refresh in display order (frame index = position):
 *   NAME.png   the subframe: ceil(W/2) x ceil(H/2) pixels, one RGB sample
 *              per 2x2 tile (8- or 16-bit PNG; 16-bit is rounded to 8);
 *   NAME.mv    optional, beside it: the samples' motion vectors and, on the
 *              first subframe of a cycle, the renderer's ordering bits
 *              (format in docs/tile-assembly.md and below); absent = no motion;
 *   -          a dropped subframe (the frame is still assembled).
 * Output: OUTDIR/frame_NNNNN.png (full W x H RGB888) and OUTDIR/stats.txt.
 *
 * .mv file (all little endian):
 *   offset 0   8 bytes  magic "TDCMV1\0\0"
 *   offset 8   uint16   tiles_x     (must equal the PNG width)
 *   offset 10  uint16   tiles_y     (must equal the PNG height)
 *   offset 12  uint32   flags: bit 0 = ordering bits follow the vectors
 *   offset 16  int16[2 * tiles_x * tiles_y]  (dx, dy) per tile, row-major,
 *              Q4 (1/16 px), backward: the point now at the traced pixel
 *              was at pixel + (dx, dy) in the previous frame
 *   then, if flag bit 0: ceil(tiles_x * tiles_y / 8) bytes of ordering bits
 *              (bit i & 7 of byte i >> 3 for tile i; 1 = bowtie)
 * `--write-stream` produces such a stream from the synthetic scenes of
 * ref/ref_assemble.c, so the tool can be tried without a renderer.
 */
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "ref_assemble.h"
#include "tdc_assemble.h"
#include <unistd.h>

#include "tdc_png.h"
#include "tdc_run.h"
#include "tdc_wire.h"

static const char k_usage[] =
    "usage: tdc-run assemble [options] -o OUTDIR SUBFRAME.png|- ...\n"
    "       tdc-run assemble --write-stream KIND -o DIR [--size WxH] [--count N] [--velocity VX,VY]\n"
    "\n"
    "Tile-ordered frame assembly (240 Hz subframes, docs/design.md §4.3) with the firmware stage.\n"
    "Each SUBFRAME.png holds one RGB sample per 2x2 tile (ceil(W/2) x ceil(H/2) pixels) of\n"
    "refresh i (i = its position in the list); SUBFRAME.mv beside it, if present, holds the\n"
    "samples' motion vectors (int16 Q4 pairs, backward) and, on frames i % 4 == 0, the\n"
    "renderer's per-tile ordering bits (format: docs/tile-assembly.md).  '-' = dropped subframe.\n"
    "Writes OUTDIR/frame_NNNNN.png (W x H RGB888) per refresh and OUTDIR/stats.txt.\n"
    "\n"
    "options:\n"
    "  -o, --output DIR       output folder (created)\n"
    "  -s, --size WxH         full frame size (default: twice the subframe size); must give\n"
    "                         ceil(W/2) x ceil(H/2) = the subframe size (odd sizes allowed)\n"
    "  -q, --quiet            no per-frame lines\n"
    "  -h, --help             this text\n"
    "  --write-stream KIND    write a synthetic stream to DIR instead (KIND: static, pan,\n"
    "                         lines, hlines) as sub_NNNNN.png + sub_NNNNN.mv\n"
    "  --count N              frames of --write-stream (default 16)\n"
    "  --velocity VX,VY       scene velocity in px/frame for --write-stream (default 1.5,0.5;\n"
    "                         rounded to 1/16 px)\n"
    "\n"
    "exit codes (docs/tools.md): 0 OK, 1 ARGS, 7 FILE, 13 INPUT, 14 REFUSED, 17 NOMEM\n";

static int usage_error(const char *fmt, const char *arg)
{
    char what[512];
    snprintf(what, sizeof what, fmt, arg);
    return tdc_fail(TDC_EXIT_ARGS, "assemble", what, "try 'tdc-run assemble --help'");
}

static int parse_size(const char *s, int *w, int *h)
{
    unsigned a, b;
    if (tdc_parse_size(s, TDC_ASM_MAX_DIM, &a, &b) != 0) return -1;
    *w = (int)a, *h = (int)b;
    return 0;
}

/* VX,VY: two finite numbers within +-2047 px/frame. */
static int parse_velocity(const char *s, double *vx, double *vy)
{
    const char *e;
    double a, b;
    if (tdc_parse_double_field(s, &e, &a) != 0 || *e != ',' || tdc_parse_double_field(e + 1, &e, &b) != 0 ||
        *e != '\0' || !(a >= -2047 && a <= 2047 && b >= -2047 && b <= 2047))
        return -1;
    *vx = a, *vy = b;
    return 0;
}

/* mkdir -p */
static int make_dirs(const char *path)
{
    char buf[4096];
    size_t n = strlen(path);
    if (n == 0 || n >= sizeof(buf)) return -1;
    memcpy(buf, path, n + 1);
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] == '/' || buf[i] == 0) {
            char keep = buf[i];
            buf[i] = 0;
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
            buf[i] = keep;
        }
    }
    return 0;
}

static const uint8_t k_mv_magic[8] = {'T', 'D', 'C', 'M', 'V', '1', 0, 0};


/* Writes a .mv file; bits may be NULL. */
static int write_mv(const char *path, uint32_t tx, uint32_t ty, const int16_t *mv, const uint8_t *bits)
{
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    uint8_t hdr[16];
    memcpy(hdr, k_mv_magic, 8);
    tdc_put_le16(hdr + 8, tx), tdc_put_le16(hdr + 10, ty), tdc_put_le32(hdr + 12, bits ? 1u : 0u);
    int ok = fwrite(hdr, 1, 16, f) == 16;
    for (size_t i = 0; ok && i < (size_t)tx * ty * 2; i++) {
        uint8_t b[2];
        tdc_put_le16s(b, mv[i]);
        ok = fwrite(b, 1, 2, f) == 2;
    }
    if (ok && bits) ok = fwrite(bits, 1, ((size_t)tx * ty + 7) / 8, f) == ((size_t)tx * ty + 7) / 8;
    return fclose(f) == 0 && ok ? 0 : -1;
}

/*
 * Reads a .mv file for a tx x ty subframe into mv (and bits, *has_bits).
 * Returns 0, 1 if the file does not exist, -1 with a message in err.
 */
static int read_mv(const char *path, uint32_t tx, uint32_t ty, int16_t *mv, uint8_t *bits, int *has_bits, char *err,
                   size_t errlen)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        if (errno == ENOENT) return 1;
        snprintf(err, errlen, "%.400s: %s", path, strerror(errno));
        return -1;
    }
    uint8_t hdr[16];
    int rc = -1;
    size_t n = (size_t)tx * ty, nb = (n + 7) / 8;
    if (fread(hdr, 1, 16, f) != 16 || memcmp(hdr, k_mv_magic, 8) != 0) {
        snprintf(err, errlen, "%.400s: not a motion-vector file (no TDCMV1 header)", path);
    } else if (tdc_get_le16(hdr + 8) != tx || tdc_get_le16(hdr + 10) != ty) {
        snprintf(err, errlen, "%.400s: motion vectors for %ux%u tiles, but the subframe has %ux%u", path,
                 tdc_get_le16(hdr + 8), tdc_get_le16(hdr + 10), tx, ty);
    } else if (tdc_get_le32(hdr + 12) & ~1u) {
        snprintf(err, errlen, "%.400s: unknown flags 0x%x", path, tdc_get_le32(hdr + 12));
    } else {
        uint8_t *raw = malloc(n * 4);
        size_t got = raw ? fread(raw, 1, n * 4, f) : 0;
        if (got != n * 4) {
            snprintf(err, errlen, "%.400s: truncated: %zu of %zu bytes of vectors", path, got, n * 4);
        } else {
            for (size_t i = 0; i < n * 2; i++) {
                mv[i] = tdc_get_le16s(raw + 2 * i);
            }
            *has_bits = (tdc_get_le32(hdr + 12) & 1u) != 0;
            if (*has_bits && fread(bits, 1, nb, f) != nb) {
                snprintf(err, errlen, "%.400s: truncated ordering bits", path);
            } else if (fgetc(f) != EOF) {
                snprintf(err, errlen, "%.400s: trailing bytes after the data", path);
            } else {
                rc = 0;
            }
        }
        free(raw);
    }
    fclose(f);
    return rc;
}

static int write_stream(const char *dir, const char *kind, int w, int h, int count, double vx, double vy)
{
    tdc_scene_kind_t k;
    if (!strcmp(kind, "static"))
        k = TDC_SCENE_STATIC;
    else if (!strcmp(kind, "pan"))
        k = TDC_SCENE_PAN;
    else if (!strcmp(kind, "lines"))
        k = TDC_SCENE_LINE;
    else if (!strcmp(kind, "hlines"))
        k = TDC_SCENE_HLINE;
    else
        return usage_error("unknown stream kind '%s' (static, pan, lines, hlines)", kind);
    int32_t vxq = (int32_t)(vx * 16.0 + (vx < 0 ? -0.5 : 0.5)), vyq = (int32_t)(vy * 16.0 + (vy < 0 ? -0.5 : 0.5));
    tdc_scene_t sc;
    if (tdc_scene_init(&sc, k, w, h, vxq, vyq, 1) != 0)
        return tdc_fail(TDC_EXIT_NOMEM, "assemble", "--write-stream", "cannot set up a %dx%d scene", w, h);
    uint32_t tx = (uint32_t)(w + 1) / 2, ty = (uint32_t)(h + 1) / 2;
    uint8_t *smp = malloc((size_t)tx * ty * 3), *bits = malloc(((size_t)tx * ty + 7) / 8);
    int16_t *mv = malloc((size_t)tx * ty * 4);
    int rc = smp && bits && mv
                 ? TDC_EXIT_OK
                 : tdc_fail(TDC_EXIT_NOMEM, "assemble", "--write-stream", "out of memory for %dx%d", w, h);
    for (int f = 0; f < count && rc == TDC_EXIT_OK; f++) {
        char path[4096], err[512];
        tdc_scene_subframe(&sc, (uint32_t)f, smp, mv, bits);
        snprintf(path, sizeof(path), "%s/sub_%05d.png", dir, f);
        if (tdc_png_write(path, smp, (int)tx, (int)ty, 8, (size_t)tx * 3, err, sizeof(err)) != 0) {
            rc = tdc_fail(TDC_EXIT_FILE, "assemble", NULL, "%s", err);
            break;
        }
        snprintf(path, sizeof(path), "%s/sub_%05d.mv", dir, f);
        if (write_mv(path, tx, ty, mv, (f & 3) == 0 ? bits : NULL) != 0) {
            rc = tdc_fail(TDC_EXIT_FILE, "assemble", path, "cannot write: %s", strerror(errno));
        }
    }
    if (rc == TDC_EXIT_OK)
        printf("wrote %d subframes (%ux%u tiles of a %dx%d %s stream) to %s\n", count, tx, ty, w, h, kind, dir);
    free(smp), free(bits), free(mv);
    tdc_scene_free(&sc);
    return rc;
}

int tdc_run_assemble_main(int argc, char **argv)
{
    const char *outdir = NULL, *stream_kind = NULL;
    int w = 0, h = 0, quiet = 0, count = 16;
    double vx = 1.5, vy = 0.5;
    enum { OPT_WRITE = 256, OPT_COUNT, OPT_VEL };
    static const struct option opts[] = {
        {"output", required_argument, 0, 'o'},
        {"size", required_argument, 0, 's'},
        {"quiet", no_argument, 0, 'q'},
        {"help", no_argument, 0, 'h'},
        {"write-stream", required_argument, 0, OPT_WRITE},
        {"count", required_argument, 0, OPT_COUNT},
        {"velocity", required_argument, 0, OPT_VEL},
        {0, 0, 0, 0},
    };
    optind = 1;
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, ":o:s:qh", opts, NULL)) != -1) {
        switch (c) {
        case 'o': outdir = optarg; break;
        case 's':
            if (parse_size(optarg, &w, &h) != 0)
                return usage_error("--size must be WxH within 1..4096, got '%s'", optarg);
            break;
        case 'q': quiet = 1; break;
        case 'h': printf("%s", k_usage); return TDC_EXIT_OK;
        case OPT_WRITE: stream_kind = optarg; break;
        case OPT_COUNT:
            if (tdc_parse_int(optarg, 1, 1000000, &count) != 0)
                return usage_error("--count must be 1..1000000, got '%s'", optarg);
            break;
        case OPT_VEL:
            if (parse_velocity(optarg, &vx, &vy) != 0)
                return usage_error("--velocity must be VX,VY in px/frame within +-2047, got '%s'", optarg);
            break;
        case ':': return usage_error("option '%s' needs a value", argv[optind - 1]);
        default: return usage_error("unknown option '%s'", argv[optind - 1]);
        }
    }
    if (!outdir) return usage_error("%s", "no output folder: give -o DIR");
    if (make_dirs(outdir) != 0) {
        return tdc_fail(TDC_EXIT_FILE, "assemble", outdir, "cannot create the output folder: %s", strerror(errno));
    }
    if (stream_kind) {
        if (optind < argc) return usage_error("--write-stream takes no subframe files (got '%s')", argv[optind]);
        return write_stream(outdir, stream_kind, w ? w : 64, h ? h : 48, count, vx, vy);
    }
    if (optind >= argc) return usage_error("%s", "no subframes given");

    /* The subframe size comes from the first PNG that is not '-'. */
    int first = optind;
    while (first < argc && !strcmp(argv[first], "-")) first++;
    if (first >= argc) return usage_error("%s", "every subframe is '-': nothing to assemble");
    tdc_image_t img;
    char err[600];
    if (tdc_png_read(argv[first], &img, err, sizeof(err)) != 0)
        return tdc_fail(tdc_in_check(argv[first]) != 0 ? TDC_EXIT_FILE : TDC_EXIT_INPUT, "assemble", NULL, "%s", err);
    uint32_t tx = (uint32_t)img.width, ty = (uint32_t)img.height;
    tdc_png_free(&img);
    if (!w) w = (int)(2 * tx), h = (int)(2 * ty);
    if ((uint32_t)(w + 1) / 2 != tx || (uint32_t)(h + 1) / 2 != ty) {
        return tdc_fail(TDC_EXIT_INPUT, "assemble", argv[first],
                        "--size %dx%d needs %dx%d subframes, the file is %ux%u", w, h, (w + 1) / 2, (h + 1) / 2, tx,
                        ty);
    }
    if (w > TDC_ASM_MAX_DIM || h > TDC_ASM_MAX_DIM) {
        return tdc_fail(TDC_EXIT_INPUT, "assemble", argv[first], "%dx%d exceeds the stage's %d pixel limit", w, h,
                        TDC_ASM_MAX_DIM);
    }

    tdc_asm_config_t cfg = {(uint16_t)w, (uint16_t)h};
    size_t n = tdc_asm_get_size(&cfg);
    void *arena = aligned_alloc(TDC_ARENA_ALIGN, TDC_ARENA_ROUND(n));
    int16_t *mv = malloc((size_t)tx * ty * 4);
    uint8_t *bits = malloc(((size_t)tx * ty + 7) / 8);
    tdc_asm_t st;
    if (!arena || !mv || !bits) {
        free(arena), free(mv), free(bits);
        return tdc_fail(TDC_EXIT_NOMEM, "assemble", NULL, "out of memory for %dx%d", w, h);
    }
    tdc_status_t ist = tdc_asm_init(&st, &cfg, arena, n);
    if (ist != TDC_OK) {
        free(arena), free(mv), free(bits);
        return tdc_fail(TDC_EXIT_REFUSED, "assemble", "stage init", "firmware status %d for %dx%d", (int)ist, w, h);
    }
    int rc = TDC_EXIT_OK;
    uint32_t frame = 0;
    for (int a = optind; a < argc; a++, frame++) {
        const char *name = argv[a];
        int dropped = !strcmp(name, "-");
        if (!dropped) {
            if (tdc_png_read(name, &img, err, sizeof(err)) != 0) {
                rc = tdc_fail(tdc_in_check(name) != 0 ? TDC_EXIT_FILE : TDC_EXIT_INPUT, "assemble", NULL, "%s", err);
                break;
            }
            if ((uint32_t)img.width != tx || (uint32_t)img.height != ty) {
                rc = tdc_fail(TDC_EXIT_INPUT, "assemble", name, "%dx%d, the stream's subframes are %ux%u", img.width,
                              img.height, tx, ty);
                tdc_png_free(&img);
                break;
            }
            if (img.bits == 16) tdc_png_to8(&img);
            /* NAME.png -> NAME.mv */
            char mvpath[4096];
            size_t len = strlen(name);
            if (len > 4 && !strcmp(name + len - 4, ".png")) len -= 4;
            snprintf(mvpath, sizeof(mvpath), "%.*s.mv", (int)len, name);
            int has_bits = 0;
            int r = read_mv(mvpath, tx, ty, mv, bits, &has_bits, err, sizeof(err));
            if (r < 0) {
                rc = tdc_fail(TDC_EXIT_INPUT, "assemble", NULL, "%s", err);
                tdc_png_free(&img);
                break;
            }
            tdc_status_t s = tdc_asm_ingest(&st, frame, (const uint8_t *)img.data, r == 0 ? mv : NULL,
                                            r == 0 && has_bits ? bits : NULL);
            tdc_png_free(&img);
            if (s != TDC_OK) {
                rc = tdc_fail(TDC_EXIT_REFUSED, "assemble", name, "firmware refused subframe %u: %s", frame,
                              tdc_status_name(s));
                break;
            }
        }
        const tdc_status_t as = tdc_asm_assemble(&st, frame);
        if (as != TDC_OK) {
            rc = tdc_fail(TDC_EXIT_REFUSED, "assemble", NULL, "firmware could not assemble frame %u: %s", frame,
                          tdc_status_name(as));
            break;
        }
        int stride;
        const uint8_t *out = tdc_asm_output(&st, &stride);
        char path[4096];
        snprintf(path, sizeof(path), "%s/frame_%05u.png", outdir, frame);
        if (tdc_png_write(path, out, w, h, 8, (size_t)stride, err, sizeof(err)) != 0) {
            rc = tdc_fail(TDC_EXIT_FILE, "assemble", NULL, "%s", err);
            break;
        }
        if (!quiet) printf("frame %5u %s -> %s\n", frame, dropped ? "(dropped subframe)" : name, path);
    }
    const tdc_asm_stats_t *s = &st.stats;
    char spath[4096];
    snprintf(spath, sizeof(spath), "%s/stats.txt", outdir);
    FILE *sf = fopen(spath, "w");
    FILE *outs[2] = {stdout, sf};
    for (int i = quiet ? 1 : 0; i < 2; i++) {
        if (!outs[i]) continue;
        fprintf(outs[i],
                "frames %u subframes %u missing %u static_frames %u pattern_checks %u pattern_disagreements %u\n"
                "new_dynamic %llu reprojected %llu reproject_edge %llu clamp_boxes %llu clamp_changed %llu "
                "clamp_no_neighbour %llu static_averaged %llu static_kept %llu window_resets %llu static_rows %llu\n",
                s->frames, s->subframes, s->subframes_missing, s->static_frames, s->pattern_checks,
                s->pattern_disagreements, (unsigned long long)s->new_dynamic, (unsigned long long)s->reprojected,
                (unsigned long long)s->reproject_edge, (unsigned long long)s->clamp_boxes,
                (unsigned long long)s->clamp_changed, (unsigned long long)s->clamp_no_neighbour,
                (unsigned long long)s->static_averaged, (unsigned long long)s->static_kept,
                (unsigned long long)s->window_resets, (unsigned long long)s->static_rows);
    }
    if ((!sf || fclose(sf) != 0) && rc == TDC_EXIT_OK)
        rc = tdc_fail(TDC_EXIT_FILE, "assemble", spath, "cannot write: %s", strerror(errno));
    free(arena), free(mv), free(bits);
    return rc;
}
