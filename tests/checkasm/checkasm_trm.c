/*
 * checkasm_trm.c - TRM's row kernels (firmware/tdc_trm_kernels.h): the
 * families of the four kernel signatures and the registered optimised
 * versions.  A new SIMD version of a TRM kernel is one line in
 * g_trm_kernels below.
 *
 * Inputs are random within each kernel's documented ranges plus the
 * extremes: codes 0/255, U rows at 0 and 255 * 2^22 alternating (the
 * largest lerp steps), fractions 0 and 2^14 - 1, residuals 0, +-2^24 and
 * tiny, s = 0 to 2^32 - 1, widths 1..8 (no vector step), 9, 17 and odd
 * sizes (vector steps plus the scalar tail), all three gamma panels'
 * tables, the encode's scan path forced on some rows.  Outputs are
 * compared over the whole buffer, so a write past the row is caught too.
 */
#include <stdio.h>
#include <string.h>

#include "checkasm.h"
#include "tdc_panels.h"
#include "tdc_trm.h"
#include "tdc_trm_kernels.h"

#define MAXW 1500u
#define URW (MAXW + 1u) /* reduced columns + the duplicate */

static uint16_t ux[2u * MAXW];
static uint32_t urow_a[3u * URW], urow_b[3u * URW];
static uint8_t src[3u * MAXW];
static int32_t res_in[3u * MAXW], res_c[3u * MAXW], res_v[3u * MAXW];
static uint8_t dst_c[3u * MAXW], dst_v[3u * MAXW];
static CHECKASM_BIG uint16_t drows[TDC_TRM_MAX_TAPS][3u * MAXW];
static uint16_t dout_c[3u * MAXW], dout_v[3u * MAXW];
static int16_t hfirst[MAXW];
static CHECKASM_BIG uint16_t hw[MAXW * TDC_TRM_MAX_TAPS + 8u];

static const tdc_panel_t *const panels[] = {&tdc_panel_htc_vive, &tdc_panel_rift_cv1, &tdc_panel_pg279q};
#define NPANELS 3u

/* Per panel: the AVX2 encode index (part of the row context). */
static uint8_t comb[NPANELS][3u * TDC_TRM_ENC_COMB + 8u];
static int one_step[NPANELS];

static void tables_once(void)
{
    static int done;
    if (done) {
        return;
    }
    done = 1;
    for (unsigned p = 0; p < NPANELS; p++) {
        one_step[p] = tdc_trm_avx2_build_encode(panels[p], comb[p]);
    }
}

static void set_ctx(tdc_trm_rowctx_t *k, unsigned p, uint32_t width, uint32_t s_q8, int force_scan)
{
    tdc_trm_rowctx_init(k, panels[p], ux, tdc_trm_wexp_q30, width, s_q8, comb[p], force_scan ? 0u : (uint32_t)one_step[p]);
}

/* One row of inputs.  mode 0 random, 1 extremes, 2 mostly static (the
 * reduced row's U(i) near U(D(I)) so the motion test sees both cases). */
static void make_row(uint32_t width, uint32_t mode)
{
    const uint32_t rw = width > 1u ? 1u + checkasm_rand_below(width) : 1u;
    const uint32_t top = 255u << 22;
    for (uint32_t x = 0; x < width; x++) {
        ux[2u * x] = (uint16_t)(mode == 1u ? (x * rw) / width : checkasm_rand_below(rw));
        const uint32_t fr = checkasm_rand_below(4u);
        ux[2u * x + 1u] = (uint16_t)(fr == 0u ? 0u : fr == 1u ? 16383u : checkasm_rand_below(16384u));
    }
    for (uint32_t i = 0; i < 3u * (rw + 1u); i++) {
        uint32_t a = checkasm_rand_below(top + 1u), b = checkasm_rand_below(top + 1u);
        if (mode == 1u) {
            a = (i / 3u + (checkasm_rand() & 1u)) & 1u ? top : 0u;
            b = checkasm_rand_below(3u) == 0u ? a : top - a;
        } else if (mode == 2u) {
            const uint32_t d = checkasm_rand_below(1u << 22); /* within a code */
            b = a + d <= top ? a + d : a - d;
        }
        urow_a[i] = a;
        urow_b[i] = b;
    }
    for (uint32_t i = 0; i < 3u * width; i++) {
        const uint32_t pick = checkasm_rand_below(8u);
        src[i] = (uint8_t)(mode == 1u ? (pick & 1u ? 255u : 0u) : checkasm_rand());
        int32_t r = (int32_t)checkasm_rand_below(1u << 25) - (1 << 24);
        if (pick == 0u || pick == 1u) {
            r = 0;
        } else if (pick == 2u) {
            r = (checkasm_rand() & 1u) ? (1 << 24) : -(1 << 24);
        } else if (pick == 3u) {
            r = (int32_t)checkasm_rand_below(64u) - 32; /* tiny: rounding of w rho */
        }
        res_in[i] = r;
    }
}

/* Row parameters of check row `row` (the same sequence as the old one-off
 * checkasm_trm: fixed widths first, then random, every 50th up to MAXW). */
typedef struct {
    uint32_t width, mode, s_q8;
    unsigned panel;
    int force_scan;
} row_params_t;

static row_params_t next_row(uint32_t row)
{
    static const uint32_t fixed_w[] = {1, 2, 7, 8, 9, 15, 16, 17, 24, 25, 97, 1440};
    static const uint32_t svals[] = {0u, 1u, 2560u, 1u << 24, 0xffffffffu};
    row_params_t r;
    r.width = row < 12u ? fixed_w[row] : 1u + checkasm_rand_below(row % 50u == 0u ? MAXW : 300u);
    r.mode = row % 3u;
    r.s_q8 = checkasm_rand_below(4u) == 0u ? svals[checkasm_rand_below(5u)] : checkasm_rand_below(1u << 16);
    r.panel = row % NPANELS;
    r.force_scan = row % 7u == 3u; /* the encode's scan path must agree too */
    return r;
}

/* Check row `row`: its parameters, context and inputs. */
static row_params_t setup_row(uint32_t row, tdc_trm_rowctx_t *k)
{
    tables_once();
    const row_params_t r = next_row(row);
    set_ctx(k, r.panel, r.width, r.s_q8, r.force_scan);
    make_row(r.width, r.mode);
    return r;
}

/* The inputs that decide output sample i of a full-res row. */
static void describe_sample(char *buf, size_t cap, uint32_t width, long i)
{
    const uint32_t x = (uint32_t)i / 3u, c = (uint32_t)i % 3u;
    if ((uint32_t)i >= 3u * width) {
        snprintf(buf, cap, "(past the row of %u pixels: written by one side only)", (unsigned)width);
        return;
    }
    const uint32_t j = ux[2u * x];
    snprintf(buf, cap,
             "pixel %u channel %u: src %u, ux (%u, frac %u), urow_a[%u] %u, [%u] %u, urow_b %u, %u, rho in %d",
             (unsigned)x, (unsigned)c, src[i], (unsigned)j, ux[2u * x + 1u], (unsigned)(3u * j + c),
             (unsigned)urow_a[3u * j + c], (unsigned)(3u * (j + 1u) + c), (unsigned)urow_a[3u * (j + 1u) + c],
             (unsigned)urow_b[3u * j + c], (unsigned)urow_b[3u * (j + 1u) + c], (int)res_in[i]);
}

/* ---- full-res row ---- */

/* full_row and rho_row: the same kernel signature; rho_row leaves the codes
 * unwritten but for the C tail, so only full_row compares them (codes) */
static void check_full_like(const checkasm_kernel_t *kr, int codes)
{
    const uint32_t rows = checkasm_runs(3000u);
    for (uint32_t row = 0; row < rows && !checkasm_failed(); row++) {
        tdc_trm_rowctx_t k;
        const row_params_t r = setup_row(row, &k);
        tdc_trm_full_counts_t nc = {0, 0}, nv = {0, 0};
        memset(dst_c, 0xa5, sizeof dst_c);
        memset(dst_v, 0xa5, sizeof dst_v);
        memset(res_c, 0x5a, sizeof res_c);
        memset(res_v, 0x5a, sizeof res_v);
        CHECKASM_REF(tdc_trm_full_row_fn, kr)(&k, urow_a, src, dst_c, res_c, &nc);
        CHECKASM_OPT(tdc_trm_full_row_fn, kr)(&k, urow_a, src, dst_v, res_v, &nv);
        long i = codes ? checkasm_diff_u8(dst_c, dst_v, sizeof dst_c) : -1;
        const long ir = checkasm_diff_i32(res_c, res_v, 3u * MAXW);
        i = i < 0 || (ir >= 0 && ir < i) ? ir : i;
        char where[256];
        if (i >= 0) {
            describe_sample(where, sizeof where, r.width, i);
            checkasm_fail("row %u width %u panel %s mode %u: sample %ld: code %u vs %u%s, rho %d vs %d; %s",
                          (unsigned)row, (unsigned)r.width, panels[r.panel]->name, (unsigned)r.mode, i, dst_c[i],
                          dst_v[i], codes ? "" : " (not compared)", (int)res_c[i], (int)res_v[i], where);
        } else if (nc.hi != nv.hi || nc.lo != nv.lo) {
            checkasm_fail("row %u width %u: clamp counts hi %u vs %u, lo %u vs %u", (unsigned)row, (unsigned)r.width,
                          (unsigned)nc.hi, (unsigned)nv.hi, (unsigned)nc.lo, (unsigned)nv.lo);
        }
    }
}
static void check_full_row(const checkasm_kernel_t *kr) { check_full_like(kr, 1); }
static void check_rho_row(const checkasm_kernel_t *kr) { check_full_like(kr, 0); }

/* ---- reduced row ---- */

static void check_reduced_row(const checkasm_kernel_t *kr)
{
    const uint32_t rows = checkasm_runs(3000u);
    for (uint32_t row = 0; row < rows && !checkasm_failed(); row++) {
        tdc_trm_rowctx_t k;
        const row_params_t r = setup_row(row, &k);
        tdc_trm_reduced_counts_t nc = {0, 0, 0}, nv = {0, 0, 0};
        memset(dst_c, 0xa5, sizeof dst_c);
        memset(dst_v, 0xa5, sizeof dst_v);
        CHECKASM_REF(tdc_trm_reduced_row_fn, kr)(&k, urow_a, urow_b, res_in, dst_c, &nc);
        CHECKASM_OPT(tdc_trm_reduced_row_fn, kr)(&k, urow_a, urow_b, res_in, dst_v, &nv);
        const long i = checkasm_diff_u8(dst_c, dst_v, sizeof dst_c);
        char where[256];
        if (i >= 0) {
            describe_sample(where, sizeof where, r.width, i);
            checkasm_fail("row %u width %u panel %s mode %u s_q8 %u: sample %ld: code %u vs %u; %s", (unsigned)row,
                          (unsigned)r.width, panels[r.panel]->name, (unsigned)r.mode, (unsigned)r.s_q8, i, dst_c[i],
                          dst_v[i], where);
        } else if (nc.computed != nv.computed || nc.skipped != nv.skipped || nc.no_res != nv.no_res) {
            checkasm_fail("row %u width %u: weight counts computed %u vs %u, skipped %u vs %u, no_res %u vs %u",
                          (unsigned)row, (unsigned)r.width, (unsigned)nc.computed, (unsigned)nv.computed,
                          (unsigned)nc.skipped, (unsigned)nv.skipped, (unsigned)nc.no_res, (unsigned)nv.no_res);
        }
    }
}

/* ---- vertical D pass ---- */

/* Weights of one kernel: random Q15 summing to exactly 32768. */
static void make_weights(uint16_t *w, uint32_t taps)
{
    uint32_t left = 32768u;
    for (uint32_t t = 0; t < taps; t++) {
        w[t] = (uint16_t)(t + 1u == taps ? left : checkasm_rand_below(left + 1u));
        left -= w[t];
    }
}

static void make_dvert(uint32_t n, uint32_t taps, uint16_t *w, const uint16_t **rows)
{
    make_weights(w, taps);
    for (uint32_t t = 0; t < taps; t++) {
        rows[t] = drows[t];
        for (uint32_t i = 0; i < n; i++) {
            drows[t][i] = (uint16_t)(checkasm_rand_below(4u) == 0u ? 65280u : checkasm_rand_below(65281u));
        }
    }
}

static void check_dvert(const checkasm_kernel_t *kr)
{
    const uint32_t runs = checkasm_runs(750u);
    for (uint32_t run = 0; run < runs && !checkasm_failed(); run++) {
        /* the first 64 runs: every length 1..64 (vector bodies and every tail) */
        const uint32_t n = run < 64u ? run + 1u : 1u + checkasm_rand_below(3u * MAXW);
        const uint32_t taps = 1u + checkasm_rand_below(TDC_TRM_MAX_TAPS);
        uint16_t w[TDC_TRM_MAX_TAPS];
        const uint16_t *rows[TDC_TRM_MAX_TAPS];
        make_dvert(n, taps, w, rows);
        memset(dout_c, 0, sizeof dout_c);
        memset(dout_v, 0, sizeof dout_v);
        CHECKASM_REF(tdc_trm_dvert_fn, kr)(rows, w, taps, n, dout_c);
        CHECKASM_OPT(tdc_trm_dvert_fn, kr)(rows, w, taps, n, dout_v);
        const long i = checkasm_diff_u16(dout_c, dout_v, 3u * MAXW);
        if (i >= 0) {
            checkasm_fail("run %u n %u taps %u: out[%ld] %u vs %u%s; rows[0..2][i] %u %u %u, w[0..2] %u %u %u",
                          (unsigned)run, (unsigned)n, (unsigned)taps, i, dout_c[i], dout_v[i],
                          (uint32_t)i >= n ? " (past n)" : "", drows[0][i], taps > 1u ? drows[1][i] : 0u,
                          taps > 2u ? drows[2][i] : 0u, w[0], taps > 1u ? w[1] : 0u, taps > 2u ? w[2] : 0u);
        }
    }
}

/* ---- horizontal D pass ---- */

/* A row of width pixels, rw columns whose kernels start at increasing
 * positions from before the row to past its end. */
static void make_dhoriz(uint32_t width, uint32_t taps, uint32_t rw)
{
    for (uint32_t i = 0; i < 3u * width; i++) {
        src[i] = (uint8_t)(checkasm_rand_below(4u) == 0u ? 255u : checkasm_rand());
    }
    for (uint32_t j = 0; j < rw; j++) {
        /* centre (j + 0.5) W / rw - 0.5, kernel starting taps/2 before it */
        hfirst[j] = (int16_t)((int32_t)(((2u * j + 1u) * width) / (2u * rw)) - (int32_t)(taps / 2u));
        make_weights(&hw[j * taps], taps);
    }
}

static void check_dhoriz(const checkasm_kernel_t *kr)
{
    const uint32_t runs = checkasm_runs(750u);
    for (uint32_t run = 0; run < runs && !checkasm_failed(); run++) {
        /* the first 64 runs: every width 1..64 (vector bodies and every tail) */
        const uint32_t width = run < 64u ? run + 1u : 1u + checkasm_rand_below(MAXW);
        const uint32_t taps = 1u + checkasm_rand_below(TDC_TRM_MAX_TAPS);
        const uint32_t rw = 1u + checkasm_rand_below(width);
        make_dhoriz(width, taps, rw);
        memset(dout_c, 0, sizeof dout_c);
        memset(dout_v, 0, sizeof dout_v);
        CHECKASM_REF(tdc_trm_dhoriz_fn, kr)(src, width, hfirst, hw, taps, rw, dout_c);
        CHECKASM_OPT(tdc_trm_dhoriz_fn, kr)(src, width, hfirst, hw, taps, rw, dout_v);
        const long i = checkasm_diff_u16(dout_c, dout_v, 3u * MAXW);
        if (i >= 0) {
            const uint32_t j = (uint32_t)i / 3u;
            checkasm_fail("run %u width %u rw %u taps %u: out[%ld] (column %u channel %u) %u vs %u%s; kernel first %d",
                          (unsigned)run, (unsigned)width, (unsigned)rw, (unsigned)taps, i, (unsigned)j,
                          (unsigned)((uint32_t)i % 3u), dout_c[i], dout_v[i], j >= rw ? " (past rw)" : "",
                          j < rw ? hfirst[j] : 0);
        }
    }
}

/* ---- benchmarks: a 1440-pixel row (one eye of a Vive-class panel) ---- */

static void bench_rows(const checkasm_kernel_t *kr, int reduced)
{
    tables_once();
    for (uint32_t m = 0; m < 2; m++) {
        tdc_trm_rowctx_t k;
        set_ctx(&k, 0, 1440u, 2560u, 0);
        make_row(1440u, m == 0 ? 0u : 2u);
        tdc_trm_full_counts_t nf = {0, 0};
        tdc_trm_reduced_counts_t nr = {0, 0, 0};
        const char *label = m == 0 ? "1440 px, random, htc-vive, s 10" : "1440 px, near-static, htc-vive, s 10";
        if (reduced) {
            CHECKASM_BENCH(kr, label, 1440u, tdc_trm_reduced_row_fn, f, f(&k, urow_a, urow_b, res_in, dst_c, &nr));
        } else {
            CHECKASM_BENCH(kr, label, 1440u, tdc_trm_full_row_fn, f, f(&k, urow_a, src, dst_c, res_c, &nf));
        }
    }
}

static void bench_full_row(const checkasm_kernel_t *kr)
{
    bench_rows(kr, 0);
}

static void bench_reduced_row(const checkasm_kernel_t *kr)
{
    bench_rows(kr, 1);
}

/* D at r = 1/2, sigma 2.5 (16 taps): 720 reduced columns of 1440 pixels. */
static void bench_dvert(const checkasm_kernel_t *kr)
{
    uint16_t w[TDC_TRM_MAX_TAPS];
    const uint16_t *rows[TDC_TRM_MAX_TAPS];
    make_dvert(3u * 720u, 16u, w, rows);
    CHECKASM_BENCH(kr, "720 columns x 3, 16 taps", 720u, tdc_trm_dvert_fn, f, f(rows, w, 16u, 3u * 720u, dout_c));
}

static void bench_dhoriz(const checkasm_kernel_t *kr)
{
    make_dhoriz(1440u, 16u, 720u);
    CHECKASM_BENCH(kr, "1440 px -> 720 columns, 16 taps", 720u, tdc_trm_dhoriz_fn, f,
                   f(src, 1440u, hfirst, hw, 16u, 720u, dout_c));
}

/* ---- U's vertical lerp: rows of code Q8 (up to 65280, the extremes
 * often) or 8-bit codes, any fraction, lengths around the vector width ---- */

static uint32_t uvert_setup(uint32_t run, uint32_t *f, uint16_t *a, uint16_t *b, uint8_t *ca, uint8_t *cb)
{
    static const uint32_t fixed_n[] = {1, 7, 8, 9, 15, 16, 17, 3u * 540u};
    const uint32_t n = run < 8u ? fixed_n[run] : 1u + checkasm_rand_below(3u * MAXW);
    *f = run % 5u == 0u ? 16383u : checkasm_rand_below(1u << 14);
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t pick = checkasm_rand_below(4u);
        a[i] = (uint16_t)(pick == 0u ? 0u : (pick == 1u ? 65280u : checkasm_rand_below(65281u)));
        b[i] = (uint16_t)(pick == 1u ? 0u : (pick == 0u ? 65280u : checkasm_rand_below(65281u)));
        ca[i] = (uint8_t)(a[i] >> 8);
        cb[i] = (uint8_t)(b[i] >> 8);
    }
    return n;
}

static void check_uvert(const checkasm_kernel_t *kr, int codes)
{
    const uint32_t runs = checkasm_runs(2000u);
    for (uint32_t run = 0; run < runs && !checkasm_failed(); run++) {
        uint32_t f;
        const uint32_t n = uvert_setup(run, &f, drows[0], drows[1], src, dst_v);
        memset(res_c, 0x5a, sizeof res_c);
        memset(res_v, 0x5a, sizeof res_v);
        if (codes) {
            CHECKASM_REF(tdc_trm_uvert_codes_fn, kr)(src, dst_v, f, n, (uint32_t *)(void *)res_c);
            CHECKASM_OPT(tdc_trm_uvert_codes_fn, kr)(src, dst_v, f, n, (uint32_t *)(void *)res_v);
        } else {
            CHECKASM_REF(tdc_trm_uvert_fn, kr)(drows[0], drows[1], f, n, (uint32_t *)(void *)res_c);
            CHECKASM_OPT(tdc_trm_uvert_fn, kr)(drows[0], drows[1], f, n, (uint32_t *)(void *)res_v);
        }
        const long i = checkasm_diff_i32(res_c, res_v, 3u * MAXW);
        if (i >= 0) {
            checkasm_fail("run %u n %u f %u: value %ld: %u vs %u (a %u, b %u)", (unsigned)run, (unsigned)n,
                          (unsigned)f, i, (unsigned)res_c[i], (unsigned)res_v[i],
                          (unsigned)(codes ? src[i] : drows[0][i]), (unsigned)(codes ? dst_v[i] : drows[1][i]));
        }
    }
}

static void check_uvert_q8(const checkasm_kernel_t *kr)
{
    check_uvert(kr, 0);
}

static void check_uvert_codes(const checkasm_kernel_t *kr)
{
    check_uvert(kr, 1);
}

static void bench_uvert(const checkasm_kernel_t *kr)
{
    uint32_t f;
    (void)uvert_setup(7u, &f, drows[0], drows[1], src, dst_v);
    CHECKASM_BENCH(kr, "540 columns x 3", 3u * 540u, tdc_trm_uvert_fn, fn,
                   fn(drows[0], drows[1], f, 3u * 540u, (uint32_t *)(void *)res_c));
}

static void bench_uvert_codes(const checkasm_kernel_t *kr)
{
    uint32_t f;
    (void)uvert_setup(7u, &f, drows[0], drows[1], src, dst_v);
    CHECKASM_BENCH(kr, "540 columns x 3", 3u * 540u, tdc_trm_uvert_codes_fn, fn,
                   fn(src, dst_v, f, 3u * 540u, (uint32_t *)(void *)res_c));
}

/* ---- families and registrations ---- */

static const checkasm_family_t trm_full_row = {"trm_full_row", check_full_row, bench_full_row};
static const checkasm_family_t trm_rho_row = {"trm_rho_row", check_rho_row, bench_full_row};
static const checkasm_family_t trm_reduced_row = {"trm_reduced_row", check_reduced_row, bench_reduced_row};
static const checkasm_family_t trm_dvert = {"trm_dvert", check_dvert, bench_dvert};
static const checkasm_family_t trm_uvert = {"trm_uvert", check_uvert_q8, bench_uvert};
static const checkasm_family_t trm_uvert_codes = {"trm_uvert_codes", check_uvert_codes, bench_uvert_codes};
static const checkasm_family_t trm_dhoriz = {"trm_dhoriz", check_dhoriz, bench_dhoriz};

static const checkasm_kernel_t g_trm_kernels[] = {
    CHECKASM_KERNEL(&trm_full_row, "avx2", tdc_trm_avx2_available, tdc_trm_full_row_c, tdc_trm_full_row_avx2),
    CHECKASM_KERNEL(&trm_rho_row, "avx2", tdc_trm_avx2_available, tdc_trm_full_row_c, tdc_trm_rho_row_avx2),
    CHECKASM_KERNEL(&trm_reduced_row, "avx2", tdc_trm_avx2_available, tdc_trm_reduced_row_c, tdc_trm_reduced_row_avx2),
    CHECKASM_KERNEL(&trm_dvert, "avx2", tdc_trm_avx2_available, tdc_trm_dvert_c, tdc_trm_dvert_avx2),
    CHECKASM_KERNEL(&trm_uvert, "avx2", tdc_trm_avx2_available, tdc_trm_uvert_c, tdc_trm_uvert_avx2),
    CHECKASM_KERNEL(&trm_uvert_codes, "avx2", tdc_trm_avx2_available, tdc_trm_uvert_codes_c, tdc_trm_uvert_codes_avx2),
    CHECKASM_KERNEL(&trm_dhoriz, "avx2", tdc_trm_avx2_available, tdc_trm_dhoriz_c, tdc_trm_dhoriz_avx2),
#if defined(TDC_TRM_MVE)
    /* Helium boards (BOARD_MVE): run under QEMU by tests/arm/checkasm_arm_main.c */
    CHECKASM_KERNEL(&trm_full_row, "mve", checkasm_mve_available, tdc_trm_full_row_c, tdc_trm_full_row_mve),
    CHECKASM_KERNEL(&trm_reduced_row, "mve", checkasm_mve_available, tdc_trm_reduced_row_c, tdc_trm_reduced_row_mve),
    CHECKASM_KERNEL(&trm_dvert, "mve", checkasm_mve_available, tdc_trm_dvert_c, tdc_trm_dvert_mve),
    CHECKASM_KERNEL(&trm_dhoriz, "mve", checkasm_mve_available, tdc_trm_dhoriz_c, tdc_trm_dhoriz_mve),
#endif
#if defined(TDC_TRM_NEON)
    /* AArch64 (every build there: NEON is in the base ISA); the rows stay C
     * on AArch64 (firmware/tdc_trm_neon.c says why) */
    CHECKASM_KERNEL(&trm_dvert, "neon", checkasm_neon_available, tdc_trm_dvert_c, tdc_trm_dvert_neon),
    CHECKASM_KERNEL(&trm_dhoriz, "neon", checkasm_neon_available, tdc_trm_dhoriz_c, tdc_trm_dhoriz_neon),
#endif
};

const checkasm_module_t checkasm_trm = {"trm", g_trm_kernels, sizeof g_trm_kernels / sizeof g_trm_kernels[0]};
