/*
 * ref_layer_hist.h - double-precision reference of the per-layer history
 * (firmware/tdc_layer_hist.h): Zeng et al. eq. 2 with eq. 4's alpha^V, the
 * history fetched bilinearly at the layer's vector and clamped to mu +- k
 * sigma of the current frame's 3x3 neighbourhood, all in doubles (exact
 * mean, sqrt, bilinear weights; the history is never rounded), so the
 * fixed-point stage is compared closed loop (tests/unit/test_layer_hist.c).
 * Shared on purpose: the inputs' quantisation (8-bit frames, Q4 vectors,
 * Q15 alpha and falloff).
 */
#ifndef REF_LAYER_HIST_H
#define REF_LAYER_HIST_H

#include <stdint.h>

#include "tdc_layer_hist.h"

typedef struct {
    tdc_lhist_config_t cfg;
    double *hist, *next, *out; /* W x H x c, code values 0..255 */
    int have;
} tdc_ref_lhist_t;

int tdc_ref_lhist_init(tdc_ref_lhist_t *r, const tdc_lhist_config_t *cfg);
void tdc_ref_lhist_free(tdc_ref_lhist_t *r);
/* As tdc_lhist_step; r->out holds the unrounded output. */
void tdc_ref_lhist_step(tdc_ref_lhist_t *r, const uint8_t *x, const int16_t *mv, const uint16_t *falloff);

#endif
