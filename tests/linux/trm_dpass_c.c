/*
 * trm_dpass_c.c - make bench-aarch64 only: the NEON D-pass names bound to
 * the portable C kernels.  Linked before the firmware library into a copy
 * of the arm64 board program (tdc-board-dpass-c), so the archive's NEON
 * object is not pulled in and the whole frame loop runs the C D passes:
 * its instruction count beside the NEON program's is what NEON saves
 * (tests/linux/a64_loop_insn.sh).
 */
#include "tdc_trm_kernels.h"

void tdc_trm_dvert_neon(const uint16_t *const *rows, const uint16_t *w, uint32_t taps, uint32_t n, uint16_t *out)
{
    tdc_trm_dvert_c(rows, w, taps, n, out);
}

void tdc_trm_dhoriz_neon(const uint8_t *row, uint32_t width, const int16_t *first, const uint16_t *w_all, uint32_t taps,
                         uint32_t rw, uint16_t *dst)
{
    tdc_trm_dhoriz_c(row, width, first, w_all, taps, rw, dst);
}
