/*
 * tdc_render_stream.c - renderer frames -> link packets -> .tdcs file.
 */
#include "tdc_render_stream.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_link_encode.h"
#include "link/tdc_link_file.h"
#include "tdc_render_internal.h"

struct tdc_render_stream {
    tdc_render_t *r;
    tdc_rstream_kind_t kind;
    tdc_link_encoder_t enc;
    tdc_link_file_t lf;
    int W, H, motion;
    uint8_t *rgb8;
    uint8_t *pkt;
    size_t cap;
};

tdc_render_stream_t *tdc_render_stream_create(const char *path, tdc_render_t *r, tdc_rstream_kind_t kind, char *err,
                                              size_t errlen)
{
    tdc_render_stream_t *s = calloc(1, sizeof *s);
    if (!s) {
        snprintf(err, errlen, "%s: out of memory", path);
        return NULL;
    }
    s->r = r;
    s->kind = kind;
    tdc_render_output_size(r, TDC_RENDER_FULL, &s->W, &s->H);
    tdc_render_features_t ft;
    tdc_render_get_features(r, &ft);
    s->motion = ft.motion;
    s->cap = (size_t)s->W * s->H * 4 + 4096;
    s->rgb8 = malloc((size_t)s->W * s->H * 3);
    s->pkt = malloc(s->cap);
    if (!s->rgb8 || !s->pkt) {
        snprintf(err, errlen, "%s: out of memory", path);
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
    info.width = (uint16_t)s->W;
    info.height = (uint16_t)s->H;
    info.eyes = 1;
    info.refresh_hz = (uint16_t)lround(sc->fps);
    tdc_link_encoder_init(&s->enc, 1, &info);
    s->lf.f = NULL;
    if (tdc_link_file_create(&s->lf, path) < 0) {
        snprintf(err, errlen, "%s: cannot create stream file", path);
        tdc_render_stream_close(s, NULL, NULL);
        return NULL;
    }
    size_t n = tdc_link_encode_stream(&s->enc, s->pkt, s->cap);
    if (!n || tdc_link_file_write(&s->lf, s->pkt, n) < 0) {
        snprintf(err, errlen, "%s: the link encoder rejected the stream header (flags 0x%x, r %u/%u)", path,
                 (unsigned)info.flags, info.r_num, info.r_den);
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

int tdc_render_stream_close(tdc_render_stream_t *s, uint32_t *packets, uint64_t *bytes)
{
    int rc = 0;
    if (!s) return -1;
    if (packets) *packets = s->lf.packets;
    if (bytes) *bytes = s->lf.bytes;
    if (s->lf.f && tdc_link_file_close(&s->lf) < 0) rc = -1;
    free(s->rgb8);
    free(s->pkt);
    free(s);
    return rc;
}
