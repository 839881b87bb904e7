/*
 * checkasm_trm.c - TRM's AVX2 row kernels against the portable C kernels,
 * bit for bit (dav1d checkasm style), and a benchmark of both.
 *
 *   checkasm_trm [--seed N] [--rows N]   check (exit 1 on the first mismatch)
 *   checkasm_trm --bench                  check, then time both per kernel
 *
 * Inputs are random within each kernel's documented ranges plus the
 * extremes: codes 0/255, U rows at 0 and 255 * 2^22 alternating (the
 * largest lerp steps), fractions 0 and 2^14 - 1, residuals 0 and +-2^24,
 * s = 0 and s = 2^24, widths 1..8 (no vector step), 9, 17 and odd sizes
 * (vector steps plus the C tail), all three gamma panels' tables.
 * Without AVX2 on this CPU the check says so and passes (nothing to check).
 */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tdc_math.h"
#include "tdc_panels.h"
#include "tdc_trm_kernels.h"

#define MAXW 1500u
#define URW (MAXW + 1u) /* reduced columns + the duplicate */

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;
static uint32_t rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (uint32_t)(rng_state >> 16);
}
static uint32_t rnd_below(uint32_t n)
{
    return n ? rnd() % n : 0u;
}

static uint32_t wexp[TDC_TRM_WEXP_ENTRIES];
static uint16_t ux[2u * MAXW];
static uint32_t urow_a[3u * URW], urow_b[3u * URW];
static uint8_t src[3u * MAXW];
static int32_t res_in[3u * MAXW], res_c[3u * MAXW], res_v[3u * MAXW];
static uint8_t dst_c[3u * MAXW], dst_v[3u * MAXW];
static uint16_t drows[TDC_TRM_MAX_TAPS][3u * MAXW], dout_c[3u * MAXW], dout_v[3u * MAXW];

static const tdc_panel_t *const panels[] = {&tdc_panel_htc_vive, &tdc_panel_rift_cv1, &tdc_panel_pg279q};

static uint8_t comb[3][3u * TDC_TRM_ENC_COMB + 8u];
static int one_step[3];

static void set_ctx(tdc_trm_rowctx_t *k, const tdc_panel_t *p, uint32_t width, uint32_t s_q8)
{
    uint32_t pi = 0;
    while (panels[pi] != p) {
        pi++;
    }
    for (int c = 0; c < 3; c++) {
        k->enc_comb[c] = comb[pi] + (size_t)c * TDC_TRM_ENC_COMB;
    }
    k->enc_one_step = (uint32_t)one_step[pi];
    for (int c = 0; c < 3; c++) {
        k->dec[c] = p->gamma[c].decode;
        k->thr[c] = p->gamma[c].enc_thresh;
        k->idx[c] = p->gamma[c].enc_index;
    }
    k->ux = ux;
    k->wexp = wexp;
    k->width = width;
    k->s_q8 = s_q8;
}

/* One row of inputs.  mode 0 random, 1 extremes, 2 mostly static (the
 * reduced row's U(i) near U(D(I)) so the motion test sees both cases). */
static void make_row(uint32_t width, uint32_t mode)
{
    const uint32_t rw = width > 1u ? 1u + rnd_below(width) : 1u;
    const uint32_t top = 255u << 22;
    for (uint32_t x = 0; x < width; x++) {
        ux[2u * x] = (uint16_t)(mode == 1u ? (x * rw) / width : rnd_below(rw));
        const uint32_t fr = rnd_below(4u);
        ux[2u * x + 1u] = (uint16_t)(fr == 0u ? 0u : fr == 1u ? 16383u : rnd_below(16384u));
    }
    for (uint32_t i = 0; i < 3u * (rw + 1u); i++) {
        uint32_t a = rnd_below(top + 1u), b = rnd_below(top + 1u);
        if (mode == 1u) {
            a = (i / 3u + (rnd() & 1u)) & 1u ? top : 0u;
            b = rnd_below(3u) == 0u ? a : top - a;
        } else if (mode == 2u) {
            const uint32_t d = rnd_below(1u << 22); /* within a code */
            b = a + d <= top ? a + d : a - d;
        }
        urow_a[i] = a;
        urow_b[i] = b;
    }
    for (uint32_t i = 0; i < 3u * width; i++) {
        const uint32_t pick = rnd_below(8u);
        src[i] = (uint8_t)(mode == 1u ? (pick & 1u ? 255u : 0u) : rnd());
        int32_t r = (int32_t)rnd_below(1u << 25) - (1 << 24);
        if (pick == 0u || pick == 1u) {
            r = 0;
        } else if (pick == 2u) {
            r = (rnd() & 1u) ? (1 << 24) : -(1 << 24);
        } else if (pick == 3u) {
            r = (int32_t)rnd_below(64u) - 32; /* tiny: rounding of w rho */
        }
        res_in[i] = r;
    }
}

static int check_full(const tdc_trm_rowctx_t *k, uint32_t row)
{
    tdc_trm_full_counts_t nc = {0, 0}, nv = {0, 0};
    memset(dst_c, 0xa5, sizeof dst_c);
    memset(dst_v, 0xa5, sizeof dst_v);
    memset(res_c, 0x5a, sizeof res_c);
    memset(res_v, 0x5a, sizeof res_v);
    tdc_trm_full_row_c(k, urow_a, src, dst_c, res_c, &nc);
    tdc_trm_full_row_avx2(k, urow_a, src, dst_v, res_v, &nv);
    const size_t nb = 3u * k->width;
    for (size_t i = 0; i < 3u * MAXW; i++) {
        if (dst_c[i] != dst_v[i] || res_c[i] != res_v[i]) {
            fprintf(stderr, "checkasm_trm: full row %" PRIu32 " width %" PRIu32 ": sample %zu%s: code %u vs %u, rho %" PRId32
                            " vs %" PRId32 "\n",
                    row, k->width, i, i < nb ? "" : " (past the row: written by one side)", dst_c[i], dst_v[i], res_c[i],
                    res_v[i]);
            return 1;
        }
    }
    if (nc.hi != nv.hi || nc.lo != nv.lo) {
        fprintf(stderr, "checkasm_trm: full row %" PRIu32 ": counts hi %u/%u lo %u/%u\n", row, nc.hi, nv.hi, nc.lo, nv.lo);
        return 1;
    }
    return 0;
}

static int check_reduced(const tdc_trm_rowctx_t *k, uint32_t row)
{
    tdc_trm_reduced_counts_t nc = {0, 0, 0}, nv = {0, 0, 0};
    memset(dst_c, 0xa5, sizeof dst_c);
    memset(dst_v, 0xa5, sizeof dst_v);
    tdc_trm_reduced_row_c(k, urow_a, urow_b, res_in, dst_c, &nc);
    tdc_trm_reduced_row_avx2(k, urow_a, urow_b, res_in, dst_v, &nv);
    for (size_t i = 0; i < 3u * MAXW; i++) {
        if (dst_c[i] != dst_v[i]) {
            fprintf(stderr, "checkasm_trm: reduced row %" PRIu32 " width %" PRIu32 " s %" PRIu32 ": sample %zu: code %u vs %u\n",
                    row, k->width, k->s_q8, i, dst_c[i], dst_v[i]);
            return 1;
        }
    }
    if (nc.computed != nv.computed || nc.skipped != nv.skipped || nc.no_res != nv.no_res) {
        fprintf(stderr, "checkasm_trm: reduced row %" PRIu32 ": counts differ\n", row);
        return 1;
    }
    return 0;
}

static int check_dvert(uint32_t n, uint32_t taps, uint32_t row)
{
    uint16_t w[TDC_TRM_MAX_TAPS];
    const uint16_t *rows[TDC_TRM_MAX_TAPS];
    uint32_t left = 32768u;
    for (uint32_t t = 0; t < taps; t++) {
        w[t] = (uint16_t)(t + 1u == taps ? left : rnd_below(left + 1u));
        left -= w[t];
        rows[t] = drows[t];
        for (uint32_t i = 0; i < n; i++) {
            drows[t][i] = (uint16_t)(rnd_below(4u) == 0u ? 65280u : rnd_below(65281u));
        }
    }
    memset(dout_c, 0, sizeof dout_c);
    memset(dout_v, 0, sizeof dout_v);
    tdc_trm_dvert_c(rows, w, taps, n, dout_c);
    tdc_trm_dvert_avx2(rows, w, taps, n, dout_v);
    if (memcmp(dout_c, dout_v, sizeof dout_c) != 0) {
        fprintf(stderr, "checkasm_trm: D vertical row %" PRIu32 " (n %" PRIu32 ", %" PRIu32 " taps) differs\n", row, n, taps);
        return 1;
    }
    return 0;
}

static int16_t hfirst[MAXW];
static uint16_t hw[MAXW * TDC_TRM_MAX_TAPS + 8u];
static uint16_t hout_c[3u * MAXW], hout_v[3u * MAXW];

/* Horizontal D pass: a row of width pixels, rw columns whose kernels start
 * at increasing positions from before the row to past its end. */
static int check_dhoriz(uint32_t row)
{
    const uint32_t width = 1u + rnd_below(MAXW), taps = 1u + rnd_below(TDC_TRM_MAX_TAPS);
    const uint32_t rw = 1u + rnd_below(width);
    for (uint32_t i = 0; i < 3u * width; i++) {
        src[i] = (uint8_t)(rnd_below(4u) == 0u ? 255u : rnd());
    }
    for (uint32_t j = 0; j < rw; j++) {
        /* centre (j + 0.5) W / rw - 0.5, kernel starting taps/2 before it */
        hfirst[j] = (int16_t)((int32_t)(((2u * j + 1u) * width) / (2u * rw)) - (int32_t)(taps / 2u));
        uint32_t left = 32768u;
        for (uint32_t t = 0; t < taps; t++) {
            hw[j * taps + t] = (uint16_t)(t + 1u == taps ? left : rnd_below(left + 1u));
            left -= hw[j * taps + t];
        }
    }
    memset(hout_c, 0, sizeof hout_c);
    memset(hout_v, 0, sizeof hout_v);
    tdc_trm_dhoriz_c(src, width, hfirst, hw, taps, rw, hout_c);
    tdc_trm_dhoriz_avx2(src, width, hfirst, hw, taps, rw, hout_v);
    if (memcmp(hout_c, hout_v, sizeof hout_c) != 0) {
        fprintf(stderr, "checkasm_trm: D horizontal row %" PRIu32 " (width %" PRIu32 ", rw %" PRIu32 ", %" PRIu32
                        " taps) differs\n", row, width, rw, taps);
        return 1;
    }
    return 0;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* Best-of-N nanoseconds per pixel of a 1440-pixel row. */
static double time_row(int which, int simd, const tdc_trm_rowctx_t *k)
{
    double best = 1e30;
    for (int rep = 0; rep < 7; rep++) {
        tdc_trm_full_counts_t nf = {0, 0};
        tdc_trm_reduced_counts_t nr = {0, 0, 0};
        const double t0 = now_s();
        for (int i = 0; i < 200; i++) {
            if (which == 0) {
                (simd ? tdc_trm_full_row_avx2 : tdc_trm_full_row_c)(k, urow_a, src, dst_c, res_c, &nf);
            } else {
                (simd ? tdc_trm_reduced_row_avx2 : tdc_trm_reduced_row_c)(k, urow_a, urow_b, res_in, dst_c, &nr);
            }
        }
        const double dt = (now_s() - t0) / (200.0 * k->width) * 1e9;
        best = dt < best ? dt : best;
    }
    return best;
}

int main(int argc, char **argv)
{
    int bench = 0;
    uint32_t rows = 3000u;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--bench") == 0) {
            bench = 1;
        } else if (strcmp(argv[i], "--seed") == 0 && i + 1 < argc) {
            rng_state = strtoull(argv[++i], NULL, 0) | 1u;
        } else if (strcmp(argv[i], "--rows") == 0 && i + 1 < argc) {
            rows = (uint32_t)strtoul(argv[++i], NULL, 0);
        } else {
            fprintf(stderr, "usage: checkasm_trm [--seed N] [--rows N] [--bench]\n");
            return 2;
        }
    }
    if (!tdc_trm_avx2_available()) {
        printf("checkasm_trm: no AVX2 kernels on this build/CPU: nothing to check (boards run the C kernels)\n");
        return 0;
    }
    for (uint32_t i = 0; i < TDC_TRM_WEXP_ENTRIES; i++) {
        wexp[i] = tdc_exp_neg_q16_q30(i << 8);
    }
    for (int p = 0; p < 3; p++) {
        one_step[p] = tdc_trm_avx2_build_encode(panels[p], comb[p]);
        printf("checkasm_trm: %s: encode index %s\n", panels[p]->name,
               one_step[p] ? "needs one threshold step" : "needs a scan (a bucket holds two thresholds)");
    }
    static const uint32_t fixed_w[] = {1, 2, 7, 8, 9, 15, 16, 17, 24, 25, 97, 1440};
    static const uint32_t svals[] = {0u, 1u, 2560u, 1u << 24, 0xffffffffu};
    uint32_t nfull = 0, nred = 0, nd = 0;
    for (uint32_t row = 0; row < rows; row++) {
        const uint32_t width = row < 12u ? fixed_w[row] : 1u + rnd_below(row % 50u == 0u ? MAXW : 300u);
        const uint32_t mode = row % 3u;
        const uint32_t s_q8 = rnd_below(4u) == 0u ? svals[rnd_below(5u)] : rnd_below(1u << 16);
        tdc_trm_rowctx_t k;
        set_ctx(&k, panels[row % 3u], width, s_q8);
        if (row % 7u == 3u) {
            k.enc_one_step = 0; /* the scan path must agree too */
        }
        make_row(width, mode);
        if (check_full(&k, row) || check_reduced(&k, row)) {
            return 1;
        }
        nfull++;
        nred++;
        if (row % 4u == 0u) {
            if (check_dvert(1u + rnd_below(3u * MAXW), 1u + rnd_below(TDC_TRM_MAX_TAPS), row) ||
                check_dhoriz(row)) {
                return 1;
            }
            nd++;
        }
    }
    printf("checkasm_trm: AVX2 == C bit for bit: %" PRIu32 " full rows, %" PRIu32 " reduced rows, %" PRIu32
           " D vertical and horizontal rows (random, extremes, widths 1..%u, 3 panels)\n",
           nfull, nred, nd, MAXW);
    if (!bench) {
        return 0;
    }
    /* A 1440-pixel row of random content (mode 0) and of mostly static
     * content (mode 2), htc-vive tables, s = 10. */
    printf("checkasm_trm --bench: ns per pixel (RGB) on one core, best of 7 x 200 rows of 1440 pixels\n");
    printf("  kernel                       C        AVX2   speed-up\n");
    const char *names[] = {"full row, random", "reduced row, random", "full row, near-static", "reduced row, near-static"};
    for (int m = 0; m < 2; m++) {
        tdc_trm_rowctx_t k;
        set_ctx(&k, &tdc_panel_htc_vive, 1440u, 2560u);
        make_row(1440u, m == 0 ? 0u : 2u);
        for (int which = 0; which < 2; which++) {
            const double tc = time_row(which, 0, &k), tv = time_row(which, 1, &k);
            printf("  %-24s %8.2f %8.2f %8.2fx\n", names[2 * m + which], tc, tv, tc / tv);
        }
    }
    return 0;
}
