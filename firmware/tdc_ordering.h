/*
 * tdc_ordering.h - per-tile pixel orderings of tile-ordered frame assembly
 * (docs/design.md §4.3, TDRT paper §3.1.1 and §3.2.3).  Shared by the firmware
 * assembly stage and the host renderer, which links this file so both sides
 * make bit-identical decisions.
 *
 * Tiles are 2x2 pixels; positions in a tile: TL = 0, TR = 1, BL = 2, BR = 3
 * (position p is pixel (2 tx + (p & 1), 2 ty + (p >> 1))).  Subframe
 * k = frame mod 4 traces, in every tile, the position tdc_ordering_pixel(o, k).
 *
 * Motion vectors: per full-res pixel an interleaved int16 pair (dx, dy) in
 * Q4 (1/16 px), BACKWARD: the surface point now at p was at p + (dx, dy) in
 * the previous frame.  The decision only uses |m| and the folded angle, so
 * the sign convention does not change it.
 *
 * Pattern bits: 1 bit per tile, tiles row-major, bit (i & 7) of byte i >> 3
 * (LSB first), 1 = bowtie, 0 = hourglass.  Tiles = ceil(W/2) x ceil(H/2).
 */
#ifndef TDC_ORDERING_H
#define TDC_ORDERING_H

#include <stdint.h>
#include <string.h>

#include "tdc_geom.h"

typedef enum { TDC_ORDER_HOURGLASS = 0, TDC_ORDER_BOWTIE = 1 } tdc_ordering_t;

/* Tile position numbers. */
enum { TDC_TILE_TL = 0, TDC_TILE_TR = 1, TDC_TILE_BL = 2, TDC_TILE_BR = 3 };

/* Tiles and bitmap bytes of a w x h frame: TDC_TILES, TDC_PATTERN_BYTES
 * (tdc_geom.h). */

/* One motion vector (dx, dy) as a 32-bit word, for equality and zero tests
 * only (so its byte order does not matter). */
static inline uint32_t tdc_mv_word(const int16_t *pair)
{
    uint32_t v;
    memcpy(&v, pair, sizeof v);
    return v;
}

/* Summary of one motion row of w vectors (w >= 1): TDC_MV_ROW_ANY if any
 * vector is non-zero, TDC_MV_ROW_UNIFORM if all equal the first (*first =
 * its tdc_mv_word).  One pass of 32-bit loads; the ordering update and the
 * assembly use it to skip per-pixel searches over rows of one vector. */
#define TDC_MV_ROW_ANY 1u
#define TDC_MV_ROW_UNIFORM 2u
unsigned tdc_mv_row_scan(const int16_t *row, uint32_t w, uint32_t *first);

/* Position traced in subframe k (k taken mod 4): hourglass TL,TR,BL,BR;
 * bowtie TL,BL,TR,BR. */
unsigned tdc_ordering_pixel(tdc_ordering_t o, unsigned k);

/*
 * The ordering decision g(l_f, a) of docs/design.md §4.3 for one tile.
 *   m = (mx_q4, my_q4): the tile's motion, Q4 px (|component| <= 32768).
 *   l_f = fractional part of |m|: |m| is floor(sqrt((mx^2 + my^2) * 2^16))
 *         in Q12 px, exact (integer square root), so l_f is exact to
 *         -2^-12 px (floor) given the Q4 input.
 *   a   = angle of m folded into [0, pi/2] (|mx|, |my|), measured in
 *         quarter turns u = a / (pi/2) in Q16 by a 33-entry atan table on
 *         min/max with linear interpolation: |error| <= 2^-13 quarter turns
 *         (asserted by tests/unit/test_ordering.c against double atan2).
 *   Band: hourglass iff (l_f - s) mod 1 in (0.25, 0.75), where s = u/2 for
 *         a <= pi/4 - gamma (a = 0 gives paper eq. 4), and iff (l_f + s)
 *         mod 1 in [0.25, 0.75] for a >= pi/4 + gamma (a = pi/2 gives paper
 *         eq. 5 with its closed ends); l_f and s compared in Q12.
 *   Random band: a in (pi/4 - gamma, pi/4 + gamma), gamma = pi/40, decided
 *         exactly by min(|mx|,|my|) * 2^16 > TAN_9PI_40_Q16 * max(...)
 *         (tan(9 pi/40) = 0.8540807 in Q16); the choice is one bit of a
 *         32-bit integer hash of (tile_x, tile_y, frame): reproducible.
 *   m = 0 returns `current`.
 * Integer only, no division in the hot path but one tdc_div_q15.
 */
tdc_ordering_t tdc_ordering_decide(int32_t mx_q4, int32_t my_q4, tdc_ordering_t current, uint32_t tile_x,
                                   uint32_t tile_y, uint32_t frame);

/*
 * Updates every tile's ordering for the 4-frame cycle starting at `frame`
 * (frame should be a multiple of 4; both renderer and controller pass the
 * first frame index of the new cycle).  For each tile, m = the longest
 * motion vector (largest dx^2 + dy^2, first in raster order on ties) over
 * the full-res pixels of the tile's 3x3 tile neighbourhood (up to 6x6
 * pixels, clipped to the frame); then bit = tdc_ordering_decide(m, bit, ...).
 * mv: w*h interleaved Q4 pairs, rows w pairs apart.  pattern_bits: in/out,
 * TDC_PATTERN_BYTES(w, h) bytes (the current orderings in, the new
 * ones out; padding bits of the last byte are left unchanged).
 */
void tdc_ordering_update(const int16_t *mv, int w, int h, uint8_t *pattern_bits, uint32_t frame);

/* Pattern bit helpers. */
static inline tdc_ordering_t tdc_ordering_get(const uint8_t *bits, uint32_t tile_index)
{
    return (tdc_ordering_t)((bits[tile_index >> 3] >> (tile_index & 7u)) & 1u);
}

static inline void tdc_ordering_set(uint8_t *bits, uint32_t tile_index, tdc_ordering_t o)
{
    uint8_t m = (uint8_t)(1u << (tile_index & 7u));
    bits[tile_index >> 3] =
        (uint8_t)(o == TDC_ORDER_BOWTIE ? (bits[tile_index >> 3] | m) : (bits[tile_index >> 3] & ~m));
}

/*
 * Static-pixel jitter (4x SSAA, docs/design.md §4.3): a fixed 4-position rotated
 * grid that advances once per 4 frames: index j = (frame / 4) mod 4,
 * offsets from the pixel centre in Q4 px:
 *   j = 0: (-2, -6)   j = 1: (+6, -2)   j = 2: (+2, +6)   j = 3: (-6, +2)
 * i.e. (+-1/8, +-3/8) px.  Dynamic pixels are sampled at the centre.
 */
void tdc_jitter_offset_q4(uint32_t frame, int32_t *dx_q4, int32_t *dy_q4);

/* Internals exposed for tests: folded angle in Q16 quarter turns (0 .. 65536)
 * and the fractional length in Q12 (0 .. 4095). */
uint32_t tdc_ordering_angle_q16(int32_t mx_q4, int32_t my_q4);
uint32_t tdc_ordering_frac_len_q12(int32_t mx_q4, int32_t my_q4);
/* 1 if the folded angle lies in the random band (pi/4 - gamma, pi/4 + gamma). */
int tdc_ordering_in_random_band(int32_t mx_q4, int32_t my_q4);
/* The random band's bit is bit 31 of tdc_hash3(tile_x, tile_y, frame)
 * (tdc_math.h). */

#endif /* TDC_ORDERING_H */
