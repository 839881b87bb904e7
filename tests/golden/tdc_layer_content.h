/*
 * tdc_layer_content.h - a deterministic layered subframe stream (integer
 * only, freestanding: golden vectors on the host and on ARM, the
 * fixed-vs-double report, the benchmark, the fuzz seeds): a fence-like
 * scene in components, sampled at each tile's pixel of the subframe:
 *   SHADING     a static floor (checker + 3-px noise), or panning at sh_v;
 *   VISIBILITY  bars of period 14 px, 5 px of full shadow (V = 51) with
 *               1-px ramps, moving at vis_v (Q4 px/frame);
 *               vectors: SHADOW kind (-vis_v where the sample is in shadow,
 *               0 where lit: splatting spreads them) or SURFACE (all 0);
 *               falloff: G < 1 on the right third (a "non-planar receiver");
 *   GLOSSY      a dim texture panning at gl_v (GLOSSY vectors -gl_v);
 *   INDIRECT    a dim static gradient (SURFACE vectors 0).
 * Vectors are backward (the point now at p was at p + mv), Q4.
 */
#ifndef TDC_LAYER_CONTENT_H
#define TDC_LAYER_CONTENT_H

#include <stdint.h>
#include <string.h>

#include "tdc_layer_link.h"

/* Zeroes the layered frame lf and points its planes at the caller's arrays:
 * value[t] = VAL[t], mv[t] = MV[t] for every layer index t (VAL and MV
 * indexable 0 .. TDC_LAYER_MAX - 1, each plane sized for the tiles),
 * falloff = FALLOFF.  The one wiring of a frame the layered stage fills or
 * the decoder writes, for the tests, benchmarks and fuzzers. */
#define TDC_LAYER_FRAME_WIRE(lf, VAL, MV, FALLOFF)                                                                     \
    do {                                                                                                               \
        memset(&(lf), 0, sizeof(lf));                                                                                  \
        for (unsigned wire_t_ = 0; wire_t_ < TDC_LAYER_MAX; wire_t_++) {                                               \
            (lf).value[wire_t_] = (VAL)[wire_t_];                                                                      \
            (lf).mv[wire_t_] = (MV)[wire_t_];                                                                          \
        }                                                                                                              \
        (lf).falloff = (FALLOFF);                                                                                      \
    } while (0)

typedef struct {
    uint16_t w, h;
    uint16_t layers;          /* TDC_LAYER_PKT_TYPE set, + TDC_LAYER_PKT_FALLOFF */
    int16_t sh_vx, sh_vy;     /* shading motion, Q4 px/frame */
    int16_t vis_vx;           /* shadow motion, Q4 px/frame */
    int16_t gl_vx, gl_vy;     /* glossy motion */
    uint8_t shadow_vectors;   /* 1: SHADOW kind, 0: SURFACE (ordinary) */
    uint8_t random_mv;        /* 1: random vectors over the whole int16 range but the sentinel (stress) */
    uint32_t seed;
} tdc_lcontent_t;

/* The layered subframe of `frame` for orderings `pattern` (tile bitmap):
 * fills out's planes (which must hold the tiles of every layer in c->layers)
 * and its header (count, types, vector kinds, tiles), out->present. */
void tdc_layer_content_subframe(const tdc_lcontent_t *c, uint32_t frame, const uint8_t *pattern,
                                tdc_layer_frame_t *out);

/* Linear-light-like exact value of visibility at pixel-centre x (Q4) at
 * frame t: 0..255 (255 = lit). */
uint32_t tdc_layer_content_vis(const tdc_lcontent_t *c, int32_t x_q4, uint32_t frame);

#endif
