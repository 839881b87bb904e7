/*
 * tdc-zeng - Zeng et al.'s evaluation (§6-§7) on the double-precision
 * reference pipeline (sim/zeng/README.md): one scene, its 1-sample frames
 * per seed, every method, RMSE and SSIM against a >= 1024-sample ground
 * truth per frame (whole frame and the effect's region), averaged over the
 * evaluated frames; and the cost of the dual vectors (a G-buffer lookup)
 * beside the primary rays (§7).
 *
 *   tdc-zeng --scene fence|glossy|occlusion|pinkroom|lights|apples [--size WxH] [--frames N]
 *            [--eval-from K] [--seeds "1 2 3 4 5"] [--gt-spp 1024]
 *            [--rough SIGMA] [--clamp-on raw|filtered] [--glossy-filter llk|fixed]
 *            [--no-falloff 0|1] [--spread K] [--ours-clamp K] [--glossy-mv pixel|splat]
 *            [--fetch-error 0|1]
 *            [--jod PPD] [--csv FILE] [--png FILE]
 *
 * CSV rows: scene,seed,method,rmse,ssim,rmse_region,ssim_region,region_px
 * (with --jod also jod,jod_region: FovVideoVDP's JOD of the evaluated frames
 * as a 60 Hz video at PPD pixels per degree, and of the effect region's
 * differences alone: the test is the reference outside the region)
 * then one row "cost,...": primary-ray ms, dual-vector ms per frame, ratio.
 * Exit codes (docs/tools.md): 0 OK, 1 ARGS, 7 FILE, 17 NOMEM.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "metrics/tdc_fvvdp.h"
#include "tdc_png.h"
#include "tdc_tool.h"
#include "zeng/zeng_eval.h"
#include "zeng/zeng_filter.h"
#include "zeng/zeng_pipe.h"

/* the one exit-code table (common/tdc_exit.h) */
#define EXIT_ARGS TDC_EXIT_ARGS
#define EXIT_FILE TDC_EXIT_FILE
#define EXIT_NOMEM TDC_EXIT_NOMEM

static const char help_text[] =
    "usage: tdc-zeng --scene fence|glossy|occlusion|pinkroom|lights|apples [--size WxH] [--frames N] [--eval-from K]\n"
    "                [--seeds \"1 2 3 4 5\"] [--gt-spp 1024] [--rough SIGMA] [--clamp-on raw|filtered]\n"
    "                [--glossy-filter llk|fixed] [--no-falloff 0|1] [--spread K] [--ours-clamp K]\n"
    "                [--glossy-mv pixel|splat] [--fetch-error 0|1] [--jod PPD] [--csv FILE] [--png FILE]\n"
    "--glossy-filter: the glossy layer's spatial filter: [LLK*19]'s lobe footprint (llk, default) or the\n"
    "fixed 15x15 joint bilateral, sigma 3 px (fixed)\n"
    "--no-falloff 1: eq. 4's alpha^V off (alpha everywhere) for the shadow scenes\n"
    "--spread K: eq. 5's spread along the lobe footprint's axes times K (1, the paper's; 0: none)\n"
    "--ours-clamp K: ours' clamp at mu +- K sigma (3, sec. 5)\n"
    "--glossy-mv splat: eq. 5's vectors weight-averaged over the glossy filter's kernel (as sec. 4.1's\n"
    "shadow vectors); pixel (default): one per pixel\n"
    "--fetch-error 1: glossy scene, on stderr: each vector's fetch from the previous frame's ground truth\n"
    "against this frame's (RMSE of the linear layer over the glossy floor): the error of the vector alone\n"
    "--jod PPD: also FovVideoVDP's JOD of the evaluated frames (60 Hz, PPD pixels per degree), whole frame\n"
    "and effect region\n"
    "--clamp-on: the clamped methods' mu +- k sigma over the 1-sample frame (raw, default) or over the\n"
    "spatially filtered frame that eq. 2 blends (filtered)\n"
    "Zeng et al.'s evaluation (sec. 6-7) on the double-precision reference pipeline (sim/zeng/README.md):\n"
    "every method's RMSE and SSIM against a >= 1024-sample ground truth, whole frame and effect region,\n"
    "and the dual vectors' cost beside the primary rays.\n"
    "exit codes (docs/tools.md): 0 OK, 1 ARGS, 7 FILE, 17 NOMEM\n";

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int usage(const char *what)
{
    fprintf(stderr, "tdc-zeng: arguments: %s: see the header of sim/zeng/zeng_main.c\n", what);
    return EXIT_ARGS;
}

static int nomem(void)
{
    fprintf(stderr, "tdc-zeng: run: allocation failed: out of memory\n");
    return EXIT_NOMEM;
}

typedef struct {
    double rmse, ssim, rmse_r, ssim_r;
    long px;
    int n;
} acc_t;

/* The display the JOD judge assumes (our choice; the paper names none): an
 * SDR desktop panel, 200 cd/m^2 peak, 1000:1, in a dark room, gamma 2.2
 * (the encoding of ze_encode), BT.709 luminance weights. */
static const tdc_fvvdp_photometry_t jod_display = {200.0, 1000.0, 0.0, 0.0, TDC_FVVDP_EOTF_GAMMA, {2.2, 2.2, 2.2},
                                                   {0.2126, 0.7152, 0.0722}};
#define JOD_FPS 60.0 /* one rendered frame per refresh of a 60 Hz panel */

/* Gamma-encoded RGB (ze_encode) -> luminance in cd/m^2 on jod_display;
 * with mask, the reference's luminance outside it. */
static void jod_lum(const double *enc, size_t n, const uint8_t *mask, const float *ref, float *out)
{
    for (size_t p = 0; p < n; p++) {
        out[p] = mask && !mask[p] ? ref[p] : (float)tdc_fvvdp_lum_rgb(&jod_display, enc + 3 * p);
    }
}

/* The options that pick one of two words (the first the default). */
enum { PICK_CLAMP_ON, PICK_GLOSSY_FILTER, PICK_NO_FALLOFF, PICK_GLOSSY_MV, PICK_FETCH_ERROR, PICK_N };
static const struct {
    const char *opt, *word[2];
} k_pick[PICK_N] = {{"--clamp-on", {"raw", "filtered"}},
                    {"--glossy-filter", {"llk", "fixed"}},
                    {"--no-falloff", {"0", "1"}},
                    {"--glossy-mv", {"pixel", "splat"}},
                    {"--fetch-error", {"0", "1"}}};

static int pick_option(const char *a)
{
    for (int k = 0; k < PICK_N; k++) {
        if (!strcmp(a, k_pick[k].opt)) {
            return k;
        }
    }
    return -1;
}

/* The error of a glossy vector alone: the previous frame's ground truth
 * fetched where each vector points (bilinear, taps on the same object, as
 * zp_step fetches the history) against this frame's ground truth, over the
 * glossy floor (linear layer, 3 channels).  fe[v]: squared error, pixels,
 * fetches that found no tap; v = trad, spec, ours. */
static void fetch_err(const zs_scene_t *sc, const zs_frame_t *f, const zs_frame_t *pf, const double *gt_prev,
                      const double *gt_now, double fe[3][3])
{
    const int w = f->w, h = f->h;
    for (size_t p = 0; p < (size_t)w * h; p++) {
        if (f->id[p] < 0 || sc->obj[f->id[p]].ks <= 0) {
            continue;
        }
        const double *vec[3] = {f->mv_trad + 2 * p, f->mv_spec + 2 * p, f->mv_eff + 2 * p};
        for (int v = 0; v < 3; v++) {
            double hv[3];
            if (vec[v][0] < -1e8 || !zf_fetch(gt_prev, 3, w, h, vec[v][0], vec[v][1], pf->id, f->id[p], hv)) {
                fe[v][2]++;
                continue;
            }
            for (int c = 0; c < 3; c++) {
                fe[v][0] += (hv[c] - gt_now[3 * p + c]) * (hv[c] - gt_now[3 * p + c]) / 3.0;
            }
            fe[v][1]++;
        }
    }
}

int main(int argc, char **argv)
{
    const char *scene_name = NULL, *csv = NULL, *png = NULL, *seeds_s = "1 2 3 4 5";
    int w = 160, h = 120, frames = 40, eval_from = 16, gt_spp = 1024;
    double rough = 0; /* 0: the scene's own */
    double jod_ppd = 0; /* 0: no JOD */
    double spread = 1.0, ours_k = 3.0;
    int picked[PICK_N] = {0}, pk; /* the two-word options: 1 when the second word was given */
    if (argc == 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
        fputs(help_text, stdout);
        return 0;
    }
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!v) {
            return usage("an option without its value");
        }
        i++;
        if (!strcmp(a, "--scene")) {
            scene_name = v;
        } else if (!strcmp(a, "--size")) {
            if (sscanf(v, "%dx%d", &w, &h) != 2 || w < 16 || h < 16 || w > 4096 || h > 4096) {
                return usage("--size: WxH, 16..4096");
            }
        } else if (!strcmp(a, "--frames")) {
            frames = atoi(v);
        } else if (!strcmp(a, "--eval-from")) {
            eval_from = atoi(v);
        } else if (!strcmp(a, "--seeds")) {
            seeds_s = v;
        } else if (!strcmp(a, "--gt-spp")) {
            gt_spp = atoi(v);
        } else if (!strcmp(a, "--csv")) {
            csv = v;
        } else if (!strcmp(a, "--rough")) {
            rough = atof(v);
            if (!(rough > 0 && rough < 1)) {
                return usage("--rough: the glossy lobe's sigma in radians, in (0, 1)");
            }
        } else if ((pk = pick_option(a)) >= 0) {
            if (strcmp(v, k_pick[pk].word[0]) && strcmp(v, k_pick[pk].word[1])) {
                char why[80];
                snprintf(why, sizeof why, "%s: %s or %s", a, k_pick[pk].word[0], k_pick[pk].word[1]);
                return usage(why);
            }
            picked[pk] = !strcmp(v, k_pick[pk].word[1]);
        } else if (!strcmp(a, "--spread")) {
            spread = atof(v);
            if (!(spread >= 0 && spread <= 4)) {
                return usage("--spread: eq. 5's spread scale, 0..4");
            }
        } else if (!strcmp(a, "--ours-clamp")) {
            ours_k = atof(v);
            if (!(ours_k > 0 && ours_k <= 10)) {
                return usage("--ours-clamp: sigmas, in (0, 10]");
            }
        } else if (!strcmp(a, "--jod")) {
            jod_ppd = atof(v);
            if (!(jod_ppd >= 1 && jod_ppd <= 200)) {
                return usage("--jod: pixels per degree, 1..200");
            }
        } else if (!strcmp(a, "--png")) {
            png = v;
        } else {
            return usage(a);
        }
    }
    const int clamp_filtered = picked[PICK_CLAMP_ON], fetch_error = picked[PICK_FETCH_ERROR];
    const int kind = scene_name ? zs_scene_by_name(scene_name) : -1;
    if (kind < 0) {
        return usage("--scene: fence, glossy, occlusion, pinkroom, lights or apples");
    }
    const int k = (int)lround(sqrt((double)gt_spp));
    if (k * k != gt_spp || gt_spp < 1) {
        return usage("--gt-spp: a square (1024 = 32^2)");
    }
    if (frames < 2 || eval_from < 1 || eval_from >= frames) {
        return usage("--frames N >= 2, 1 <= --eval-from < N");
    }
    long seeds[64];
    int nseeds = 0;
    for (const char *p = seeds_s; *p && nseeds < 64;) {
        char *end;
        long s = strtol(p, &end, 10);
        if (end == p) {
            break;
        }
        seeds[nseeds++] = s;
        p = end;
    }
    if (!nseeds) {
        return usage("--seeds: a list of integers");
    }
    FILE *out = stdout;
    if (csv && !(out = fopen(csv, "w"))) {
        fprintf(stderr, "tdc-zeng: --csv: cannot create %s: %s\n", csv, strerror(errno));
        return EXIT_FILE;
    }
    zs_scene_t sc;
    zs_scene_init(&sc, kind);
    sc.glossy_fixed = picked[PICK_GLOSSY_FILTER];
    sc.no_falloff = picked[PICK_NO_FALLOFF];
    sc.spread = spread;
    sc.glossy_splat = picked[PICK_GLOSSY_MV];
    for (int o = 0; o < sc.nobj && rough > 0; o++) {
        if (sc.obj[o].ks > 0) {
            sc.obj[o].rough = rough;
        }
    }
    const size_t n = (size_t)w * h;
    const int nev = frames - eval_from;
    /* ground truth layers of the evaluated frames, and three before them
     * (the shadow region spans where the shadow was) */
    const int g0 = eval_from >= 3 ? eval_from - 3 : 0, ngt = frames - g0;
    double *gt = malloc((size_t)ngt * n * 3 * sizeof(double));
    double *rgb = malloc(n * 3 * sizeof(double)), *ref = malloc(n * 3 * sizeof(double));
    double *enc = malloc(n * 3 * sizeof(double)), *encr = malloc(n * 3 * sizeof(double));
    double *map = malloc(n * sizeof(double));
    uint8_t *mask = malloc(n);
    int *last_dis = malloc(n * sizeof(int));
    uint8_t *strip = png ? malloc(n * 3 * (ZM_N + 1)) : NULL;
    float *lref = jod_ppd > 0 ? malloc(n * sizeof(float)) : NULL, *ltest = jod_ppd > 0 ? malloc(n * sizeof(float)) : NULL;
    if (jod_ppd > 0 && (!lref || !ltest)) {
        return nomem();
    }
    const tdc_fvvdp_geometry_t jod_geom = tdc_fvvdp_geometry_ppd(w, h, jod_ppd > 0 ? jod_ppd : 60);
    zs_frame_t fa, fb;
    if (!gt || !rgb || !ref || !enc || !encr || !map || !mask || !last_dis || (png && !strip) ||
        zs_frame_alloc(&fa, w, h) || zs_frame_alloc(&fb, w, h)) {
        return nomem();
    }
    for (int f = g0; f < frames; f++) {
        zs_ground_truth(&sc, f, w, h, gt_spp, gt + (size_t)(f - g0) * n * 3);
    }
    fprintf(out, "scene,seed,method,rmse,ssim,rmse_region,ssim_region,region_px%s\n", jod_ppd > 0 ? ",jod,jod_region" : "");
    double t_primary = 0, t_dual = 0;
    long n_cost = 0;
    double fe[3][3]; /* trad, spec, ours: squared error, pixels, missed fetches */
    memset(fe, 0, sizeof fe);
    for (int si = 0; si < nseeds; si++) {
        zp_state_t st[ZM_N];
        acc_t acc[ZM_N];
        memset(acc, 0, sizeof acc);
        int use[ZM_N];
        for (int m = 0; m < ZM_N; m++) {
            use[m] = m != ZM_SPEC || sc.noisy == ZL_GLOSSY;
            if (use[m] && zp_init(&st[m], m, w, h)) {
                return nomem();
            }
            st[m].seed = (uint64_t)seeds[si];
            st[m].clamp_filtered = clamp_filtered;
            st[m].clamp_k = ours_k;
        }
        /* the JOD judges: jm[m][0] whole frame, [1] region; the first used
         * method's whole-frame judge holds the reference, the others share it
         * (fed after it, frame by frame); the first evaluated frame pads the
         * temporal history (FovVideoVDP's "replicate") */
        tdc_fvvdp_t *jm[ZM_N][2];
        memset(jm, 0, sizeof jm);
        int jo = -1;
        for (int m = 0; m < ZM_N && jod_ppd > 0; m++) {
            if (!use[m]) {
                continue;
            }
            char why[160];
            for (int r = 0; r < 2; r++) {
                jm[m][r] = jo < 0 ? tdc_fvvdp_new(&jod_geom, JOD_FPS, why, sizeof why)
                                  : tdc_fvvdp_new_shared(jm[jo][0], why, sizeof why);
                if (!jm[m][r]) {
                    fprintf(stderr, "tdc-zeng: --jod: the judge refused: %s\n", why);
                    return EXIT_ARGS;
                }
                if (jo < 0) {
                    jo = m;
                }
            }
        }
        for (size_t p = 0; p < n; p++) {
            last_dis[p] = -1000;
        }
        zs_frame_t *f = &fa, *pf = &fb;
        for (int fr = 0; fr < frames; fr++) {
            zs_render(&sc, fr, (uint64_t)seeds[si], f);
            if (fr > 0 && si == 0) {
                /* §7: the dual vectors' cost beside the primary rays of
                 * the same frame (thread CPU time) */
                zs_cam_t cam, pcam;
                zs_camera(&sc, fr, w, h, &cam);
                zs_camera(&sc, fr - 1, w, h, &pcam);
                double t0 = now_ms();
                for (int y = 0; y < h; y++) {
                    for (int x = 0; x < w; x++) {
                        double d[3];
                        const double px = x + 0.5 - 0.5 * w, py = y + 0.5 - 0.5 * h;
                        for (int c = 0; c < 3; c++) {
                            d[c] = cam.fpx * cam.f[c] + px * cam.r[c] - py * cam.u[c];
                        }
                        const double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                        d[0] /= l;
                        d[1] /= l;
                        d[2] /= l;
                        int id;
                        (void)zs_intersect(&sc, fr, cam.pos, d, INFINITY, &id, NULL);
                        rgb[(size_t)y * w + x] = id;
                    }
                }
                double t1 = now_ms();
                for (int y = 0; y < h; y++) {
                    for (int x = 0; x < w; x++) {
                        double o2[2];
                        ref[(size_t)y * w + x] = zp_dual_vector(&sc, fr, f, pf, &cam, &pcam, x, y, o2) + o2[0];
                    }
                }
                double t2 = now_ms();
                t_primary += t1 - t0;
                t_dual += t2 - t1;
                n_cost++;
            }
            if (fetch_error && sc.noisy == ZL_GLOSSY && fr > g0) {
                fetch_err(&sc, f, pf, gt + (size_t)(fr - 1 - g0) * n * 3, gt + (size_t)(fr - g0) * n * 3, fe);
            }
            for (int m = 0; m < ZM_N; m++) {
                if (use[m]) {
                    zp_step(&st[m], &sc, fr, f, pf);
                }
            }
            /* disocclusions (the occlusion region): the traditional vector
             * lands on another object in the previous frame */
            if (fr > 0) {
                for (int y = 0; y < h; y++) {
                    for (int x = 0; x < w; x++) {
                        const size_t p = (size_t)y * w + x;
                        const int qx = (int)floor(f->mv_trad[2 * p]), qy = (int)floor(f->mv_trad[2 * p + 1]);
                        if (qx >= 0 && qy >= 0 && qx < w && qy < h && pf->id[(size_t)qy * w + qx] != f->id[p]) {
                            last_dis[p] = fr;
                        }
                    }
                }
            }
            if (fr >= eval_from) {
                const double *gl = gt + (size_t)(fr - g0) * n * 3;
                zs_composite(&sc, f, gl, ref);
                ze_encode(ref, encr, w, h);
                for (size_t p = 0; p < n; p++) {
                    if (sc.noisy == ZL_VIS) {
                        int in = 0;
                        for (int b = fr - 3 < g0 ? g0 : fr - 3; b <= fr; b++) {
                            in |= gt[(size_t)(b - g0) * n * 3 + 3 * p] < 0.98;
                        }
                        mask[p] = (uint8_t)in;
                    } else if (sc.noisy == ZL_GLOSSY) {
                        mask[p] = f->id[p] >= 0 && sc.obj[f->id[p]].ks > 0;
                    } else {
                        mask[p] = fr - last_dis[p] < 8;
                    }
                }
                if (jo >= 0) {
                    jod_lum(encr, n, NULL, NULL, lref);
                }
                for (int m = 0; m < ZM_N; m++) {
                    if (!use[m]) {
                        continue;
                    }
                    zs_composite(&sc, f, st[m].out, rgb);
                    ze_encode(rgb, enc, w, h);
                    for (int r = 0; r < 2 && jo >= 0; r++) { /* the owner (jo, whole frame) first */
                        jod_lum(enc, n, r ? mask : NULL, lref, ltest);
                        if (isnan(tdc_fvvdp_frame(jm[m][r], ltest, m == jo && !r ? lref : NULL, NULL))) {
                            return nomem();
                        }
                    }
                    ze_ssim_map(enc, encr, w, h, map);
                    double r0, s0, r1, s1;
                    ze_region(enc, encr, map, NULL, w, h, &r0, &s0);
                    long px = ze_region(enc, encr, map, mask, w, h, &r1, &s1);
                    acc[m].rmse += r0;
                    acc[m].ssim += s0;
                    if (px > 0 && !isnan(s1)) {
                        acc[m].rmse_r += r1;
                        acc[m].ssim_r += s1;
                        acc[m].n++;
                    }
                    acc[m].px += px;
                    if (strip && si == 0 && fr == frames - 1) {
                        for (int y = 0; y < h; y++) {
                            for (int x = 0; x < w * 3; x++) {
                                size_t row = (size_t)y * w * 3 * (ZM_N + 1);
                                strip[row + (size_t)(m + 1) * w * 3 + x] =
                                    (uint8_t)lround(255.0 * enc[(size_t)y * w * 3 + x]);
                                strip[row + x] = (uint8_t)lround(255.0 * encr[(size_t)y * w * 3 + x]);
                            }
                        }
                    }
                }
            }
            zs_frame_t *t = f;
            f = pf;
            pf = t;
        }
        for (int m = 0; m < ZM_N; m++) {
            if (!use[m]) {
                continue;
            }
            fprintf(out, "%s,%ld,%s,%.6f,%.6f,%.6f,%.6f,%ld", zs_scene_name(kind), seeds[si], zp_method_name(m),
                    acc[m].rmse / nev, acc[m].ssim / nev, acc[m].n ? acc[m].rmse_r / acc[m].n : NAN,
                    acc[m].n ? acc[m].ssim_r / acc[m].n : NAN, acc[m].px / nev);
            if (jo >= 0) {
                fprintf(out, ",%.4f,%.4f", tdc_fvvdp_jod(jm[m][0]), tdc_fvvdp_jod(jm[m][1]));
            }
            fputc('\n', out);
            zp_free(&st[m]);
        }
        for (int m = ZM_N; m-- > 0;) { /* the owner last: the others read its planes */
            if (m != jo) {
                tdc_fvvdp_free(jm[m][0]);
                tdc_fvvdp_free(jm[m][1]);
            }
        }
        if (jo >= 0) {
            tdc_fvvdp_free(jm[jo][1]);
            tdc_fvvdp_free(jm[jo][0]);
        }
    }
    if (fetch_error && sc.noisy == ZL_GLOSSY) {
        static const char *const fname[3] = {"trad", "spec", "ours (eq. 5)"};
        for (int v = 0; v < 3; v++) {
            fprintf(stderr, "tdc-zeng: fetch error, %s vectors: RMSE %.5f over %.0f floor pixels (%.0f fetches missed)\n",
                    fname[v], sqrt(fe[v][0] / fmax(fe[v][1], 1.0)), fe[v][1], fe[v][2]);
        }
    }
    fprintf(out, "cost,primary_ms_per_frame,dual_ms_per_frame,dual_over_primary\n");
    fprintf(out, "cost,%.4f,%.4f,%.4f\n", t_primary / n_cost, t_dual / n_cost, t_dual / t_primary);
    if (csv ? fclose(out) != 0 : fflush(out) != 0) {
        fprintf(stderr, "tdc-zeng: --csv: cannot write %s: %s\n", csv ? csv : "stdout", strerror(errno));
        return EXIT_FILE;
    }
    if (strip) {
        char err[256];
        if (tdc_png_write(png, strip, w * (ZM_N + 1), h, 8, (size_t)w * 3 * (ZM_N + 1), err, sizeof err)) {
            fprintf(stderr, "tdc-zeng: --png: cannot write %s: %s\n", png, err);
            return EXIT_FILE;
        }
    }
    zs_frame_free(&fa);
    zs_frame_free(&fb);
    free(gt);
    free(rgb);
    free(ref);
    free(enc);
    free(encr);
    free(map);
    free(mask);
    free(last_dis);
    free(strip);
    free(lref);
    free(ltest);
    return 0;
}
