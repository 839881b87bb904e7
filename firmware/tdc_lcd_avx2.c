/*
 * tdc_lcd_avx2.c - the stateful LCD inverse's hot run with x86-64 AVX2
 * (tdc_lcd_kernels.h): the same bytes and return value as
 * tdc_lcd_st_run8_c (tests/checkasm/checkasm_lcd.c checks and benchmarks
 * both; the golden vectors run through it on any AVX2 host).
 *
 * 8 pixels (24 sub-pixels) per step, three vectors of 8 sub-pixels: the
 * index c * 65536 + (state << 8 | wanted) per lane (the channel pattern of
 * the three vectors is fixed because a step starts on a pixel), three
 * 32-bit gathers of the 16-bit entries (the high half, the next entry, is
 * masked off), drive = byte 0 and next state = byte 1 of each lane packed
 * back to bytes.  Where a drive is 0 or 255 the reach limits are gathered
 * too, and each sub-pixel out of reach goes to miss() with its old state,
 * in ascending order, before the step is stored, as in the C run.  Integer only
 * (tests/rules/check_simd_nofloat.sh); other targets get 0 from
 * tdc_lcd_avx2_available() and the C run behind the AVX2 name.
 */
#include "tdc_lcd_kernels.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(TDC_NO_SIMD)

#include <immintrin.h>

#define TDC_AVX2 __attribute__((target("avx2")))

int tdc_lcd_avx2_available(void)
{
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2");
}

/* One vector of 8 sub-pixels: wanted codes, states, the lookups (channel
 * pattern chan: c per lane). */
typedef struct {
    __m256i w, q, e;
} run8_vec_t;

static inline TDC_AVX2 run8_vec_t run8_lookup(const uint16_t *lut, const uint8_t *in, const uint8_t *state,
                                              __m256i chan)
{
    run8_vec_t v;
    v.w = _mm256_cvtepu8_epi32(_mm_loadl_epi64((const __m128i *)(const void *)in));
    v.q = _mm256_cvtepu8_epi32(_mm_loadl_epi64((const __m128i *)(const void *)state));
    const __m256i idx = _mm256_add_epi32(_mm256_or_si256(_mm256_slli_epi32(v.q, 8), v.w), _mm256_slli_epi32(chan, 16));
    v.e = _mm256_and_si256(_mm256_i32gather_epi32((const int *)(const void *)lut, idx, 2), _mm256_set1_epi32(0xffff));
    return v;
}

/* Byte b of each 32-bit lane of e, as 8 bytes. */
static inline TDC_AVX2 __m128i run8_bytes(__m256i e, int b)
{
    const __m256i pick = b ? _mm256_setr_epi8(1, 5, 9, 13, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 1, 5, 9, 13,
                                              -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1)
                           : _mm256_setr_epi8(0, 4, 8, 12, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 0, 4, 8, 12,
                                              -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1);
    const __m256i s = _mm256_shuffle_epi8(e, pick);
    return _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(s, _mm256_setr_epi32(0, 4, 1, 1, 1, 1, 1, 1)));
}

/* Lanes whose drive (byte 0) is 0 or 255, as an 8-bit mask. */
static inline TDC_AVX2 uint32_t run8_edges(__m256i e)
{
    const __m256i d = _mm256_and_si256(e, _mm256_set1_epi32(0xff));
    const __m256i m =
        _mm256_or_si256(_mm256_cmpeq_epi32(d, _mm256_setzero_si256()), _mm256_cmpeq_epi32(d, _mm256_set1_epi32(0xff)));
    return (uint32_t)_mm256_movemask_ps(_mm256_castsi256_ps(m));
}

/* Lanes out of reach (w > whi[c][q] or w < wlo[c][q]), as an 8-bit mask:
 * byte gathers as 32-bit loads ending at the byte (base - 3, top byte). */
static inline TDC_AVX2 uint32_t run8_reach(const run8_vec_t *v, __m256i chan, const uint8_t *whi, const uint8_t *wlo)
{
    const __m256i idx = _mm256_add_epi32(v->q, _mm256_slli_epi32(chan, 8));
    const __m256i hi = _mm256_srli_epi32(_mm256_i32gather_epi32((const int *)(const void *)(whi - 3), idx, 1), 24);
    const __m256i lo = _mm256_srli_epi32(_mm256_i32gather_epi32((const int *)(const void *)(wlo - 3), idx, 1), 24);
    const __m256i m = _mm256_or_si256(_mm256_cmpgt_epi32(v->w, hi), _mm256_cmpgt_epi32(lo, v->w));
    return (uint32_t)_mm256_movemask_ps(_mm256_castsi256_ps(m));
}

TDC_AVX2 void tdc_lcd_st_run8_avx2(const uint16_t *lut, const uint8_t *whi, const uint8_t *wlo, const uint8_t *in,
                                   uint8_t *out, uint8_t *state, uint32_t i, uint32_t w3, tdc_lcd_st_miss_fn *miss,
                                   void *ctx)
{
    /* channel of each lane for the vectors at sub-pixels 0, 8, 16 of a step */
    const __m256i c0 = _mm256_setr_epi32(0, 1, 2, 0, 1, 2, 0, 1);
    const __m256i c1 = _mm256_setr_epi32(2, 0, 1, 2, 0, 1, 2, 0);
    const __m256i c2 = _mm256_setr_epi32(1, 2, 0, 1, 2, 0, 1, 2);
    for (; i + 24u <= w3; i += 24u) {
        const run8_vec_t v0 = run8_lookup(lut, in + i, state + i, c0);
        const run8_vec_t v1 = run8_lookup(lut, in + i + 8u, state + i + 8u, c1);
        const run8_vec_t v2 = run8_lookup(lut, in + i + 16u, state + i + 16u, c2);
        const uint32_t edges = run8_edges(v0.e) | run8_edges(v1.e) << 8 | run8_edges(v2.e) << 16;
        if (edges != 0u) {
            /* only a drive of 0 or 255 can be out of reach; in ascending s, old state */
            uint32_t m = edges & (run8_reach(&v0, c0, whi, wlo) | run8_reach(&v1, c1, whi, wlo) << 8 |
                                  run8_reach(&v2, c2, whi, wlo) << 16);
            while (m != 0u) {
                const uint32_t s = i + (uint32_t)__builtin_ctz(m);
                miss(ctx, s, state[s], in[s]);
                m &= m - 1u;
            }
        }
        _mm_storel_epi64((__m128i *)(void *)(out + i), run8_bytes(v0.e, 0));
        _mm_storel_epi64((__m128i *)(void *)(out + i + 8u), run8_bytes(v1.e, 0));
        _mm_storel_epi64((__m128i *)(void *)(out + i + 16u), run8_bytes(v2.e, 0));
        _mm_storel_epi64((__m128i *)(void *)(state + i), run8_bytes(v0.e, 1));
        _mm_storel_epi64((__m128i *)(void *)(state + i + 8u), run8_bytes(v1.e, 1));
        _mm_storel_epi64((__m128i *)(void *)(state + i + 16u), run8_bytes(v2.e, 1));
    }
    /* the last pixels: the C run on the rest of the row */
    tdc_lcd_st_run8_c(lut, whi, wlo, in, out, state, i, w3, miss, ctx);
}

#else /* no AVX2 on this target: the C run behind the same name */

int tdc_lcd_avx2_available(void)
{
    return 0;
}

void tdc_lcd_st_run8_avx2(const uint16_t *lut, const uint8_t *whi, const uint8_t *wlo, const uint8_t *in, uint8_t *out,
                          uint8_t *state, uint32_t i, uint32_t w3, tdc_lcd_st_miss_fn *miss, void *ctx)
{
    tdc_lcd_st_run8_c(lut, whi, wlo, in, out, state, i, w3, miss, ctx);
}

#endif
