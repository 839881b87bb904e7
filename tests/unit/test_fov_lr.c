/*
 * test_fov_lr.c - the log-rectilinear foveation kind (firmware/tdc_fov_lr.c
 * behind tdc_fov_frame) against its double-precision reference
 * (ref/ref_fov_lr.c), and its properties:
 *  - fixed point vs double: max abs error of the 8-bit output against the
 *    unrounded reference, share within 1 LSB, per case (gaze centre,
 *    off-centre, each corner, outside; disk 0 / 12.443 % / 1; TAA runs);
 *    target >= 99.9 % within 1 LSB and max <= 2 LSB;
 *  - the forward/inverse pair round-trips (double), the fixed-point forward
 *    map is monotone, hits both ends exactly and stays within 0.01 texel of
 *    the double one; the default k gives one texel per pixel at the gaze;
 *  - the summed-area buffer conserves the picture's integral and is exact
 *    on a uniform field; stripes finer than a texel average out in the
 *    periphery (what area averaging is for); the same in linear light (the
 *    simulator's sender): every code of a uniform field exact under any
 *    gamma, stripes to their linear-light mean;
 *  - the footprint prefilter of the kernel log-polar samples (the same box,
 *    ref_fov_lr_box_mean, over ref_fov_lod_cone's side): a uniform field
 *    exact for every code, stripes finer than the box to their mean, no
 *    jump when the box moves; the footprint of ref_fov_lp_samples is the
 *    cell of the exact inverse of eq. 2.2 (central differences);
 *  - a uniform field remaps to exactly that field (any gaze, corners,
 *    outside, with TAA and random motion);
 *  - bad parameters (unknown transform, k out of range, alpha != 1, no
 *    scratch attached, scratch too narrow) are refused with nothing written.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "tdc_cmocka.h"

#include "fov_fixture.h"
#include "ref_fov_lr.h"
#include "tdc_sim_codes.h"
#include "tdc_fov_lr.h"

#define W 160
#define H 100

static uint32_t g_rng = 12345u;
static double rndu(void)
{
    g_rng = g_rng * 1664525u + 1013904223u;
    return (g_rng >> 8) / 16777216.0;
}

/* a stage with TAA or not and its log-rectilinear scratch attached */
typedef struct {
    tdc_fov_t st;
    tdc_fov_lr_t lr;
    void *mem, *lmem;
} rig_t;

static void rig_init(rig_t *r, int w, int h, int taa)
{
    const tdc_fov_config_t cfg = {(uint16_t)w, (uint16_t)h, (uint8_t)taa};
    const size_t n = tdc_fov_get_size(&cfg), ln = tdc_fov_lr_get_size((uint16_t)w);
    assert_int_equal(ln, TDC_FOV_LR_MEM_BYTES(w));
    r->mem = aligned_alloc(8, (n + 7) & ~(size_t)7);
    r->lmem = aligned_alloc(8, (ln + 7) & ~(size_t)7);
    assert_int_equal(tdc_fov_init(&r->st, &cfg, r->mem, n), TDC_OK);
    assert_int_equal(tdc_fov_lr_init(&r->lr, (uint16_t)w, r->lmem, ln - 1), TDC_ERR_SIZE);
    assert_int_equal(tdc_fov_lr_init(&r->lr, (uint16_t)w, r->lmem, ln), TDC_OK);
    assert_int_equal(tdc_fov_lr_attach(&r->st, &r->lr), TDC_OK);
}

static void rig_free(rig_t *r)
{
    free(r->mem);
    free(r->lmem);
}

/* Log-rectilinear parameters: the sender's default k per axis, quantised as the header carries them */
static void lr_params(ref_fov_params_t *rp, int w, int h, double cx, double cy, double disk)
{
    memset(rp, 0, sizeof *rp);
    rp->cx = cx;
    rp->cy = cy;
    rp->alpha = 1;
    rp->disk = disk;
    rp->lp_w = (int)floor(0.555 * w);
    rp->lp_h = (int)floor(0.555 * h);
    rp->transform = 1;
    fov_quantise(rp);
    rp->kx = ref_fov_lr_k(w, rp->lp_w, rp->cx);
    rp->ky = ref_fov_lr_k(h, rp->lp_h, rp->cy);
    fov_quantise(rp);
}

/* The display-resolution picture (also the disk) and the area-averaged buffer of it */
static void lr_inputs(const ref_fov_geom_t *g, double t, uint8_t *lp, uint8_t *img)
{
    for (int j = 0; j < g->height; j++) {
        for (int i = 0; i < g->width; i++) {
            fov_picture(i + 0.5 - t, j + 0.5, 0, img + ((size_t)j * g->width + i) * 3);
        }
    }
    double *sat = ref_fov_lr_sat(img, (size_t)g->width * 3, g->width, g->height, NULL);
    assert_non_null(sat);
    ref_fov_lr_buffer(sat, g->width, g->height, &g->ax, &g->ay, lp, (size_t)g->lp_w * 3, NULL, NULL);
    free(sat);
}

static fov_worst_t g_worst = {0, 100, 0};

static void run_case(const char *name, double cx, double cy, double disk, int taa)
{
    ref_fov_params_t rp;
    lr_params(&rp, W, H, cx, cy, disk);
    tdc_fov_params_t fp;
    fov_params(&rp, &fp);
    rig_t r;
    rig_init(&r, W, H, taa);
    fov_case_t c;
    assert_int_equal(fov_case_open(&c, W, H, &rp, taa), 0);
    const int frames = taa ? 8 : 1;
    for (int f = 0; f < frames; f++) {
        lr_inputs(&c.g, taa ? 1.3 * f : 0, c.lp, c.disk);
        assert_int_equal(fov_case_frame(&c, &r.st, &fp, &rp), TDC_OK);
    }
    assert_int_equal(r.lr.frames, (uint32_t)frames);
    double share;
    const int ok = fov_err_done(&c.err, &g_worst, &share);
    printf("  %-14s disk %6.3f %s k %6.2f,%6.2f: max %.3f LSB, within 1 LSB %.4f %%  %s\n", name, disk,
           taa ? "taa" : "   ", rp.kx, rp.ky, c.err.maxe, share, ok ? "ok" : "FAIL");
    fov_case_close(&c);
    rig_free(&r);
}

static void test_fixed_vs_double(void **state)
{
    (void)state;
    static const fov_gaze_t gz[] = {FOV_REF_GAZES(W, H), {"far outside", -W, 2.0 * H}};
    static const double disks[] = {0, 0.12443, 1};
    for (unsigned d = 0; d < 3; d++) {
        for (unsigned k = 0; k < sizeof gz / sizeof gz[0]; k++) {
            run_case(gz[k].name, gz[k].cx, gz[k].cy, disks[d], 0);
        }
    }
    run_case("centre", W / 2.0, H / 2.0, 0.12443, 1);
    run_case("off-centre", 37.3, 61.7, 0.12443, 1);
    run_case("corner BR", W, H, 0, 1);
    run_case("outside left", -70.5, 40.0, 0.12443, 1);
    printf("worst case: max %.3f LSB, within 1 LSB %.4f %%\n", g_worst.max, g_worst.share);
    assert_false(g_worst.fail);
}

/* The forward/inverse pair, the fixed-point forward map, the default k. */
static void test_round_trip(void **state)
{
    (void)state;
    double worst_rt = 0, worst_fx = 0;
    for (int c = 0; c < 300; c++) {
        const int N = 16 + (int)(rndu() * 4000), n = 4 + (int)(rndu() * (N - 4));
        double gc = rndu() * 3 * N - N; /* within one screen outside */
        gc = lround(gc * 256) / 256.0;
        double k = c % 3 == 0 ? ref_fov_lr_k(N, n, gc) : 1 + rndu() * 4000;
        k = fmin(lround(k * 16), 65535) / 16.0;
        ref_fov_lr_axis_t a;
        ref_fov_lr_axis(&a, gc, k, N, n);
        tdc_fov_lr_axis_t fa;
        tdc_fov_lr_axis(&fa, (int32_t)lround(gc * 256), (uint16_t)lround(k * 16), (uint16_t)N, (uint16_t)n);
        assert_int_equal(tdc_fov_lr_fwd_q16(&fa, 0), 0);
        assert_int_equal(tdc_fov_lr_fwd_q16(&fa, N * 256), (uint32_t)n << 16);
        assert_int_equal(tdc_fov_lr_fwd_q16(&fa, -5000), 0); /* clamped ends */
        assert_int_equal(tdc_fov_lr_fwd_q16(&fa, N * 256 + 9), (uint32_t)n << 16);
        uint32_t prev = 0;
        for (int s = 0; s <= 400; s++) {
            const double x = N * s / 400.0;
            const double u = ref_fov_lr_fwd(&a, x);
            const double e = fabs(ref_fov_lr_inv(&a, u) - x) / (1 + fabs(x - gc));
            worst_rt = e > worst_rt ? e : worst_rt;
            const int32_t xq = (int32_t)lround(x * 256);
            const uint32_t uf = tdc_fov_lr_fwd_q16(&fa, xq);
            assert_true(uf >= prev); /* monotone */
            prev = uf;
            /* tdc_fov_lr.h's bound: four log2 table values of error <= 2.84e-6 each, over S in log2 units,
             * plus the Q16 rounding */
            const double bound = n * 4 * 2.84e-6 / (a.S / log(2.0)) + 1.0 / 65536;
            const double ef = fabs(uf / 65536.0 - ref_fov_lr_fwd(&a, xq / 256.0)) / bound;
            worst_fx = ef > worst_fx ? ef : worst_fx;
        }
        if (c % 3 == 0 && k > 1.0 && k < 4095) { /* the default k: one texel per pixel at the gaze */
            const double gcl = fmin(fmax(gc, 0), N);
            if (gcl == gc) {
                assert_true(fabs(ref_fov_lr_density(&a, gc) - 1) < 0.01);
            }
        }
    }
    printf("round trip |x(u(x)) - x| / (1 + |x - c|) <= %.3g; fixed-point u error <= %.3f of the stated bound\n",
           worst_rt, worst_fx);
    assert_true(worst_rt < 1e-9);
    assert_true(worst_fx <= 1.0);
}

/* Summed-area averages: integral conserved, uniform exact, fine stripes averaged out. */
static void test_area_average(void **state)
{
    (void)state;
    const int w = 200, h = 120;
    uint8_t *img = malloc((size_t)w * h * 3);
    for (int k = 0; k < w * h * 3; k++) img[k] = (uint8_t)(rndu() * 256);
    double *sat = ref_fov_lr_sat(img, (size_t)w * 3, w, h, NULL);
    ref_fov_lr_axis_t ax, ay;
    ref_fov_lr_axis(&ax, 63.3, ref_fov_lr_k(w, 111, 63.3), w, 111);
    ref_fov_lr_axis(&ay, 90.1, ref_fov_lr_k(h, 66, 90.1), h, 66);
    uint8_t *lp = malloc(111 * 66 * 3);
    double *avg = malloc(111 * 66 * 3 * sizeof(double));
    ref_fov_lr_buffer(sat, w, h, &ax, &ay, lp, 111 * 3, avg, NULL);
    double tot[3] = {0, 0, 0}, mass[3] = {0, 0, 0};
    for (int k = 0; k < w * h * 3; k++) tot[k % 3] += img[k];
    for (int j = 0; j < 66; j++) {
        for (int m = 0; m < 111; m++) {
            const double area = (ref_fov_lr_inv(&ax, m + 1) - ref_fov_lr_inv(&ax, m)) *
                                (ref_fov_lr_inv(&ay, j + 1) - ref_fov_lr_inv(&ay, j));
            for (int ch = 0; ch < 3; ch++) mass[ch] += avg[((size_t)j * 111 + m) * 3 + ch] * area;
        }
    }
    for (int ch = 0; ch < 3; ch++) assert_true(fabs(mass[ch] - tot[ch]) < 1e-6 * tot[ch]);
    free(sat);
    /* vertical stripes of period 2 px: every texel wider than a few pixels is ~ the mean */
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) memset(img + ((size_t)j * w + i) * 3, (i & 1) ? 250 : 10, 3);
    sat = ref_fov_lr_sat(img, (size_t)w * 3, w, h, NULL);
    ref_fov_lr_axis(&ax, 63.3, 4.0, w, 111); /* a small k: wide texels in the periphery */
    ref_fov_lr_buffer(sat, w, h, &ax, &ay, lp, 111 * 3, avg, NULL);
    int wide = 0;
    for (int m = 0; m < 111; m++) {
        const double x0 = ref_fov_lr_inv(&ax, m), x1 = ref_fov_lr_inv(&ax, m + 1);
        if (x1 - x0 >= 4) { /* >= 2 periods: |avg - 130| <= 120 / (periods) */
            wide++;
            assert_true(fabs(avg[m * 3] - 130) <= 240 / (x1 - x0) + 1e-9);
        }
    }
    assert_true(wide > 10);
    /* uniform field: every texel exactly the value */
    memset(img, 77, (size_t)w * h * 3);
    free(sat);
    sat = ref_fov_lr_sat(img, (size_t)w * 3, w, h, NULL);
    ref_fov_lr_buffer(sat, w, h, &ax, &ay, lp, 111 * 3, NULL, NULL);
    for (int k = 0; k < 111 * 66 * 3; k++) assert_int_equal(lp[k], 77);
    free(sat);
    free(img);
    free(lp);
    free(avg);
}

/* Linear light (the simulator's sender and prefilter): codes decoded by the
 * panel gamma, averaged, encoded back. */
static double lin_mean_code(int a, int b, double gamma) /* linear-light mean of codes a, b, as a code (unrounded) */
{
    return 255 * pow((pow(a / 255.0, gamma) + pow(b / 255.0, gamma)) / 2, 1 / gamma);
}

static void test_area_average_linear(void **state)
{
    (void)state;
    const int w = 200, h = 120;
    uint8_t *img = malloc((size_t)w * h * 3);
    uint8_t *lp = malloc(111 * 66 * 3);
    double *avg = malloc(111 * 66 * 3 * sizeof(double));
    ref_fov_lr_axis_t ax, ay;
    ref_fov_lr_axis(&ax, 63.3, 4.0, w, 111);
    ref_fov_lr_axis(&ay, 90.1, ref_fov_lr_k(h, 66, 90.1), h, 66);
    static const double gammas[][3] = {{2.2, 2.2, 2.2}, {1.0, 1.8, 2.6}};
    for (int gi = 0; gi < 2; gi++) {
        double lut[3 * 256];
        ref_fov_lin_lut(gammas[gi], lut);
        for (int c = 0; c < 256; c += 5) { /* uniform: exactly the code back */
            memset(img, c, (size_t)w * h * 3);
            double *sat = ref_fov_lr_sat(img, (size_t)w * 3, w, h, lut);
            ref_fov_lr_buffer(sat, w, h, &ax, &ay, lp, 111 * 3, NULL, gammas[gi]);
            for (int k = 0; k < 111 * 66 * 3; k++) assert_int_equal(lp[k], c);
            free(sat);
        }
    }
    /* stripes 10 / 250 of period 2 px: the linear-light mean (code 183 at
     * gamma 2.2), not the codes' 130 */
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) memset(img + ((size_t)j * w + i) * 3, (i & 1) ? 250 : 10, 3);
    double lut[3 * 256];
    ref_fov_lin_lut(gammas[0], lut);
    double *sat = ref_fov_lr_sat(img, (size_t)w * 3, w, h, lut);
    ref_fov_lr_buffer(sat, w, h, &ax, &ay, lp, 111 * 3, avg, gammas[0]);
    const double l10 = lut[10], l250 = lut[250], mean = (l10 + l250) / 2, target = lin_mean_code(10, 250, 2.2);
    int wide = 0;
    for (int m = 0; m < 111; m++) {
        const double x0 = ref_fov_lr_inv(&ax, m), x1 = ref_fov_lr_inv(&ax, m + 1);
        if (x1 - x0 >= 4) {
            wide++;
            const double tol = (l250 - l10) / (x1 - x0) + 1e-12; /* half a stripe at each end */
            assert_true(fabs(avg[m * 3] - mean) <= tol);
            assert_int_equal(lp[m * 3], tdc_sim_encode_code(avg[m * 3], 2.2));
            if (x1 - x0 >= 40) {
                assert_true(fabs(lp[m * 3] - target) <= 1.5);
            }
        }
    }
    printf("stripes 10/250: linear-light texel %d (the codes' mean 130)\n", (int)lround(target));
    assert_true(wide > 10);
    assert_true(target > 180);
    free(sat);
    free(img);
    free(lp);
    free(avg);
}

/* The kernel log-polar samples' footprint prefilter (the simulator's
 * photograph and procedural sources): box means over ref_fov_lod_cone. */
static void test_footprint_prefilter(void **state)
{
    (void)state;
    const int w = 160, h = 100;
    uint8_t *img = malloc((size_t)w * h * 3);
    double lut[3 * 256];
    const double gamma[3] = {2.2, 2.4, 1.8};
    ref_fov_lin_lut(gamma, lut);
    /* uniform: every code back exactly, any centre (also off the screen) and side */
    for (int c = 0; c < 256; c++) {
        memset(img, c, (size_t)w * h * 3);
        double *sat = ref_fov_lr_sat(img, (size_t)w * 3, w, h, lut);
        for (int t = 0; t < 40; t++) {
            const double x = -50 + rndu() * (w + 100), y = -50 + rndu() * (h + 100), side = 1 + rndu() * 60;
            double m[3];
            ref_fov_lr_box_mean(sat, w, h, x, y, side, m);
            for (int ch = 0; ch < 3; ch++) assert_int_equal(tdc_sim_encode_code(m[ch], gamma[ch]), c);
        }
        free(sat);
    }
    /* stripes of period 2 px (0 / 255): a box of side s >= 4 inside the
     * screen is their linear mean 1/2 within 1/(2 s) (half a stripe at each
     * end); a 1-px box on a stripe is that stripe (point-like) */
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) memset(img + ((size_t)j * w + i) * 3, (i & 1) ? 255 : 0, 3);
    double *sat = ref_fov_lr_sat(img, (size_t)w * 3, w, h, lut);
    double worst = 0;
    for (int t = 0; t < 2000; t++) {
        const double side = 4 + rndu() * 40;
        const double x = side / 2 + rndu() * (w - side), y = side / 2 + rndu() * (h - side);
        double m[3];
        ref_fov_lr_box_mean(sat, w, h, x, y, side, m);
        worst = fmax(worst, fabs(m[0] - 0.5) * side);
        assert_true(fabs(m[0] - 0.5) <= 0.5 / side + 1e-12);
    }
    double one[3];
    ref_fov_lr_box_mean(sat, w, h, 21.5, 30.5, 1.0, one);
    assert_true(fabs(one[0] - 1.0) < 1e-12);
    /* the box moves continuously: 1e-6 px changes the mean by at most 1e-6 / side per unit contrast */
    for (int t = 0; t < 500; t++) {
        const double side = 2 + rndu() * 30, x = side + rndu() * (w - 2 * side), y = side + rndu() * (h - 2 * side);
        double a[3], b[3];
        ref_fov_lr_box_mean(sat, w, h, x, y, side, a);
        ref_fov_lr_box_mean(sat, w, h, x + 1e-6, y, side, b);
        assert_true(fabs(a[0] - b[0]) <= 2e-6 / side + 1e-12);
    }
    printf("footprint box over 2-px stripes: |mean - 1/2| * side <= %.3f (bound 0.5)\n", worst);
    free(sat);
    free(img);
    /* ref_fov_lp_samples: the positions are the exact inverse of eq. 2.2,
     * the sides ref_fov_lod_cone's, and the footprint is the cell's longer
     * side (central differences of the positions, where > 1 px) */
    const ref_fov_params_t p = {0.45 * w, 0.55 * h, 4.0, 0.12443, 89, 56, 0, 0, 0};
    ref_fov_geom_t g;
    ref_fov_geom(&g, w, h, &p);
    const size_t n = (size_t)(g.lp_w - g.u0) * g.lp_h;
    double *xy = malloc(n * 2 * sizeof(double)), *side = malloc(n * sizeof(double));
    for (int lod = TDC_FOV_LOD_OFF; lod <= TDC_FOV_LOD_THESIS; lod++) {
        const double jx = lod == TDC_FOV_LOD_FOOTPRINT ? 0.3 : -0.2, jy = 0.1;
        assert_int_equal(ref_fov_lp_samples(&g, g.u0, jx, jy, TDC_FOV_JITTER_TEXEL, lod, xy, side), n);
        int checked = 0;
        size_t k = 0;
        for (int j = 0; j < g.lp_h; j++) {
            for (int i = g.u0; i < g.lp_w; i++, k++) {
                const double u = fmax(i + jx, 0);
                double x, y;
                ref_fov_from_lp(&g, u, j + jy, &x, &y);
                assert_true(x == xy[2 * k] && y == xy[2 * k + 1]);
                assert_true(side[k] >= 1);
                if (lod == TDC_FOV_LOD_OFF) {
                    assert_true(side[k] == 1);
                } else if (lod == TDC_FOV_LOD_THESIS) {
                    assert_true(side[k] <= 8);
                } else if (u > 1) {
                    double xa, ya, xb, yb, xc, yc, xd, yd;
                    ref_fov_from_lp(&g, u - 1e-4, j + jy, &xa, &ya);
                    ref_fov_from_lp(&g, u + 1e-4, j + jy, &xb, &yb);
                    ref_fov_from_lp(&g, u, j + jy - 1e-4, &xc, &yc);
                    ref_fov_from_lp(&g, u, j + jy + 1e-4, &xd, &yd);
                    const double rad = hypot(xb - xa, yb - ya) / 2e-4, tan_ = hypot(xd - xc, yd - yc) / 2e-4;
                    const double cell = fmax(fmax(rad, tan_), 1);
                    assert_true(fabs(side[k] - cell) <= 1e-3 * cell);
                    checked++;
                }
            }
        }
        if (lod == TDC_FOV_LOD_FOOTPRINT) {
            assert_true(checked > (int)n / 2);
        }
    }
    /* the TAA jitter: TEXEL moves a peripheral sample by up to half a cell
     * (many display pixels), PIXEL by at most half a texel and about half a
     * display pixel per axis (the cell varies a little over the offset) */
    double worst_px = 0, worst_texel_mode = 0;
    for (int j = 0; j < g.lp_h; j++) {
        for (int i = g.u0; i < g.lp_w; i++) {
            double x0, y0, u, v, x, y;
            ref_fov_from_lp(&g, i, j, &x0, &y0);
            for (int mode = TDC_FOV_JITTER_TEXEL; mode <= TDC_FOV_JITTER_PIXEL; mode++) {
                ref_fov_lp_jitter(mode, g.L, g.alpha, g.lp_w, g.lp_h, i, j, 0.5, -0.5, &u, &v);
                assert_true(fabs(u - i) <= 0.5 && fabs(v - j) <= 0.5);
                ref_fov_from_lp(&g, u, v, &x, &y);
                const double d = hypot(x - x0, y - y0);
                if (mode == TDC_FOV_JITTER_PIXEL) {
                    worst_px = fmax(worst_px, d);
                    assert_true(d <= 0.55 * M_SQRT2);
                } else {
                    worst_texel_mode = fmax(worst_texel_mode, d);
                }
            }
        }
    }
    printf("jitter (0.5, -0.5): texel moves a sample up to %.2f px, pixel up to %.3f px\n", worst_texel_mode,
           worst_px);
    assert_true(worst_texel_mode > 3);
    free(xy);
    free(side);
}

/* A uniform field stays exactly uniform: any gaze, disk, TAA with motion. */
static void test_uniform(void **state)
{
    (void)state;
    const int w = 57, h = 41;
    for (int c = 0; c < 60; c++) {
        const int taa = c & 1;
        rig_t r;
        rig_init(&r, w, h, taa);
        ref_fov_params_t rp;
        double cx = rndu() * 3 * w - w, cy = rndu() * 3 * h - h;
        if (c < 8) { /* the corners, twice */
            cx = (c & 2) ? w : 0;
            cy = (c & 4) ? h : 0;
        }
        lr_params(&rp, w, h, cx, cy, rndu() < 0.2 ? 0 : rndu());
        tdc_fov_params_t fp;
        fov_params(&rp, &fp);
        if (c % 5 == 4) { /* any k, not only the default */
            fp.lr_k_q4[0] = (uint16_t)(16 + rndu() * 65519);
            fp.lr_k_q4[1] = (uint16_t)(16 + rndu() * 65519);
        }
        uint8_t *lp = malloc((size_t)fp.lp_w * fp.lp_h * 3), *img = malloc((size_t)w * h * 3),
                *out = malloc((size_t)w * h * 3);
        int16_t *mv = malloc((size_t)fp.lp_w * fp.lp_h * 4);
        const uint8_t col[3] = {(uint8_t)(rndu() * 256), (uint8_t)(rndu() * 256), (uint8_t)(rndu() * 256)};
        for (int k = 0; k < fp.lp_w * fp.lp_h; k++) memcpy(lp + 3 * k, col, 3);
        for (int k = 0; k < w * h; k++) memcpy(img + 3 * k, col, 3);
        for (int f = 0; f < 4; f++) {
            for (int k = 0; k < fp.lp_w * fp.lp_h * 2; k++) mv[k] = (int16_t)(rndu() * 400 - 200);
            assert_int_equal(tdc_fov_frame(&r.st, &fp, lp, (size_t)fp.lp_w * 3, mv, (size_t)fp.lp_w * 2, img,
                                           (size_t)w * 3, 11111, out, (size_t)w * 3),
                             TDC_OK);
            for (int k = 0; k < w * h; k++) assert_memory_equal(out + 3 * k, col, 3);
        }
        free(lp);
        free(img);
        free(out);
        free(mv);
        rig_free(&r);
    }
}

/* Bad parameters: refused, nothing written, the stage still works after. */
static void test_refused(void **state)
{
    (void)state;
    const int w = 40, h = 30;
    rig_t r;
    rig_init(&r, w, h, 1);
    ref_fov_params_t rp;
    lr_params(&rp, w, h, 13.5, 20.25, 0.12443);
    tdc_fov_params_t ok;
    fov_params(&rp, &ok);
    static uint8_t lp[40 * 30 * 3], img[40 * 30 * 3], out[40 * 30 * 3], keep[40 * 30 * 3];
    for (size_t k = 0; k < sizeof lp; k++) lp[k] = (uint8_t)(k * 7), img[k] = (uint8_t)(k * 13);
    assert_int_equal(tdc_fov_frame(&r.st, &ok, lp, (size_t)ok.lp_w * 3, NULL, 0, img, (size_t)w * 3, 0, out,
                                   (size_t)w * 3),
                     TDC_OK);
    memcpy(keep, out, sizeof out);
    const uint32_t frames = r.st.frames;
    for (int c = 0; c < 7; c++) {
        tdc_fov_params_t p = ok;
        tdc_status_t want = TDC_ERR_ARG;
        rig_t narrow;
        int detached = 0;
        switch (c) {
        case 0: p.transform = 2; break;
        case 1: p.lr_k_q4[0] = 0; break;
        case 2: p.lr_k_q4[1] = 15; break; /* below 1 px */
        case 3: p.alpha_q8 = 1024; break; /* alpha means nothing here: must be 1 */
        case 4: detached = 1; break;      /* a stage without log-rectilinear scratch */
        case 5: p.gaze_x_q8 = -w * 256 - 1; break;
        default: /* scratch for a narrower display */
            rig_init(&narrow, w - 1, h, 0);
            assert_int_equal(tdc_fov_lr_attach(&r.st, &narrow.lr), TDC_ERR_SIZE);
            rig_free(&narrow);
            continue;
        }
        if (detached) assert_int_equal(tdc_fov_lr_attach(&r.st, NULL), TDC_OK);
        tdc_fov_geom_t g;
        if (c < 4) assert_int_equal(tdc_fov_geom(&g, (uint16_t)w, (uint16_t)h, &p), TDC_ERR_ARG);
        assert_int_equal(tdc_fov_frame(&r.st, &p, lp, (size_t)ok.lp_w * 3, NULL, 0, img, (size_t)w * 3, 0, out,
                                       (size_t)w * 3),
                         want);
        assert_memory_equal(out, keep, sizeof out); /* nothing written: the last good frame */
        if (detached) assert_int_equal(tdc_fov_lr_attach(&r.st, &r.lr), TDC_OK);
    }
    assert_int_equal(r.st.frames, frames);
    assert_int_equal(tdc_fov_frame(&r.st, &ok, lp, (size_t)ok.lp_w * 3, NULL, 0, img, (size_t)w * 3, 0, out,
                                   (size_t)w * 3),
                     TDC_OK);
    assert_int_equal(tdc_fov_lr_init(&r.lr, 3, r.lmem, 4096), TDC_ERR_ARG);
    assert_int_equal(tdc_fov_lr_get_size(8193), 0);
    rig_free(&r);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_round_trip), cmocka_unit_test(test_area_average),
    cmocka_unit_test(test_area_average_linear),
    cmocka_unit_test(test_footprint_prefilter), cmocka_unit_test(test_uniform),
    cmocka_unit_test(test_refused),    cmocka_unit_test(test_fixed_vs_double),
)
