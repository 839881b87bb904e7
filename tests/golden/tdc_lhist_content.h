/*
 * tdc_lhist_content.h - integer test content for the per-layer history
 * (firmware/tdc_layer_hist.h), shared by its golden vectors and its
 * reference test: a layer frame of stripes and a disc panning by (vx, vy)
 * Q4 px a frame with hash noise of amplitude `noise` (a 1-sample layer),
 * and the vectors that track the pan (optionally a hash vector per pixel
 * over +-range Q4, some of them leaving the frame) and falloff weights.
 * Freestanding, no float.
 */
#ifndef TDC_LHIST_CONTENT_H
#define TDC_LHIST_CONTENT_H

#include <stdint.h>

#include "tdc_math.h"

typedef struct {
    uint16_t w, h;
    uint8_t ch, noise;
    int16_t vx, vy;  /* pan, Q4 px a frame */
    int16_t range;   /* > 0: hash vectors in [-range, range] Q4 instead of the pan's */
    uint8_t falloff; /* 1: hash falloff weights in [2^14, 2^15] */
    uint32_t seed;
} tdc_lhist_content_t;

static inline void tdc_lhist_content(const tdc_lhist_content_t *c, uint32_t f, uint8_t *x, int16_t *mv, uint16_t *g)
{
    for (uint32_t y = 0; y < c->h; y++) {
        for (uint32_t px = 0; px < c->w; px++) {
            const uint32_t p = y * c->w + px;
            /* scene coordinates in Q4: the content moves by (vx, vy) a frame */
            const int32_t sx = (int32_t)(px << 4) - c->vx * (int32_t)f, sy = (int32_t)(y << 4) - c->vy * (int32_t)f;
            const int32_t dx = sx - 160, dy = sy - 128;
            const uint32_t disc = (uint32_t)(dx * dx + dy * dy) < 96u * 96u;
            for (uint32_t k = 0; k < c->ch; k++) {
                int32_t v = ((((sx + (int32_t)k * 40) >> 5) & 3) * 40 + 60) + (disc ? 70 : 0);
                v += (int32_t)(tdc_hash3(p * 3u + k, f, c->seed) % (2u * c->noise + 1u)) - c->noise;
                x[p * c->ch + k] = (uint8_t)(v < 0 ? 0 : (v > 255 ? 255 : v));
            }
            if (c->range > 0) {
                const uint32_t r = 2u * (uint32_t)c->range + 1u;
                mv[2 * p] = (int16_t)((int32_t)(tdc_hash3(p, f, c->seed + 1u) % r) - c->range);
                mv[2 * p + 1] = (int16_t)((int32_t)(tdc_hash3(p, f, c->seed + 2u) % r) - c->range);
            } else {
                mv[2 * p] = (int16_t)-c->vx;
                mv[2 * p + 1] = (int16_t)-c->vy;
            }
            g[p] = (uint16_t)(c->falloff ? 16384u + tdc_hash3(p, f, c->seed + 3u) % 16385u : 32768u);
        }
    }
}

#endif
