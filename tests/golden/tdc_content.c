/* tdc_content.c - deterministic test contents (see tdc_content.h). */
#include "tdc_content.h"

#include "tdc_math.h"

static const char *const k_names[TDC_CONTENT_COUNT] = {"edge",      "text",    "noise", "black",   "white",
                                                       "primaries", "checker", "flash", "gradient"};

const char *tdc_content_name(tdc_content_t c)
{
    return (unsigned)c < TDC_CONTENT_COUNT ? k_names[c] : "?";
}


static void put(uint8_t *p, uint8_t r, uint8_t g, uint8_t b)
{
    p[0] = r;
    p[1] = g;
    p[2] = b;
}

void tdc_content_frame(tdc_content_t c, uint32_t t, uint32_t seed, uint8_t *rgb, int w, int h, int stride)
{
    for (int y = 0; y < h; y++) {
        uint8_t *row = rgb + (long)y * stride;
        for (int x = 0; x < w; x++) {
            uint8_t *p = row + 3 * x;
            switch (c) {
            case TDC_CONTENT_EDGE: {
                /* edge position moves 3 px/frame and wraps; bright side has a
                 * slight tint so the channels differ */
                int pos = (int)((t * 3u + (uint32_t)w / 4u) % (uint32_t)w);
                if (x < pos) {
                    put(p, 250, 245, 240);
                } else {
                    put(p, 8, 10, 12);
                }
                break;
            }
            case TDC_CONTENT_TEXT: {
                /* 6x9 cells, each a pseudo glyph of 1-px strokes on paper */
                uint32_t yy = (uint32_t)y + t * 2u;
                uint32_t cx = (uint32_t)x / 6u, cy = yy / 9u;
                uint32_t gx = (uint32_t)x % 6u, gy = yy % 9u;
                uint32_t glyph = tdc_mix32(cx * 7919u + cy * 104729u + seed);
                int ink = 0;
                if (gx < 5u && gy < 7u && (glyph & 7u) != 0u) {
                    /* strokes: a few vertical and horizontal bars per glyph */
                    ink = ((glyph >> 3) & (1u << gx)) && (gy >= ((glyph >> 9) & 3u)) ? 1 : 0;
                    ink |= ((glyph >> 12) & (1u << (gy % 7u))) && gx < 4u ? 1 : 0;
                }
                if (ink) {
                    put(p, 20, 20, 28);
                } else {
                    put(p, 235, 232, 220);
                }
                break;
            }
            case TDC_CONTENT_NOISE: {
                uint32_t v = tdc_mix32(((uint32_t)y * 65521u + (uint32_t)x) ^ (t * 2654435761u) ^ seed);
                put(p, (uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16));
                break;
            }
            case TDC_CONTENT_BLACK: put(p, 0, 0, 0); break;
            case TDC_CONTENT_WHITE: put(p, 255, 255, 255); break;
            case TDC_CONTENT_PRIMARIES: {
                static const uint8_t bars[8][3] = {{255, 0, 0},   {0, 255, 0},   {0, 0, 255},     {0, 255, 255},
                                                   {255, 0, 255}, {255, 255, 0}, {255, 255, 255}, {0, 0, 0}};
                int b = (int)((long)x * 8 / w);
                put(p, bars[b][0], bars[b][1], bars[b][2]);
                break;
            }
            case TDC_CONTENT_CHECKER:
                if ((x + y) & 1) {
                    put(p, 255, 255, 255);
                } else {
                    put(p, 0, 0, 0);
                }
                break;
            case TDC_CONTENT_FLASH:
                if (t & 1u) {
                    put(p, 255, 255, 255);
                } else {
                    put(p, 0, 0, 0);
                }
                break;
            case TDC_CONTENT_GRADIENT: {
                uint32_t v = ((uint32_t)x + (uint32_t)y + t) * 255u / (uint32_t)(w + h);
                put(p, (uint8_t)(v & 255u), (uint8_t)((v * 3u / 4u) & 255u), (uint8_t)(255u - (v & 255u)));
                break;
            }
            default: put(p, 0, 0, 0); break;
            }
        }
    }
}
