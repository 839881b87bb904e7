/*
 * tdc_trm_mve.c - TRM's full-res and reduced row kernels with Arm Helium
 * (M-profile Vector Extension, integer only) for Cortex-M55 boards.  They
 * produce the same bytes as the portable C kernels in tdc_trm_rows.c
 * (tests/checkasm/checkasm_trm_mve.c checks that under QEMU mps3-an547 on
 * random rows, extremes and every width 1..64; the golden vectors run
 * through them on that board).
 *
 * Built only where the board says so (BOARD_MVE := 1 in its board.mk: the
 * object gets -mcpu=cortex-m55+nofp -mfloat-abi=softfp, which enables the
 * integer MVE instructions and no floating point at all, and every other
 * object is told TDC_TRM_MVE=1 so tdc_trm.c calls these); elsewhere the
 * file is empty.  Soft-float objects link with it: softfp passes
 * arguments in core registers like soft.
 *
 * Layout: 4 consecutive pixels per step, one vector per colour channel
 * (every lane uses that channel's gamma tables: gathers with one base);
 * interleaved RGB is read and written with gathers/scatters of stride 3.
 * Pixels past the last multiple of 4 go through the C kernel (same bytes).
 *
 * Exactness (why 32-bit lanes give the C path's 64-bit results; the same
 * splits as tdc_trm_avx2.c):
 *  - hlerp: floor((v0 2^14 + d f + 2^19) / 2^20) with d = v1 - v0 =
 *    dh 2^14 + dl (dl in [0, 2^14)), X = v0 + dh f = Xh 2^6 + Xl: the sum is
 *    Xh 2^20 + Z, Z = Xl 2^14 + dl f + 2^19 in [0, 2^29), result
 *    Xh + (Z >> 20).  v0 < 2^30 and |dh f| < 2^30 keep X in int32.
 *  - alpha + round(w rho / 2^15): rho = rh 2^15 + rl (rl in [0, 2^15)):
 *    w rh + ((w rl + 2^14) >> 15); w <= 2^15, |rho| <= 2^24: int32.
 *  - encode: the index start and forward threshold steps of tdc_gamma_encode,
 *    per lane, until no lane moves.
 *  - the motion weight's division (no integer divide in MVE): the lanes
 *    that need it run tdc_trm_motion_weight_q15 one by one, as C does.
 */
#include "tdc_trm_kernels.h"

#if defined(__ARM_FEATURE_MVE) && defined(TDC_TRM_MVE)

#include <arm_mve.h>

/* Horizontal lerp, 4 pixels of one channel at reduced offsets i3 (+ c). */
static inline uint32x4_t trm_hlerp4(const uint32_t *urow, uint32x4_t i, uint32x4_t f)
{
    const int32x4_t v0 = vreinterpretq_s32_u32(vldrwq_gather_shifted_offset_u32(urow, i));
    const int32x4_t v1 = vreinterpretq_s32_u32(vldrwq_gather_shifted_offset_u32(urow + 3, i));
    const int32x4_t fs = vreinterpretq_s32_u32(f);
    const int32x4_t d = vsubq_s32(v1, v0);
    const int32x4_t dh = vshrq_n_s32(d, 14);
    const int32x4_t dl = vandq_s32(d, vdupq_n_s32(0x3fff));
    const int32x4_t x = vaddq_s32(v0, vmulq_s32(dh, fs));
    const int32x4_t xh = vshrq_n_s32(x, 6);
    const int32x4_t xl = vandq_s32(x, vdupq_n_s32(63));
    const uint32x4_t z = vreinterpretq_u32_s32(
        vaddq_s32(vaddq_s32(vshlq_n_s32(xl, 14), vmulq_s32(dl, fs)), vdupq_n_s32(1 << 19)));
    return vreinterpretq_u32_s32(vaddq_s32(xh, vreinterpretq_s32_u32(vshrq_n_u32(z, 20))));
}

/* Gamma decode of code Q16 (as tdc_gamma_decode_q16): uint32 arithmetic. */
static inline uint32x4_t trm_dec4(const uint32_t *dec, uint32x4_t g)
{
    const uint32x4_t k = vshrq_n_u32(g, 16);
    const uint32x4_t f = vandq_u32(vshrq_n_u32(g, 4), vdupq_n_u32(0xfff));
    const uint32x4_t a = vldrwq_gather_shifted_offset_u32(dec, k);
    const uint32x4_t b = vldrwq_gather_shifted_offset_u32(dec + 1, k);
    return vaddq_u32(a, vshrq_n_u32(vaddq_u32(vmulq_u32(vsubq_u32(b, a), f), vdupq_n_u32(0x800)), 12));
}

/* Gamma encode of L in [0, 2^24] (as tdc_gamma_encode). */
static inline uint32x4_t trm_enc4(const uint16_t *idx, const uint32_t *thr, uint32x4_t l)
{
    uint32x4_t k = vldrhq_gather_shifted_offset_u32(idx, vshrq_n_u32(l, TDC_LIN_FRAC - TDC_ENC_INDEX_BITS));
    for (;;) {
        /* 255 > k (vcmpneq_n with a constant ICEs gcc 12: trunc_int_for_mode) */
        const mve_pred16_t room = vcmphiq_u32(vdupq_n_u32(255u), k);
        const uint32x4_t k1 = vaddq_n_u32(k, 1u);
        /* lanes at 255 read thr[255] again (in range) and do not move */
        const uint32x4_t t = vldrwq_gather_shifted_offset_u32(thr, vminq_u32(k1, vdupq_n_u32(255u)));
        const mve_pred16_t adv = vcmpcsq_m_u32(l, t, room); /* l >= t where k < 255 */
        if (adv == 0u) {
            return k;
        }
        k = vpselq_u32(k1, k, adv);
    }
}

/* Lanes set in a predicate (4 bits per 32-bit lane). */
static inline uint32_t trm_lanes(mve_pred16_t p)
{
    return vaddvq_p_u32(vdupq_n_u32(1u), p);
}

typedef struct {
    uint32x4_t i3, f, x3;
} trm_step_t;

static inline trm_step_t trm_step(const tdc_trm_rowctx_t *k, uint32_t x)
{
    static const uint32_t lane2[4] = {0, 2, 4, 6}, lane3[4] = {0, 3, 6, 9};
    trm_step_t s;
    const uint32x4_t o = vaddq_n_u32(vld1q_u32(lane2), 2u * x);
    const uint32x4_t ui = vldrhq_gather_shifted_offset_u32(k->ux, o);
    s.i3 = vmulq_n_u32(ui, 3u);
    s.f = vldrhq_gather_shifted_offset_u32(k->ux + 1, o);
    s.x3 = vaddq_n_u32(vld1q_u32(lane3), 3u * x);
    return s;
}

static tdc_trm_rowctx_t trm_tail_ctx(const tdc_trm_rowctx_t *k, uint32_t x)
{
    tdc_trm_rowctx_t t = *k;
    t.ux = k->ux + 2u * x;
    t.width = k->width - x;
    return t;
}

void tdc_trm_full_row_mve(const tdc_trm_rowctx_t *k, const uint32_t *urow, const uint8_t *src, uint8_t *dst,
                          tdc_res_t *res, tdc_trm_full_counts_t *n)
{
    const uint32_t w4 = k->width & ~3u;
    uint32_t nhi = 0, nlo = 0;
    const int32x4_t one = vdupq_n_s32(TDC_LIN_ONE), zero = vdupq_n_s32(0);
    for (uint32_t x = 0; x < w4; x += 4u) {
        const trm_step_t s = trm_step(k, x);
        for (uint32_t c = 0; c < 3u; c++) {
            const uint32x4_t xc = vaddq_n_u32(s.x3, c);
            const int32x4_t lu =
                vreinterpretq_s32_u32(trm_dec4(k->dec[c], trm_hlerp4(urow, vaddq_n_u32(s.i3, c), s.f)));
            const uint32x4_t code = vldrbq_gather_offset_u32(src, xc);
            const int32x4_t li = vreinterpretq_s32_u32(vldrwq_gather_shifted_offset_u32(k->dec[c], code));
            /* beta = 2 LI - Lu in [-1, 2] (Q24) */
            const int32x4_t beta = vsubq_s32(vaddq_s32(li, li), lu);
            nhi += trm_lanes(vcmpgtq_s32(beta, one));
            nlo += trm_lanes(vcmpltq_s32(beta, zero));
            const int32x4_t shown = vminq_s32(vmaxq_s32(beta, zero), one);
            vstrwq_scatter_shifted_offset_s32(res, xc, vsubq_s32(beta, shown));
            vstrbq_scatter_offset_u32(dst, xc, trm_enc4(k->idx[c], k->thr[c], vreinterpretq_u32_s32(shown)));
        }
    }
    n->hi += nhi;
    n->lo += nlo;
    if (w4 < k->width) {
        const tdc_trm_rowctx_t t = trm_tail_ctx(k, w4);
        tdc_trm_full_row_c(&t, urow, src + 3u * w4, dst + 3u * w4, res + 3u * w4, n);
    }
}

void tdc_trm_reduced_row_mve(const tdc_trm_rowctx_t *k, const uint32_t *urow_a, const uint32_t *urow_b,
                             const tdc_res_t *res, uint8_t *dst, tdc_trm_reduced_counts_t *n)
{
    const uint32_t w4 = k->width & ~3u;
    uint32_t computed = 0, skipped = 0, no_res = 0;
    const int32x4_t one = vdupq_n_s32(TDC_LIN_ONE), zero = vdupq_n_s32(0);
    const uint32x4_t half = vdupq_n_u32(1u << 15); /* half a code in code Q16 */
    for (uint32_t x = 0; x < w4; x += 4u) {
        const trm_step_t s = trm_step(k, x);
        for (uint32_t c = 0; c < 3u; c++) {
            const uint32x4_t xc = vaddq_n_u32(s.x3, c);
            const uint32x4_t ic = vaddq_n_u32(s.i3, c);
            const uint32x4_t gb = trm_hlerp4(urow_b, ic, s.f);
            const int32x4_t alpha = vreinterpretq_s32_u32(trm_dec4(k->dec[c], gb));
            const int32x4_t rho = vreinterpretq_s32_u32(
                vldrwq_gather_shifted_offset_u32((const uint32_t *)(const void *)res, xc));
            const mve_pred16_t nz = vcmpneq_s32(rho, zero);
            int32x4_t shown = alpha;
            no_res += 4u - trm_lanes(nz);
            if (nz) {
                /* the motion test at the link's precision (tdc_trm_rows.c) */
                uint32x4_t ga = trm_hlerp4(urow_a, ic, s.f);
                const mve_pred16_t down = vcmphiq_u32(ga, vaddq_u32(gb, half));
                const mve_pred16_t up = vcmphiq_u32(gb, vaddq_u32(ga, half));
                ga = vpselq_u32(vsubq_u32(ga, half), vpselq_u32(vaddq_u32(ga, half), gb, up), down);
                const mve_pred16_t moved = vcmpneq_u32(ga, gb) & nz;
                skipped += trm_lanes(nz) - trm_lanes(moved);
                int32x4_t wq = vdupq_n_s32(32768); /* c = 0 known: exp(0) = 1 */
                if (moved) {
                    computed += trm_lanes(moved);
                    const uint32x4_t la = trm_dec4(k->dec[c], ga);
                    uint32_t av[4], bv[4];
                    int32_t wv[4];
                    vst1q_u32(av, la);
                    vst1q_u32(bv, vreinterpretq_u32_s32(alpha));
                    vst1q_s32(wv, wq);
                    for (unsigned l = 0; l < 4u; l++) {
                        if ((moved >> (4u * l)) & 1u) {
                            wv[l] = tdc_trm_motion_weight_q15(k, (tdc_lin_t)av[l], (tdc_lin_t)bv[l]);
                        }
                    }
                    wq = vld1q_s32(wv);
                }
                /* alpha' = alpha + round(w rho / 2^15), split exactly */
                const int32x4_t rh = vshrq_n_s32(rho, 15);
                const int32x4_t rl = vandq_s32(rho, vdupq_n_s32(0x7fff));
                const int32x4_t add = vaddq_s32(
                    vmulq_s32(wq, rh),
                    vreinterpretq_s32_u32(vshrq_n_u32(
                        vreinterpretq_u32_s32(vaddq_s32(vmulq_s32(wq, rl), vdupq_n_s32(1 << 14))), 15)));
                shown = vpselq_s32(vaddq_s32(alpha, add), alpha, nz);
            }
            shown = vminq_s32(vmaxq_s32(shown, zero), one);
            vstrbq_scatter_offset_u32(dst, xc, trm_enc4(k->idx[c], k->thr[c], vreinterpretq_u32_s32(shown)));
        }
    }
    n->computed += computed;
    n->skipped += skipped;
    n->no_res += no_res;
    if (w4 < k->width) {
        const tdc_trm_rowctx_t t = trm_tail_ctx(k, w4);
        tdc_trm_reduced_row_c(&t, urow_a, urow_b, res + 3u * w4, dst + 3u * w4, n);
    }
}

#else

/* Not a Helium build: an empty object (ISO C wants one declaration). */
typedef int tdc_trm_mve_unused_t;

#endif
