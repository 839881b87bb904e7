/*
 * tdc_trm_kernels.h - TRM's per-row kernels, internal to the stage.
 *
 * tdc_trm.c walks the frame; these do the per-pixel work of one row.  The
 * portable C kernels (tdc_trm_rows.c) are the reference and what boards
 * run; tdc_trm_avx2.c has host versions with x86 AVX2 integer SIMD that
 * must produce the same bytes (tests/checkasm/checkasm_trm.c checks that on random
 * and extreme rows and benchmarks both).  tdc_trm_init() picks the AVX2
 * kernels when the CPU has AVX2 (tdc_trm_set_simd() overrides).
 *
 * Formats as tdc_trm.h: urow rows are vertically interpolated reduced rows
 * in code Q22 with (rw + 1) * 3 entries (the last pixel duplicated); ux holds
 * per full-res column the left reduced column and the bilinear fraction Q14
 * as interleaved uint16 pairs; residual rho is Q24 linear light; codes and
 * rows are RGB888 interleaved.
 */
#ifndef TDC_TRM_KERNELS_H
#define TDC_TRM_KERNELS_H

#include "tdc_fixed.h"
#include "tdc_panel.h"
#include "tdc_math.h"

/* Entries of the exp(-x) weight table, x = k/256 for k < 17*256 (+1 end). */
#define TDC_TRM_WEXP_ENTRIES (17u * 256u + 1u)

/* Entries per channel of the AVX2 kernels' one-step encode index. */
#define TDC_TRM_ENC_COMB (1024u + 4096u - 16u + 1u)

/* What a row kernel needs; built per frame from tdc_trm_t. */
typedef struct {
    const uint32_t *dec[3]; /* gamma decode, 257 entries, Q24 */
    const uint32_t *thr[3]; /* encode thresholds, 256 entries, Q24 */
    const uint16_t *idx[3]; /* encode index, TDC_ENC_INDEX_SIZE entries */
    const uint16_t *ux;     /* 2 * width: (reduced column, fraction Q14) */
    const uint32_t *wexp;   /* TDC_TRM_WEXP_ENTRIES: exp(-k/256), Q30 */
    uint32_t width;         /* full-res pixels in the row */
    uint32_t s_q8;          /* motion sensitivity s, Q8 */
    /* AVX2 kernels only: per channel a combined encode index (uint8,
     * TDC_TRM_ENC_COMB entries): entry L >> 6 for L < 2^16, entry
     * 1008 + (L >> 12) above; each is the largest code whose threshold is
     * <= the bucket's start.  enc_one_step: no bucket holds two thresholds,
     * so one compare finishes the encode. */
    const uint8_t *enc_comb[3];
    uint32_t enc_one_step;
} tdc_trm_rowctx_t;

/* Builds the row context from its parts: panel's gamma tables, the U table
 * ux, the exp table wexp (tdc_trm_wexp_q30), the row width, s, and the
 * AVX2 encode index (3 x TDC_TRM_ENC_COMB bytes, tdc_trm_avx2_build_encode;
 * NULL without).  tdc_trm.c builds one per frame from its state; checkasm
 * builds them from its own random tables: one builder, no copy. */
void tdc_trm_rowctx_init(tdc_trm_rowctx_t *k, const tdc_panel_t *panel, const uint16_t *ux, const uint32_t *wexp,
                         uint32_t width, uint32_t s_q8, const uint8_t *enc_comb, uint32_t enc_one_step);

/* exp(-x) at x = k / 256 in Q30, k < TDC_TRM_WEXP_ENTRIES: the table of
 * tdc_trm_weight_q15, const (flash on a board, shared by both eyes).  It is
 * generated at build time by `tdc-tablegen --trm` from the firmware's own
 * tdc_exp_neg_q16_q30(k << 8), so it holds exactly the values the stage would
 * build into each eye's arena at every stream start (17,412 B of RAM per
 * eye, and 35 % of a fuzz_frameloop execution); test_trm checks every
 * entry against that function. */
extern const uint32_t tdc_trm_wexp_q30[TDC_TRM_WEXP_ENTRIES];

typedef struct {
    uint32_t hi, lo; /* pixel-channels with beta > 1, beta < 0 */
} tdc_trm_full_counts_t;

typedef struct {
    uint32_t computed, skipped, no_res; /* as tdc_trm_stats_t's weight counters */
} tdc_trm_reduced_counts_t;

/* Full-res row: beta = 2 lin(I) - lin(U(D(I))), dst = enc(clamp(beta)),
 * res = beta - clamp(beta).  Counts are added to *n. */
typedef void tdc_trm_full_row_fn(const tdc_trm_rowctx_t *k, const uint32_t *urow, const uint8_t *src, uint8_t *dst,
                                 tdc_res_t *res, tdc_trm_full_counts_t *n);
/* Reduced row: alpha = lin(U(i)), w = exp(-s c), dst = enc(clamp(alpha + w rho)). */
typedef void tdc_trm_reduced_row_fn(const tdc_trm_rowctx_t *k, const uint32_t *urow_a, const uint32_t *urow_b,
                                    const tdc_res_t *res, uint8_t *dst, tdc_trm_reduced_counts_t *n);
/* Vertical pass of D: out[i] = (sum_t w[t] rows[t][i] + 2^14) >> 15 for
 * i < n (weights Q15 summing to 32768, values code Q8). */
typedef void tdc_trm_dvert_fn(const uint16_t *const *rows, const uint16_t *w, uint32_t taps, uint32_t n, uint16_t *out);

/* Horizontal pass of D over one full-res row of codes (width pixels, RGB):
 * for each reduced column j < rw the kernel first[j] .. first[j] + taps - 1
 * (clamped to the row) with weights w[j * taps + t] (Q15, summing to 32768);
 * dst gets rw x 3 values in code Q8.  The AVX2 version may read the weight
 * table 2 bytes past its end (the arena keeps more after it). */
typedef void tdc_trm_dhoriz_fn(const uint8_t *row, uint32_t width, const int16_t *first, const uint16_t *w,
                               uint32_t taps, uint32_t rw, uint16_t *dst);

/* U's vertical lerp of two reduced rows (n values, code Q8 or 8-bit codes)
 * at fraction f (Q14): dst = a 2^14 + (b - a) f in code Q22, exact. */
typedef void tdc_trm_uvert_fn(const uint16_t *a, const uint16_t *b, uint32_t f, uint32_t n, uint32_t *dst);
typedef void tdc_trm_uvert_codes_fn(const uint8_t *a, const uint8_t *b, uint32_t f, uint32_t n, uint32_t *dst);
tdc_trm_uvert_fn tdc_trm_uvert_c, tdc_trm_uvert_avx2;
tdc_trm_uvert_codes_fn tdc_trm_uvert_codes_c, tdc_trm_uvert_codes_avx2;

tdc_trm_full_row_fn tdc_trm_full_row_c;
/* Helium (MVE) row kernels, Cortex-M55 boards (tdc_trm_mve.c; BOARD_MVE). */
tdc_trm_full_row_fn tdc_trm_full_row_mve;
tdc_trm_reduced_row_fn tdc_trm_reduced_row_mve;
tdc_trm_dvert_fn tdc_trm_dvert_mve;
tdc_trm_dhoriz_fn tdc_trm_dhoriz_mve;
/* AArch64 Advanced SIMD (NEON) D passes, every AArch64 build: NEON is in
 * the ARMv8-A base (tdc_trm_neon.c; the rows stay C there, see that file). */
#if defined(__aarch64__) && defined(__ARM_NEON) && !defined(TDC_NO_SIMD)
#define TDC_TRM_NEON 1
#endif
tdc_trm_dvert_fn tdc_trm_dvert_neon;
tdc_trm_dhoriz_fn tdc_trm_dhoriz_neon;
/* What a board runs for the rows and D passes (AVX2 on hosts is chosen at
 * run time). */
#if defined(TDC_TRM_MVE)
#define TDC_TRM_FULL_ROW_BOARD tdc_trm_full_row_mve
#define TDC_TRM_REDUCED_ROW_BOARD tdc_trm_reduced_row_mve
#define TDC_TRM_DVERT_BOARD tdc_trm_dvert_mve
#define TDC_TRM_DHORIZ_BOARD tdc_trm_dhoriz_mve
#elif defined(TDC_TRM_NEON)
#define TDC_TRM_FULL_ROW_BOARD tdc_trm_full_row_c
#define TDC_TRM_REDUCED_ROW_BOARD tdc_trm_reduced_row_c
#define TDC_TRM_DVERT_BOARD tdc_trm_dvert_neon
#define TDC_TRM_DHORIZ_BOARD tdc_trm_dhoriz_neon
#else
#define TDC_TRM_FULL_ROW_BOARD tdc_trm_full_row_c
#define TDC_TRM_REDUCED_ROW_BOARD tdc_trm_reduced_row_c
#define TDC_TRM_DVERT_BOARD tdc_trm_dvert_c
#define TDC_TRM_DHORIZ_BOARD tdc_trm_dhoriz_c
#endif
tdc_trm_dhoriz_fn tdc_trm_dhoriz_c;
tdc_trm_reduced_row_fn tdc_trm_reduced_row_c;
tdc_trm_dvert_fn tdc_trm_dvert_c;

/* 1 when this build has the AVX2 kernels and the CPU runs them. */
int tdc_trm_avx2_available(void);
/* Fills 3 x TDC_TRM_ENC_COMB bytes (+ 8 of padding) for the AVX2 encode;
 * returns 1 when every bucket holds at most one threshold. */
int tdc_trm_avx2_build_encode(const tdc_panel_t *panel, uint8_t *comb);
tdc_trm_full_row_fn tdc_trm_full_row_avx2;
/* rho and the counts of tdc_trm_full_row_avx2, the codes in dst only for the
 * pixels after the last 16-pixel block (the recompute of rho discards them) */
tdc_trm_full_row_fn tdc_trm_rho_row_avx2;
tdc_trm_dhoriz_fn tdc_trm_dhoriz_avx2;
tdc_trm_reduced_row_fn tdc_trm_reduced_row_avx2;
tdc_trm_dvert_fn tdc_trm_dvert_avx2;

/* The context of the pixels [x, width) of a row: the SIMD kernels run the
 * C kernel on the tail of a row that does not fill a vector. */
static inline tdc_trm_rowctx_t tdc_trm_tail_ctx(const tdc_trm_rowctx_t *k, uint32_t x)
{
    tdc_trm_rowctx_t t = *k;
    t.ux = k->ux + 2u * x;
    t.width = k->width - x;
    return t;
}

/*
 * w = exp(-x), x in Q16, from the Q30 table with linear interpolation and
 * one rounding to Q15.  Error: 0.5 LSB rounding plus the interpolation's
 * (1/256)^2 / 8 * 32768 = 0.06 LSB (asserted <= 0.6 in tests/unit/test_trm.c).
 * Beyond x = 17, exp(-x) < 2^-24: 0.
 */
static inline int32_t tdc_trm_weight_q15(const uint32_t *wexp, uint64_t x_q16)
{
    if (x_q16 >= (uint64_t)(TDC_TRM_WEXP_ENTRIES - 1u) << 8) {
        return 0;
    }
    const uint32_t k = (uint32_t)(x_q16 >> 8), f = (uint32_t)(x_q16 & 255u);
    /* entries Q30, decreasing: a - (a - b) f / 256, then one rounding to
     * Q15; (a - b) < 2^23 times f < 2^8 fits 32 bits */
    const uint32_t a = wexp[k], b = wexp[k + 1u];
    const uint32_t v = a - (((a - b) * f) >> 8);
    return (int32_t)((v + (1u << 14)) >> 15);
}

/*
 * The motion weight of one pixel-channel that moved: c = |A - B| / (A + B)
 * in Q30 (A, B linear light Q24, A + B <= 2^25; s multiplies its error, so
 * Q15 is not enough), s c in Q16 (Q8 * Q30 -> Q38, rounded; s_q8 < 2^32
 * keeps it < 2^62), w = exp(-s c) in Q15.
 */
static inline int32_t tdc_trm_motion_weight_q15(const tdc_trm_rowctx_t *k, tdc_lin_t a, tdc_lin_t b)
{
    const uint32_t diff = (uint32_t)tdc_abs32(a - b);
    const int32_t c_q30 = tdc_div_q30(diff, (uint32_t)a + (uint32_t)b);
    const uint64_t sc = tdc_urshr64((uint64_t)k->s_q8 * (uint32_t)c_q30, 22); /* Q8 * Q30 -> Q16 */
    return tdc_trm_weight_q15(k->wexp, sc);
}

/* Gaze-aware TRM (tdc_trm_gaze.c): whether row y has a tile with k < 1,
 * and the full row with beta = I + k (I - U D I) (C only: it runs only
 * where the eye does not track the content). */
struct tdc_trm_gaze; /* tdc_trm.h */
int tdc_trm_gaze_row_active(const struct tdc_trm_gaze *g, uint32_t y);
void tdc_trm_gaze_full_row(const tdc_trm_rowctx_t *k, const struct tdc_trm_gaze *g, uint32_t y, const uint32_t *urow,
                           const uint8_t *src, uint8_t *dst, tdc_res_t *res, tdc_trm_full_counts_t *n);

/* ---- per-pixel helpers of the C row kernels (tdc_trm_rows.c) and the
 * gaze-aware full row (tdc_trm_gaze.c): one definition ---- */

/* Horizontal lerp of a vertically interpolated row (code Q22) between
 * samples i and i + 3 (the next pixel, same channel): code Q16.
 * Scaling: |v1 - v0| < 2^30 times f < 2^14 needs 64 bits; rounded once. */
static inline uint32_t tdc_trm_hlerp(const uint32_t *restrict urow, uint32_t i, uint32_t f_q14)
{
    const int64_t v0 = urow[i], v1 = urow[i + 3u];
    return (uint32_t)tdc_rshr_round64(v0 * (1 << 14) + (v1 - v0) * (int64_t)f_q14, 20);
}

/* One channel's gamma tables as restrict-qualified locals: the byte stores
 * of the output frame may alias anything, so without these the compiler
 * reloads every table pointer after each store. */
typedef struct {
    const uint32_t *restrict dec;
    const uint32_t *restrict thr;
    const uint16_t *restrict idx;
} tdc_trm_gamma_t;

static inline void tdc_trm_gamma_locals(const tdc_trm_rowctx_t *k, tdc_trm_gamma_t g[3])
{
    for (int c = 0; c < 3; c++) {
        g[c].dec = k->dec[c];
        g[c].thr = k->thr[c];
        g[c].idx = k->idx[c];
    }
}

/* As tdc_gamma_decode_q16. */
static inline tdc_lin_t tdc_trm_dec_q16(const tdc_trm_gamma_t *g, uint32_t g_q16)
{
    const uint32_t k = g_q16 >> 16, f = (g_q16 >> 4) & 0xfffu;
    const uint32_t a = g->dec[k], b = g->dec[k + 1u];
    return (tdc_lin_t)(a + (((b - a) * f + 0x800u) >> 12));
}

/* As tdc_gamma_encode; lin already clamped to [0, 2^24] by the caller. */
static inline uint32_t tdc_trm_enc(const tdc_trm_gamma_t *g, int32_t lin)
{
    uint32_t k = g->idx[(uint32_t)lin >> (TDC_LIN_FRAC - TDC_ENC_INDEX_BITS)];
    while (k < 255u && (uint32_t)lin >= g->thr[k + 1u]) {
        k++;
    }
    return k;
}

/* One pixel-channel of a full row from its beta (Q24, in [-1, 2]): shown =
 * clamp(beta, 0, 1) encoded into *dst, rho = beta - shown into *res,
 * clamps counted. */
static inline void tdc_trm_put_beta(const tdc_trm_gamma_t *g, int32_t beta, tdc_res_t *res, uint8_t *dst, uint32_t *nhi,
                                    uint32_t *nlo)
{
    int32_t shown = beta;
    if (beta > TDC_LIN_ONE) {
        shown = TDC_LIN_ONE;
        (*nhi)++;
    } else if (beta < 0) {
        shown = 0;
        (*nlo)++;
    }
    *res = beta - shown; /* rho, Q24 (see tdc_res_t) */
    *dst = (uint8_t)tdc_trm_enc(g, shown);
}

#endif /* TDC_TRM_KERNELS_H */
