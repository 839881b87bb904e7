/*
 * tdc_fov_mve.c - the foveated remap's tap kernel (tdc_fov_kernels.h) with
 * Helium (MVE), for Cortex-M55 boards; the C kernel elsewhere.
 */
#include "tdc_fov_kernels.h"

void tdc_fov_tap2_row_mve(const tdc_fov_tap2_args_t *a, uint32_t n)
{
    tdc_fov_tap2_row_c(a, n);
}
