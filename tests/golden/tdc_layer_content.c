/* tdc_layer_content.c - the layered test stream (tdc_layer_content.h). */
#include "tdc_layer_content.h"

#include "tdc_math.h"
#include "tdc_ordering.h"

static uint32_t floor_code(int32_t x, int32_t y, uint32_t seed, uint32_t c)
{
    const int32_t cx = x >= 0 ? x / 8 : -((-x + 7) / 8), cy = y >= 0 ? y / 8 : -((-y + 7) / 8);
    const uint32_t chk = (uint32_t)(cx + cy) & 1u;
    const int32_t bx = x >= 0 ? x / 3 : -((-x + 2) / 3), by = y >= 0 ? y / 3 : -((-y + 2) / 3);
    const uint32_t n = tdc_hash3((uint32_t)bx, (uint32_t)by, seed + c) & 31u;
    return (chk ? 150u : 100u) + n - (c == 2u ? 20u : 0u);
}

uint32_t tdc_layer_content_vis(const tdc_lcontent_t *c, int32_t x_q4, uint32_t frame)
{
    const int32_t period = 14 * 16;
    int32_t u = x_q4 - (int32_t)c->vis_vx * (int32_t)(frame % 65536u);
    int32_t m = u % period;
    m = m < 0 ? m + period : m;
    uint32_t s; /* shadow fraction, Q4 */
    if (m < 16) {
        s = (uint32_t)m;
    } else if (m <= 80) {
        s = 16u;
    } else if (m < 96) {
        s = (uint32_t)(96 - m);
    } else {
        s = 0u;
    }
    return 255u - (s * 204u + 8u) / 16u; /* full shadow: 51 */
}

static int16_t rnd_mv(uint32_t h)
{
    int32_t v = (int32_t)(h & 0xFFFFu) - 32768;
    return (int16_t)(v == -32768 ? -32767 : v);
}

void tdc_layer_content_subframe(const tdc_lcontent_t *c, uint32_t frame, const uint8_t *pattern,
                                tdc_layer_frame_t *out)
{
    const uint32_t tx = (c->w + 1u) / 2u, ty = (c->h + 1u) / 2u;
    const uint32_t types = c->layers & TDC_LAYER_PKT_TYPES;
    out->present = (uint16_t)c->layers;
    out->hdr.version = TDC_LAYER_LAYOUT_VERSION;
    out->hdr.tiles_x = (uint16_t)tx;
    out->hdr.tiles_y = (uint16_t)ty;
    out->hdr.flags = (c->layers & TDC_LAYER_PKT_FALLOFF) ? 1u : 0u;
    out->hdr.reserved = 0;
    unsigned n = 0;
    for (unsigned i = 0; i < TDC_LAYER_MAX; i++) {
        out->hdr.type[i] = 0;
        out->hdr.mv_kind[i] = 0;
    }
    static const uint8_t kinds0[TDC_LAYER_MAX] = {TDC_LAYER_MV_SURFACE, TDC_LAYER_MV_SHADOW, TDC_LAYER_MV_GLOSSY,
                                                  TDC_LAYER_MV_SURFACE};
    for (unsigned t = 1; t <= TDC_LAYER_MAX; t++) {
        if (types & TDC_LAYER_PKT_TYPE(t)) {
            out->hdr.type[n] = (uint8_t)t;
            out->hdr.mv_kind[n] = (t == TDC_LAYER_VISIBILITY && !c->shadow_vectors) ? TDC_LAYER_MV_SURFACE
                                                                                    : kinds0[t - 1u];
            n++;
        }
    }
    out->hdr.count = (uint8_t)n;
    uint32_t k = 0;
    for (uint32_t y = 0; y < ty; y++) {
        for (uint32_t x = 0; x < tx; x++, k++) {
            const unsigned pos = tdc_ordering_pixel(tdc_ordering_get(pattern, k), frame & 3u);
            const int32_t px = (int32_t)(2u * x + (pos & 1u)), py = (int32_t)(2u * y + (pos >> 1));
            const uint32_t hr = tdc_hash3((uint32_t)px, (uint32_t)py, frame * 7u + c->seed);
            if (types & TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING)) {
                /* the floor point now at p was at p + mv = p - v */
                const int32_t fx = px - ((int32_t)c->sh_vx * (int32_t)frame) / 16;
                const int32_t fy = py - ((int32_t)c->sh_vy * (int32_t)frame) / 16;
                for (uint32_t ch = 0; ch < 3u; ch++) {
                    out->value[0][k * 3u + ch] = (uint8_t)floor_code(fx, fy, c->seed, ch);
                }
                out->mv[0][2u * k] = c->random_mv ? rnd_mv(hr) : (int16_t)-c->sh_vx;
                out->mv[0][2u * k + 1u] = c->random_mv ? rnd_mv(hr >> 16) : (int16_t)-c->sh_vy;
            }
            const uint32_t v = tdc_layer_content_vis(c, px * 16 + 8, frame);
            if (types & TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY)) {
                out->value[1][k] = (uint8_t)v;
                const int shadowed = v < 255u && c->shadow_vectors;
                out->mv[1][2u * k] = c->random_mv ? rnd_mv(hr * 3u) : (int16_t)(shadowed ? -c->vis_vx : 0);
                out->mv[1][2u * k + 1u] = c->random_mv ? rnd_mv(hr * 5u) : 0;
                if (c->layers & TDC_LAYER_PKT_FALLOFF) {
                    out->falloff[k] = (uint16_t)(3u * (uint32_t)px >= 2u * c->w && v < 255u
                                                     ? 16384u + (hr & 16383u)
                                                     : TDC_LAYER_W_ONE);
                }
            }
            if (types & TDC_LAYER_PKT_TYPE(TDC_LAYER_GLOSSY)) {
                const int32_t gx = px - ((int32_t)c->gl_vx * (int32_t)frame) / 16;
                const int32_t gy = py - ((int32_t)c->gl_vy * (int32_t)frame) / 16;
                for (uint32_t ch = 0; ch < 3u; ch++) {
                    out->value[2][k * 3u + ch] = (uint8_t)(floor_code(gx * 2 + 5, gy * 2 + 3, c->seed + 9u, ch) / 2u);
                }
                out->mv[2][2u * k] = c->random_mv ? rnd_mv(hr * 7u) : (int16_t)-c->gl_vx;
                out->mv[2][2u * k + 1u] = c->random_mv ? rnd_mv(hr * 11u) : (int16_t)-c->gl_vy;
            }
            if (types & TDC_LAYER_PKT_TYPE(TDC_LAYER_INDIRECT)) {
                for (uint32_t ch = 0; ch < 3u; ch++) {
                    out->value[3][k * 3u + ch] = (uint8_t)(10u + ((uint32_t)px + (uint32_t)py + ch * 5u) % 24u);
                }
                out->mv[3][2u * k] = 0;
                out->mv[3][2u * k + 1u] = 0;
            }
        }
    }
}
