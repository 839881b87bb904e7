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
 * back to bytes.  A step with a drive of 0 or 255 is left to the caller, as
 * the C run does.  Integer only (tests/rules/check_simd_nofloat.sh); other
 * targets get 0 from tdc_lcd_avx2_available() and the C run behind the AVX2
 * name.
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

/* Lookups of 8 sub-pixels (chan: c * 65536 per lane). */
static inline TDC_AVX2 __m256i run8_lookup(const uint16_t *lut, const uint8_t *in, const uint8_t *state, __m256i chan)
{
    const __m256i w = _mm256_cvtepu8_epi32(_mm_loadl_epi64((const __m128i *)(const void *)in));
    const __m256i q = _mm256_cvtepu8_epi32(_mm_loadl_epi64((const __m128i *)(const void *)state));
    const __m256i idx = _mm256_add_epi32(_mm256_or_si256(_mm256_slli_epi32(q, 8), w), chan);
    return _mm256_and_si256(_mm256_i32gather_epi32((const int *)(const void *)lut, idx, 2), _mm256_set1_epi32(0xffff));
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

/* All-ones lanes where the drive (byte 0) is 0 or 255. */
static inline TDC_AVX2 __m256i run8_edges(__m256i e)
{
    const __m256i d = _mm256_and_si256(e, _mm256_set1_epi32(0xff));
    return _mm256_or_si256(_mm256_cmpeq_epi32(d, _mm256_setzero_si256()),
                           _mm256_cmpeq_epi32(d, _mm256_set1_epi32(0xff)));
}

TDC_AVX2 uint32_t tdc_lcd_st_run8_avx2(const uint16_t *lut, const uint8_t *in, uint8_t *out, uint8_t *state, uint32_t i,
                                       uint32_t w3)
{
    /* c * 65536 of each lane for the vectors at sub-pixels 0, 8, 16 of a step */
    const __m256i c0 = _mm256_setr_epi32(0, 65536, 131072, 0, 65536, 131072, 0, 65536);
    const __m256i c1 = _mm256_setr_epi32(131072, 0, 65536, 131072, 0, 65536, 131072, 0);
    const __m256i c2 = _mm256_setr_epi32(65536, 131072, 0, 65536, 131072, 0, 65536, 131072);
    for (; i + TDC_LCD_RUN8_STEP <= w3; i += TDC_LCD_RUN8_STEP) {
        const __m256i e0 = run8_lookup(lut, in + i, state + i, c0);
        const __m256i e1 = run8_lookup(lut, in + i + 8u, state + i + 8u, c1);
        const __m256i e2 = run8_lookup(lut, in + i + 16u, state + i + 16u, c2);
        const __m256i edges = _mm256_or_si256(_mm256_or_si256(run8_edges(e0), run8_edges(e1)), run8_edges(e2));
        if (!_mm256_testz_si256(edges, edges)) {
            return i; /* a drive of 0 or 255: the caller's full loop takes this step */
        }
        _mm_storel_epi64((__m128i *)(void *)(out + i), run8_bytes(e0, 0));
        _mm_storel_epi64((__m128i *)(void *)(out + i + 8u), run8_bytes(e1, 0));
        _mm_storel_epi64((__m128i *)(void *)(out + i + 16u), run8_bytes(e2, 0));
        _mm_storel_epi64((__m128i *)(void *)(state + i), run8_bytes(e0, 1));
        _mm_storel_epi64((__m128i *)(void *)(state + i + 8u), run8_bytes(e1, 1));
        _mm_storel_epi64((__m128i *)(void *)(state + i + 16u), run8_bytes(e2, 1));
    }
    return i < w3 ? i : w3;
}

#else /* no AVX2 on this target: the C run behind the same name */

int tdc_lcd_avx2_available(void)
{
    return 0;
}

uint32_t tdc_lcd_st_run8_avx2(const uint16_t *lut, const uint8_t *in, uint8_t *out, uint8_t *state, uint32_t i,
                              uint32_t w3)
{
    return tdc_lcd_st_run8_c(lut, in, out, state, i, w3);
}

#endif
