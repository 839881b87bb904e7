/*
 * tdc_trm_neon.c - TRM's D passes (the prefilter D of the reduced frame,
 * tdc_trm_kernels.h) with AArch64 Advanced SIMD (NEON, integer only), for
 * the Linux boards (Raspberry Pi 4/5 and Zero 2, Rockchip, i.MX).  They
 * produce the same bytes as the portable C kernels in tdc_trm_rows.c
 * (tests/checkasm/checkasm_trm.c checks that under qemu-aarch64 in
 * `make test`; the golden vectors run through them there).
 *
 * Built for every AArch64 target (NEON is part of the ARMv8-A base: no run
 * time test) unless TDC_NO_SIMD; tdc_trm.c calls them through
 * TDC_TRM_D*_BOARD.  Elsewhere the file is empty.
 *
 * Where NEON pays (instructions under qemu-aarch64, docs/boards.md
 * "AArch64"): the two D passes are multiply-adds over contiguous data, 4 to 8
 * lanes at a time: 6.75x and 2.52x fewer instructions than C, 16 % fewer
 * for the board's whole loop on the htc-vive TRM stream.  The full and
 * reduced rows (three quarters of what is left) are not here yet: per
 * pixel-channel they make five to seven look-ups at data-dependent
 * addresses (the U row twice, gamma decode twice, the encode index and its
 * threshold scan); NEON has no gather, so each look-up stays one load per
 * lane plus moving the index out of and the value into a vector, and only
 * the arithmetic between them would be vectorised (AVX2, with gathers, gets
 * 1.25x on the full row).
 *
 * Exactness: both passes sum w * v in uint32 lanes exactly as C does
 * (vertical: weights sum to 2^15, values <= 65280: < 2^31; horizontal:
 * codes <= 255: < 2^23), then the same rounding shift.
 */
#include "tdc_trm.h" /* TDC_TRM_MAX_TAPS */
#include "tdc_trm_kernels.h"

#if defined(TDC_TRM_NEON)

#include <arm_neon.h>

/* Vertical pass of D: 8 outputs per step (two uint32x4 accumulators that
 * start at the rounding bias 2^14), the last n % 8 in scalar C form. */
void tdc_trm_dvert_neon(const uint16_t *const *rows, const uint16_t *w, uint32_t taps, uint32_t n, uint16_t *out)
{
    uint32_t i = 0;
    for (; i + 8u <= n; i += 8u) {
        uint32x4_t lo = vdupq_n_u32(1u << 14), hi = lo;
        for (uint32_t t = 0; t < taps; t++) {
            const uint16x8_t v = vld1q_u16(rows[t] + i);
            lo = vmlal_n_u16(lo, vget_low_u16(v), w[t]);
            hi = vmlal_high_n_u16(hi, v, w[t]);
        }
        /* <= 65280 after the shift: the narrowing keeps every bit */
        vst1q_u16(out + i, vcombine_u16(vshrn_n_u32(lo, 15), vshrn_n_u32(hi, 15)));
    }
    for (; i < n; i++) {
        uint32_t acc = 0;
        for (uint32_t t = 0; t < taps; t++) {
            acc += w[t] * (uint32_t)rows[t][i];
        }
        out[i] = (uint16_t)((acc + (1u << 14)) >> 15);
    }
}

/* Taps 8c .. 8c + 7 of a column, weighted, into the channel sums r, g, b. */
#define TRM_DH_CHUNK(p, wt, r, g, b)                                                           \
    do {                                                                                      \
        const uint8x8x3_t px_ = vld3_u8(p); /* 8 RGB pixels split by channel */              \
        const uint16x8_t w_ = (wt), r_ = vmovl_u8(px_.val[0]), g_ = vmovl_u8(px_.val[1]),     \
                         b_ = vmovl_u8(px_.val[2]);                                           \
        r = vmlal_high_u16(vmlal_u16(r, vget_low_u16(r_), vget_low_u16(w_)), r_, w_);         \
        g = vmlal_high_u16(vmlal_u16(g, vget_low_u16(g_), vget_low_u16(w_)), g_, w_);         \
        b = vmlal_high_u16(vmlal_u16(b, vget_low_u16(b_), vget_low_u16(w_)), b_, w_);         \
    } while (0)

/* Horizontal pass of D: one reduced column per step, its taps 8 at a time
 * (lanes past the last tap get weight 0: the last chunk's mask).  A column
 * whose kernel reaches past either end of the row, or whose last 8-tap
 * read would, goes through the C kernel (its clamp to the edge); a column
 * whose 8-wide weight read would pass the end of the weight table reads a
 * copy.  The three sums are reduced together and stored as four uint16
 * (the fourth is the next column's first, written again by it), the last
 * column's three one by one. */
void tdc_trm_dhoriz_neon(const uint8_t *row, uint32_t width, const int16_t *first, const uint16_t *w_all, uint32_t taps,
                         uint32_t rw, uint16_t *dst)
{
    const uint32_t chunks = (taps + 7u) / 8u, span = 8u * chunks;
    const uint16x8_t lane = {0, 1, 2, 3, 4, 5, 6, 7};
    const uint16x8_t keep_last = vcltq_u16(vaddq_u16(lane, vdupq_n_u16((uint16_t)(span - 8u))), vdupq_n_u16((uint16_t)taps));
    uint16_t wpad[TDC_TRM_MAX_TAPS + 8u] = {0};
    for (uint32_t j = 0; j < rw; j++) {
        const int32_t k0 = first[j];
        if (k0 < 0 || (uint32_t)k0 + span > width) {
            tdc_trm_dhoriz_c(row, width, first + j, w_all + (size_t)j * taps, taps, 1u, dst + 3u * j);
            continue;
        }
        const uint16_t *w = w_all + (size_t)j * taps;
        if ((size_t)j * taps + span > (size_t)rw * taps) {
            for (uint32_t t = 0; t < taps; t++) {
                wpad[t] = w[t];
            }
            w = wpad;
        }
        const uint8_t *p = row + 3u * (uint32_t)k0;
        uint32x4_t ar = vdupq_n_u32(0), ag = ar, ab = ar;
        for (uint32_t c = 0; c + 1u < chunks; c++) {
            TRM_DH_CHUNK(p + 24u * c, vld1q_u16(w + 8u * c), ar, ag, ab);
        }
        TRM_DH_CHUNK(p + 24u * (chunks - 1u), vandq_u16(vld1q_u16(w + span - 8u), keep_last), ar, ag, ab);
        /* (sum r, sum g, sum b, sum b) by pairwise adds, + 2^6, >> 7: <= 65280 */
        const uint32x4_t s = vpaddq_u32(vpaddq_u32(ar, ag), vpaddq_u32(ab, ab));
        const uint16x4_t o = vshrn_n_u32(vaddq_u32(s, vdupq_n_u32(64u)), 7);
        if (j + 1u < rw) {
            vst1_u16(dst + 3u * j, o);
        } else {
            vst1_lane_u16(dst + 3u * j, o, 0);
            vst1_lane_u16(dst + 3u * j + 1u, o, 1);
            vst1_lane_u16(dst + 3u * j + 2u, o, 2);
        }
    }
}

#else

/* Not an AArch64 build: an empty object (ISO C wants one declaration). */
typedef int tdc_trm_neon_unused_t;

#endif
