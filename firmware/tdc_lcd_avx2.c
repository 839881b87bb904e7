/*
 * tdc_lcd_avx2.c - the stateful LCD inverse's row with x86-64 AVX2
 * (tdc_lcd_kernels.h): the same bytes, residual, counters and return value
 * as tdc_lcd_st_row8_c (tests/checkasm/checkasm_lcd.c checks and benchmarks
 * both; the golden vectors run through it on any AVX2 host).
 *
 * 8 pixels (24 sub-pixels) per step, three vectors of 8 sub-pixels (the
 * channel pattern of the three vectors is fixed because a step starts on a
 * pixel): per lane the index c * 65536 + (state << 8 | wanted), a 32-bit
 * gather of the 16-bit entry (the high half, the next entry, masked off),
 * drive = byte 0 and next state = byte 1 packed back to bytes.  The
 * out-of-reach path stays in vectors too (it used to drop to the C loop,
 * which cost more than the gathers saved on moving text, docs/lcd.md §8):
 * when a vector has a drive of 0 or 255, gathers of the reach limits whi /
 * wlo at c * 256 + state, then, for the lanes out of reach, masked gathers
 * of the limit light (lhi or llo) and of decode(wanted); the miss is added
 * to the residual row with the C path's saturation and clamp, and counted
 * by popcounts of the lane masks.  The row's last w3 mod 24 sub-pixels go
 * through the C row.
 *
 * Scaling and overflow: indices < 3 * 65536 (lut) and < 768; decode and the
 * limit lights are in [0, 2^24], so |miss| <= 2^24; res + miss is formed
 * wrapping and the lanes where it wrapped (operands of one sign, sum of the
 * other) take the clamp bound of the operands' sign, exactly as
 * tdc_clamp32(tdc_add_sat32(.), +-2^24) does.  Integer only
 * (tests/rules/check_simd_nofloat.sh); other targets get 0 from
 * tdc_lcd_avx2_available() and the C row behind the AVX2 name.
 */
#include "tdc_lcd_kernels.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(TDC_NO_SIMD)

#include <immintrin.h>

#define TDC_AVX2 __attribute__((target("avx2,popcnt")))

int tdc_lcd_avx2_available(void)
{
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt");
}

/* Byte b of each 32-bit lane of e, as 8 bytes. */
static inline TDC_AVX2 __m128i row8_bytes(__m256i e, int b)
{
    const __m256i pick = b ? _mm256_setr_epi8(1, 5, 9, 13, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 1, 5, 9, 13,
                                              -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1)
                           : _mm256_setr_epi8(0, 4, 8, 12, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 0, 4, 8, 12,
                                              -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1);
    const __m256i s = _mm256_shuffle_epi8(e, pick);
    return _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(s, _mm256_setr_epi32(0, 4, 1, 1, 1, 1, 1, 1)));
}

/* The lanes of one vector of 8 sub-pixels with a drive of 0 or 255 (edge:
 * lane mask), where alone a target can be out of reach, one by one as the
 * C row does them (moving text: ~1 in 6 sub-pixels; gathers of the reach
 * limits for the whole vector measured slower, docs/lcd.md §8); w, q:
 * wanted and state per lane, c256: c * 256 per lane.  Returns the lanes
 * with a miss. */
static inline TDC_AVX2 uint32_t row8_reach(const tdc_lcd_st_tabs_t *t, uint32_t edge, __m256i w, __m256i q,
                                           __m256i c256, int32_t *res, tdc_lcd_st_counts_t *n)
{
    _Alignas(32) int32_t kk[8], ww[8], cw[8];
    _mm256_store_si256((__m256i *)(void *)kk, _mm256_add_epi32(c256, q));
    _mm256_store_si256((__m256i *)(void *)cw, _mm256_add_epi32(c256, w));
    _mm256_store_si256((__m256i *)(void *)ww, w);
    uint32_t missed = 0;
    while (edge) {
        const int l = __builtin_ctz(edge);
        edge &= edge - 1u;
        const int32_t k = kk[l], wl = ww[l];
        int32_t lim;
        if (wl > t->whi[k]) {
            lim = t->lhi[k];
        } else if (wl < t->wlo[k]) {
            lim = t->llo[k];
        } else {
            continue; /* in reach */
        }
        /* decode and limit lights in [0, 2^24]: |miss| <= 2^24 */
        const int32_t miss = t->dec[cw[l]] - lim;
        if (miss == 0) {
            continue;
        }
        missed |= 1u << l;
        if (miss > 0) {
            n->clamped_high++;
        } else {
            n->clamped_low++;
        }
        if (res) {
            /* tdc_clamp32(tdc_add_sat32(res, miss), +-2^24): res + miss in 64 bits */
            const int64_t v = (int64_t)res[l] + miss;
            res[l] = (int32_t)(v > (1 << 24) ? (1 << 24) : (v < -(1 << 24) ? -(1 << 24) : v));
            n->residual_added++;
        }
    }
    return missed;
}

/* All-ones lanes where the drive (byte 0) is 0 or 255. */
static inline TDC_AVX2 __m256i row8_edges(__m256i e)
{
    const __m256i d = _mm256_and_si256(e, _mm256_set1_epi32(0xff));
    return _mm256_or_si256(_mm256_cmpeq_epi32(d, _mm256_setzero_si256()),
                           _mm256_cmpeq_epi32(d, _mm256_set1_epi32(0xff)));
}

TDC_AVX2 uint32_t tdc_lcd_st_row8_avx2(const tdc_lcd_st_tabs_t *t, const uint8_t *in, uint8_t *out, uint8_t *state,
                                       uint32_t w3, int32_t *res, tdc_lcd_st_counts_t *n)
{
    /* c * 65536 and c * 256 of each lane for the vectors at sub-pixels 0, 8, 16 of a step */
    const __m256i ch[3] = {_mm256_setr_epi32(0, 1, 2, 0, 1, 2, 0, 1), _mm256_setr_epi32(2, 0, 1, 2, 0, 1, 2, 0),
                           _mm256_setr_epi32(1, 2, 0, 1, 2, 0, 1, 2)};
    const uint16_t *lut = t->lut;
    uint32_t nmiss = 0, i = 0;
    for (; i + 24u <= w3; i += 24u) {
        __m256i w[3], q[3], e[3], edges[3];
        for (int v = 0; v < 3; v++) {
            w[v] = _mm256_cvtepu8_epi32(_mm_loadl_epi64((const __m128i *)(const void *)(in + i + 8u * (unsigned)v)));
            q[v] = _mm256_cvtepu8_epi32(_mm_loadl_epi64((const __m128i *)(const void *)(state + i + 8u * (unsigned)v)));
            const __m256i idx =
                _mm256_add_epi32(_mm256_or_si256(_mm256_slli_epi32(q[v], 8), w[v]), _mm256_slli_epi32(ch[v], 16));
            e[v] = _mm256_i32gather_epi32((const int *)(const void *)lut, idx, 2);
            edges[v] = row8_edges(e[v]);
        }
        for (int v = 0; v < 3; v++) {
            _mm_storel_epi64((__m128i *)(void *)(out + i + 8u * (unsigned)v), row8_bytes(e[v], 0));
            _mm_storel_epi64((__m128i *)(void *)(state + i + 8u * (unsigned)v), row8_bytes(e[v], 1));
        }
        for (int v = 0; v < 3; v++) {
            const uint32_t edge = (uint32_t)_mm256_movemask_ps(_mm256_castsi256_ps(edges[v]));
            if (edge) {
                int32_t *r = res ? res + i + 8u * (unsigned)v : 0;
                nmiss += (uint32_t)__builtin_popcount(row8_reach(t, edge, w[v], q[v], _mm256_slli_epi32(ch[v], 8), r, n));
            }
        }
    }
    if (i < w3) {
        nmiss += tdc_lcd_st_row8_c(t, in + i, out + i, state + i, w3 - i, res ? res + i : 0, n);
    }
    return nmiss;
}

#else /* no AVX2 on this target: the C row behind the same name */

int tdc_lcd_avx2_available(void)
{
    return 0;
}

uint32_t tdc_lcd_st_row8_avx2(const tdc_lcd_st_tabs_t *t, const uint8_t *in, uint8_t *out, uint8_t *state, uint32_t w3,
                              int32_t *res, tdc_lcd_st_counts_t *n)
{
    return tdc_lcd_st_row8_c(t, in, out, state, w3, res, n);
}

#endif
