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
 */
#include <string.h>

#include "checkasm.h"
#include "tdc_fov_kernels.h"

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

/* Helium boards (TDC_TRM_MVE, their start-up enables the MVE unit): always
 * runnable there; elsewhere the MVE name is the C kernel and is skipped. */
static int mve_available(void)
{
#if defined(TDC_TRM_MVE)
    return 1;
#else
    return 0;
#endif
}

static const checkasm_kernel_t g_fov_kernels[] = {
    CHECKASM_KERNEL(&fov_tap2, "avx2", tdc_fov_avx2_available, tdc_fov_tap2_row_c, tdc_fov_tap2_row_avx2),
    CHECKASM_KERNEL(&fov_tap2, "mve", mve_available, tdc_fov_tap2_row_c, tdc_fov_tap2_row_mve),
};

const checkasm_module_t checkasm_fov = {"fov", g_fov_kernels, sizeof g_fov_kernels / sizeof g_fov_kernels[0]};
