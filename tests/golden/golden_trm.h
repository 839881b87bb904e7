/* golden_trm.h - the TRM pair step shared by golden_trm.c and golden_trmgaze.c. */
#ifndef TDC_GOLDEN_TRM_H
#define TDC_GOLDEN_TRM_H

#include <stdint.h>

#include "tdc_trm.h"

/* The stage configuration of a TRM-family vector: the default for a w x h
 * panel at 90 Hz with the ratio rn/rd. */
void tdc_golden_trm_config(tdc_trm_config_t *cfg, uint32_t w, uint32_t h, uint32_t rn, uint32_t rd);

uint64_t tdc_golden_trm_step(tdc_trm_t *trm, uint32_t t, const uint8_t *in, uint8_t *out, uint8_t *red, tdc_res_t *rho_row,
                             uint32_t w, uint32_t h, int *ok);

#endif
