/*
 * tdc_render_stream.c - renderer frames -> link packets -> .tdcs file.
 */
#include "tdc_render_stream.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_link_encode.h"
#include "tdc_link_file.h"
#include "tdc_render_internal.h"

struct tdc_render_stream {
    tdc_render_t *r;
    tdc_rstream_kind_t kind;
    tdc_link_encoder_t enc;
    tdc_link_file_t lf;
    int W, H, motion;
    uint32_t layer_set;  /* LAYERS packet flags (TDC_RSTREAM_LAYERS) */
    uint8_t mv_kind[TDC_LAYER_MAX];
    tdc_layer_frame_t lf8; /* the planes of one layered packet */
    uint8_t *rgb8;
    uint8_t *pkt;
    size_t cap;
};

/* The layer set of a layered stream (stage elision) and its planes. */
static int layer_planes(tdc_render_stream_t *s, const tdc_render_features_t *ft)
{
    const tdc_render_config_t *c = &s->r->cfg;
    const tdc_scene_t *sc = tdc_render_scene(s->r);
    int glossy = 0;
    for (int i = 0; i < sc->nmaterials; i++) glossy |= sc->materials[i].roughness > 0;
    uint32_t set = TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING);
    if (ft->moving_blocker && c->shadow_mv)
        set |= TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY) | TDC_LAYER_PKT_FALLOFF;
    if (ft->mirrors && c->max_bounces > 0) set |= TDC_LAYER_PKT_TYPE(TDC_LAYER_GLOSSY);
    if (c->indirect && ft->lights) set |= TDC_LAYER_PKT_TYPE(TDC_LAYER_INDIRECT);
    s->layer_set = set;
    uint8_t dual = c->dual_mv ? TDC_LAYER_MV_DUAL : TDC_LAYER_MV_SURFACE;
    s->mv_kind[TDC_LAYER_SHADING - 1] = dual;
    s->mv_kind[TDC_LAYER_VISIBILITY - 1] = TDC_LAYER_MV_SHADOW;
    s->mv_kind[TDC_LAYER_GLOSSY - 1] = glossy ? TDC_LAYER_MV_GLOSSY : TDC_LAYER_MV_MIRROR;
    s->mv_kind[TDC_LAYER_INDIRECT - 1] = dual;
    size_t tiles = (size_t)TDC_TILES(s->W) * TDC_TILES(s->H);
    for (uint32_t t = 1; t <= TDC_LAYER_MAX; t++) {
        if (!(set & TDC_LAYER_PKT_TYPE(t))) continue;
        s->lf8.value[t - 1] = malloc(tiles * tdc_layer_value_bytes(t));
        s->lf8.mv[t - 1] = malloc(tiles * 2 * sizeof(int16_t));
        if (!s->lf8.value[t - 1] || !s->lf8.mv[t - 1]) return -1;
    }
    if (set & TDC_LAYER_PKT_FALLOFF && !(s->lf8.falloff = malloc(tiles * sizeof(uint16_t)))) return -1;
    return 0;
}

tdc_render_stream_t *tdc_render_stream_create(const char *path, tdc_render_t *r, tdc_rstream_kind_t kind, char *err,
                                              size_t errlen)
{
    tdc_render_stream_t *s = calloc(1, sizeof *s);
    if (!s) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    s->r = r;
    s->kind = kind;
    tdc_render_output_size(r, TDC_RENDER_FULL, &s->W, &s->H);
    tdc_render_features_t ft;
    tdc_render_get_features(r, &ft);
    s->motion = ft.motion;
    s->cap = (size_t)s->W * s->H * 7 + 4096; /* LAYERS: at most 7 B/px */
    s->rgb8 = malloc((size_t)s->W * s->H * 3);
    s->pkt = malloc(s->cap);
    if (!s->rgb8 || !s->pkt) {
        snprintf(err, errlen, "out of memory");
        tdc_render_stream_close(s, NULL, NULL);
        return NULL;
    }
    const tdc_scene_t *sc = tdc_render_scene(r);
    tdc_link_stream_info_t info;
    memset(&info, 0, sizeof info);
    info.flags = ft.motion ? TDC_LINK_STREAM_MOTION : 0;
    if (ft.motion && ft.mirrors) info.flags |= TDC_LINK_STREAM_MIRRORS;
    info.r_num = 1;
    info.r_den = 1;
    if (kind == TDC_RSTREAM_TRM) {
        /* r = num/1000 of the renderer's reduced_factor, reduced by the gcd
         * (0.5 -> 1/2); the decoder's reduced size round(n num / den) then
         * equals the renderer's lround(n r) */
        unsigned num = (unsigned)lround(r->cfg.reduced_factor * 1000), den = 1000, a = num, b = den;
        while (b) {
            unsigned t = a % b;
            a = b;
            b = t;
        }
        info.flags |= TDC_LINK_STREAM_REDUCED;
        info.r_num = (uint16_t)(num / (a ? a : 1));
        info.r_den = (uint16_t)(den / (a ? a : 1));
    }
    if (kind == TDC_RSTREAM_SUBFRAMES)
        info.flags |= TDC_LINK_STREAM_SUBFRAMES | (ft.motion ? TDC_LINK_STREAM_SAMPLE_MV : 0);
    if (kind == TDC_RSTREAM_LAYERS) {
        info.flags |= TDC_LINK_STREAM_SUBFRAMES | TDC_LINK_STREAM_LAYERS;
        if (layer_planes(s, &ft) < 0) {
            snprintf(err, errlen, "out of memory");
            tdc_render_stream_close(s, NULL, NULL);
            return NULL;
        }
    }
    info.width = (uint16_t)s->W;
    info.height = (uint16_t)s->H;
    info.eyes = 1;
    info.refresh_hz = (uint16_t)lround(sc->fps);
    tdc_link_encoder_init(&s->enc, 1, &info);
    s->lf.f = NULL;
    if (tdc_link_file_create(&s->lf, path) < 0) {
        snprintf(err, errlen, "%s", s->lf.err);
        tdc_render_stream_close(s, NULL, NULL);
        return NULL;
    }
    size_t n = tdc_link_encode_stream(&s->enc, s->pkt, s->cap);
    if (!n || tdc_link_file_write(&s->lf, s->pkt, n) < 0) {
        snprintf(err, errlen, "the link encoder rejected the stream header (flags 0x%x, r %u/%u)%s%s",
                 (unsigned)info.flags, info.r_num, info.r_den, n ? ": " : "", n ? s->lf.err : "");
        tdc_render_stream_close(s, NULL, NULL);
        return NULL;
    }
    return s;
}

uint32_t tdc_render_stream_flags(const tdc_render_stream_t *s)
{
    return s->enc.info.flags;
}

static int put(tdc_render_stream_t *s, size_t n)
{
    return n && tdc_link_file_write(&s->lf, s->pkt, n) == 0 ? 0 : -1;
}

int tdc_render_stream_frame(tdc_render_stream_t *s, uint32_t frame, tdc_render_mode_t mode, const float *rgb,
                            const int16_t *mv)
{
    int w, h, rc = 0;
    tdc_render_output_size(s->r, mode, &w, &h);
    tdc_render_linear_to_rgb888(rgb, (size_t)w * h, s->rgb8);
    uint32_t W = (uint32_t)s->W, H = (uint32_t)s->H;
    switch (mode) {
    case TDC_RENDER_SUBFRAME:
        if ((frame & 3u) == 0)
            rc |=
                put(s, tdc_link_encode_pattern(&s->enc, s->pkt, s->cap, 0, frame, tdc_render_pattern_bits(s->r), W, H));
        rc |= put(s, tdc_link_encode_subframe(&s->enc, s->pkt, s->cap, 0, frame, TDC_PIXFMT_RGB888, s->rgb8, W, H));
        if (s->motion && mv) rc |= put(s, tdc_link_encode_motion(&s->enc, s->pkt, s->cap, 0, frame, mv, W, H, 1));
        break;
    case TDC_RENDER_FULL:
    case TDC_RENDER_REDUCED:
        rc |=
            put(s, tdc_link_encode_frame(&s->enc, s->pkt, s->cap,
                                         mode == TDC_RENDER_REDUCED ? TDC_LINK_KIND_REDUCED : TDC_LINK_KIND_FULL, 0,
                                         frame, TDC_PIXFMT_RGB888, s->rgb8, (uint32_t)w, (uint32_t)h, (uint32_t)w * 3));
        if (s->motion && mv && mode == TDC_RENDER_FULL)
            rc |= put(s, tdc_link_encode_motion(&s->enc, s->pkt, s->cap, 0, frame, mv, W, H, 0));
        break;
    default: return -1;
    }
    return rc ? -1 : 0;
}

uint32_t tdc_render_stream_layer_set(const tdc_render_stream_t *s)
{
    return s->layer_set;
}

int tdc_render_stream_layers(tdc_render_stream_t *s, uint32_t frame, const tdc_render_out_t *out)
{
    const uint32_t set = s->layer_set;
    const int vis = (set & TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY)) != 0;
    const int gl = (set & TDC_LAYER_PKT_TYPE(TDC_LAYER_GLOSSY)) != 0;
    const int ind = (set & TDC_LAYER_PKT_TYPE(TDC_LAYER_INDIRECT)) != 0;
    const int dual = s->r->cfg.dual_mv;
    if (s->kind != TDC_RSTREAM_LAYERS || !out->rgb || !out->mv || !out->mv_surf || (dual && !out->mv_dual) ||
        (vis && (!out->shade || !out->vis || !out->mv_shadow || !out->shadow_weight || !out->shadow_src)) ||
        (gl && (!out->refl || !out->mv_refl)) || (ind && !out->indirect))
        return -1;
    int w, h, rc = 0;
    tdc_render_output_size(s->r, TDC_RENDER_SUBFRAME, &w, &h);
    const size_t n = (size_t)w * h;
    /* SHADING: the unshadowed shading under a VISIBILITY layer, else the
     * frame less what the other layers carry (clamped at 0) */
    float *lin = malloc(n * 3 * sizeof(float));
    if (!lin) return -1;
    for (size_t i = 0; i < n * 3; i++) {
        float v = vis ? out->shade[i] : out->rgb[i] - (gl ? out->refl[i] : 0.0f) - (ind ? out->indirect[i] : 0.0f);
        lin[i] = v > 0 ? v : 0;
    }
    tdc_layer_frame_t *L = &s->lf8;
    tdc_render_linear_to_rgb888(lin, n, L->value[TDC_LAYER_SHADING - 1]);
    /* the shading's and the indirect layer's vectors: dual where the pixel
     * was disoccluded (the dual MV differs from the single-layer MV there;
     * where it equals it, it was not, or the two are the same vector) */
    int16_t *ms = L->mv[TDC_LAYER_SHADING - 1];
    for (size_t i = 0; i < 2 * n; i += 2) {
        int dis = dual && (out->mv_dual[i] != out->mv[i] || out->mv_dual[i + 1] != out->mv[i + 1]);
        ms[i] = dis ? out->mv_dual[i] : out->mv_surf[i];
        ms[i + 1] = dis ? out->mv_dual[i + 1] : out->mv_surf[i + 1];
    }
    if (vis) {
        uint8_t *v8 = L->value[TDC_LAYER_VISIBILITY - 1];
        int16_t *mv = L->mv[TDC_LAYER_VISIBILITY - 1];
        for (size_t i = 0; i < n; i++) {
            float v = out->vis[i];
            v8[i] = (uint8_t)(v >= 1 ? 255 : v > 0 ? (int)(v * 255 + 0.5f) : 0);
            int src = out->shadow_src[i];
            mv[2 * i] = src ? out->mv_shadow[2 * i] : out->mv_surf[2 * i];
            mv[2 * i + 1] = src ? out->mv_shadow[2 * i + 1] : out->mv_surf[2 * i + 1];
            /* eq. 4 weight at tracked shadows; the surface vector elsewhere is trusted */
            float g = src ? out->shadow_weight[i] : 1.0f;
            L->falloff[i] = (uint16_t)(g >= 1 ? TDC_LAYER_W_ONE : g > 0 ? (uint32_t)(g * 32768 + 0.5f) : 0u);
        }
    }
    if (gl) {
        tdc_render_linear_to_rgb888(out->refl, n, L->value[TDC_LAYER_GLOSSY - 1]);
        memcpy(L->mv[TDC_LAYER_GLOSSY - 1], out->mv_refl, n * 2 * sizeof(int16_t));
    }
    if (ind) {
        tdc_render_linear_to_rgb888(out->indirect, n, L->value[TDC_LAYER_INDIRECT - 1]);
        memcpy(L->mv[TDC_LAYER_INDIRECT - 1], ms, n * 2 * sizeof(int16_t));
    }
    free(lin);
    uint32_t W = (uint32_t)s->W, H = (uint32_t)s->H;
    if ((frame & 3u) == 0)
        rc |= put(s, tdc_link_encode_pattern(&s->enc, s->pkt, s->cap, 0, frame, tdc_render_pattern_bits(s->r), W, H));
    rc |= put(s, tdc_link_encode_layers(&s->enc, s->pkt, s->cap, 0, frame, L, set, s->mv_kind, W, H));
    return rc ? -1 : 0;
}

int tdc_render_stream_close(tdc_render_stream_t *s, uint32_t *packets, uint64_t *bytes)
{
    int rc = 0;
    if (!s) return -1;
    if (packets) *packets = s->lf.packets;
    if (bytes) *bytes = s->lf.bytes;
    if (s->lf.f && tdc_link_file_close(&s->lf) < 0) rc = -1;
    free(s->rgb8);
    free(s->pkt);
    for (int t = 0; t < TDC_LAYER_MAX; t++) {
        free(s->lf8.value[t]);
        free(s->lf8.mv[t]);
    }
    free(s->lf8.falloff);
    free(s);
    return rc;
}
