/*
 * ref_asm.h - the double-precision reference of tile-ordered frame assembly
 * itself (TDRT paper §3.2, docs/design.md §4.3): what the simulator links
 * (its asm-ref-* modes) without the synthetic stream of ref_assemble.h,
 * whose scene names would clash with the simulator's own.
 *
 * The reference keeps its own state (heap, host only).  Its previous frame
 * is its own 8-bit output (the output frame format is RGB888, and the paper
 * reprojects from the previous output frame); everything else - bilinear
 * weights, mean, sigma, box, window mean - is computed in double and rounded
 * half up only when written to the 8-bit output.
 */
#ifndef REF_ASM_H
#define REF_ASM_H

#include <stddef.h>
#include <stdint.h>

#include "tdc_ordering.h"

/* Ordering decision in double: l_f = |m| - floor|m|, a = atan2 folded,
 * band (0.25, 0.75) shifted by +-0.5 a/(pi/2), random band |a - pi/4| <
 * pi/40 decided by tdc_hash3 (tdc_math.h: the definition of the random choice). */
tdc_ordering_t tdc_ref_ordering_decide(double mx, double my, tdc_ordering_t current, uint32_t tile_x, uint32_t tile_y,
                                       uint32_t frame);

typedef struct tdc_ref_asm tdc_ref_asm_t;

tdc_ref_asm_t *tdc_ref_asm_new(int w, int h);
void tdc_ref_asm_free(tdc_ref_asm_t *r);
/* Same contract as tdc_asm_ingest / tdc_asm_assemble (returns 0 or -1). */
int tdc_ref_asm_ingest(tdc_ref_asm_t *r, uint32_t frame, const uint8_t *samples, const int16_t *mvs,
                       const uint8_t *pattern_bits);
int tdc_ref_asm_assemble(tdc_ref_asm_t *r, uint32_t frame);
/* Last output, RGB888 rows w*3 bytes apart; and its unrounded values. */
const uint8_t *tdc_ref_asm_output(const tdc_ref_asm_t *r);
const double *tdc_ref_asm_output_exact(const tdc_ref_asm_t *r);

/*
 * The colour box an old dynamic pixel is clamped to (variance sampling,
 * TDRT §3.2.1, Fig. 7).  The firmware implements only the paper's choice
 * (NEWEST); the two alternatives the paper rejects exist here so that the
 * simulator can judge them (tdc-sim modes asm-ref-*, the tdrt-fig7 group):
 *   NEWEST  the pixel's immediate (8) neighbours that are in the most recent
 *           subframe (the paper's, and the firmware's, box)
 *   ALL     all 8 immediate neighbours: a new neighbour gives its sample, an
 *           old one the previous output frame bilinearly resampled at its
 *           position + m (the value it has before its own clamp), i.e. old
 *           pixel information in the box ("old pixel information would be used")
 *   SUB3X3  a 3x3 area of the most recent subframe: the newest sample of each
 *           of the 9 tiles around the pixel's tile (a 6x6-pixel footprint)
 */
typedef enum { TDC_REF_NBHD_NEWEST = 0, TDC_REF_NBHD_ALL, TDC_REF_NBHD_SUB3X3 } tdc_ref_nbhd_t;
void tdc_ref_asm_set_nbhd(tdc_ref_asm_t *r, tdc_ref_nbhd_t nbhd);

#endif
