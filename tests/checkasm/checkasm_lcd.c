/*
 * checkasm_lcd.c - checkasm module of the LCD stage: the stateful inverse's
 * hot run (tdc_lcd_kernels.h), optimised versions against the portable C
 * run, bit for bit: drive and state rows (nothing written outside the
 * run's steps) and the steps it stops at.
 *
 * Inputs: a dense lookup with drives in 1..254 except a share of 0 / 255
 * entries, random
 * wanted codes and states with runs of the extremes (black, white), every
 * width 1..64 pixels and then random ones, and every start pixel of the
 * first rows.
 */
#include <string.h>

#include "checkasm.h"
#include "tdc_lcd_kernels.h"

#define LMAXW 1440u /* pixels per row */

/* padding after the lookup (tdc_lcd_kernels.h: the AVX2 gathers read 2 bytes past an entry) */
static uint16_t g_lut_pad[3u * 65536u + 8u] CHECKASM_BIG;
static uint8_t g_in[3u * LMAXW] CHECKASM_BIG, g_st0[3u * LMAXW] CHECKASM_BIG;
static uint8_t g_out_c[3u * LMAXW] CHECKASM_BIG, g_out_v[3u * LMAXW] CHECKASM_BIG;
static uint8_t g_st_c[3u * LMAXW] CHECKASM_BIG, g_st_v[3u * LMAXW] CHECKASM_BIG;

#define LUT (g_lut_pad)

/* edge_share: 1 in edge_share lookup entries is a drive of 0 or 255. */
static void make_tables(uint32_t edge_share)
{
    for (uint32_t k = 0; k < 3u * 65536u + 8u; k++) {
        uint32_t d = 1u + checkasm_rand_below(254u);
        if (edge_share && checkasm_rand_below(edge_share) == 0u) {
            d = checkasm_rand_below(2u) ? 255u : 0u;
        }
        g_lut_pad[k] = (uint16_t)(d | checkasm_rand_below(256u) << 8);
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
    }
}

/* The stage's loop: run, leave the step it stops at (the stage's full loop
 * takes it) and run on; both sides must stop at the same steps. */
static int run_both(const checkasm_kernel_t *kr, uint32_t w3, uint32_t start, uint32_t run)
{
    memcpy(g_st_c, g_st0, w3);
    memcpy(g_st_v, g_st0, w3);
    memset(g_out_c, 0xA5, sizeof g_out_c);
    memset(g_out_v, 0xA5, sizeof g_out_v);
    const unsigned wd = (unsigned)(w3 / 3u);
    for (uint32_t i = start; i < w3; i += TDC_LCD_RUN8_STEP) {
        const uint32_t a = CHECKASM_REF(tdc_lcd_st_run8_fn, kr)(LUT, g_in, g_out_c, g_st_c, i, w3);
        const uint32_t b = CHECKASM_OPT(tdc_lcd_st_run8_fn, kr)(LUT, g_in, g_out_v, g_st_v, i, w3);
        if (a != b) {
            return checkasm_fail("run %u width %u from %u: stops at %u vs %u", (unsigned)run, wd, (unsigned)i,
                                 (unsigned)a, (unsigned)b);
        }
        i = a;
    }
    long k = checkasm_diff_u8(g_out_c, g_out_v, sizeof g_out_c);
    if (k < 0) {
        k = checkasm_diff_u8(g_st_c, g_st_v, w3);
        if (k >= 0) {
            return checkasm_fail("run %u width %u: state[%ld] %u vs %u (wanted %u, old state %u)", (unsigned)run, wd, k,
                                 g_st_c[k], g_st_v[k], g_in[k], g_st0[k]);
        }
        return 0;
    }
    return checkasm_fail("run %u width %u start %u: out[%ld] %u vs %u (wanted %u, state %u)%s", (unsigned)run, wd,
                         (unsigned)start, k, g_out_c[k], g_out_v[k], (uint32_t)k < w3 ? g_in[k] : 0u,
                         (uint32_t)k < w3 ? g_st0[k] : 0u,
                         (uint32_t)k >= w3     ? " (past the row)"
                         : (uint32_t)k < start ? " (before the start)"
                                               : "");
}

static void check_run8(const checkasm_kernel_t *kr)
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
        const uint32_t start = run % 100u < 64u ? 3u * checkasm_rand_below(w) : 0u;
        if (run_both(kr, 3u * w, start, run)) {
            return;
        }
    }
}

static void bench_run8(const checkasm_kernel_t *kr)
{
    make_tables(4096u);
    const uint32_t w3 = 3u * LMAXW;
    for (uint32_t s = 0; s < w3; s++) {
        g_in[s] = (uint8_t)(1u + checkasm_rand_below(254u));
        g_st0[s] = (uint8_t)checkasm_rand_below(256u);
    }
    CHECKASM_BENCH(kr, "1440 px, 1/4096 edges", LMAXW, tdc_lcd_st_run8_fn, f, {
        memcpy(g_st_c, g_st0, w3);
        for (uint32_t i = 0; i < w3; i += TDC_LCD_RUN8_STEP) {
            i = f(LUT, g_in, g_out_c, g_st_c, i, w3);
        }
    });
}

static const checkasm_family_t lcd_st_run8 = {"lcd_st_run8", check_run8, bench_run8};

static const checkasm_kernel_t g_lcd_kernels[] = {
    CHECKASM_KERNEL(&lcd_st_run8, "avx2", tdc_lcd_avx2_available, tdc_lcd_st_run8_c, tdc_lcd_st_run8_avx2),
};

const checkasm_module_t checkasm_lcd = {"lcd", g_lcd_kernels, sizeof g_lcd_kernels / sizeof g_lcd_kernels[0]};
