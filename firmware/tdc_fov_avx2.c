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
#include "tdc_fov.h"
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

/* ---------------------------------------------------------------------
 * The geometry pass (tdc_fov_geom_row_fn), 8 pixels a step where all 8 take
 * tdc_fov.c's two-tap path: outside the disk's blend band (b = 256), at
 * least 4 px from the gaze (|x'|^2 >= 2^20: the radial table), inside the
 * table, and sigma = 1/2 at both nodes (then the interpolated sigma is 1/2
 * exactly).  Any other group of 8, the row's tail and log-rectilinear rows
 * go through the C row, so the two produce the same bytes by construction
 * of the same formulas (checked by checkasm's fov_geom, the golden vectors
 * and test_fov on AVX2 hosts):
 *   |x'|^2 in 64-bit lanes; its octave e by a binary search on |x'|^2 >> 16
 *   (< 2^31: |x'| < 2^23 Q8); the top 24 bits by variable 64-bit shifts;
 *   the products the C code takes in 64 bits (u's interpolation < 2^46, the
 *   ratio's (n << clz) * inv < 2^64, the atan fraction < 2^38, turns * lp_h
 *   < 2^45) with _mm256_mul_epu32 on the even and odd lanes, keeping the low
 *   32 bits of the shifted result as the C casts do; the rest in 32 bits as
 *   in C (the tent weight's uint32 arithmetic wraps the same way).
 * ------------------------------------------------------------------- */

/* (a * b + add) >> sh per 32-bit lane, the product in 64 bits, the low 32 bits of the result. */
static TDC_AVX2 inline __m256i mul_shr(__m256i a, __m256i b, __m256i add64, int sh)
{
    const __m256i e = _mm256_srli_epi64(_mm256_add_epi64(_mm256_mul_epu32(a, b), add64), sh);
    const __m256i o = _mm256_srli_epi64(
        _mm256_add_epi64(_mm256_mul_epu32(_mm256_srli_epi64(a, 32), _mm256_srli_epi64(b, 32)), add64), sh);
    return _mm256_blend_epi32(e, _mm256_slli_epi64(o, 32), 0xAA);
}

/* (a * c + b * d + add) >> sh per 32-bit lane, in 64 bits (the radial table's u). */
static TDC_AVX2 inline __m256i mul2_shr(__m256i a, __m256i c, __m256i b, __m256i d, __m256i add64, int sh)
{
    const __m256i e = _mm256_add_epi64(_mm256_add_epi64(_mm256_mul_epu32(a, c), _mm256_mul_epu32(b, d)), add64);
    const __m256i o = _mm256_add_epi64(
        _mm256_add_epi64(_mm256_mul_epu32(_mm256_srli_epi64(a, 32), _mm256_srli_epi64(c, 32)),
                         _mm256_mul_epu32(_mm256_srli_epi64(b, 32), _mm256_srli_epi64(d, 32))),
        add64);
    return _mm256_blend_epi32(_mm256_srli_epi64(e, sh), _mm256_slli_epi64(_mm256_srli_epi64(o, sh), 32), 0xAA);
}

/* floor(log2(x)) per lane for 0 < x < 2^31 (0 for x = 0). */
static TDC_AVX2 inline __m256i floor_log2(__m256i x)
{
    const __m256i z = _mm256_setzero_si256();
    __m256i l = z;
#define FOV_LG_STEP(k)                                                     \
    do {                                                                   \
        const __m256i t = _mm256_srli_epi32(x, k);                         \
        const __m256i m = _mm256_cmpgt_epi32(t, z);                        \
        x = _mm256_blendv_epi8(x, t, m);                                   \
        l = _mm256_add_epi32(l, _mm256_and_si256(m, _mm256_set1_epi32(k))); \
    } while (0)
    FOV_LG_STEP(16);
    FOV_LG_STEP(8);
    FOV_LG_STEP(4);
    FOV_LG_STEP(2);
    FOV_LG_STEP(1);
#undef FOV_LG_STEP
    return l;
}

/* tdc_clamp32 per lane: x < lo ? lo : min(x, hi) (the same order when lo > hi). */
static TDC_AVX2 inline __m256i clamp_v(__m256i x, __m256i lo, __m256i hi)
{
    return _mm256_blendv_epi8(_mm256_min_epi32(x, hi), lo, _mm256_cmpgt_epi32(lo, x));
}

/* The low 32 bits of two vectors of 4 x 64 as one vector of 8 x 32 (lanes 0-3 from lo). */
static TDC_AVX2 inline __m256i pack_lo32(__m256i lo, __m256i hi)
{
    const __m256i idx = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
    return _mm256_permute2x128_si256(_mm256_permutevar8x32_epi32(lo, idx), _mm256_permutevar8x32_epi32(hi, idx),
                                     0x20);
}

TDC_AVX2 void tdc_fov_geom_row_avx2(const tdc_fov_geom_args_t *a, int32_t x0, int32_t x1)
{
    const tdc_fov_geom_t *g = a->g;
    if (a->lr || a->half_lo >= a->half_hi) { /* no two neighbouring nodes with sigma = 1/2 */
        tdc_fov_geom_row_c(a, x0, x1);
        return;
    }
    const __m256i z = _mm256_setzero_si256();
    const uint64_t e0 = (uint64_t)1 << TDC_FOV_NODE_E0; /* b = 256 iff |x'|^2 >= r_d^2; the table from 2^20 */
    const __m256i lim = _mm256_set1_epi64x((int64_t)(g->r_disk2_q16 > e0 ? g->r_disk2_q16 : e0));
    const __m256i dy2 = _mm256_set1_epi64x((int64_t)a->dy2);
    const __m256i ayv = _mm256_set1_epi32((int32_t)a->ay), invy = _mm256_set1_epi32((int32_t)a->inv_y);
    const __m256i hlo = _mm256_set1_epi32((int32_t)a->half_lo), hhi1 = _mm256_set1_epi32((int32_t)a->half_hi - 1);
    const __m256i lpw16 = _mm256_set1_epi32((int32_t)((uint32_t)g->lp_w << 16));
    const __m256i lph = _mm256_set1_epi32((int32_t)g->lp_h), stride = _mm256_set1_epi32((int32_t)a->lp_stride);
    const __m256i cmin = _mm256_set1_epi32((int32_t)g->u0), cmax = _mm256_set1_epi32((int32_t)g->lp_w - 1);
    const __m256i lo16 = _mm256_set1_epi32(0xFFFF), one = _mm256_set1_epi32(1), three = _mm256_set1_epi32(3);
    const __m256i r15 = _mm256_set1_epi64x(32768), r16 = _mm256_set1_epi32(32768), r8 = _mm256_set1_epi32(128);
    const __m256i q30 = _mm256_set1_epi32(1 << 30);
    const __m256i q31 = _mm256_set1_epi32((int32_t)(1u << 31)), step0 = _mm256_set1_epi32((int32_t)TDC_FOV_STEP0);
    const __m256i n256 = _mm256_set1_epi32(256), n23 = _mm256_set1_epi32(23), lane = _mm256_setr_epi32(0, 256, 512, 768, 1024, 1280, 1536, 1792);
    const int *rad = (const int *)(const void *)a->rad, *atn = (const int *)(const void *)a->atan_tab;
    const int *tent = (const int *)(const void *)a->tent_tab;
    const int dyneg = a->dy < 0;
    int32_t x = x0;
    for (; x + 8 <= x1; x += 8) {
        const __m256i dx = _mm256_add_epi32(_mm256_set1_epi32(x * 256 + 128 - g->cx_q8), lane);
        const __m256i dxl = _mm256_cvtepi32_epi64(_mm256_castsi256_si128(dx));
        const __m256i dxh = _mm256_cvtepi32_epi64(_mm256_extracti128_si256(dx, 1));
        const __m256i r2l = _mm256_add_epi64(_mm256_mul_epi32(dxl, dxl), dy2);
        const __m256i r2h = _mm256_add_epi64(_mm256_mul_epi32(dxh, dxh), dy2);
        /* b = 256 (outside r_d, so outside the blend band too) and |x'|^2 >= 2^20 */
        const __m256i near = _mm256_or_si256(_mm256_cmpgt_epi64(lim, r2l), _mm256_cmpgt_epi64(lim, r2h));
        if (!_mm256_testz_si256(near, near)) {
            tdc_fov_geom_row_c(a, x, x + 8);
            continue;
        }
        /* the octave e of |x'|^2 and its top 24 bits */
        const __m256i e = _mm256_add_epi32(
            floor_log2(pack_lo32(_mm256_srli_epi64(r2l, 16), _mm256_srli_epi64(r2h, 16))), _mm256_set1_epi32(16));
        const __m256i shr = _mm256_max_epi32(_mm256_sub_epi32(e, n23), z), shl = _mm256_max_epi32(_mm256_sub_epi32(n23, e), z);
        const __m256i m24l = _mm256_sllv_epi64(_mm256_srlv_epi64(r2l, _mm256_cvtepu32_epi64(_mm256_castsi256_si128(shr))),
                                               _mm256_cvtepu32_epi64(_mm256_castsi256_si128(shl)));
        const __m256i m24h =
            _mm256_sllv_epi64(_mm256_srlv_epi64(r2h, _mm256_cvtepu32_epi64(_mm256_extracti128_si256(shr, 1))),
                              _mm256_cvtepu32_epi64(_mm256_extracti128_si256(shl, 1)));
        const __m256i m24 = pack_lo32(m24l, m24h);
        const __m256i n = _mm256_or_si256(_mm256_slli_epi32(_mm256_sub_epi32(e, _mm256_set1_epi32(TDC_FOV_NODE_E0)), 7),
                                          _mm256_and_si256(_mm256_srli_epi32(m24, 16), _mm256_set1_epi32(127)));
        const __m256i f = _mm256_and_si256(m24, lo16);
        /* both nodes in the run with sigma = 1/2 (so inside the table): half_lo <= n < half_hi */
        const __m256i bad = _mm256_or_si256(_mm256_cmpgt_epi32(hlo, n), _mm256_cmpgt_epi32(n, hhi1));
        if (!_mm256_testz_si256(bad, bad)) {
            tdc_fov_geom_row_c(a, x, x + 8);
            continue;
        }
        const __m256i n2 = _mm256_slli_epi32(n, 1);
        const __m256i ua = _mm256_i32gather_epi32(rad, n2, 4);
        const __m256i ub = _mm256_i32gather_epi32(rad, _mm256_add_epi32(n2, _mm256_set1_epi32(2)), 4);
        /* lerp_u, clipped at lp_w */
        const __m256i u = _mm256_min_epu32(mul2_shr(ua, _mm256_sub_epi32(_mm256_set1_epi32(65536), f), ub, f, r15, 16), lpw16);
        /* the angle: the octant ratio by the column's or the row's reciprocal, the atan table, symmetry */
        const __m256i ax = _mm256_abs_epi32(dx);
        const __m256i colm = _mm256_cmpgt_epi32(ax, ayv); /* ax > ay: ratio ay / ax */
        const __m256i num = _mm256_blendv_epi8(ax, ayv, colm), den = _mm256_blendv_epi8(ayv, ax, colm);
        const __m256i inv = _mm256_blendv_epi8(invy, _mm256_loadu_si256((const __m256i *)(const void *)(a->colinv + x)), colm);
        const __m256i clz = _mm256_sub_epi32(_mm256_set1_epi32(31), floor_log2(den));
        const __m256i t = mul_shr(_mm256_sllv_epi32(num, clz), inv, z, 33);
        const __m256i idx = _mm256_srli_epi32(t, 22), fr = _mm256_and_si256(_mm256_srli_epi32(t, 6), lo16);
        /* a0 = atan[idx], a1 = atan[idx + 1] (a0 at idx = 256): one 64-bit gather per 4 pixels */
        const __m256i i255 = _mm256_min_epi32(idx, _mm256_set1_epi32(255));
        const __m256i pl = _mm256_i32gather_epi64((const long long *)(const void *)atn, _mm256_castsi256_si128(i255), 4);
        const __m256i ph = _mm256_i32gather_epi64((const long long *)(const void *)atn, _mm256_extracti128_si256(i255, 1), 4);
        const __m256i plo = pack_lo32(pl, ph), phi = pack_lo32(_mm256_srli_epi64(pl, 32), _mm256_srli_epi64(ph, 32));
        const __m256i at_end = _mm256_cmpeq_epi32(idx, n256);
        const __m256i a0 = _mm256_blendv_epi8(plo, phi, at_end), a1 = phi;
        __m256i an = _mm256_add_epi32(a0, mul_shr(_mm256_sub_epi32(a1, a0), fr, r15, 16));
        an = _mm256_blendv_epi8(an, _mm256_sub_epi32(q30, an), _mm256_cmpgt_epi32(ayv, ax));
        an = _mm256_blendv_epi8(an, _mm256_sub_epi32(q31, an), _mm256_cmpgt_epi32(z, dx));
        if (dyneg) {
            an = _mm256_sub_epi32(z, an);
        }
        const __m256i v = mul_shr(an, lph, z, 16);
        const __m256i j0 = _mm256_srli_epi32(v, 16), fv = _mm256_srli_epi32(_mm256_and_si256(v, lo16), 1);
        const __m256i j0p = _mm256_add_epi32(j0, one);
        const __m256i j1 = _mm256_andnot_si256(_mm256_cmpeq_epi32(j0p, lph), j0p);
        if (a->taa) {
            const __m256i ui = _mm256_srli_epi32(_mm256_add_epi32(u, r16), 16);
            const __m256i vi = _mm256_srli_epi32(_mm256_add_epi32(v, r16), 16);
            const __m256i vw = _mm256_and_si256(_mm256_cmpgt_epi32(lph, vi), vi); /* vi >= lp_h -> 0 */
            const __m256i ij = _mm256_or_si256(clamp_v(ui, cmin, cmax), _mm256_slli_epi32(vw, 16));
            _mm256_storeu_si256((__m256i *)(void *)(a->ij + x), ij);
        }
        /* the two taps: tent weights of frac(u), the columns clamped to the carried ones */
        const __m256i fu = _mm256_and_si256(u, lo16), k = _mm256_srli_epi32(fu, 8), fru = _mm256_and_si256(fu, _mm256_set1_epi32(255));
        /* ta = tent[k], tb = tent[k + 1], k <= 255 */
        const __m256i tl = _mm256_i32gather_epi64((const long long *)(const void *)tent, _mm256_castsi256_si128(k), 4);
        const __m256i th = _mm256_i32gather_epi64((const long long *)(const void *)tent, _mm256_extracti128_si256(k, 1), 4);
        const __m256i ta = pack_lo32(tl, th), tb = pack_lo32(_mm256_srli_epi64(tl, 32), _mm256_srli_epi64(th, 32));
        const __m256i w0 = _mm256_sub_epi32(ta, _mm256_srli_epi32(_mm256_add_epi32(_mm256_mullo_epi32(_mm256_sub_epi32(ta, tb), fru), r8), 8));
        const __m256i ci = _mm256_srli_epi32(u, 16);
        const __m256i c0 = clamp_v(ci, cmin, cmax);
        const __m256i c1 = clamp_v(_mm256_add_epi32(ci, one), cmin, cmax);
        const __m256i c3 = _mm256_mullo_epi32(c0, three);
        const __m256i o0 = _mm256_or_si256(_mm256_add_epi32(_mm256_mullo_epi32(j0, stride), c3), _mm256_and_si256(_mm256_cmpeq_epi32(c0, c1), step0));
        const __m256i o1 = _mm256_add_epi32(_mm256_mullo_epi32(j1, stride), c3);
        _mm256_storeu_si256((__m256i *)(void *)(a->off0 + x), o0);
        _mm256_storeu_si256((__m256i *)(void *)(a->off1 + x), o1);
        _mm256_storeu_si256((__m256i *)(void *)(a->wf + x), _mm256_or_si256(w0, _mm256_slli_epi32(fv, 16)));
        _mm_storeu_si128((__m128i *)(void *)(a->b + x), _mm_set1_epi16(256));
    }
    if (x < x1) {
        tdc_fov_geom_row_c(a, x, x1);
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

void tdc_fov_geom_row_avx2(const tdc_fov_geom_args_t *a, int32_t x0, int32_t x1)
{
    tdc_fov_geom_row_c(a, x0, x1);
}

#endif
