/*
 * tdc_fov_mve.c - the foveated remap's tap kernel (tdc_fov_kernels.h) with
 * Arm Helium (M-profile Vector Extension, integer only) for Cortex-M55
 * boards.  Same values as the C kernel (the checkasm core,
 * tests/checkasm/checkasm_fov.c, checks that under QEMU mps3-an547; the
 * golden vectors run through it on that board).
 *
 * Built as TRM's Helium kernels are (firmware/tdc_trm_mve.c): only where
 * the board says so (BOARD_MVE := 1: this object gets -mcpu=cortex-m55+nofp
 * -mfloat-abi=softfp, every object TDC_TRM_MVE=1 so tdc_fov.c calls it);
 * elsewhere the C kernel behind the same name.
 *
 * Layout: 4 pixels per step, the planar descriptors loaded as vectors, the
 * 12 sample bytes of each pixel (2 columns x 2 rows x RGB) by byte gathers
 * (exactly the bytes the C kernel reads, so no end-of-buffer case), the
 * weights and sums in 32-bit lanes (the C kernel's arithmetic, < 2^31),
 * stored to the uint16 planes by narrowing stores.  The last n mod 4
 * pixels go through the C pixel.
 */
#include "tdc_fov_kernels.h"

#if defined(__ARM_FEATURE_MVE) && defined(TDC_TRM_MVE)

#include <arm_mve.h>

void tdc_fov_tap2_row_mve(const tdc_fov_tap2_args_t *a, uint32_t n)
{
    const uint32x4_t flag = vdupq_n_u32(TDC_FOV_STEP0), three = vdupq_n_u32(3u);
    const uint32x4_t one15 = vdupq_n_u32(32768u), lo16 = vdupq_n_u32(0xFFFFu);
    uint32_t k = 0;
    for (; k + 4u <= n; k += 4u) {
        const uint32x4_t o0f = vldrwq_u32(a->off0 + k), o1 = vldrwq_u32(a->off1 + k), wf = vldrwq_u32(a->wf + k);
        const uint32x4_t o0 = vbicq_u32(o0f, flag);
        const uint32x4_t msk = vreinterpretq_u32_s32(vshrq_n_s32(vreinterpretq_s32_u32(o0f), 31));
        const uint32x4_t st = vbicq_u32(three, msk); /* 0 where the flag is set, else 3 */
        const uint32x4_t w0 = vandq_u32(wf, lo16), fv = vshrq_n_u32(wf, 16), w1 = vsubq_u32(one15, w0);
        const uint32x4_t wa = vshrq_n_u32(vaddq_n_u32(vmulq_u32(w0, fv), 16384u), 15);
        const uint32x4_t wb = vshrq_n_u32(vaddq_n_u32(vmulq_u32(w1, fv), 16384u), 15);
        const uint32x4_t w00 = vsubq_u32(w0, wa), w01 = vsubq_u32(w1, wb);
        const uint32x4_t o0s = vaddq_u32(o0, st), o1s = vaddq_u32(o1, st);
        for (uint32_t c = 0; c < 3u; c++) {
            const uint8_t *b = a->lp + c;
            uint32x4_t s = vmulq_u32(w00, vldrbq_gather_offset_u32(b, o0));
            s = vaddq_u32(s, vmulq_u32(vldrbq_gather_offset_u32(b, o0s), w01)); /* MVE has no vector x vector MLA */
            s = vaddq_u32(s, vmulq_u32(vldrbq_gather_offset_u32(b, o1), wa));
            s = vaddq_u32(s, vmulq_u32(vldrbq_gather_offset_u32(b, o1s), wb));
            vstrhq_u32(a->out[c] + k, vshrq_n_u32(vaddq_n_u32(s, 64u), 7));
        }
    }
    for (; k < n; k++) {
        tdc_fov_tap2_px(a, k);
    }
}

#else /* not a Helium board: the C kernel behind the same name */

void tdc_fov_tap2_row_mve(const tdc_fov_tap2_args_t *a, uint32_t n)
{
    tdc_fov_tap2_row_c(a, n);
}

#endif
