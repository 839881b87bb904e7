/*
 * ref_layers.h - double-precision reference of the layered tile assembly
 * (firmware/tdc_layers.h), written from Zeng et al. §4-§5 and TDRT §3.2:
 * the same per-layer rules in doubles (exact mean, sqrt, exp, pow gamma),
 * 8-bit history between frames (the firmware's state), so the fixed-point
 * stage can be compared closed loop (tests/unit/test_layers_ref.c).
 *
 * The one quantisation shared on purpose: the clean-up sigma is floored to
 * 1/16 px before the Gaussian (the firmware's table index), as a part of the
 * algorithm's definition; the weights themselves are exact exp().
 */
#ifndef REF_LAYERS_H
#define REF_LAYERS_H

#include <stdint.h>

#include "tdc_layer_link.h"

typedef struct tdc_ref_lasm tdc_ref_lasm_t;

typedef struct {
    int width, height;
    unsigned layers; /* TDC_LAYER_PKT_TYPE set */
    int clamp_k;     /* 1 or 3 */
    int cleanup;
    int splat_radius;
    double alpha;
    double gamma[3]; /* panel gamma per channel */
    int history;     /* 1: per-layer history (ref_layer_hist.h) on each assembled layer, as tdc_layers.h */
} tdc_ref_lasm_config_t;

tdc_ref_lasm_t *tdc_ref_lasm_new(const tdc_ref_lasm_config_t *cfg);
void tdc_ref_lasm_free(tdc_ref_lasm_t *r);
/* As tdc_lasm_ingest (lf->present, planes by type); pattern_bits may be NULL. */
int tdc_ref_lasm_ingest(tdc_ref_lasm_t *r, uint32_t frame, const tdc_layer_frame_t *lf, const uint8_t *pattern_bits);
int tdc_ref_lasm_assemble(tdc_ref_lasm_t *r, uint32_t frame);
/* Displayed frame RGB888 (rounded) and unrounded codes (doubles). */
const uint8_t *tdc_ref_lasm_output(const tdc_ref_lasm_t *r);
const double *tdc_ref_lasm_output_exact(const tdc_ref_lasm_t *r);
/* Layer type t's last frame as recombined (8-bit; with history the rounded
 * history output), NULL if not kept. */
const uint8_t *tdc_ref_lasm_layer(const tdc_ref_lasm_t *r, unsigned type);

#endif
