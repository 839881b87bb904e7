/*
 * tdc_fov_kernels.h - the foveated remap's tap kernel (eq. 4.4 at sigma_u =
 * 1/2 with the bilinear step along v), internal to the stage.
 *
 * tdc_fov.c walks a display row twice: the geometry pass (eq. 2.2 from the
 * radial table and the per-column reciprocals, eq. 4.4's sigma) writes for
 * every pixel a tap descriptor; this kernel then reads the log-polar samples
 * and blends them.  The portable C kernel (tdc_fov.c) is the reference and
 * what the Cortex-M7 runs; tdc_fov_avx2.c (x86-64 hosts) and tdc_fov_mve.c
 * (Helium, Cortex-M55 boards) must produce the same values
 * (tests/checkasm/checkasm_fov.c checks that on random and extreme rows and
 * benchmarks them).  tdc_fov_init() picks AVX2 when the CPU has it.
 *
 * Pixel k of the row: two columns c0 = floor(u) and c1 = c0 + 1 (clamped to
 * the carried columns: step 0 when both clamp to one), two rows j0 and j1
 * (the angle's neighbours, periodic).
 *   off0[k]  byte offset of sample (c0, j0) in lp; bit 31: step 0 (else 3)
 *   off1[k]  byte offset of sample (c0, j1)
 *   wf[k]    w0 | fv << 16: w0 the Q15 weight of c0 (c1 gets 2^15 - w0),
 *            w0 <= 2^15; fv the Q15 fraction toward j1, fv < 2^15
 * Output (planes of n uint16, Q8 codes):
 *   w1 = 2^15 - w0, a = (w0 fv + 2^14) >> 15, b = (w1 fv + 2^14) >> 15,
 *   out_c = ((w0 - a) p(c0,j0) + (w1 - b) p(c1,j0) + a p(c0,j1) + b p(c1,j1) + 64) >> 7.
 * Scaling and overflow: w0 fv < 2^30; the four weights are >= 0 and sum
 * to 2^15 exactly, so the sum < 255 * 2^15 < 2^23 and out <= 255 * 256.
 * Every offset + step + 2 < lp_bytes (the caller's descriptors; the SIMD
 * kernels rely on it and fall back to C for a group that reads within 4
 * bytes of the end).
 */
#ifndef TDC_FOV_KERNELS_H
#define TDC_FOV_KERNELS_H

#include <stddef.h>
#include <stdint.h>

#include "tdc_fixed.h"

#define TDC_FOV_STEP0 0x80000000u /* off0 flag: both columns are the same sample */

typedef struct {
    const uint8_t *lp;
    size_t lp_bytes; /* readable bytes from lp */
    const uint32_t *off0, *off1, *wf;
    uint16_t *out[3]; /* R, G, B planes */
} tdc_fov_tap2_args_t;

typedef void tdc_fov_tap2_row_fn(const tdc_fov_tap2_args_t *a, uint32_t n);

tdc_fov_tap2_row_fn tdc_fov_tap2_row_c;
tdc_fov_tap2_row_fn tdc_fov_tap2_row_avx2; /* the C kernel on targets without AVX2 */
tdc_fov_tap2_row_fn tdc_fov_tap2_row_mve;  /* Helium; the C kernel elsewhere */

/* 1 when this build has the AVX2 kernel and the CPU runs it. */
int tdc_fov_avx2_available(void);

/* What a board runs (AVX2 on hosts is chosen at run time). */
#if defined(TDC_TRM_MVE) /* Helium boards (BOARD_MVE): every object is told */
#define TDC_FOV_TAP2_BOARD tdc_fov_tap2_row_mve
#else
#define TDC_FOV_TAP2_BOARD tdc_fov_tap2_row_c
#endif

/* One pixel of the kernel: the C reference, also the SIMD kernels' tail. */
static inline void tdc_fov_tap2_px(const tdc_fov_tap2_args_t *a, uint32_t k)
{
    const uint32_t o0 = a->off0[k] & ~TDC_FOV_STEP0, o1 = a->off1[k];
    const uint32_t st = (a->off0[k] & TDC_FOV_STEP0) ? 0u : 3u;
    const uint32_t w0 = a->wf[k] & 0xFFFFu, fv = a->wf[k] >> 16, w1 = 32768u - w0;
    const uint32_t wa = (w0 * fv + 16384u) >> 15, wb = (w1 * fv + 16384u) >> 15;
    const uint32_t w00 = w0 - wa, w01 = w1 - wb;
    const uint8_t *p0 = a->lp + o0, *p1 = a->lp + o1, *q0 = p0 + st, *q1 = p1 + st;
    /* the channels written out: -O2 keeps a 3-trip loop, with its overhead per pixel */
    a->out[0][k] = (uint16_t)((w00 * p0[0] + w01 * q0[0] + wa * p1[0] + wb * q1[0] + 64u) >> 7);
    a->out[1][k] = (uint16_t)((w00 * p0[1] + w01 * q0[1] + wa * p1[1] + wb * q1[1] + 64u) >> 7);
    a->out[2][k] = (uint16_t)((w00 * p0[2] + w01 * q0[2] + wa * p1[2] + wb * q1[2] + 64u) >> 7);
}

/* The geometry pass marks a pixel whose colour it computed itself (sigma
 * > 1/2, or a log-rectilinear periphery) with this bit of b[i]. */
#define TDC_FOV_GEN_FLAG 512u

/* eq. 2.2's angle in Q32 turns from the octant ratio t = min/max (Q30):
 * the arctangent table (tdc_fov_tables.h, 257 entries), then symmetry.  The
 * stage's tdc_fov_turns_q32 and the geometry row kernels. */
static inline uint32_t tdc_fov_turns_from_ratio(const uint32_t *atan_tab, uint32_t t, uint32_t ax, uint32_t ay,
                                                int32_t dx, int32_t dy)
{
    const uint32_t idx = t >> 22, fr = (t >> 6) & 0xFFFFu;
    const uint32_t a0 = atan_tab[idx];
    const uint32_t a1 = idx < 256u ? atan_tab[idx + 1u] : a0;
    uint32_t a = a0 + (uint32_t)tdc_urshr64((uint64_t)(a1 - a0) * fr, 16);
    if (ay > ax) {
        a = (1u << 30) - a;
    }
    if (dx < 0) {
        a = (1u << 31) - a;
    }
    if (dy < 0) {
        a = 0u - a;
    }
    return a;
}

#endif /* TDC_FOV_KERNELS_H */
