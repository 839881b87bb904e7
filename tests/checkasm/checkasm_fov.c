/*
 * checkasm_fov.c - checkasm module of the foveated remap: the tap kernel
 * (tdc_fov_kernels.h), optimised versions against the portable C kernel,
 * bit for bit on the three output planes (nothing written past n).
 *
 * Inputs: a random log-polar buffer (any stride >= 3 lp_w), descriptors
 * with random samples, both steps, weights 0 / 2^15 / random and fractions
 * 0 / 2^15 - 1 / random, descriptors at the buffer's very end (the last
 * sample of the last row: the SIMD kernels' C fall-back) and at its start,
 * every row length 1..40 and then random ones.
 *
 * fov_geom: the geometry pass (tdc_fov_geom_row_fn) of a real stage's
 * frame (tdc_fov_geom_args: its radial table and reciprocals) on random
 * displays up to 600 x 600, gazes on, at the corners of and outside the
 * screen, alpha 1..8, disks 0..1, TAA (the nearest samples) on or off, a
 * random row and span [x0, x1) of it: every output (descriptors, nearest
 * samples, colours, blend weights) bit for bit.
 */
#include <string.h>

#include "checkasm.h"
#include "tdc_fov.h"
#include "tdc_fov_kernels.h"
#include "tdc_fov_link.h"

#define FMAXN 2048u /* pixels per row */
#define FLPW 600u
#define FLPH 200u

static uint8_t g_lp[FLPH * (FLPW * 3u + 16u)] CHECKASM_BIG;
static uint32_t g_off0[FMAXN] CHECKASM_BIG, g_off1[FMAXN] CHECKASM_BIG, g_wf[FMAXN] CHECKASM_BIG;
static uint16_t g_out_c[3u * FMAXN + 16u] CHECKASM_BIG, g_out_v[3u * FMAXN + 16u] CHECKASM_BIG;

typedef struct {
    uint32_t lp_w, lp_h;
    size_t stride, bytes;
} fov_lp_t;

static fov_lp_t make_lp(void)
{
    fov_lp_t l;
    l.lp_w = 4u + checkasm_rand_below(FLPW - 3u);
    l.lp_h = 4u + checkasm_rand_below(FLPH - 3u);
    l.stride = (size_t)l.lp_w * 3u + (checkasm_rand_below(2u) ? checkasm_rand_below(16u) : 0u);
    l.bytes = (size_t)(l.lp_h - 1u) * l.stride + (size_t)l.lp_w * 3u;
    for (size_t k = 0; k < sizeof g_lp; k++) {
        g_lp[k] = (uint8_t)checkasm_rand();
    }
    return l;
}

static void make_desc(const fov_lp_t *l, uint32_t n)
{
    for (uint32_t k = 0; k < n; k++) {
        const uint32_t kind = checkasm_rand_below(16u);
        uint32_t c0 = checkasm_rand_below(l->lp_w), j0 = checkasm_rand_below(l->lp_h);
        if (kind == 0u) {
            c0 = l->lp_w - 1u; /* the buffer's last sample */
            j0 = l->lp_h - 1u;
        } else if (kind == 1u) {
            c0 = 0;
            j0 = 0;
        }
        const uint32_t j1 = j0 + 1u == l->lp_h ? 0u : j0 + 1u;
        const uint32_t step0 = c0 + 1u == l->lp_w || checkasm_rand_below(8u) == 0u;
        uint32_t w0 = checkasm_rand_below(32769u), fv = checkasm_rand_below(32768u);
        if (kind == 2u) {
            w0 = 32768u;
        } else if (kind == 3u) {
            w0 = 0;
        }
        if (kind == 4u) {
            fv = 0;
        } else if (kind == 5u) {
            fv = 32767u;
        }
        g_off0[k] = (uint32_t)((size_t)j0 * l->stride + (size_t)c0 * 3u) | (step0 ? TDC_FOV_STEP0 : 0u);
        g_off1[k] = (uint32_t)((size_t)j1 * l->stride + (size_t)c0 * 3u);
        g_wf[k] = w0 | fv << 16;
    }
}

static int run_both(const checkasm_kernel_t *kr, const fov_lp_t *l, uint32_t n, uint32_t run)
{
    memset(g_out_c, 0xA5, sizeof g_out_c);
    memset(g_out_v, 0xA5, sizeof g_out_v);
    const tdc_fov_tap2_args_t ac = {g_lp, l->bytes, g_off0, g_off1, g_wf, {g_out_c, g_out_c + n, g_out_c + 2u * n}};
    const tdc_fov_tap2_args_t av = {g_lp, l->bytes, g_off0, g_off1, g_wf, {g_out_v, g_out_v + n, g_out_v + 2u * n}};
    CHECKASM_REF(tdc_fov_tap2_row_fn, kr)(&ac, n);
    CHECKASM_OPT(tdc_fov_tap2_row_fn, kr)(&av, n);
    const long k = checkasm_diff_u16(g_out_c, g_out_v, sizeof g_out_c / sizeof g_out_c[0]);
    if (k < 0) {
        return 0;
    }
    const uint32_t px = (uint32_t)k % (n ? n : 1u);
    return checkasm_fail("run %u n %u lp %ux%u stride %u: plane %ld pixel %u: %u vs %u (off0 %08x off1 %u wf %08x)%s",
                         (unsigned)run, (unsigned)n, (unsigned)l->lp_w, (unsigned)l->lp_h, (unsigned)l->stride,
                         k / (long)(n ? n : 1u), (unsigned)px, g_out_c[k], g_out_v[k], (unsigned)g_off0[px],
                         (unsigned)g_off1[px], (unsigned)g_wf[px], (uint32_t)k >= 3u * n ? " (past the planes)" : "");
}

static void check_tap2(const checkasm_kernel_t *kr)
{
    const uint32_t runs = checkasm_runs(300u);
    fov_lp_t l = make_lp();
    for (uint32_t run = 0; run < runs && !checkasm_failed(); run++) {
        if (run % 50u == 49u) {
            l = make_lp();
        }
        const uint32_t n = run < 40u ? run + 1u : 1u + checkasm_rand_below(FMAXN);
        make_desc(&l, n);
        if (run_both(kr, &l, n, run)) {
            return;
        }
    }
}

static void bench_tap2(const checkasm_kernel_t *kr)
{
    fov_lp_t l = make_lp();
    l.lp_w = FLPW;
    l.lp_h = FLPH;
    l.stride = FLPW * 3u;
    l.bytes = (size_t)FLPH * l.stride;
    /* a display row through the periphery: neighbouring pixels on neighbouring samples */
    const uint32_t n = 1080u;
    for (uint32_t k = 0; k < n; k++) {
        const uint32_t c0 = 300u + k / 4u, j0 = 20u + k / 16u;
        g_off0[k] = (uint32_t)(j0 * l.stride + c0 * 3u);
        g_off1[k] = (uint32_t)((j0 + 1u) * l.stride + c0 * 3u);
        g_wf[k] = checkasm_rand_below(32769u) | checkasm_rand_below(32768u) << 16;
    }
    const tdc_fov_tap2_args_t a = {g_lp, l.bytes, g_off0, g_off1, g_wf, {g_out_c, g_out_c + n, g_out_c + 2u * n}};
    CHECKASM_BENCH(kr, "1080 px", n, tdc_fov_tap2_row_fn, f, f(&a, n));
}

static const checkasm_family_t fov_tap2 = {"fov_tap2", check_tap2, bench_tap2};


/* ---- fov_geom ---- */
#define GMAXW 600u
static uint64_t g_stage_mem[TDC_FOV_MEM_BYTES(GMAXW, GMAXW, 0) / 8u + 1u] CHECKASM_BIG;
static uint32_t g_go[2][4][GMAXW] CHECKASM_BIG; /* off0, off1, wf, ij of the C and the optimised row */
static uint16_t g_ggen[2][3u * GMAXW] CHECKASM_BIG, g_gbw[2][GMAXW] CHECKASM_BIG; /* gen (3 per pixel), b */

typedef struct {
    tdc_fov_t st;
    tdc_fov_params_t p;
    fov_lp_t l;
} geom_case_t;

static int geom_case(geom_case_t *c, int bench)
{
    const uint32_t W = bench ? 600u : 16u + checkasm_rand_below(GMAXW - 15u);
    const uint32_t H = bench ? 600u : 16u + checkasm_rand_below(GMAXW - 15u);
    const tdc_fov_config_t cfg = {(uint16_t)W, (uint16_t)H, 0};
    if (tdc_fov_init(&c->st, &cfg, g_stage_mem, sizeof g_stage_mem) != TDC_OK) {
        return checkasm_fail("fov_geom: stage %ux%u does not fit", (unsigned)W, (unsigned)H);
    }
    tdc_fov_params_t *p = &c->p;
    memset(p, 0, sizeof *p);
    const uint32_t where = checkasm_rand_below(8u);
    const int32_t gx = (int32_t)(where == 0u ? 0u : where == 1u ? W * 256u : checkasm_rand_below(W * 256u));
    const int32_t gy = (int32_t)(where == 2u ? H * 256u : checkasm_rand_below(H * 256u));
    p->gaze_x_q8 = bench ? (int32_t)(W * 115u) : (where == 3u ? gx - (int32_t)(W * 200u) : gx); /* 3: outside */
    p->gaze_y_q8 = bench ? (int32_t)(H * 128u) : gy;
    p->alpha_q8 = (uint16_t)(bench ? 1024u : 256u + checkasm_rand_below(7u * 256u + 1u));
    const uint32_t dk = checkasm_rand_below(6u);
    p->disk_q15 = (uint16_t)(bench ? 4077u : dk == 0u ? 0u : dk == 1u ? 32768u : checkasm_rand_below(16384u));
    p->lp_w = tdc_fov_lp_size(18187, (uint16_t)W);
    p->lp_h = tdc_fov_lp_size(18187, (uint16_t)H);
    c->l.lp_w = p->lp_w;
    c->l.lp_h = p->lp_h;
    c->l.stride = (size_t)p->lp_w * 3u + checkasm_rand_below(8u);
    c->l.bytes = (size_t)(p->lp_h - 1u) * c->l.stride + (size_t)p->lp_w * 3u;
    for (size_t k = 0; k < c->l.bytes; k++) {
        g_lp[k] = (uint8_t)checkasm_rand();
    }
    return 0;
}

static void geom_bufs(tdc_fov_geom_args_t *a, unsigned side)
{
    a->off0 = g_go[side][0];
    a->off1 = g_go[side][1];
    a->wf = g_go[side][2];
    a->ij = g_go[side][3];
    a->gen = g_ggen[side];
    a->b = g_gbw[side];
}

static void check_geom(const checkasm_kernel_t *kr)
{
    const uint32_t runs = checkasm_runs(400u);
    geom_case_t c;
    for (uint32_t run = 0; run < runs && !checkasm_failed(); run++) {
        if (run % 20u == 0u && geom_case(&c, 0)) {
            return;
        }
        const int32_t W = c.st.cfg.width, y = (int32_t)checkasm_rand_below(c.st.cfg.height);
        tdc_fov_geom_t g;
        tdc_fov_geom_args_t a;
        if (tdc_fov_geom_args(&c.st, &c.p, g_lp, c.l.stride, y, &g, &a) != TDC_OK) {
            checkasm_fail("fov_geom run %u: parameters refused", (unsigned)run);
            return;
        }
        a.taa = (int)checkasm_rand_below(2u);
        const int32_t x0 = run % 4u ? (int32_t)checkasm_rand_below((uint32_t)W) : 0;
        const int32_t x1 = run % 4u ? x0 + (int32_t)checkasm_rand_below((uint32_t)(W - x0) + 1u) : W;
        memset(g_go, 0xA5, sizeof g_go);
        memset(g_ggen, 0xA5, sizeof g_ggen);
        memset(g_gbw, 0xA5, sizeof g_gbw);
        geom_bufs(&a, 0);
        CHECKASM_REF(tdc_fov_geom_row_fn, kr)(&a, x0, x1);
        geom_bufs(&a, 1);
        CHECKASM_OPT(tdc_fov_geom_row_fn, kr)(&a, x0, x1);
        static const char *const names[] = {"off0", "off1", "wf", "ij", "gen", "gen", "gen", "b"};
        for (unsigned o = 0; o < 8u; o++) {
            const int u32 = o < 4u;
            for (int32_t x = x0; x < x1; x++) {
                const uint32_t vc = u32 ? g_go[0][o][x] : o < 7u ? g_ggen[0][3 * x + (int32_t)(o - 4u)] : g_gbw[0][x];
                const uint32_t vo = u32 ? g_go[1][o][x] : o < 7u ? g_ggen[1][3 * x + (int32_t)(o - 4u)] : g_gbw[1][x];
                if (vc != vo) {
                    checkasm_fail("fov_geom run %u: %ux%u gaze (%d, %d)/256 alpha %u/256 disk %u/32768 taa %d row %d "
                                  "[%d, %d): %s[%d] %08x vs %08x",
                                  (unsigned)run, (unsigned)W, (unsigned)c.st.cfg.height, (int)c.p.gaze_x_q8,
                                  (int)c.p.gaze_y_q8, (unsigned)c.p.alpha_q8, (unsigned)c.p.disk_q15, a.taa, (int)y,
                                  (int)x0, (int)x1, names[o], (int)x, (unsigned)vc, (unsigned)vo);
                    return;
                }
            }
        }
    }
}

static void bench_geom(const checkasm_kernel_t *kr)
{
    geom_case_t c;
    if (geom_case(&c, 1)) {
        return;
    }
    tdc_fov_geom_t g;
    tdc_fov_geom_args_t a;
    if (tdc_fov_geom_args(&c.st, &c.p, g_lp, c.l.stride, 120, &g, &a) != TDC_OK) {
        return;
    }
    geom_bufs(&a, 0);
    /* a 600 px row 180 px above the gaze of a 600 x 600 display (alpha 4, 12.4 % disk) */
    CHECKASM_BENCH(kr, "600 px", 600u, tdc_fov_geom_row_fn, f, f(&a, 0, 600));
}

static const checkasm_family_t fov_geom = {"fov_geom", check_geom, bench_geom};

static const checkasm_kernel_t g_fov_kernels[] = {
    CHECKASM_KERNEL(&fov_tap2, "avx2", tdc_fov_avx2_available, tdc_fov_tap2_row_c, tdc_fov_tap2_row_avx2),
    CHECKASM_KERNEL(&fov_tap2, "mve", checkasm_mve_available, tdc_fov_tap2_row_c, tdc_fov_tap2_row_mve),
    CHECKASM_KERNEL(&fov_geom, "avx2", tdc_fov_avx2_available, tdc_fov_geom_row_c, tdc_fov_geom_row_avx2),
};

const checkasm_module_t checkasm_fov = {"fov", g_fov_kernels, sizeof g_fov_kernels / sizeof g_fov_kernels[0]};
