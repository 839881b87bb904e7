/*
 * ref_assemble.h - double-precision reference of tile-ordered frame assembly
 * (TDRT paper §3.2, docs/design.md §4.3), written straight from the text, plus a
 * synthetic 240 Hz subframe stream (an analytic "renderer") for the tests,
 * golden-free error reports and the benchmark.  The assembly's own
 * declarations are in ref_asm.h (the simulator includes only that).
 */
#ifndef REF_ASSEMBLE_H
#define REF_ASSEMBLE_H

#include <stddef.h>
#include <stdint.h>

#include "ref_asm.h"
#include "tdc_ordering.h"

/* ------------------------------------------------------------------------
 * Synthetic subframe stream.
 * ---------------------------------------------------------------------- */
typedef enum {
    TDC_SCENE_STATIC = 0, /* fine texture, no motion: jittered samples */
    TDC_SCENE_PAN,        /* textured panorama moving (vx, vy) px/frame */
    TDC_SCENE_LINE,       /* 1-px-wide bright vertical lines moving vx over a static background */
    TDC_SCENE_HLINE       /* 1-px-wide horizontal lines moving vy */
} tdc_scene_kind_t;

typedef struct {
    tdc_scene_kind_t kind;
    int w, h;
    int32_t vx_q4, vy_q4; /* scene velocity, Q4 px/frame (MV = -v) */
    uint32_t seed;
    int16_t *mvbuf;   /* renderer's full-res motion buffer (like the controller's) */
    uint8_t *pattern; /* renderer's orderings */
} tdc_scene_t;

/* Allocates buffers; all tiles start hourglass, motion zero. */
int tdc_scene_init(tdc_scene_t *s, tdc_scene_kind_t kind, int w, int h, int32_t vx_q4, int32_t vy_q4, uint32_t seed);
void tdc_scene_free(tdc_scene_t *s);

/* Colour of the scene at continuous position (x, y) (pixel centres at
 * integers) at frame t, 0..255 per channel (double). */
void tdc_scene_color(const tdc_scene_t *s, double x, double y, uint32_t t, double rgb[3]);

/* Motion at pixel (x, y), frame t: backward Q4 MV (0 where static). */
void tdc_scene_mv(const tdc_scene_t *s, int x, int y, uint32_t t, int16_t mv[2]);

/*
 * Renders subframe `frame`: at the first frame of a cycle the renderer
 * decides orderings with tdc_ordering_update over its motion buffer (frame
 * index = that frame) and writes them to bits_out (if not NULL).  Then, per
 * tile, traces the pixel the ordering names: pixel centre if the pixel's
 * motion is non-zero, centre + tdc_jitter_offset_q4 otherwise; colour
 * rounded to 8 bits; MV of the pixel.  samples: tiles RGB888; mvs: tiles Q4
 * pairs.
 */
void tdc_scene_subframe(tdc_scene_t *s, uint32_t frame, uint8_t *samples, int16_t *mvs, uint8_t *bits_out);

/* ------------------------------------------------------------------------
 * Error statistics of 8-bit outputs against the reference.
 * ---------------------------------------------------------------------- */
typedef struct {
    uint64_t n;       /* samples compared */
    uint64_t hist[4]; /* |diff| = 0, 1, 2, >= 3 LSB */
    int max_abs;      /* largest |diff| */
    double max_exact; /* largest |fixed - unrounded reference| */
} tdc_asm_err_t;

/* Accumulates |fixed - ref8| and |fixed - exact| over n bytes. */
void tdc_asm_err_add(tdc_asm_err_t *e, const uint8_t *fixed, const uint8_t *ref8, const double *exact, size_t n);

#endif
