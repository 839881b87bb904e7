/*
 * tdc_sim_blockmatch.h - motion estimated from two decoded frames by block
 * matching, as a headset compositor doing ASW-style extrapolation has to:
 * it sees the frames, not the renderer's motion vectors.
 *
 * Hierarchical search on luma: a 3-level box pyramid, full search of
 * +-TDC_BM_RANGE/4 px at the coarsest level for 8x8 blocks, then +-1 px
 * refinement of the parent's and its neighbours' vectors at each finer
 * level (the best of them), the zero vector as a candidate at full
 * resolution, a parabola through the SADs for the sub-pixel part (+-0.5 px)
 * and a 3x3 component-wise median over the block vectors (outliers in flat
 * blocks).  Ties prefer the shorter vector (SAD + TDC_BM_LAMBDA |d|1), so
 * flat content does not move.
 *
 * Convention: backward, like the renderer's MVs (docs/design.md §4.4): the content
 * at p in `cur` was at p + d in `prev`.  Output per pixel, Q4 px, scaled by
 * `scale` (0.5: a vector over two frames turned into one frame's).
 */
#ifndef TDC_SIM_BLOCKMATCH_H
#define TDC_SIM_BLOCKMATCH_H

#include <stdint.h>

#define TDC_BM_BLOCK 8     /* block size at every pyramid level, px of that level */
#define TDC_BM_LEVELS 3    /* full, 1/2, 1/4 resolution */
#define TDC_BM_RANGE 32    /* full-resolution search range, px (+-) */
#define TDC_BM_LAMBDA 1e-4 /* SAD penalty per full-resolution px of vector length (mean luma 0..1) */

typedef struct {
    int w[TDC_BM_LEVELS], h[TDC_BM_LEVELS];
    int bw[TDC_BM_LEVELS], bh[TDC_BM_LEVELS]; /* blocks per level */
    float *lum[2][TDC_BM_LEVELS];             /* prev, cur luma pyramids */
    float *vec[TDC_BM_LEVELS];                /* block vectors (x, y) per level, px of that level */
    float *med;                               /* median-filtered full-resolution block vectors */
} tdc_bm_t;

/* 0, or -1 when out of memory (then tdc_bm_free). */
int tdc_bm_init(tdc_bm_t *bm, int w, int h);
/* Backward MVs of cur relative to prev (RGB888, w*h*3) into mv (w*h*2 Q4), times scale. */
void tdc_bm_estimate(tdc_bm_t *bm, const uint8_t *prev, const uint8_t *cur, double scale, int16_t *mv);
void tdc_bm_free(tdc_bm_t *bm);

#endif
