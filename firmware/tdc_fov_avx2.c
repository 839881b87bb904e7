/*
 * tdc_fov_avx2.c - the foveated remap's tap kernel (tdc_fov_kernels.h) with
 * x86-64 AVX2 integer SIMD, for host builds.  Same values as the C kernel
 * (tests/checkasm/checkasm_fov.c checks that bit for bit and benchmarks
 * both; the golden vectors run through it on any AVX2 host).
 *
 * 8 pixels per step: the descriptors are planar (off0, off1, wf), the four
 * samples of each pixel come from four 32-bit gathers (R, G, B and the next
 * byte, which is masked off), the weights and the three channel sums in
 * 32-bit lanes (the C kernel's arithmetic: every value < 2^31), the output
 * planes are packed to uint16.  A group whose gathers would read within 4
 * bytes of the end of lp runs through the C pixel instead (the 4th byte of
 * the last sample).  Integer only (tests/rules/check_simd_nofloat.sh);
 * other targets get 0 from tdc_fov_avx2_available() and the C kernel behind
 * the AVX2 name.
 */
#include "tdc_fov_kernels.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(TDC_NO_SIMD)

#include <immintrin.h>

#define TDC_AVX2 __attribute__((target("avx2")))

int tdc_fov_avx2_available(void)
{
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2");
}

TDC_AVX2 void tdc_fov_tap2_row_avx2(const tdc_fov_tap2_args_t *a, uint32_t n)
{
    const __m256i flag = _mm256_set1_epi32((int)TDC_FOV_STEP0), lo16 = _mm256_set1_epi32(0xFFFF);
    const __m256i one15 = _mm256_set1_epi32(32768), half = _mm256_set1_epi32(16384), r64 = _mm256_set1_epi32(64);
    const __m256i three = _mm256_set1_epi32(3), byte = _mm256_set1_epi32(255);
    /* the largest offset a group may use: o + 3 + 4 <= lp_bytes (4-byte reads) */
    const int64_t lim = (int64_t)a->lp_bytes - 7;
    const __m256i limv = _mm256_set1_epi32((int32_t)(lim > 0x7FFFFFFF ? 0x7FFFFFFF : (lim < -1 ? -1 : lim)));
    const int *base = (const int *)(const void *)a->lp;
    uint32_t k = 0;
    for (; k + 8u <= n; k += 8u) {
        const __m256i o0f = _mm256_loadu_si256((const __m256i *)(const void *)(a->off0 + k));
        const __m256i o1 = _mm256_loadu_si256((const __m256i *)(const void *)(a->off1 + k));
        const __m256i wf = _mm256_loadu_si256((const __m256i *)(const void *)(a->wf + k));
        const __m256i o0 = _mm256_andnot_si256(flag, o0f);
        /* offsets < 2^31: signed compares; any lane past the limit -> C for this group */
        const __m256i over = _mm256_or_si256(_mm256_cmpgt_epi32(o0, limv), _mm256_cmpgt_epi32(o1, limv));
        if (!_mm256_testz_si256(over, over)) {
            for (uint32_t j = k; j < k + 8u; j++) {
                tdc_fov_tap2_px(a, j);
            }
            continue;
        }
        const __m256i st = _mm256_andnot_si256(_mm256_srai_epi32(o0f, 31), three); /* 0 or 3 */
        const __m256i g00 = _mm256_i32gather_epi32(base, o0, 1);
        const __m256i g01 = _mm256_i32gather_epi32(base, _mm256_add_epi32(o0, st), 1);
        const __m256i g10 = _mm256_i32gather_epi32(base, o1, 1);
        const __m256i g11 = _mm256_i32gather_epi32(base, _mm256_add_epi32(o1, st), 1);
        const __m256i w0 = _mm256_and_si256(wf, lo16), fv = _mm256_srli_epi32(wf, 16);
        const __m256i w1 = _mm256_sub_epi32(one15, w0);
        const __m256i wa = _mm256_srli_epi32(_mm256_add_epi32(_mm256_mullo_epi32(w0, fv), half), 15);
        const __m256i wb = _mm256_srli_epi32(_mm256_add_epi32(_mm256_mullo_epi32(w1, fv), half), 15);
        const __m256i w00 = _mm256_sub_epi32(w0, wa), w01 = _mm256_sub_epi32(w1, wb);
        __m256i out[3];
#define FOV_CH(c, sh)                                                                                            \
    out[c] = _mm256_srli_epi32(                                                                                  \
        _mm256_add_epi32(                                                                                        \
            _mm256_add_epi32(                                                                                    \
                _mm256_add_epi32(_mm256_mullo_epi32(w00, _mm256_and_si256(_mm256_srli_epi32(g00, sh), byte)),    \
                                 _mm256_mullo_epi32(w01, _mm256_and_si256(_mm256_srli_epi32(g01, sh), byte))),   \
                _mm256_add_epi32(_mm256_mullo_epi32(wa, _mm256_and_si256(_mm256_srli_epi32(g10, sh), byte)),     \
                                 _mm256_mullo_epi32(wb, _mm256_and_si256(_mm256_srli_epi32(g11, sh), byte)))),   \
            r64),                                                                                                \
        7)
        FOV_CH(0, 0);
        FOV_CH(1, 8);
        FOV_CH(2, 16);
#undef FOV_CH
        for (int c = 0; c < 3; c++) {
            /* 8 x 32-bit (< 2^16) -> 8 x uint16: packus within lanes, then the two halves together */
            const __m256i pk = _mm256_permute4x64_epi64(_mm256_packus_epi32(out[c], out[c]), 0x08);
            _mm_storeu_si128((__m128i *)(void *)(a->out[c] + k), _mm256_castsi256_si128(pk));
        }
    }
    for (; k < n; k++) {
        tdc_fov_tap2_px(a, k);
    }
}

#else /* no AVX2 on this target: the C kernel behind the same name */

int tdc_fov_avx2_available(void)
{
    return 0;
}

void tdc_fov_tap2_row_avx2(const tdc_fov_tap2_args_t *a, uint32_t n)
{
    tdc_fov_tap2_row_c(a, n);
}

#endif
