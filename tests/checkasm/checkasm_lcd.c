/*
 * checkasm_lcd.c - checkasm module of the LCD stage: the stateful inverse's
 * row (tdc_lcd_kernels.h), optimised versions against the portable C row,
 * bit for bit: drive and state rows (nothing written past the row), the
 * residual row, the three counters and the return value.
 *
 * Inputs: consistent tables as tdc_lcd_st_build makes them (a wanted code
 * above whi / below wlo of its state gets drive 255 / 0; in-reach entries
 * have drives 1..254 except a share of 0 / 255 that must NOT count as a
 * miss), limit lights and decode in [0, 2^24] with runs of equal values (a
 * miss of exactly 0), random wanted codes and states with runs of black and
 * white, residuals near +-2^24 and near +-2^31 (saturation, clamp), with and
 * without a residual row, every width 1..64 pixels and then random ones.
 */
#include <string.h>

#include "checkasm.h"
#include "tdc_lcd_kernels.h"

#define LMAXW 1440u /* pixels per row */

/* tables with the readable slack of tdc_lcd_kernels.h after each */
static uint16_t g_lut[3u * 65536u + 8u] CHECKASM_BIG;
static uint8_t g_whi[3u * 256u + 8u], g_wlo[3u * 256u + 8u];
static int32_t g_lhi[3u * 256u], g_llo[3u * 256u], g_dec[3u * 256u];
static const tdc_lcd_st_tabs_t g_tabs = {g_lut, g_whi, g_wlo, g_lhi, g_llo, g_dec};

static uint8_t g_in[3u * LMAXW + 64u] CHECKASM_BIG, g_st0[3u * LMAXW] CHECKASM_BIG;
static uint8_t g_out_c[3u * LMAXW + 64u] CHECKASM_BIG, g_out_v[3u * LMAXW + 64u] CHECKASM_BIG;
static uint8_t g_st_c[3u * LMAXW + 64u] CHECKASM_BIG, g_st_v[3u * LMAXW + 64u] CHECKASM_BIG;
static int32_t g_res0[3u * LMAXW] CHECKASM_BIG, g_res_c[3u * LMAXW + 16u] CHECKASM_BIG,
    g_res_v[3u * LMAXW + 16u] CHECKASM_BIG;

static int32_t rand_light(void)
{
    /* [0, 2^24], a few coarse values so that want == limit (miss 0) happens */
    return checkasm_rand_below(8u) == 0u ? (int32_t)(checkasm_rand_below(5u) << 22)
                                         : (int32_t)checkasm_rand_below((1u << 24) + 1u);
}

/* edge_share: 1 in edge_share in-reach entries is a drive of 0 or 255 anyway. */
static void make_tables(uint32_t edge_share)
{
    for (uint32_t k = 0; k < 3u * 256u; k++) {
        /* reach: wide, narrow, or everything in reach */
        const uint32_t kind = checkasm_rand_below(4u);
        uint32_t lo = kind == 0u ? 0u : checkasm_rand_below(128u), hi = kind == 0u ? 255u : 128u + checkasm_rand_below(128u);
        g_wlo[k] = (uint8_t)lo;
        g_whi[k] = (uint8_t)hi;
        g_lhi[k] = rand_light();
        g_llo[k] = rand_light();
        g_dec[k] = rand_light();
        for (uint32_t w = 0; w < 256u; w++) {
            uint32_t d = 1u + checkasm_rand_below(254u);
            if (edge_share && checkasm_rand_below(edge_share) == 0u) {
                d = checkasm_rand_below(2u) ? 255u : 0u;
            }
            d = w > hi ? 255u : (w < lo ? 0u : d);
            g_lut[(k >> 8) * 65536u + ((k & 255u) << 8) + w] = (uint16_t)(d | checkasm_rand_below(256u) << 8);
        }
    }
    for (uint32_t k = 3u * 65536u; k < 3u * 65536u + 8u; k++) {
        g_lut[k] = (uint16_t)checkasm_rand();
    }
}

static int32_t rand_res(void)
{
    switch (checkasm_rand_below(6u)) {
    case 0: return (int32_t)(checkasm_rand_below(2u) ? (1u << 24) - checkasm_rand_below(64u) : 0u - (1u << 24));
    case 1: return (int32_t)(checkasm_rand_below(2u) ? 0x7fffffffu - checkasm_rand_below(1u << 25) : 0x80000000u + checkasm_rand_below(1u << 25));
    default: return (int32_t)checkasm_rand_below(1u << 25) - (1 << 24);
    }
}

static void make_row(uint32_t w3)
{
    const uint32_t style = checkasm_rand_below(4u);
    for (uint32_t s = 0; s < w3; s++) {
        uint32_t w = checkasm_rand_below(256u), q = checkasm_rand_below(256u);
        if (style == 1u && checkasm_rand_below(3u) == 0u) {
            w = checkasm_rand_below(2u) ? 255u : 0u; /* black and white */
        } else if (style == 2u) {
            q = w; /* settled */
        }
        g_in[s] = (uint8_t)w;
        g_st0[s] = (uint8_t)q;
        g_res0[s] = rand_res();
    }
}

static int run_both(const checkasm_kernel_t *kr, uint32_t w3, int with_res, uint32_t run)
{
    memcpy(g_st_c, g_st0, w3);
    memcpy(g_st_v, g_st0, w3);
    memset(g_out_c, 0xA5, sizeof g_out_c);
    memset(g_out_v, 0xA5, sizeof g_out_v);
    memset(g_st_c + w3, 0x5A, 64u);
    memset(g_st_v + w3, 0x5A, 64u);
    memcpy(g_res_c, g_res0, w3 * sizeof *g_res0);
    memcpy(g_res_v, g_res0, w3 * sizeof *g_res0);
    for (uint32_t k = w3; k < w3 + 16u; k++) {
        g_res_c[k] = g_res_v[k] = 0x12345678;
    }
    tdc_lcd_st_counts_t nc = {1, 2, 3}, nv = {1, 2, 3};
    const uint32_t a = CHECKASM_REF(tdc_lcd_st_row8_fn, kr)(&g_tabs, g_in, g_out_c, g_st_c, w3, with_res ? g_res_c : 0, &nc);
    const uint32_t b = CHECKASM_OPT(tdc_lcd_st_row8_fn, kr)(&g_tabs, g_in, g_out_v, g_st_v, w3, with_res ? g_res_v : 0, &nv);
    const unsigned wd = (unsigned)(w3 / 3u);
    if (a != b) {
        return checkasm_fail("run %u width %u: %u vs %u sub-pixels out of reach", (unsigned)run, wd, (unsigned)a,
                             (unsigned)b);
    }
    if (nc.clamped_low != nv.clamped_low || nc.clamped_high != nv.clamped_high ||
        nc.residual_added != nv.residual_added) {
        return checkasm_fail("run %u width %u: counters low/high/added %u/%u/%u vs %u/%u/%u", (unsigned)run, wd,
                             (unsigned)nc.clamped_low, (unsigned)nc.clamped_high, (unsigned)nc.residual_added,
                             (unsigned)nv.clamped_low, (unsigned)nv.clamped_high, (unsigned)nv.residual_added);
    }
    long k = checkasm_diff_u8(g_out_c, g_out_v, sizeof g_out_c);
    if (k >= 0) {
        return checkasm_fail("run %u width %u: out[%ld] %u vs %u (wanted %u, state %u)%s", (unsigned)run, wd, k,
                             g_out_c[k], g_out_v[k], (uint32_t)k < w3 ? g_in[k] : 0u, (uint32_t)k < w3 ? g_st0[k] : 0u,
                             (uint32_t)k >= w3 ? " (past the row)" : "");
    }
    k = checkasm_diff_u8(g_st_c, g_st_v, w3 + 64u);
    if (k >= 0) {
        return checkasm_fail("run %u width %u: state[%ld] %u vs %u (wanted %u, old state %u)", (unsigned)run, wd, k,
                             g_st_c[k], g_st_v[k], (uint32_t)k < w3 ? g_in[k] : 0u, (uint32_t)k < w3 ? g_st0[k] : 0u);
    }
    k = checkasm_diff_i32(g_res_c, g_res_v, w3 + 16u);
    if (k >= 0) {
        return checkasm_fail("run %u width %u: residual[%ld] %ld vs %ld (was %ld, wanted %u, state %u)", (unsigned)run,
                             wd, k, (long)g_res_c[k], (long)g_res_v[k], (uint32_t)k < w3 ? (long)g_res0[k] : 0L,
                             (uint32_t)k < w3 ? g_in[k] : 0u, (uint32_t)k < w3 ? g_st0[k] : 0u);
    }
    return 0;
}

static void check_row8(const checkasm_kernel_t *kr)
{
    static const uint32_t shares[] = {0u, 4096u, 64u, 8u};
    const uint32_t runs = checkasm_runs(400u);
    for (uint32_t run = 0; run < runs && !checkasm_failed(); run++) {
        if (run % 100u == 0u) {
            make_tables(shares[(run / 100u) % 4u]);
        }
        /* every width 1..64 pixels first (vector steps and every tail) */
        const uint32_t w = run % 100u < 64u ? run % 100u + 1u : 1u + checkasm_rand_below(LMAXW);
        make_row(3u * w);
        if (run_both(kr, 3u * w, (run & 3u) != 3u, run)) {
            return;
        }
    }
}

/* Two rows: drives 1..254 only (no reach test), and black-and-white moving
 * text's share of out-of-reach targets (1 in 6 sub-pixels, the report's
 * counters: ~17 %). */
static void bench_row8(const checkasm_kernel_t *kr)
{
    make_tables(4096u);
    const uint32_t w3 = 3u * LMAXW;
    static const char *const label[2] = {"1440 px, in reach", "1440 px, 1/6 out of reach"};
    for (int r = 0; r < 2; r++) {
        for (uint32_t s = 0; s < w3; s++) {
            const uint32_t k = (s % 3u) * 256u + checkasm_rand_below(256u);
            const uint32_t lo = g_wlo[k], hi = g_whi[k];
            uint32_t w = lo + checkasm_rand_below(hi - lo + 1u);
            if (r && checkasm_rand_below(6u) == 0u) {
                w = hi < 255u ? 255u : (lo > 0u ? 0u : w);
            }
            g_in[s] = (uint8_t)w;
            g_st0[s] = (uint8_t)(k & 255u);
            g_res0[s] = 0;
        }
        tdc_lcd_st_counts_t n = {0, 0, 0};
        CHECKASM_BENCH(kr, label[r], LMAXW, tdc_lcd_st_row8_fn, f, {
            memcpy(g_st_c, g_st0, w3);
            f(&g_tabs, g_in, g_out_c, g_st_c, w3, g_res_c, &n);
        });
    }
}

static const checkasm_family_t lcd_st_row8 = {"lcd_st_row8", check_row8, bench_row8};

static const checkasm_kernel_t g_lcd_kernels[] = {
    CHECKASM_KERNEL(&lcd_st_row8, "avx2", tdc_lcd_avx2_available, tdc_lcd_st_row8_c, tdc_lcd_st_row8_avx2),
};

const checkasm_module_t checkasm_lcd = {"lcd", g_lcd_kernels, sizeof g_lcd_kernels / sizeof g_lcd_kernels[0]};
