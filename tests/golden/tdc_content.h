/*
 * tdc_content.h - deterministic test contents (RGB888 frames) shared by the
 * golden vectors, the fixed-vs-float reports, the stability tests and the
 * demo.  Freestanding: integer only, no allocation.
 */
#ifndef TDC_CONTENT_H
#define TDC_CONTENT_H

#include <stdint.h>

typedef enum {
    TDC_CONTENT_EDGE = 0, /* high-contrast vertical edge moving 3 px/frame */
    TDC_CONTENT_TEXT,     /* glyph-like strokes scrolling up 2 px/frame */
    TDC_CONTENT_NOISE,    /* uniform noise, new every frame */
    TDC_CONTENT_BLACK,
    TDC_CONTENT_WHITE,
    TDC_CONTENT_PRIMARIES, /* static bars: R G B C M Y W K */
    TDC_CONTENT_CHECKER,   /* static 1-pixel checkerboard, black/white */
    TDC_CONTENT_FLASH,     /* whole frame alternating black/white every frame */
    TDC_CONTENT_GRADIENT,  /* smooth diagonal ramp panning 1 px/frame */
    TDC_CONTENT_COUNT
} tdc_content_t;

/* Short lowercase name ("edge", "text", ...). */
const char *tdc_content_name(tdc_content_t c);

/* Fill frame t of content c: w x h RGB888, stride bytes per row, seed for
 * the random contents. */
void tdc_content_frame(tdc_content_t c, uint32_t t, uint32_t seed, uint8_t *rgb, int w, int h, int stride);

#endif
