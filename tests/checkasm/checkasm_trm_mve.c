/*
 * checkasm_trm_mve.c - the Helium (MVE) TRM row kernels (firmware/
 * tdc_trm_mve.c) against the portable C kernels, bit for bit, on the
 * Cortex-M55 under QEMU mps3-an547 (dav1d checkasm style: same inputs into
 * both, outputs and counters compared; runs in `make test` through
 * tests/arm/run_checkasm_qemu.sh).
 *
 * Inputs: every width 1..64 (vector body plus the C tail), random rows and
 * rows of extremes: U rows at 0 and at the largest code Q22 (65280 << 14),
 * alternating (largest lerp steps), fractions 0 and 2^14 - 1, codes 0 and
 * 255, residuals 0 and +-2^24, s = 0, 10 and 2^32 - 1, U(D(I)) equal to
 * U(i) (static pixels: the weight skipped) and half a code apart (the
 * motion test's shrink), both panels' gamma tables.
 */
#include <stdint.h>
#include <string.h>

#include "board.h"
#include "tdc_panels.h"
#include "tdc_semihost.h"
#include "tdc_trm.h"
#include "tdc_trm_kernels.h"

#define MAXW 64u
#define RW_MAX (MAXW / 2u + 1u)

static uint64_t g_arena[TDC_TRM_MEM_BYTES(MAXW, 8, 1, 2) / 8u + 1u];
static uint32_t g_ua[(RW_MAX + 1u) * 3u], g_ub[(RW_MAX + 1u) * 3u];
static uint16_t g_ux[2u * MAXW];
static uint8_t g_src[3u * MAXW], g_dc[3u * MAXW], g_dm[3u * MAXW];
static tdc_res_t g_rc[3u * MAXW], g_rm[3u * MAXW], g_rho[3u * MAXW];

static uint32_t g_rng = 0x12345678u;
static uint32_t rnd(void)
{
    g_rng ^= g_rng << 13;
    g_rng ^= g_rng >> 17;
    g_rng ^= g_rng << 5;
    return g_rng;
}

static void put_u32(int fd, uint32_t v)
{
    char d[11], s[12];
    int n = 0, k = 0;
    do {
        d[n++] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v);
    while (n) {
        s[k++] = d[--n];
    }
    s[k] = 0;
    tdc_semihost_puts(fd, s);
}

static int fail(const char *what, uint32_t width, uint32_t trial)
{
    tdc_semihost_puts(2, "checkasm-mve: MISMATCH ");
    tdc_semihost_puts(2, what);
    tdc_semihost_puts(2, " width ");
    put_u32(2, width);
    tdc_semihost_puts(2, " trial ");
    put_u32(2, trial);
    tdc_semihost_puts(2, "\n");
    return 1;
}

/* Code Q22 of a vertically interpolated row: < 65281 << 14. */
static uint32_t urow_value(uint32_t mode, uint32_t i)
{
    const uint32_t top = 65280u << 14;
    switch (mode) {
    case 0: return rnd() % (top + 1u);
    case 1: return 0u;
    case 2: return top;
    case 3: return (i / 3u) & 1u ? top : 0u;
    default: return (rnd() & 0xff00u) << 14; /* whole codes */
    }
}

int main(void)
{
    const tdc_panel_t *panels[2] = {&tdc_panel_htc_vive, &tdc_panel_rift_cv1};
    static const uint32_t s_vals[3] = {0u, 2560u, 0xffffffffu};
    uint32_t rows_full = 0, rows_red = 0;
    for (uint32_t p = 0; p < 2u; p++) {
        tdc_trm_config_t cfg;
        tdc_trm_default_config(&cfg, (uint16_t)MAXW, 8, 90);
        tdc_trm_t trm;
        if (tdc_trm_init(&trm, &cfg, panels[p], g_arena, sizeof g_arena) != TDC_OK) {
            tdc_semihost_puts(2, "checkasm-mve: TRM init failed\n");
            return 1;
        }
        tdc_trm_rowctx_t k;
        memset(&k, 0, sizeof k);
        for (int c = 0; c < 3; c++) {
            k.dec[c] = panels[p]->gamma[c].decode;
            k.thr[c] = panels[p]->gamma[c].enc_thresh;
            k.idx[c] = panels[p]->gamma[c].enc_index;
        }
        k.ux = g_ux;
        k.wexp = trm.wexp;
        for (uint32_t width = 1; width <= MAXW; width++) {
            const uint32_t rw = width / 2u + 1u;
            k.width = width;
            for (uint32_t trial = 0; trial < 24u; trial++) {
                const uint32_t mode = trial % 5u;
                k.s_q8 = s_vals[trial % 3u];
                for (uint32_t x = 0; x < width; x++) {
                    g_ux[2u * x] = (uint16_t)(rnd() % rw);
                    g_ux[2u * x + 1u] = (uint16_t)(trial % 7u == 0u ? 0u : trial % 7u == 1u ? 16383u : rnd() & 16383u);
                }
                for (uint32_t i = 0; i < (rw + 1u) * 3u; i++) {
                    g_ua[i] = urow_value(mode, i);
                    const uint32_t r = rnd() % 4u;
                    /* U(i) equal to U(D(I)), half a code off, or unrelated */
                    g_ub[i] = r == 0u   ? g_ua[i]
                              : r == 1u ? (g_ua[i] >= (1u << 13) ? g_ua[i] - (1u << 13) : g_ua[i] + (1u << 13))
                                        : urow_value(mode, i);
                }
                for (uint32_t i = 0; i < 3u * width; i++) {
                    const uint32_t r = rnd();
                    g_src[i] = (uint8_t)(mode == 1u ? 0u : mode == 2u ? 255u : r);
                    const uint32_t q = (r >> 8) % 6u;
                    g_rho[i] = q == 0u   ? 0
                               : q == 1u ? TDC_LIN_ONE
                               : q == 2u ? -TDC_LIN_ONE
                                         : (int32_t)((r >> 3) % (2u * TDC_LIN_ONE + 1u)) - TDC_LIN_ONE;
                }
                /* full row */
                memset(g_dc, 0xa5, sizeof g_dc);
                memset(g_dm, 0xa5, sizeof g_dm);
                memset(g_rc, 0x5a, sizeof g_rc);
                memset(g_rm, 0x5a, sizeof g_rm);
                tdc_trm_full_counts_t nc = {0, 0}, nm = {0, 0};
                tdc_trm_full_row_c(&k, g_ua, g_src, g_dc, g_rc, &nc);
                tdc_trm_full_row_mve(&k, g_ua, g_src, g_dm, g_rm, &nm);
                if (memcmp(g_dc, g_dm, sizeof g_dc) || memcmp(g_rc, g_rm, sizeof g_rc) || nc.hi != nm.hi ||
                    nc.lo != nm.lo) {
                    return fail("full row", width, trial);
                }
                rows_full++;
                /* reduced row */
                memset(g_dc, 0xa5, sizeof g_dc);
                memset(g_dm, 0xa5, sizeof g_dm);
                tdc_trm_reduced_counts_t rc = {0, 0, 0}, rm = {0, 0, 0};
                tdc_trm_reduced_row_c(&k, g_ua, g_ub, g_rho, g_dc, &rc);
                tdc_trm_reduced_row_mve(&k, g_ua, g_ub, g_rho, g_dm, &rm);
                if (memcmp(g_dc, g_dm, sizeof g_dc) || rc.computed != rm.computed || rc.skipped != rm.skipped ||
                    rc.no_res != rm.no_res) {
                    return fail("reduced row", width, trial);
                }
                rows_red++;
            }
        }
    }
    /* D passes: the stage's own kernels (every width 1..64, both ratios'
     * tables), random and extreme rows */
    static uint8_t drow[3u * MAXW];
    static uint16_t dc[3u * MAXW], dm[3u * MAXW], vrows[TDC_TRM_MAX_TAPS][3u * MAXW];
    uint32_t rows_d = 0;
    for (uint32_t width = 1; width <= MAXW; width++) {
        for (uint32_t r = 0; r < 2u; r++) {
            tdc_trm_config_t cfg;
            tdc_trm_default_config(&cfg, (uint16_t)width, 8, 90);
            cfg.r_num = r ? 2 : 1;
            cfg.r_den = r ? 5 : 2;
            tdc_trm_t trm;
            if (tdc_trm_init(&trm, &cfg, &tdc_panel_htc_vive, g_arena, sizeof g_arena) != TDC_OK) {
                return fail("D init", width, r);
            }
            for (uint32_t trial = 0; trial < 6u; trial++) {
                for (uint32_t i = 0; i < 3u * width; i++) {
                    drow[i] = (uint8_t)(trial == 0u ? 0u : trial == 1u ? 255u : rnd());
                }
                memset(dc, 0x5a, sizeof dc);
                memset(dm, 0x5a, sizeof dm);
                tdc_trm_dhoriz_c(drow, width, trm.dx_first, trm.dx_w, trm.dtaps, trm.rw, dc);
                tdc_trm_dhoriz_mve(drow, width, trm.dx_first, trm.dx_w, trm.dtaps, trm.rw, dm);
                if (memcmp(dc, dm, sizeof dc)) {
                    return fail("D horizontal", width, trial);
                }
                const uint16_t *rp[TDC_TRM_MAX_TAPS];
                for (uint32_t t = 0; t < trm.dtaps; t++) {
                    for (uint32_t i = 0; i < 3u * width; i++) {
                        vrows[t][i] = (uint16_t)(trial == 0u ? 0u : trial == 1u ? 65280u : rnd() % 65281u);
                    }
                    rp[t] = vrows[t];
                }
                memset(dc, 0x5a, sizeof dc);
                memset(dm, 0x5a, sizeof dm);
                tdc_trm_dvert_c(rp, &trm.dy_w[(trial % trm.rh) * trm.dtaps], trm.dtaps, 3u * width, dc);
                tdc_trm_dvert_mve(rp, &trm.dy_w[(trial % trm.rh) * trm.dtaps], trm.dtaps, 3u * width, dm);
                if (memcmp(dc, dm, sizeof dc)) {
                    return fail("D vertical", width, trial);
                }
                rows_d++;
            }
        }
    }
    tdc_semihost_puts(1, "checkasm-mve: ");
    put_u32(1, rows_d);
    tdc_semihost_puts(1, " D horizontal and vertical rows bit-exact with C\n");
    tdc_semihost_puts(1, "checkasm-mve: ");
    put_u32(1, rows_full);
    tdc_semihost_puts(1, " full rows and ");
    put_u32(1, rows_red);
    tdc_semihost_puts(1, " reduced rows bit-exact with C (widths 1..64, 2 panels)\n");
    return 0;
}
