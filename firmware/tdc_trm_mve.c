/*
 * tdc_trm_mve.c - TRM's full-res and reduced row kernels with Arm Helium
 * (M-profile Vector Extension, integer only) for Cortex-M55 boards.  They
 * produce the same bytes as the portable C kernels in tdc_trm_rows.c
 * (the checkasm core, tests/checkasm/checkasm_trm.c, checks that under QEMU
 * mps3-an547 on random rows, extremes and every width 1..64; the golden
 * vectors run through them on that board).
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
    /* low parts by subtraction and constants as scalar operands: Helium
     * has 8 vector registers, and every constant vector is one less */
    const int32x4_t d = vsubq_s32(v1, v0);
    const int32x4_t dh = vshrq_n_s32(d, 14);
    const int32x4_t dl = vsubq_s32(d, vshlq_n_s32(dh, 14));
    const int32x4_t x = vaddq_s32(v0, vmulq_s32(dh, fs));
    const int32x4_t xh = vshrq_n_s32(x, 6);
    const int32x4_t xl = vsubq_s32(x, vshlq_n_s32(xh, 6));
    const uint32x4_t z = vreinterpretq_u32_s32(vaddq_n_s32(vaddq_s32(vshlq_n_s32(xl, 14), vmulq_s32(dl, fs)), 1 << 19));
    return vreinterpretq_u32_s32(vaddq_s32(xh, vreinterpretq_s32_u32(vshrq_n_u32(z, 20))));
}

/* Gamma decode of code Q16 (as tdc_gamma_decode_q16): uint32 arithmetic. */
static inline uint32x4_t trm_dec4(const uint32_t *dec, uint32x4_t g)
{
    const uint32x4_t k = vshrq_n_u32(g, 16);
    const uint32x4_t f = vshrq_n_u32(vshlq_n_u32(g, 16), 20); /* (g >> 4) & 0xfff */
    const uint32x4_t a = vldrwq_gather_shifted_offset_u32(dec, k);
    const uint32x4_t b = vldrwq_gather_shifted_offset_u32(dec + 1, k);
    return vaddq_u32(a, vshrq_n_u32(vaddq_n_u32(vmulq_u32(vsubq_u32(b, a), f), 0x800u), 12));
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

/* clamp(v, 0, 2^24) without constant vectors: max(v, 0) = v & ~(v >> 31);
 * with m = v - 2^24, min(v, 2^24) = 2^24 + (m & (m >> 31)). */
static inline int32x4_t trm_clamp_lin(int32x4_t v)
{
    const int32x4_t p = vbicq_s32(v, vshrq_n_s32(v, 31));
    const int32x4_t m = vsubq_n_s32(p, TDC_LIN_ONE);
    return vaddq_n_s32(vandq_s32(m, vshrq_n_s32(m, 31)), TDC_LIN_ONE);
}

typedef struct {
    uint32x4_t i3, f, x3;
} trm_step_t;

static inline trm_step_t trm_step(const tdc_trm_rowctx_t *k, uint32_t x)
{
    trm_step_t s;
    const uint32x4_t o = vidupq_n_u32(2u * x, 2); /* 2x, 2x + 2, ... */
    const uint32x4_t ui = vldrhq_gather_shifted_offset_u32(k->ux, o);
    s.i3 = vmulq_n_u32(ui, 3u);
    s.f = vldrhq_gather_shifted_offset_u32(k->ux + 1, o);
    s.x3 = vmulq_n_u32(vidupq_n_u32(x, 1), 3u);
    return s;
}

void tdc_trm_full_row_mve(const tdc_trm_rowctx_t *k, const uint32_t *urow, const uint8_t *src, uint8_t *dst,
                          tdc_res_t *res, tdc_trm_full_counts_t *n)
{
    const uint32_t w4 = k->width & ~3u;
    /* per-lane counts of beta > 1 and beta < 0, summed once at the end */
    uint32x4_t chi = vdupq_n_u32(0u), clo = vdupq_n_u32(0u);
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
            /* beta > 2^24: the sign of 2^24 - beta; beta < 0: its sign */
            chi = vaddq_u32(chi, vshrq_n_u32(vreinterpretq_u32_s32(vsubq_s32(vdupq_n_s32(TDC_LIN_ONE), beta)), 31));
            clo = vaddq_u32(clo, vshrq_n_u32(vreinterpretq_u32_s32(beta), 31));
            const int32x4_t shown = trm_clamp_lin(beta);
            vstrwq_scatter_shifted_offset_s32(res, xc, vsubq_s32(beta, shown));
            vstrbq_scatter_offset_u32(dst, xc, trm_enc4(k->idx[c], k->thr[c], vreinterpretq_u32_s32(shown)));
        }
    }
    n->hi += vaddvq_u32(chi);
    n->lo += vaddvq_u32(clo);
    if (w4 < k->width) {
        const tdc_trm_rowctx_t t = tdc_trm_tail_ctx(k, w4);
        tdc_trm_full_row_c(&t, urow, src + 3u * w4, dst + 3u * w4, res + 3u * w4, n);
    }
}

void tdc_trm_reduced_row_mve(const tdc_trm_rowctx_t *k, const uint32_t *urow_a, const uint32_t *urow_b,
                             const tdc_res_t *res, uint8_t *dst, tdc_trm_reduced_counts_t *n)
{
    const uint32_t w4 = k->width & ~3u;
    uint32_t computed = 0, skipped = 0, no_res = 0;
    const uint32_t half = 1u << 15; /* half a code in code Q16 */
    for (uint32_t x = 0; x < w4; x += 4u) {
        const trm_step_t s = trm_step(k, x);
        for (uint32_t c = 0; c < 3u; c++) {
            const uint32x4_t xc = vaddq_n_u32(s.x3, c);
            const uint32x4_t ic = vaddq_n_u32(s.i3, c);
            const uint32x4_t gb = trm_hlerp4(urow_b, ic, s.f);
            const int32x4_t alpha = vreinterpretq_s32_u32(trm_dec4(k->dec[c], gb));
            const int32x4_t rho =
                vreinterpretq_s32_u32(vldrwq_gather_shifted_offset_u32((const uint32_t *)(const void *)res, xc));
            const mve_pred16_t nz = vcmpneq_s32(rho, vdupq_n_s32(0));
            int32x4_t shown = alpha;
            no_res += 4u - trm_lanes(nz);
            if (nz) {
                /* the motion test at the link's precision (tdc_trm_rows.c) */
                uint32x4_t ga = trm_hlerp4(urow_a, ic, s.f);
                const mve_pred16_t down = vcmphiq_u32(ga, vaddq_n_u32(gb, half));
                const mve_pred16_t up = vcmphiq_u32(gb, vaddq_n_u32(ga, half));
                ga = vpselq_u32(vsubq_n_u32(ga, half), vpselq_u32(vaddq_n_u32(ga, half), gb, up), down);
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
                const int32x4_t rl = vsubq_s32(rho, vshlq_n_s32(rh, 15));
                const int32x4_t add =
                    vaddq_s32(vmulq_s32(wq, rh),
                              vreinterpretq_s32_u32(
                                  vshrq_n_u32(vreinterpretq_u32_s32(vaddq_n_s32(vmulq_s32(wq, rl), 1 << 14)), 15)));
                shown = vpselq_s32(vaddq_s32(alpha, add), alpha, nz);
            }
            shown = trm_clamp_lin(shown);
            vstrbq_scatter_offset_u32(dst, xc, trm_enc4(k->idx[c], k->thr[c], vreinterpretq_u32_s32(shown)));
        }
    }
    n->computed += computed;
    n->skipped += skipped;
    n->no_res += no_res;
    if (w4 < k->width) {
        const tdc_trm_rowctx_t t = tdc_trm_tail_ctx(k, w4);
        tdc_trm_reduced_row_c(&t, urow_a, urow_b, res + 3u * w4, dst + 3u * w4, n);
    }
}

/* Vertical pass of D (tdc_trm_kernels.h), 4 outputs per step, the tail
 * predicated: (sum_t w[t] rows[t][i] + 2^14) >> 15 with the bias as the
 * accumulator's start; the sum stays below 2^31 (weights sum to 2^15,
 * values <= 65280). */
void tdc_trm_dvert_mve(const uint16_t *const *rows, const uint16_t *w, uint32_t taps, uint32_t n, uint16_t *out)
{
    for (uint32_t i = 0; i < n; i += 4u) {
        const mve_pred16_t p = vctp32q(n - i);
        uint32x4_t acc = vdupq_n_u32(1u << 14);
        for (uint32_t t = 0; t < taps; t++) {
            acc = vmlaq_n_u32(acc, vldrhq_z_u32(rows[t] + i, p), w[t]);
        }
        vstrhq_p_u32(out + i, vshrq_n_u32(acc, 15), p);
    }
}

/* Horizontal pass of D (tdc_trm_kernels.h): 4 reduced columns per step,
 * taps read with gathers at the clamped full-res columns (the C kernel's
 * clamp-to-edge), the last rw % 4 columns by the C kernel. */
void tdc_trm_dhoriz_mve(const uint8_t *row, uint32_t width, const int16_t *first, const uint16_t *w_all, uint32_t taps,
                        uint32_t rw, uint16_t *dst)
{
    const int32x4_t wmax = vdupq_n_s32((int32_t)width - 1);
    uint32_t j = 0;
    for (; j + 4u <= rw; j += 4u) {
        const int32x4_t k0 = vldrhq_s32(first + j);
        const uint32x4_t jt = vmulq_n_u32(vidupq_n_u32(j, 1), taps);
        uint32x4_t a0 = vdupq_n_u32(64u), a1 = vdupq_n_u32(64u), a2 = vdupq_n_u32(64u); /* + 2^6: rounding */
        for (uint32_t t = 0; t < taps; t++) {
            const int32x4_t q = vminq_s32(vmaxq_s32(vaddq_n_s32(k0, (int32_t)t), vdupq_n_s32(0)), wmax);
            const uint32x4_t o = vmulq_n_u32(vreinterpretq_u32_s32(q), 3u);
            const uint32x4_t wt = vldrhq_gather_shifted_offset_u32(w_all, vaddq_n_u32(jt, t));
            a0 = vaddq_u32(a0, vmulq_u32(vldrbq_gather_offset_u32(row, o), wt));
            a1 = vaddq_u32(a1, vmulq_u32(vldrbq_gather_offset_u32(row + 1, o), wt));
            a2 = vaddq_u32(a2, vmulq_u32(vldrbq_gather_offset_u32(row + 2, o), wt));
        }
        const uint32x4_t o3 = vmulq_n_u32(vidupq_n_u32(j, 1), 3u);
        vstrhq_scatter_shifted_offset_u32(dst, o3, vshrq_n_u32(a0, 7));
        vstrhq_scatter_shifted_offset_u32(dst + 1, o3, vshrq_n_u32(a1, 7));
        vstrhq_scatter_shifted_offset_u32(dst + 2, o3, vshrq_n_u32(a2, 7));
    }
    if (j < rw) {
        tdc_trm_dhoriz_c(row, width, first + j, w_all + (size_t)j * taps, taps, rw - j, dst + 3u * j);
    }
}

#else

/* Not a Helium build: an empty object (ISO C wants one declaration). */
typedef int tdc_trm_mve_unused_t;

#endif
