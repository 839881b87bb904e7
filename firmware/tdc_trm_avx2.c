/*
 * tdc_trm_avx2.c - TRM's row kernels with x86-64 AVX2 integer SIMD, for
 * host builds.  They produce the same bytes as the portable C kernels in
 * tdc_trm_rows.c (tests/checkasm/checkasm_trm.c checks that and benchmarks both;
 * the golden vectors run through them on any AVX2 host).
 *
 * Layout: 8 consecutive pixels per step, one vector per colour channel, so
 * every lane of a vector uses the same channel's gamma tables (gathers with
 * one base).  Interleaved RGB inputs are read with gathers (stride 3);
 * outputs are re-interleaved with permutes and blends.  Integer only: the
 * object is checked for floating-point instructions by
 * tests/check_simd_nofloat.sh.  Other targets get 0 from
 * tdc_trm_avx2_available() and the C kernels behind the AVX2 names.
 *
 * Exactness notes (why 32-bit lanes give the C path's 64-bit results):
 *  - hlerp: C computes floor((v0 2^14 + (v1 - v0) f + 2^19) / 2^20) in 64
 *    bits.  With d = v1 - v0 = dh 2^14 + dl (dl in [0, 2^14)) and
 *    X = v0 + dh f = Xh 2^6 + Xl (Xl in [0, 64)), the sum is
 *    Xh 2^20 + Z with Z = Xl 2^14 + dl f + 2^19 in [0, 2^29): the result is
 *    Xh + (Z >> 20).  |dh f| < 2^30 and v0 < 2^30 keep X in int32.
 *  - alpha + round(w rho / 2^15): with rho = rh 2^15 + rl (rl in
 *    [0, 2^15)), floor((w rho + 2^14) / 2^15) = w rh + ((w rl + 2^14) >> 15);
 *    w <= 2^15, |rho| <= 2^24 keep both products in int32.
 *  - encode: the forward scan over thresholds finds the largest k with
 *    thr[k] <= L from any start k0 with thr[k0] <= L, so a finer index
 *    than the panel's (64-wide buckets below L = 2^16, where the dark codes
 *    crowd) gives the same code; with at most one threshold per bucket
 *    (checked when the index is built) one compare replaces the scan and
 *    its data-dependent branch, which stalled the gathers behind it.
 *  - the motion weight's division: the reciprocal by the Newton steps of
 *    tdc_recip_norm_q30_newton in 64-bit lanes, corrected and checked
 *    against its defining inequality (trm_recip4), so it is the exact
 *    floor the C path gets from a divide instruction.
 */
#include "tdc_trm.h" /* TDC_TRM_MAX_TAPS */
#include "tdc_trm_kernels.h"

/* Portable C: builds the AVX2 kernels' encode index (tdc_trm_kernels.h). */
int tdc_trm_avx2_build_encode(const tdc_panel_t *panel, uint8_t *comb)
{
    int one_step = 1;
    for (uint32_t c = 0; c < 3u; c++) {
        const uint32_t *thr = panel->gamma[c].enc_thresh;
        uint8_t *t = comb + (size_t)c * TDC_TRM_ENC_COMB;
        uint32_t k = 0;
        for (uint32_t i = 0; i < TDC_TRM_ENC_COMB; i++) {
            const uint32_t lo = i < 1024u ? i << 6 : (i - 1008u) << 12;
            const uint32_t hi = i < 1024u ? lo + 63u : lo + 4095u;
            while (k < 255u && thr[k + 1u] <= lo) {
                k++;
            }
            t[i] = (uint8_t)k;
            uint32_t inside = 0; /* thresholds in (lo, hi] */
            for (uint32_t j = k + 1u; j <= 255u && thr[j] <= hi; j++) {
                inside++;
            }
            if (inside > 1u) {
                one_step = 0;
            }
        }
    }
    for (uint32_t i = 3u * TDC_TRM_ENC_COMB; i < 3u * TDC_TRM_ENC_COMB + 8u; i++) {
        comb[i] = 0; /* read, never used, by the 32-bit gathers */
    }
    return one_step;
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(TDC_NO_SIMD)

#include <immintrin.h>

#define TDC_AVX2 __attribute__((target("avx2,popcnt")))

int tdc_trm_avx2_available(void)
{
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt");
}

/* Horizontal lerp (see the header comment): 8 pixels of one channel. */
static inline TDC_AVX2 __m256i trm_hlerp8(const uint32_t *urow, __m256i i0, __m256i f)
{
    const __m256i v0 = _mm256_i32gather_epi32((const int *)urow, i0, 4);
    const __m256i v1 = _mm256_i32gather_epi32((const int *)(urow + 3), i0, 4);
    const __m256i d = _mm256_sub_epi32(v1, v0);
    const __m256i dh = _mm256_srai_epi32(d, 14);
    const __m256i dl = _mm256_and_si256(d, _mm256_set1_epi32(0x3fff));
    const __m256i x = _mm256_add_epi32(v0, _mm256_mullo_epi32(dh, f));
    const __m256i xh = _mm256_srai_epi32(x, 6);
    const __m256i xl = _mm256_and_si256(x, _mm256_set1_epi32(63));
    const __m256i z = _mm256_add_epi32(_mm256_add_epi32(_mm256_slli_epi32(xl, 14), _mm256_mullo_epi32(dl, f)),
                                       _mm256_set1_epi32(1 << 19));
    return _mm256_add_epi32(xh, _mm256_srli_epi32(z, 20));
}

/* Gamma decode of code Q16 (as tdc_gamma_decode_q16); (b - a) f < 2^31. */
static inline TDC_AVX2 __m256i trm_dec8(const uint32_t *dec, __m256i g)
{
    const __m256i k = _mm256_srli_epi32(g, 16);
    const __m256i f = _mm256_and_si256(_mm256_srli_epi32(g, 4), _mm256_set1_epi32(0xfff));
    const __m256i a = _mm256_i32gather_epi32((const int *)dec, k, 4);
    const __m256i b = _mm256_i32gather_epi32((const int *)(dec + 1), k, 4);
    const __m256i step = _mm256_add_epi32(_mm256_mullo_epi32(_mm256_sub_epi32(b, a), f), _mm256_set1_epi32(0x800));
    return _mm256_add_epi32(a, _mm256_srli_epi32(step, 12));
}

/* Gamma encode of L in [0, 2^24] (as tdc_gamma_encode), 8 lanes at a time:
 * a start code from the combined index (tdc_trm_avx2_build_encode) ... */
static inline TDC_AVX2 __m256i trm_enc_start(const uint8_t *comb, __m256i l)
{
    const __m256i fine = _mm256_cmpgt_epi32(_mm256_set1_epi32(1 << 16), l);
    const __m256i i = _mm256_blendv_epi8(_mm256_add_epi32(_mm256_srli_epi32(l, 12), _mm256_set1_epi32(1008)),
                                         _mm256_srli_epi32(l, 6), fine);
    return _mm256_and_si256(_mm256_i32gather_epi32((const int *)(const void *)comb, i, 1), _mm256_set1_epi32(0xff));
}

/* ... then forward steps: k + 1 where k < 255 and L >= thr[k + 1]; *adv
 * gets the lanes that moved. */
static inline TDC_AVX2 __m256i trm_enc_step(const uint32_t *thr, __m256i k, __m256i l, __m256i *adv)
{
    const __m256i top = _mm256_set1_epi32(255);
    const __m256i t =
        _mm256_i32gather_epi32((const int *)thr, _mm256_min_epi32(_mm256_add_epi32(k, _mm256_set1_epi32(1)), top), 4);
    *adv = _mm256_andnot_si256(_mm256_cmpgt_epi32(t, l), _mm256_cmpgt_epi32(top, k));
    return _mm256_sub_epi32(k, *adv);
}

/* Encode of N vectors (entry e holds channel e % 3): the index gathers of
 * all, then one threshold step of all, so the gathers overlap; further
 * steps only for a panel whose index has a bucket with two thresholds. */
#define TRM_ENC_MAX 6
static inline TDC_AVX2 void trm_enc8xn(const tdc_trm_rowctx_t *k, const __m256i *l, __m256i *code, int n)
{
    __m256i kk[TRM_ENC_MAX], adv[TRM_ENC_MAX];
#pragma GCC unroll 6
    for (int e = 0; e < n; e++) {
        kk[e] = trm_enc_start(k->enc_comb[e % 3], l[e]);
    }
#pragma GCC unroll 6
    for (int e = 0; e < n; e++) {
        kk[e] = trm_enc_step(k->thr[e % 3], kk[e], l[e], &adv[e]);
    }
    if (!k->enc_one_step) {
        for (int e = 0; e < n; e++) {
            while (!_mm256_testz_si256(adv[e], adv[e])) {
                kk[e] = trm_enc_step(k->thr[e % 3], kk[e], l[e], &adv[e]);
            }
        }
    }
#pragma GCC unroll 6
    for (int e = 0; e < n; e++) {
        code[e] = kk[e];
    }
}

/*
 * The reciprocal floor((2^62 + floor(d/2)) / d) of tdc_recip_norm_q30 for
 * the normalised d (in [2^31, 2^32)) in the low half of each 64-bit lane:
 * the Newton steps of tdc_recip_norm_q30_newton in 64-bit lanes, then two
 * correction steps each way and a check of the defining inequality
 * x d <= 2^62 + floor(d/2) < (x + 1) d.  *ok is cleared when a lane fails
 * the check (never seen; the caller then uses the scalar path).  d is in
 * the low half of each lane with the high half zero, so "and with a mask,
 * then subtract" subtracts d itself.
 * Ranges: x stays in (2^30, 2^32), so every product is an unsigned 32 x 32
 * multiply below 2^63 and the signed 64-bit compares are exact.
 */
static inline TDC_AVX2 __m256i trm_recip4(__m256i d, int *ok)
{
    const __m256i zero = _mm256_setzero_si256();
    __m256i x = _mm256_sub_epi64(_mm256_set1_epi64x(3031741621LL),
                                 _mm256_srli_epi64(_mm256_mul_epu32(_mm256_set1_epi64x(2021161081LL), d), 32));
    for (int it = 0; it < 3; it++) {
        /* e = 1 - d x in Q30 (signed, small); x += floor(x e / 2^30) */
        const __m256i e =
            _mm256_sub_epi64(_mm256_set1_epi64x(1LL << 30), _mm256_srli_epi64(_mm256_mul_epu32(d, x), 32));
        const __m256i neg = _mm256_cmpgt_epi64(zero, e);
        const __m256i prod = _mm256_mul_epu32(x, _mm256_blendv_epi8(e, _mm256_sub_epi64(zero, e), neg));
        const __m256i up = _mm256_srli_epi64(prod, 30);
        const __m256i down =
            _mm256_sub_epi64(zero, _mm256_srli_epi64(_mm256_add_epi64(prod, _mm256_set1_epi64x((1LL << 30) - 1)), 30));
        x = _mm256_add_epi64(x, _mm256_blendv_epi8(up, down, neg));
    }
    const __m256i t = _mm256_add_epi64(_mm256_set1_epi64x(1LL << 62), _mm256_srli_epi64(d, 1));
    /* After the Newton steps x - floor is in {-1, 0, 1, 2} for every d in
     * [2^31, 2^32) (checked exhaustively, all 2^31 values, when this was
     * written): two steps down, one up, keeping p = x d by adding or
     * subtracting d instead of multiplying again; then the check, so the
     * scalar fallback is a safety net that is never taken. */
    __m256i p = _mm256_mul_epu32(x, d);
    for (int i = 0; i < 2; i++) {
        const __m256i over = _mm256_cmpgt_epi64(p, t); /* x d > t: x - 1 */
        x = _mm256_add_epi64(x, over);
        p = _mm256_sub_epi64(p, _mm256_and_si256(over, d));
    }
    const __m256i q = _mm256_add_epi64(p, d);
    const __m256i up = _mm256_xor_si256(_mm256_cmpgt_epi64(q, t), _mm256_set1_epi32(-1)); /* (x + 1) d <= t */
    x = _mm256_sub_epi64(x, up);
    p = _mm256_blendv_epi8(p, q, up);
    const __m256i bad =
        _mm256_or_si256(_mm256_cmpgt_epi64(p, t),
                        _mm256_xor_si256(_mm256_cmpgt_epi64(_mm256_add_epi64(p, d), t), _mm256_set1_epi32(-1)));
    if (!_mm256_testz_si256(bad, bad)) {
        *ok = 0;
    }
    return x;
}

/* 8 lanes of 32-bit values -> the even lanes and the odd lanes, each in
 * the low half of a 64-bit lane, and back. */
static inline TDC_AVX2 __m256i trm_even(__m256i v)
{
    return _mm256_and_si256(v, _mm256_set1_epi64x(0xffffffffLL));
}
static inline TDC_AVX2 __m256i trm_odd(__m256i v)
{
    return _mm256_srli_epi64(v, 32);
}
static inline TDC_AVX2 __m256i trm_join(__m256i even, __m256i odd)
{
    return _mm256_blend_epi32(even, _mm256_slli_epi64(odd, 32), 0xaa);
}

/*
 * w = exp(-s |a - b| / (a + b)) in Q15 for 8 lanes: exactly
 * tdc_trm_motion_weight_q15 (tdc_div_q30, the Q16 product with s, the exp
 * table), with the division as above.  *ok as trm_recip4.
 */
static inline TDC_AVX2 __m256i trm_motion_weight8(const tdc_trm_rowctx_t *k, __m256i a, __m256i b, int *ok)
{
    const __m256i zero = _mm256_setzero_si256();
    const __m256i diff = _mm256_abs_epi32(_mm256_sub_epi32(a, b));
    const __m256i den = _mm256_add_epi32(a, b);
    const __m256i den0 = _mm256_cmpeq_epi32(den, zero);
    const __m256i whole = _mm256_cmpgt_epi32(_mm256_add_epi32(diff, _mm256_set1_epi32(1)), den); /* diff >= den */
    /* normalise: shift = clz(den), dn = den << shift; den 0 gets any valid dn */
    __m256i dn = _mm256_blendv_epi8(den, _mm256_set1_epi32(1), den0), sh = zero;
    static const int steps[5] = {16, 8, 4, 2, 1};
    for (int i = 0; i < 5; i++) {
        const __m256i top = _mm256_srlv_epi32(dn, _mm256_set1_epi32(32 - steps[i]));
        const __m256i m = _mm256_cmpeq_epi32(top, zero);
        sh = _mm256_add_epi32(sh, _mm256_and_si256(m, _mm256_set1_epi32(steps[i])));
        dn = _mm256_blendv_epi8(dn, _mm256_sllv_epi32(dn, _mm256_set1_epi32(steps[i])), m);
    }
    const __m256i num = _mm256_sllv_epi32(diff, sh); /* diff < den: < 2^32 */
    const __m256i round31 = _mm256_set1_epi64x(1LL << 31);
    const __m256i ce =
        _mm256_srli_epi64(_mm256_add_epi64(_mm256_mul_epu32(trm_even(num), trm_recip4(trm_even(dn), ok)), round31), 32);
    const __m256i co =
        _mm256_srli_epi64(_mm256_add_epi64(_mm256_mul_epu32(trm_odd(num), trm_recip4(trm_odd(dn), ok)), round31), 32);
    __m256i c = trm_join(ce, co); /* Q30 */
    c = _mm256_blendv_epi8(c, _mm256_set1_epi32(1 << 30), whole);
    c = _mm256_andnot_si256(den0, c);
    /* s c: Q8 x Q30 -> Q16, rounded, in 64 bits; beyond the table w = 0 */
    const __m256i s = _mm256_set1_epi64x((long long)k->s_q8);
    const __m256i round21 = _mm256_set1_epi64x(1LL << 21),
                  last = _mm256_set1_epi64x(((long long)TDC_TRM_WEXP_ENTRIES - 1) * 256 - 1);
    const __m256i se = _mm256_srli_epi64(_mm256_add_epi64(_mm256_mul_epu32(s, trm_even(c)), round21), 22);
    const __m256i so = _mm256_srli_epi64(_mm256_add_epi64(_mm256_mul_epu32(s, trm_odd(c)), round21), 22);
    const __m256i bige = _mm256_cmpgt_epi64(se, last), bigo = _mm256_cmpgt_epi64(so, last);
    const __m256i big = _mm256_blend_epi32(bige, bigo, 0xaa);
    const __m256i sc = trm_join(_mm256_andnot_si256(bige, se), _mm256_andnot_si256(bigo, so)); /* < 2^21 */
    const __m256i kk = _mm256_srli_epi32(sc, 8), f = _mm256_and_si256(sc, _mm256_set1_epi32(255));
    const __m256i wa = _mm256_i32gather_epi32((const int *)k->wexp, kk, 4);
    const __m256i wb = _mm256_i32gather_epi32((const int *)(k->wexp + 1), kk, 4);
    const __m256i v = _mm256_sub_epi32(wa, _mm256_srli_epi32(_mm256_mullo_epi32(_mm256_sub_epi32(wa, wb), f), 8));
    return _mm256_andnot_si256(big, _mm256_srli_epi32(_mm256_add_epi32(v, _mm256_set1_epi32(1 << 14)), 15));
}

/* Lanes set in a compare mask. */
static inline TDC_AVX2 uint32_t trm_count8(__m256i m)
{
    return (uint32_t)_mm_popcnt_u32((uint32_t)_mm256_movemask_epi8(m)) / 4u;
}

/* (R0..R7, G0..G7, B0..B7) -> R0 G0 B0 R1 ... B7 in three vectors. */
static inline TDC_AVX2 void trm_interleave3(__m256i r, __m256i g, __m256i b, __m256i o[3])
{
    const __m256i p0 = _mm256_setr_epi32(0, 0, 0, 1, 1, 1, 2, 2);
    const __m256i p1 = _mm256_setr_epi32(2, 3, 3, 3, 4, 4, 4, 5);
    const __m256i p2 = _mm256_setr_epi32(5, 5, 6, 6, 6, 7, 7, 7);
    o[0] = _mm256_blend_epi32(
        _mm256_blend_epi32(_mm256_permutevar8x32_epi32(r, p0), _mm256_permutevar8x32_epi32(g, p0), 0x92),
        _mm256_permutevar8x32_epi32(b, p0), 0x24);
    o[1] = _mm256_blend_epi32(
        _mm256_blend_epi32(_mm256_permutevar8x32_epi32(r, p1), _mm256_permutevar8x32_epi32(g, p1), 0x24),
        _mm256_permutevar8x32_epi32(b, p1), 0x49);
    o[2] = _mm256_blend_epi32(
        _mm256_blend_epi32(_mm256_permutevar8x32_epi32(r, p2), _mm256_permutevar8x32_epi32(g, p2), 0x49),
        _mm256_permutevar8x32_epi32(b, p2), 0x92);
}

/* Codes (0..255 in 32-bit lanes, one vector per channel) -> 24 RGB bytes. */
static inline TDC_AVX2 void trm_store_codes(uint8_t *dst, __m256i r, __m256i g, __m256i b)
{
    __m256i o[3];
    trm_interleave3(r, g, b, o);
    const __m256i lowbytes = _mm256_setr_epi8(0, 4, 8, 12, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 0, 4, 8, 12,
                                              -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1);
    const __m256i gather2 = _mm256_setr_epi32(0, 4, 1, 1, 1, 1, 1, 1);
    for (int j = 0; j < 3; j++) {
        const __m256i p = _mm256_permutevar8x32_epi32(_mm256_shuffle_epi8(o[j], lowbytes), gather2);
        _mm_storel_epi64((__m128i *)(void *)(dst + 8 * j), _mm256_castsi256_si128(p));
    }
}

/* Per-step constants: reduced column * 3, fraction, pixel offsets * 3. */
typedef struct {
    __m256i i3, f, x3;
} trm_step_t;

static inline TDC_AVX2 trm_step_t trm_step(const tdc_trm_rowctx_t *k, uint32_t x)
{
    trm_step_t s;
    const __m256i uxv = _mm256_loadu_si256((const __m256i *)(const void *)(k->ux + 2u * x));
    const __m256i ui = _mm256_and_si256(uxv, _mm256_set1_epi32(0xffff));
    s.i3 = _mm256_add_epi32(_mm256_add_epi32(ui, ui), ui);
    s.f = _mm256_srli_epi32(uxv, 16);
    s.x3 = _mm256_add_epi32(_mm256_set1_epi32((int)(3u * x)), _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21));
    return s;
}

/* The full row; codes = 0: rho and the counts only (dst written only by the
 * C tail), the recompute of rho for a reduced frame, which discards the
 * codes: the encode is 12 of the 48 gathers of a 16-pixel step. */
static inline __attribute__((always_inline)) TDC_AVX2 void trm_full_row(const tdc_trm_rowctx_t *k, const uint32_t *urow,
                                                                        const uint8_t *src, uint8_t *dst, tdc_res_t *res,
                                                                        tdc_trm_full_counts_t *n, const int codes)
{
    const __m256i one = _mm256_set1_epi32(TDC_LIN_ONE), zero = _mm256_setzero_si256();
    uint32_t x = 0, nhi = 0, nlo = 0;
    /* 16 pixels per step, in phases over the 6 (block, channel) vectors so
     * that each phase's gathers are independent and overlap: a gather's
     * latency (~20 cycles) chained four deep per channel is what bounds this
     * loop.  The byte gathers read 3 bytes past a pixel-channel: keep one
     * pixel after the last vector for the C tail.  Entry e = 3 block + c. */
    for (; x + 17u <= k->width; x += 16u) {
        const trm_step_t s0 = trm_step(k, x), s1 = trm_step(k, x + 8u);
        __m256i ui[6], in[6], g[6], lu[6], li[6], shown[6], code[6], rho[6];
#pragma GCC unroll 6
        for (int e = 0; e < 6; e++) {
            const trm_step_t *s = e < 3 ? &s0 : &s1;
            ui[e] = _mm256_add_epi32(s->i3, _mm256_set1_epi32(e % 3));
            in[e] = _mm256_and_si256(_mm256_i32gather_epi32((const int *)(const void *)src,
                                                            _mm256_add_epi32(s->x3, _mm256_set1_epi32(e % 3)), 1),
                                     _mm256_set1_epi32(0xff));
        }
#pragma GCC unroll 6
        for (int e = 0; e < 6; e++) {
            g[e] = trm_hlerp8(urow, ui[e], e < 3 ? s0.f : s1.f);
            li[e] = _mm256_i32gather_epi32((const int *)k->dec[e % 3], in[e], 4);
        }
#pragma GCC unroll 6
        for (int e = 0; e < 6; e++) {
            lu[e] = trm_dec8(k->dec[e % 3], g[e]);
        }
#pragma GCC unroll 6
        for (int e = 0; e < 6; e++) {
            const __m256i beta = _mm256_sub_epi32(_mm256_add_epi32(li[e], li[e]), lu[e]);
            shown[e] = _mm256_min_epi32(_mm256_max_epi32(beta, zero), one);
            nhi += trm_count8(_mm256_cmpgt_epi32(beta, one));
            nlo += trm_count8(_mm256_cmpgt_epi32(zero, beta));
            rho[e] = _mm256_sub_epi32(beta, shown[e]);
        }
        if (codes) {
            trm_enc8xn(k, shown, code, 6);
        }
        for (int b = 0; b < 2; b++) {
            __m256i o[3];
            trm_interleave3(rho[3 * b], rho[3 * b + 1], rho[3 * b + 2], o);
            for (int j = 0; j < 3; j++) {
                _mm256_storeu_si256((__m256i *)(void *)(res + 3u * x + 24u * (uint32_t)b + 8u * (uint32_t)j), o[j]);
            }
            if (codes) {
                trm_store_codes(dst + 3u * x + 24u * (uint32_t)b, code[3 * b], code[3 * b + 1], code[3 * b + 2]);
            }
        }
    }
    n->hi += nhi;
    n->lo += nlo;
    if (x < k->width) {
        const tdc_trm_rowctx_t t = tdc_trm_tail_ctx(k, x);
        tdc_trm_full_row_c(&t, urow, src + 3u * x, dst + 3u * x, res + 3u * x, n);
    }
}

TDC_AVX2 void tdc_trm_full_row_avx2(const tdc_trm_rowctx_t *k, const uint32_t *urow, const uint8_t *src, uint8_t *dst,
                                    tdc_res_t *res, tdc_trm_full_counts_t *n)
{
    trm_full_row(k, urow, src, dst, res, n, 1);
}

TDC_AVX2 void tdc_trm_rho_row_avx2(const tdc_trm_rowctx_t *k, const uint32_t *urow, const uint8_t *src, uint8_t *dst,
                                   tdc_res_t *res, tdc_trm_full_counts_t *n)
{
    trm_full_row(k, urow, src, dst, res, n, 0);
}

TDC_AVX2 void tdc_trm_reduced_row_avx2(const tdc_trm_rowctx_t *k, const uint32_t *urow_a, const uint32_t *urow_b,
                                       const tdc_res_t *res, uint8_t *dst, tdc_trm_reduced_counts_t *n)
{
    const __m256i one = _mm256_set1_epi32(TDC_LIN_ONE), zero = _mm256_setzero_si256();
    const __m256i half = _mm256_set1_epi32(1 << 15); /* half a code in code Q16 */
    uint32_t x = 0, computed = 0, skipped = 0, no_res = 0;
    /* in phases over the channels, as the full row */
    for (; x + 8u <= k->width; x += 8u) {
        const trm_step_t s = trm_step(k, x);
        __m256i ui[3], gb[3], alpha[3], rho[3], has[3], shown[3], code[3];
        uint32_t nhas = 0;
#pragma GCC unroll 3
        for (int c = 0; c < 3; c++) {
            ui[c] = _mm256_add_epi32(s.i3, _mm256_set1_epi32(c));
            gb[c] = trm_hlerp8(urow_b, ui[c], s.f);
            rho[c] = _mm256_i32gather_epi32((const int *)res, _mm256_add_epi32(s.x3, _mm256_set1_epi32(c)), 4);
        }
#pragma GCC unroll 3
        for (int c = 0; c < 3; c++) {
            alpha[c] = trm_dec8(k->dec[c], gb[c]);
            has[c] = _mm256_xor_si256(_mm256_cmpeq_epi32(rho[c], zero), _mm256_set1_epi32(-1));
            nhas += trm_count8(has[c]);
            shown[c] = alpha[c];
        }
        no_res += 24u - nhas;
        if (nhas != 0u) {
            __m256i ga[3], gs[3], still[3], moved[3], w[3];
            uint32_t nmoved = 0;
#pragma GCC unroll 3
            for (int c = 0; c < 3; c++) {
                ga[c] = trm_hlerp8(urow_a, ui[c], s.f);
            }
#pragma GCC unroll 3
            for (int c = 0; c < 3; c++) {
                /* motion test at the link's precision (tdc_trm_rows.c) */
                const __m256i gt = _mm256_cmpgt_epi32(ga[c], _mm256_add_epi32(gb[c], half));
                const __m256i lt = _mm256_cmpgt_epi32(gb[c], _mm256_add_epi32(ga[c], half));
                gs[c] = _mm256_blendv_epi8(gb[c], _mm256_sub_epi32(ga[c], half), gt);
                gs[c] = _mm256_blendv_epi8(gs[c], _mm256_add_epi32(ga[c], half), lt);
                const __m256i eq = _mm256_cmpeq_epi32(gs[c], gb[c]);
                still[c] = _mm256_and_si256(has[c], eq);
                moved[c] = _mm256_andnot_si256(eq, has[c]);
                w[c] = _mm256_and_si256(still[c], _mm256_set1_epi32(32768));
                skipped += trm_count8(still[c]);
                nmoved += trm_count8(moved[c]);
            }
            if (nmoved != 0u) {
                computed += nmoved;
                /* w = exp(-s c) of the lanes that moved: a division each,
                 * in scalar C through the C kernel's own function */
                __m256i la[3];
#pragma GCC unroll 3
                for (int c = 0; c < 3; c++) {
                    la[c] = trm_dec8(k->dec[c], gs[c]);
                }
                /* all three channels together (their Newton chains
                 * overlap), lanes that did not move are dropped after */
                int ok = 1;
                __m256i wm[3];
#pragma GCC unroll 3
                for (int c = 0; c < 3; c++) {
                    wm[c] = trm_motion_weight8(k, la[c], alpha[c], &ok);
                }
                if (!ok) {
                    /* a vector reciprocal missed its bound: scalar */
                    for (int c = 0; c < 3; c++) {
                        int32_t lav[8], alv[8], wl[8];
                        _mm256_storeu_si256((__m256i *)(void *)lav, la[c]);
                        _mm256_storeu_si256((__m256i *)(void *)alv, alpha[c]);
                        for (int l = 0; l < 8; l++) {
                            wl[l] = tdc_trm_motion_weight_q15(k, lav[l], alv[l]);
                        }
                        wm[c] = _mm256_loadu_si256((const __m256i *)(const void *)wl);
                    }
                }
#pragma GCC unroll 3
                for (int c = 0; c < 3; c++) {
                    w[c] = _mm256_blendv_epi8(w[c], wm[c], moved[c]);
                }
            }
#pragma GCC unroll 3
            for (int c = 0; c < 3; c++) {
                /* alpha + round(w rho / 2^15), split as in the header comment */
                const __m256i rh = _mm256_srai_epi32(rho[c], 15);
                const __m256i rl = _mm256_and_si256(rho[c], _mm256_set1_epi32(0x7fff));
                const __m256i lo =
                    _mm256_srli_epi32(_mm256_add_epi32(_mm256_mullo_epi32(w[c], rl), _mm256_set1_epi32(1 << 14)), 15);
                const __m256i v = _mm256_add_epi32(alpha[c], _mm256_add_epi32(_mm256_mullo_epi32(w[c], rh), lo));
                shown[c] = _mm256_min_epi32(_mm256_max_epi32(v, zero), one);
            }
        }
        trm_enc8xn(k, shown, code, 3);
        trm_store_codes(dst + 3u * x, code[0], code[1], code[2]);
    }
    n->computed += computed;
    n->skipped += skipped;
    n->no_res += no_res;
    if (x < k->width) {
        const tdc_trm_rowctx_t t = tdc_trm_tail_ctx(k, x);
        tdc_trm_reduced_row_c(&t, urow_a, urow_b, res + 3u * x, dst + 3u * x, n);
    }
}

/* U's vertical lerp, 8 values a step: the C kernel's int32 products. */
TDC_AVX2 void tdc_trm_uvert_avx2(const uint16_t *a, const uint16_t *b, uint32_t f, uint32_t n, uint32_t *dst)
{
    const __m256i fv = _mm256_set1_epi32((int)f);
    uint32_t i = 0;
    for (; i + 8u <= n; i += 8u) {
        const __m256i va = _mm256_cvtepu16_epi32(_mm_loadu_si128((const __m128i *)(const void *)(a + i)));
        const __m256i vb = _mm256_cvtepu16_epi32(_mm_loadu_si128((const __m128i *)(const void *)(b + i)));
        const __m256i v = _mm256_add_epi32(_mm256_slli_epi32(va, 14), _mm256_mullo_epi32(_mm256_sub_epi32(vb, va), fv));
        _mm256_storeu_si256((__m256i *)(void *)(dst + i), v);
    }
    tdc_trm_uvert_c(a + i, b + i, f, n - i, dst + i);
}

TDC_AVX2 void tdc_trm_uvert_codes_avx2(const uint8_t *a, const uint8_t *b, uint32_t f, uint32_t n, uint32_t *dst)
{
    const __m256i fv = _mm256_set1_epi32((int)f);
    uint32_t i = 0;
    for (; i + 8u <= n; i += 8u) {
        const __m256i va = _mm256_cvtepu8_epi32(_mm_loadl_epi64((const __m128i *)(const void *)(a + i)));
        const __m256i vb = _mm256_cvtepu8_epi32(_mm_loadl_epi64((const __m128i *)(const void *)(b + i)));
        const __m256i d = _mm256_slli_epi32(_mm256_mullo_epi32(_mm256_sub_epi32(vb, va), fv), 8);
        _mm256_storeu_si256((__m256i *)(void *)(dst + i), _mm256_add_epi32(_mm256_slli_epi32(va, 22), d));
    }
    tdc_trm_uvert_codes_c(a + i, b + i, f, n - i, dst + i);
}

TDC_AVX2 void tdc_trm_dvert_avx2(const uint16_t *const *rows, const uint16_t *w, uint32_t taps, uint32_t n,
                                 uint16_t *out)
{
    const __m256i bias = _mm256_set1_epi32(1 << 14);
    uint32_t i = 0;
    for (; i + 16u <= n; i += 16u) {
        __m256i a0 = _mm256_setzero_si256(), a1 = _mm256_setzero_si256();
        for (uint32_t t = 0; t < taps; t++) {
            const __m256i wt = _mm256_set1_epi32(w[t]);
            const __m256i v = _mm256_loadu_si256((const __m256i *)(const void *)(rows[t] + i));
            a0 = _mm256_add_epi32(a0, _mm256_mullo_epi32(wt, _mm256_cvtepu16_epi32(_mm256_castsi256_si128(v))));
            a1 = _mm256_add_epi32(a1, _mm256_mullo_epi32(wt, _mm256_cvtepu16_epi32(_mm256_extracti128_si256(v, 1))));
        }
        /* sums < 2^31 (tdc_trm_dvert_c): results <= 65280 pack unsaturated */
        a0 = _mm256_srli_epi32(_mm256_add_epi32(a0, bias), 15);
        a1 = _mm256_srli_epi32(_mm256_add_epi32(a1, bias), 15);
        const __m256i p = _mm256_permute4x64_epi64(_mm256_packus_epi32(a0, a1), 0xd8);
        _mm256_storeu_si256((__m256i *)(void *)(out + i), p);
    }
    if (i < n) {
        const uint16_t *tail[TDC_TRM_MAX_TAPS];
        for (uint32_t t = 0; t < taps; t++) {
            tail[t] = rows[t] + i;
        }
        tdc_trm_dvert_c(tail, w, taps, n - i, out + i);
    }
}

TDC_AVX2 void tdc_trm_dhoriz_avx2(const uint8_t *row, uint32_t width, const int16_t *first, const uint16_t *w,
                                  uint32_t taps, uint32_t rw, uint16_t *dst)
{
    /* 8 reduced columns per step; one 32-bit gather per tap reads a whole
     * pixel (R, G, B and the next byte), so the last tap must end one pixel
     * before the row does: blocks near the edges go to the C kernel */
    const int32_t wlast = (int32_t)width - 2;
    const __m256i ff = _mm256_set1_epi32(0xff), bias = _mm256_set1_epi32(64);
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    uint32_t j = 0;
    while (j < rw) {
        if (j + 8u > rw || first[j] < 0 || first[j + 7u] + (int32_t)taps - 1 > wlast) {
            /* first[] increases with j: lanes 0 and 7 bound the block */
            const uint32_t n = j + 8u <= rw ? 8u : rw - j;
            tdc_trm_dhoriz_c(row, width, first + j, w + (size_t)j * taps, taps, n, dst + 3u * j);
            j += n;
            continue;
        }
        const __m256i k0 = _mm256_cvtepi16_epi32(_mm_loadu_si128((const __m128i *)(const void *)(first + j)));
        const __m256i pix = _mm256_add_epi32(_mm256_add_epi32(k0, k0), k0); /* byte offset 3 k0 */
        const __m256i widx =
            _mm256_mullo_epi32(_mm256_add_epi32(_mm256_set1_epi32((int)j), lane), _mm256_set1_epi32((int)taps));
        __m256i ar = _mm256_setzero_si256(), ag = ar, ab = ar;
        for (uint32_t t = 0; t < taps; t++) {
            const __m256i off = _mm256_set1_epi32((int)t);
            const __m256i v = _mm256_i32gather_epi32((const int *)(const void *)row,
                                                     _mm256_add_epi32(pix, _mm256_set1_epi32((int)(3u * t))), 1);
            const __m256i wt =
                _mm256_and_si256(_mm256_i32gather_epi32((const int *)(const void *)w, _mm256_add_epi32(widx, off), 2),
                                 _mm256_set1_epi32(0xffff));
            ar = _mm256_add_epi32(ar, _mm256_mullo_epi32(wt, _mm256_and_si256(v, ff)));
            ag = _mm256_add_epi32(ag, _mm256_mullo_epi32(wt, _mm256_and_si256(_mm256_srli_epi32(v, 8), ff)));
            ab = _mm256_add_epi32(ab, _mm256_mullo_epi32(wt, _mm256_and_si256(_mm256_srli_epi32(v, 16), ff)));
        }
        __m256i o[3];
        trm_interleave3(_mm256_srli_epi32(_mm256_add_epi32(ar, bias), 7),
                        _mm256_srli_epi32(_mm256_add_epi32(ag, bias), 7),
                        _mm256_srli_epi32(_mm256_add_epi32(ab, bias), 7), o);
        /* 24 values <= 65280 -> uint16 */
        _mm256_storeu_si256((__m256i *)(void *)(dst + 3u * j),
                            _mm256_permute4x64_epi64(_mm256_packus_epi32(o[0], o[1]), 0xd8));
        _mm_storeu_si128((__m128i *)(void *)(dst + 3u * j + 16u),
                         _mm256_castsi256_si128(_mm256_permute4x64_epi64(_mm256_packus_epi32(o[2], o[2]), 0xd8)));
        j += 8u;
    }
}

#else /* no AVX2 on this target: the portable kernels behind the same names */

int tdc_trm_avx2_available(void)
{
    return 0;
}

void tdc_trm_full_row_avx2(const tdc_trm_rowctx_t *k, const uint32_t *urow, const uint8_t *src, uint8_t *dst,
                           tdc_res_t *res, tdc_trm_full_counts_t *n)
{
    tdc_trm_full_row_c(k, urow, src, dst, res, n);
}

void tdc_trm_reduced_row_avx2(const tdc_trm_rowctx_t *k, const uint32_t *urow_a, const uint32_t *urow_b,
                              const tdc_res_t *res, uint8_t *dst, tdc_trm_reduced_counts_t *n)
{
    tdc_trm_reduced_row_c(k, urow_a, urow_b, res, dst, n);
}

void tdc_trm_rho_row_avx2(const tdc_trm_rowctx_t *k, const uint32_t *urow, const uint8_t *src, uint8_t *dst,
                          tdc_res_t *res, tdc_trm_full_counts_t *n)
{
    tdc_trm_full_row_c(k, urow, src, dst, res, n);
}

void tdc_trm_dvert_avx2(const uint16_t *const *rows, const uint16_t *w, uint32_t taps, uint32_t n, uint16_t *out)
{
    tdc_trm_dvert_c(rows, w, taps, n, out);
}

void tdc_trm_uvert_avx2(const uint16_t *a, const uint16_t *b, uint32_t f, uint32_t n, uint32_t *dst)
{
    tdc_trm_uvert_c(a, b, f, n, dst);
}

void tdc_trm_uvert_codes_avx2(const uint8_t *a, const uint8_t *b, uint32_t f, uint32_t n, uint32_t *dst)
{
    tdc_trm_uvert_codes_c(a, b, f, n, dst);
}

void tdc_trm_dhoriz_avx2(const uint8_t *row, uint32_t width, const int16_t *first, const uint16_t *w, uint32_t taps,
                         uint32_t rw, uint16_t *dst)
{
    tdc_trm_dhoriz_c(row, width, first, w, taps, rw, dst);
}

#endif
