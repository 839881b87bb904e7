/*
 * test_lcd_state.c - the stateful LCD inverse (TDC_LCD_MODE_STATEFUL,
 * firmware/tdc_lcd_state.c): against a double-precision reference written
 * from the table convention (tdc_lcd.h), table validation at init (every
 * fault class), the first frame, the residual of unreachable light, and the
 * property it exists for: on the simulated panel (sim/lcd) its per-refresh
 * light error is far below the plain gamma inverse's on moving content.
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

#include "golden/tdc_content.h"
#include "lcd/tdc_lcdsim.h"
#include "tdc_gamma.h"
#include "tdc_lcd.h"
#include "tdc_panels.h"

#define W 48
#define H 32
#define N ((size_t)W * H * 3)

static _Alignas(8) uint8_t g_arena[TDC_LCD_MEM_BYTES(W, H) + 64];

static const tdc_lcd_rate_t *rate_of(const tdc_panel_t *pn, unsigned hz)
{
    for (unsigned r = 0; r < pn->lcd->nrates; r++) {
        if (pn->lcd->rate[r].rate_hz == hz) {
            return &pn->lcd->rate[r];
        }
    }
    return NULL;
}

/* Double bilinear interpolation of an n x n Q4 table at codes (a, b). */
static double interp_d(const uint16_t *t, int n, double a, double b)
{
    double x = a / 255.0 * (n - 1), y = b / 255.0 * (n - 1);
    int i = (int)x, j = (int)y;
    i = i > n - 2 ? n - 2 : i;
    j = j > n - 2 ? n - 2 : j;
    double fx = x - i, fy = y - j;
    const uint16_t *r0 = t + i * n + j, *r1 = r0 + n;
    double p = r0[0] + (r0[1] - r0[0]) * fy, q = r1[0] + (r1[1] - r1[0]) * fy;
    return (p + (q - p) * fx) / 16.0;
}

/* Fixed point against the reference on random and moving frames: the
 * reference keeps its state continuous (no rounding), so differences show
 * what the integer lookup and the 8-bit state cost. */
static void compare(const tdc_panel_t *pn, unsigned hz)
{
    const tdc_lcd_rate_t *rt = rate_of(pn, hz);
    assert_non_null(rt);
    const int sn = rt->st_n; /* pg279q 33, lcd-240 65 nodes (make lcd-profiles) */
    assert_true(sn == 17 || sn == 33 || sn == 65);
    tdc_lcd_config_t c = {W, H, (uint16_t)hz, TDC_LCD_MODE_STATEFUL, 8};
    tdc_lcd_t st;
    assert_int_equal(tdc_lcd_init(&st, &c, pn, g_arena, sizeof g_arena), TDC_OK);
    static uint8_t in[N], out[N];
    static double s_ref[N];
    long n = 0, within = 0;
    double maxd = 0.0, sum2 = 0.0;
    uint32_t rng = 12345u;
    for (int t = 0; t < 24; t++) {
        if (t < 12) {
            tdc_content_frame(t & 1 ? TDC_CONTENT_EDGE : TDC_CONTENT_GRADIENT, (uint32_t)(t * 5), 7, in, W, H, W * 3);
        } else {
            for (size_t i = 0; i < N; i++) {
                rng ^= rng << 13;
                rng ^= rng >> 17;
                rng ^= rng << 5;
                in[i] = (uint8_t)(rng >> 24);
            }
        }
        assert_int_equal(tdc_lcd_frame(&st, in, W * 3, out, W * 3, NULL), TDC_OK);
        for (size_t i = 0; i < N; i++) {
            const int ch = (int)(i % 3);
            if (t == 0) {
                assert_int_equal(out[i], in[i]); /* first frame: drive = wanted */
                s_ref[i] = in[i];
                continue;
            }
            double v = interp_d(rt->st_od[ch], sn, s_ref[i], in[i]);
            /* out of reach (more than half a code beyond the reach limit
             * from this state): the limit drive */
            const double x = s_ref[i] / 255.0 * (sn - 1);
            const int ri = x >= sn - 1 ? sn - 2 : (int)x;
            const double fr = x - ri;
            const uint16_t *rc = rt->st_reach[ch];
            const double lo = rc[ri] + (rc[ri + 1] - rc[ri]) * fr,
                         hi = rc[sn + ri] + (rc[sn + 1 + ri] - rc[sn + ri]) * fr;
            v = 16.0 * in[i] > hi + 8.0 ? 255.0 : (16.0 * in[i] < lo - 8.0 ? 0.0 : v);
            double d = fabs(out[i] - v);
            maxd = d > maxd ? d : maxd;
            sum2 += d * d;
            within += d <= 1.0;
            n++;
            s_ref[i] = interp_d(rt->st_next[ch], sn, s_ref[i], floor(v + 0.5));
        }
    }
    printf("stateful %s %u Hz: drive vs double reference over %ld sub-pixels: max %.3f codes, RMS %.3f, "
           "%.2f %% within 1 code\n",
           pn->name, hz, n, maxd, sqrt(sum2 / n), 100.0 * within / n);
    assert_true(within >= 0.99 * n);
    /* At a reach limit the drive jumps to 0 / 255; the reference's continuous
     * state can fall on the other side of it than the 8-bit state: one such
     * sub-pixel differs by the jump (measured max 9.8 codes at 144 Hz). */
    assert_true(maxd < 16.0);
}

static void test_vs_reference(void **state)
{
    (void)state;
    compare(&tdc_panel_pg279q, 144);
    compare(&tdc_panel_pg279q, 120);
    compare(&tdc_panel_lcd_240, 240);
}

/* A writable copy of one rate's tables to corrupt. */
static uint16_t g_od[3][33 * 33], g_nx[3][33 * 33], g_rc[3][66];
static struct tdc_lcd_profile g_prof;

static const tdc_panel_t *corruptible(tdc_panel_t *pn)
{
    *pn = tdc_panel_pg279q;
    const tdc_lcd_rate_t *src = rate_of(&tdc_panel_pg279q, 144);
    g_prof = *tdc_panel_pg279q.lcd;
    for (unsigned r = 0; r < g_prof.nrates; r++) {
        if (g_prof.rate[r].rate_hz == 144) {
            for (int ch = 0; ch < 3; ch++) {
                memcpy(g_od[ch], src->st_od[ch], sizeof g_od[ch]);
                memcpy(g_nx[ch], src->st_next[ch], sizeof g_nx[ch]);
                memcpy(g_rc[ch], src->st_reach[ch], sizeof g_rc[ch]);
                g_prof.rate[r].st_od[ch] = g_od[ch];
                g_prof.rate[r].st_next[ch] = g_nx[ch];
                g_prof.rate[r].st_reach[ch] = g_rc[ch];
            }
        }
    }
    pn->lcd = &g_prof;
    return pn;
}

static int init_fault(const tdc_panel_t *pn, tdc_status_t *rc)
{
    tdc_lcd_config_t c = {W, H, 144, TDC_LCD_MODE_STATEFUL, 8};
    tdc_lcd_t st;
    *rc = tdc_lcd_init(&st, &c, pn, g_arena, sizeof g_arena);
    return st.table_fault;
}

static void test_bad_tables(void **state)
{
    (void)state;
    tdc_panel_t pn;
    tdc_status_t rc;
    assert_int_equal(init_fault(corruptible(&pn), &rc), TDC_LCD_TABLE_OK);
    assert_int_equal(rc, TDC_OK);
    corruptible(&pn);
    g_od[1][5 * 33 + 7] = 255 * 16 + 1; /* above the largest code */
    assert_int_equal(init_fault(&pn, &rc), TDC_LCD_TABLE_RANGE);
    assert_int_equal(rc, TDC_ERR_PANEL);
    corruptible(&pn);
    g_nx[2][33 * 33 - 1] = 60000;
    assert_int_equal(init_fault(&pn, &rc), TDC_LCD_TABLE_RANGE);
    corruptible(&pn);
    g_od[0][10 * 33 + 20] = (uint16_t)(g_od[0][10 * 33 + 19] - 32); /* drive falls as wanted light rises */
    assert_int_equal(init_fault(&pn, &rc), TDC_LCD_TABLE_MONOTONE);
    assert_int_equal(rc, TDC_ERR_PANEL);
    corruptible(&pn);
    g_rc[1][3] = (uint16_t)(g_rc[1][33 + 3] + 1); /* lo above hi */
    assert_int_equal(init_fault(&pn, &rc), TDC_LCD_TABLE_REACH);
    corruptible(&pn);
    g_rc[0][33 + 20] = 100; /* a settled bright state cannot hold itself */
    assert_int_equal(init_fault(&pn, &rc), TDC_LCD_TABLE_REACH);
    corruptible(&pn);
    for (unsigned r = 0; r < g_prof.nrates; r++) {
        if (g_prof.rate[r].rate_hz == 144) {
            g_prof.rate[r].st_next[2] = NULL;
        }
    }
    assert_int_equal(init_fault(&pn, &rc), TDC_LCD_TABLE_MISSING);
    corruptible(&pn);
    for (unsigned r = 0; r < g_prof.nrates; r++) {
        g_prof.rate[r].st_n = 0; /* a profile fitted without transitions */
    }
    assert_int_equal(init_fault(&pn, &rc), TDC_LCD_TABLE_MISSING);
    assert_int_equal(rc, TDC_ERR_PANEL);
}

/* From black, full white is out of reach in one 144 Hz refresh: drive 255,
 * the missing light (wanted - the reach limit from state 0) goes to rho. */
static void test_residual(void **state)
{
    (void)state;
    const tdc_panel_t *pn = &tdc_panel_pg279q;
    const tdc_lcd_rate_t *rt = rate_of(pn, 144);
    tdc_lcd_config_t c = {W, H, 144, TDC_LCD_MODE_STATEFUL, 8};
    tdc_lcd_t st;
    assert_int_equal(tdc_lcd_init(&st, &c, pn, g_arena, sizeof g_arena), TDC_OK);
    static uint8_t in[N], out[N];
    static tdc_res_t res[N];
    memset(in, 0, sizeof in);
    assert_int_equal(tdc_lcd_frame(&st, in, W * 3, out, W * 3, res), TDC_OK);
    memset(in, 255, sizeof in);
    for (size_t i = 0; i < N; i++) {
        res[i] = 1000;
    }
    assert_int_equal(tdc_lcd_frame(&st, in, W * 3, out, W * 3, res), TDC_OK);
    for (size_t i = 0; i < N; i++) {
        const int ch = (int)(i % 3);
        assert_int_equal(out[i], 255);
        const int32_t lhi = tdc_gamma_decode_gval(&pn->gamma[ch], (uint32_t)rt->st_reach[ch][33] << 4);
        assert_int_equal(res[i], 1000 + (int32_t)pn->gamma[ch].decode[255] - lhi);
        assert_true(res[i] > TDC_LIN_ONE / 10); /* a real shortfall, not rounding */
    }
    assert_int_equal(st.stats.clamped_high, N);
    assert_int_equal(st.stats.residual_added, N);
    /* Falling back to black from the state the tables say white reached
     * (~0.7 of white's code) is out of reach too: negative residual. */
    memset(in, 0, sizeof in);
    memset(res, 0, sizeof res);
    assert_int_equal(tdc_lcd_frame(&st, in, W * 3, out, W * 3, res), TDC_OK);
    for (size_t i = 0; i < N; i++) {
        assert_int_equal(out[i], 0);
        assert_true(res[i] < 0);
    }
}

/* Pair mode: what the first refresh of a pair cannot deliver goes to the
 * second (not to rho), and nothing is carried from a second refresh into
 * the next pair; at 6 bits of state the same holds through the packed path. */
static void test_pair_carry(void **state)
{
    (void)state;
    const tdc_panel_t *pn = &tdc_panel_pg279q;
    for (unsigned bits = 8; bits >= 6; bits -= 2) {
        tdc_lcd_config_t cp = {W, H, 144, TDC_LCD_MODE_STATEFUL_PAIR, (uint8_t)bits};
        tdc_lcd_config_t cs = {W, H, 144, TDC_LCD_MODE_STATEFUL, (uint8_t)bits};
        static _Alignas(8) uint8_t arena2[TDC_LCD_MEM_BYTES(W, H) + 64];
        tdc_lcd_t sp, ss;
        assert_int_equal(tdc_lcd_init(&sp, &cp, pn, g_arena, sizeof g_arena), TDC_OK);
        assert_int_equal(tdc_lcd_init(&ss, &cs, pn, arena2, sizeof arena2), TDC_OK);
        assert_int_equal(tdc_lcd_cfg_history_bytes(&cp), tdc_lcd_cfg_history_bytes(&cs) + N);
        static uint8_t in[N], op[N], os[N];
        static tdc_res_t rp[N], rs[N];
        /* frame 0 (no history, first of a pair): black; frame 1: black */
        memset(in, 0, sizeof in);
        for (int t = 0; t < 2; t++) {
            assert_int_equal(tdc_lcd_frame(&sp, in, W * 3, op, W * 3, rp), TDC_OK);
            assert_int_equal(tdc_lcd_frame(&ss, in, W * 3, os, W * 3, rs), TDC_OK);
        }
        /* frame 2 (first of a pair): white, out of reach from black */
        memset(in, 255, sizeof in);
        memset(rp, 0, sizeof rp);
        memset(rs, 0, sizeof rs);
        assert_int_equal(tdc_lcd_frame(&sp, in, W * 3, op, W * 3, rp), TDC_OK);
        assert_int_equal(tdc_lcd_frame(&ss, in, W * 3, os, W * 3, rs), TDC_OK);
        for (size_t i = 0; i < N; i++) {
            assert_int_equal(op[i], 255);
            assert_int_equal(rp[i], 0); /* owed to the second refresh, not to rho */
            assert_true(rs[i] > 0);     /* the per-refresh mode puts it into rho */
            assert_true(sp.st_debt[i] > 0);
        }
        /* frame 3 (second): mid grey; the pair mode drives brighter to pay */
        memset(in, 128, sizeof in);
        assert_int_equal(tdc_lcd_frame(&sp, in, W * 3, op, W * 3, rp), TDC_OK);
        assert_int_equal(tdc_lcd_frame(&ss, in, W * 3, os, W * 3, rs), TDC_OK);
        long brighter = 0;
        for (size_t i = 0; i < N; i++) {
            assert_true(op[i] >= os[i]);
            brighter += op[i] > os[i] + 8;
        }
        assert_true(brighter == (long)N);
        /* frame 4 (first of the next pair): same grey; nothing carried over */
        memset(rp, 0, sizeof rp);
        assert_int_equal(tdc_lcd_frame(&sp, in, W * 3, op, W * 3, rp), TDC_OK);
        for (size_t i = 0; i < N; i++) {
            assert_true(sp.st_debt[i] == 0 || op[i] == 0 || op[i] == 255);
        }
    }
}

/* Per-refresh light error on the simulated panel, moving content. */
/* small != 0: only sub-pixels whose wanted code changed by 1..32 codes
 * (transitions one refresh can complete); else all of them. */
static double sim_rms(const char *sim, const tdc_panel_t *pn, unsigned hz, tdc_lcd_mode_t mode, tdc_content_t ct,
                      int speed, int small)
{
    tdc_lcdsim_panel_t sp;
    char err[256];
    assert_int_equal(tdc_lcdsim_load(sim, &sp, err, sizeof err), 0);
    tdc_lcd_config_t c = {W, H, (uint16_t)hz, (uint8_t)mode, 8};
    tdc_lcd_t st;
    assert_int_equal(tdc_lcd_init(&st, &c, pn, g_arena, sizeof g_arena), TDC_OK);
    tdc_lcdsim_t s;
    assert_int_equal(tdc_lcdsim_init(&s, &sp, N), 0);
    static uint8_t in[N], out[N], prev[N];
    static double lum[N];
    double sum2 = 0.0;
    long n = 0;
    for (int t = 0; t < 16; t++) {
        memcpy(prev, in, N);
        tdc_content_frame(ct, (uint32_t)(t * speed), 7, in, W, H, W * 3);
        assert_int_equal(tdc_lcd_frame(&st, in, W * 3, out, W * 3, NULL), TDC_OK);
        if (t == 0) {
            tdc_lcdsim_settle(&s, out);
        }
        tdc_lcdsim_frame(&s, out, hz, lum);
        for (size_t i = 0; t >= 2 && i < N; i++) {
            const int dw = abs((int)in[i] - (int)prev[i]);
            if (small && (dw == 0 || dw > 32)) {
                continue;
            }
            double ref = sp.black + (1.0 - sp.black) * pow(in[i] / 255.0, sp.gamma[i % 3]);
            sum2 += (lum[i] - ref) * (lum[i] - ref);
            n++;
        }
    }
    tdc_lcdsim_free(&s);
    return sqrt(sum2 / n);
}

static void test_beats_gamma_on_the_panel(void **state)
{
    (void)state;
    static const struct {
        const char *sim;
        const tdc_panel_t *pn;
        unsigned hz;
    } p[] = {{"sim/lcd/panels/pg279q.lcdsim", &tdc_panel_pg279q, 144},
             {"sim/lcd/panels/lcd-240.lcdsim", &tdc_panel_lcd_240, 240}};
    for (int k = 0; k < 2; k++) {
        /* gradient at 1 px/frame: small steps (one refresh completes them) */
        double g = sim_rms(p[k].sim, p[k].pn, p[k].hz, TDC_LCD_MODE_GAMMA, TDC_CONTENT_GRADIENT, 1, 1);
        double s = sim_rms(p[k].sim, p[k].pn, p[k].hz, TDC_LCD_MODE_STATEFUL, TDC_CONTENT_GRADIENT, 1, 1);
        /* the edge: every sub-pixel, full swings partly out of reach in one refresh */
        double ge = sim_rms(p[k].sim, p[k].pn, p[k].hz, TDC_LCD_MODE_GAMMA, TDC_CONTENT_EDGE, 1, 0);
        double se = sim_rms(p[k].sim, p[k].pn, p[k].hz, TDC_LCD_MODE_STATEFUL, TDC_CONTENT_EDGE, 1, 0);
        printf("%s %u Hz per-refresh RMS light error: gradient small steps gamma %.4f %% stateful %.4f %% (%.2fx); "
               "edge 3 px/frame, all gamma %.4f %% stateful %.4f %% (%.2fx)\n",
               p[k].pn->name, p[k].hz, 100 * g, 100 * s, s / g, 100 * ge, 100 * se, se / ge);
        /* Where the panel lags (pg279q small steps, the 240 Hz panel's swings)
         * the tables halve the error or better; where plain gamma is already
         * within 0.1 % (lcd-240 small steps: 0.05 %), the tables' own floor
         * (interpolation, 8-bit state; ~0.1 %) may show but stays small. */
        assert_true(k == 0 ? s < 0.5 * g : s < g + 0.001);
        assert_true(k == 0 ? se < ge : se < 0.5 * ge);
    }
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_vs_reference),
    cmocka_unit_test(test_bad_tables),
    cmocka_unit_test(test_residual),
    cmocka_unit_test(test_pair_carry),
    cmocka_unit_test(test_beats_gamma_on_the_panel),
)
