/* tdc_sim_link.c - link encoder -> firmware decoder for the simulator. */
#include "simulator/tdc_sim_link.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tdc_wire.h" /* packet sizes */

/* the simulator's stream flags are the wire's */
_Static_assert(TDC_SIM_LINK_REDUCED == TDC_LINK_STREAM_REDUCED && TDC_SIM_LINK_SUBFRAMES == TDC_LINK_STREAM_SUBFRAMES &&
                   TDC_SIM_LINK_MOTION == TDC_LINK_STREAM_MOTION && TDC_SIM_LINK_SAMPLE_MV == TDC_LINK_STREAM_SAMPLE_MV &&
                   TDC_SIM_LINK_FOVEATED == TDC_LINK_STREAM_FOVEATED,
               "TDC_SIM_LINK_* differ from TDC_LINK_STREAM_*");

#include "tdc_link_encode.h"
#include "tdc_link.h"

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts); /* CPU time: robust to a loaded host */
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct {
    tdc_link_encoder_t enc;
    tdc_link_decoder_t dec;
    tdc_link_buffers_t buf;
    uint8_t *pkt;
    size_t cap;
    uint8_t *staging;
} link_priv_t;

/* Feeds one packet; returns 0 if a packet event of the expected kind came. */
static int feed(tdc_sim_link_t *l, size_t n, int kind)
{
    link_priv_t *p = l->priv;
    if (n == 0) {
        l->errors++;
        return -1;
    }
    double t0 = now_s();
    size_t off = 0;
    int ok = -1;
    while (off < n) {
        tdc_link_event_t ev;
        off += tdc_link_feed(&p->dec, p->pkt + off, n - off, &ev);
        if (ev.type == TDC_LINK_EV_PACKET && ev.kind == kind) {
            ok = 0;
        } else if (ev.type == TDC_LINK_EV_ERROR) {
            l->errors++;
        }
    }
    /* drain queued events */
    for (;;) {
        tdc_link_event_t ev;
        tdc_link_feed(&p->dec, p->pkt, 0, &ev);
        if (ev.type == TDC_LINK_EV_NONE) {
            break;
        }
        if (ev.type == TDC_LINK_EV_PACKET && ev.kind == kind) {
            ok = 0;
        } else if (ev.type == TDC_LINK_EV_ERROR) {
            l->errors++;
        }
    }
    l->decode_s += now_s() - t0;
    l->bytes += n;
    l->packets++;
    return ok;
}

int tdc_sim_link_init(tdc_sim_link_t *l, int w, int h, int eyes, uint32_t flags, uint16_t r_num, uint16_t r_den,
                      uint16_t hz)
{
    memset(l, 0, sizeof(*l));
    l->w = w;
    l->h = h;
    l->eyes = eyes == 2 ? 2 : 1;
    l->flags = flags;
    l->r_num = r_num ? r_num : 1;
    l->r_den = r_den ? r_den : 1;
    l->hz = hz;
    l->rw = (int)TDC_REDUCED_DIM(w, l->r_num, l->r_den);
    l->rh = (int)TDC_REDUCED_DIM(h, l->r_num, l->r_den);
    /* only the buffers of the stream's packet kinds */
    int sub = (flags & TDC_SIM_LINK_SUBFRAMES) != 0, red = (flags & TDC_SIM_LINK_REDUCED) != 0;
    const int lay = (flags & TDC_SIM_LINK_LAYERS) != 0;
    const size_t tiles = TDC_TILE_COUNT(w, h);
    for (int e = 0; e < l->eyes; e++) {
        l->full[e] = calloc(TDC_LINK_FRAME_BYTES(w, h), 1);
        l->reduced[e] = red ? calloc(TDC_LINK_FRAME_BYTES(l->rw, l->rh), 1) : NULL;
        l->subframe[e] = sub ? calloc(TDC_LINK_SUBFRAME_BYTES(w, h), 1) : NULL;
        l->pattern[e] = sub ? calloc(TDC_PATTERN_BYTES(w, h) + 1, 1) : NULL;
        l->motion[e] = (flags & TDC_SIM_LINK_MOTION) ? calloc(TDC_LINK_MOTION_COUNT(w, h), sizeof(int16_t)) : NULL;
        l->sample_motion[e] = sub ? calloc(TDC_LINK_SAMPLE_MOTION_COUNT(w, h), sizeof(int16_t)) : NULL;
        int lay_ok = 1;
        if (lay) {
            tdc_layer_frame_t *lf = calloc(1, sizeof(*lf));
            l->layers[e] = lf;
            lay_ok = lf != NULL;
            for (unsigned t = 0; lf && t < TDC_LAYER_MAX; t++) {
                lf->value[t] = calloc(tiles * 3u, 1);
                lf->mv[t] = calloc(tiles * 2u, sizeof(int16_t));
                lay_ok = lay_ok && lf->value[t] && lf->mv[t];
            }
            if (lf) {
                lf->falloff = calloc(tiles, sizeof(uint16_t));
                lay_ok = lay_ok && lf->falloff;
            }
        }
        const int fov = (flags & TDC_SIM_LINK_FOVEATED) != 0; /* delta <= 1: lp_w x lp_h <= w x h */
        l->fov_lp[e] = fov ? calloc(TDC_LINK_FRAME_BYTES(w, h), 1) : NULL;
        l->fov_mv[e] = fov ? calloc(TDC_LINK_MOTION_COUNT(w, h), sizeof(int16_t)) : NULL;
        if (!l->full[e] || (red && !l->reduced[e]) || (fov && (!l->fov_lp[e] || !l->fov_mv[e])) || !lay_ok ||
            (sub && (!l->subframe[e] || !l->pattern[e] || !l->sample_motion[e]))) {
            tdc_sim_link_free(l);
            return -1;
        }
    }
    link_priv_t *p = calloc(1, sizeof(*p));
    if (!p) {
        tdc_sim_link_free(l);
        return -1;
    }
    l->priv = p;
    size_t stage = TDC_LINK_STAGING_BYTES(w, h);
    if (lay && TDC_LINK_STAGING_LAYERS_BYTES(w, h) > stage) {
        stage = TDC_LINK_STAGING_LAYERS_BYTES(w, h);
    }
    p->cap = stage + TDC_LINK_HEADER_BYTES; /* the largest packet */
    p->pkt = malloc(p->cap);
    p->staging = malloc(stage);
    if (!p->pkt || !p->staging) {
        tdc_sim_link_free(l);
        return -1;
    }
    p->buf.staging = p->staging;
    p->buf.staging_bytes = stage;
    p->buf.full_stride = (uint32_t)w * 3u;
    p->buf.reduced_bytes = TDC_LINK_FRAME_BYTES(l->rw, l->rh);
    for (int e = 0; e < l->eyes; e++) {
        p->buf.full[e] = l->full[e];
        p->buf.reduced[e] = l->reduced[e];
        p->buf.subframe[e] = l->subframe[e];
        p->buf.motion[e] = l->motion[e];
        p->buf.sample_motion[e] = l->sample_motion[e];
        p->buf.pattern[e] = l->pattern[e];
        p->buf.layers[e] = l->layers[e];
        p->buf.fov_lp[e] = l->fov_lp[e];
        p->buf.fov_mv[e] = l->fov_mv[e];
    }
    p->buf.fov_lp_bytes = TDC_LINK_FRAME_BYTES(w, h);
    p->buf.fov_mv_count = TDC_LINK_MOTION_COUNT(w, h);
    tdc_link_config_t cfg = {(uint16_t)w, (uint16_t)h, (uint8_t)l->eyes};
    if (tdc_link_decoder_init(&p->dec, &cfg, &p->buf) != TDC_OK) {
        tdc_sim_link_free(l);
        return -1;
    }
    return tdc_sim_link_stream(l);
}

void tdc_sim_link_free(tdc_sim_link_t *l)
{
    link_priv_t *p = l->priv;
    if (p) {
        free(p->pkt);
        free(p->staging);
        free(p);
    }
    l->priv = NULL;
    for (int e = 0; e < 2; e++) {
        free(l->full[e]);
        free(l->reduced[e]);
        free(l->subframe[e]);
        free(l->pattern[e]);
        free(l->motion[e]);
        free(l->sample_motion[e]);
        if (l->layers[e]) {
            for (unsigned t = 0; t < TDC_LAYER_MAX; t++) {
                free(l->layers[e]->value[t]);
                free(l->layers[e]->mv[t]);
            }
            free(l->layers[e]->falloff);
            free(l->layers[e]);
            l->layers[e] = NULL;
        }
        free(l->fov_lp[e]);
        free(l->fov_mv[e]);
        l->full[e] = l->reduced[e] = l->subframe[e] = l->pattern[e] = l->fov_lp[e] = NULL;
        l->motion[e] = l->sample_motion[e] = l->fov_mv[e] = NULL;
    }
}

int tdc_sim_link_stream(tdc_sim_link_t *l)
{
    l->stream_id++;
    link_priv_t *p = l->priv;
    tdc_link_stream_info_t info;
    memset(&info, 0, sizeof(info));
    info.flags = l->flags;
    info.r_num = (l->flags & TDC_SIM_LINK_REDUCED) ? l->r_num : 1;
    info.r_den = (l->flags & TDC_SIM_LINK_REDUCED) ? l->r_den : 1;
    info.width = (uint16_t)l->w;
    info.height = (uint16_t)l->h;
    info.eyes = (uint8_t)l->eyes;
    info.refresh_hz = l->hz;
    double t0 = now_s();
    tdc_link_encoder_init(&p->enc, l->stream_id, &info);
    size_t n = tdc_link_encode_stream(&p->enc, p->pkt, p->cap);
    l->encode_s += now_s() - t0;
    return feed(l, n, TDC_LINK_KIND_STREAM);
}

/* A FULL or REDUCED packet of a w x h RGB888 frame; 0 when accepted. */
static int send_frame(tdc_sim_link_t *l, tdc_link_kind_t kind, int eye, uint32_t frame, const uint8_t *rgb, int w,
                      int h)
{
    link_priv_t *p = l->priv;
    double t0 = now_s();
    size_t n = tdc_link_encode_frame(&p->enc, p->pkt, p->cap, kind, (uint32_t)eye, frame, TDC_PIXFMT_RGB888, rgb,
                                     (uint32_t)w, (uint32_t)h, (uint32_t)w * 3u);
    l->encode_s += now_s() - t0;
    return feed(l, n, (int)kind);
}

int tdc_sim_link_full(tdc_sim_link_t *l, int eye, uint32_t frame, const uint8_t *rgb)
{
    return send_frame(l, TDC_LINK_KIND_FULL, eye, frame, rgb, l->w, l->h);
}

int tdc_sim_link_reduced(tdc_sim_link_t *l, int eye, uint32_t frame, const uint8_t *rgb)
{
    return send_frame(l, TDC_LINK_KIND_REDUCED, eye, frame, rgb, l->rw, l->rh);
}

/* A PATTERN packet (the cycle's tile orderings); 0 when accepted. */
static int send_pattern(tdc_sim_link_t *l, int eye, uint32_t frame, const uint8_t *pattern)
{
    link_priv_t *p = l->priv;
    const double t0 = now_s();
    const size_t n = tdc_link_encode_pattern(&p->enc, p->pkt, p->cap, (uint32_t)eye, frame, pattern, (uint32_t)l->w,
                                             (uint32_t)l->h);
    l->encode_s += now_s() - t0;
    return feed(l, n, TDC_LINK_KIND_PATTERN);
}

int tdc_sim_link_subframe(tdc_sim_link_t *l, int eye, uint32_t frame, const uint8_t *samples, const int16_t *mv,
                          const uint8_t *pattern)
{
    int rc = 0;
    link_priv_t *p = l->priv;
    double t0 = now_s();
    size_t n;
    if (pattern) {
        rc |= send_pattern(l, eye, frame, pattern);
        t0 = now_s();
    }
    n = tdc_link_encode_subframe(&p->enc, p->pkt, p->cap, (uint32_t)eye, frame, TDC_PIXFMT_RGB888, samples,
                                 (uint32_t)l->w, (uint32_t)l->h);
    l->encode_s += now_s() - t0;
    rc |= feed(l, n, TDC_LINK_KIND_SUBFRAME);
    if (mv) {
        t0 = now_s();
        n = tdc_link_encode_motion(&p->enc, p->pkt, p->cap, (uint32_t)eye, frame, mv, (uint32_t)l->w, (uint32_t)l->h,
                                   1);
        l->encode_s += now_s() - t0;
        rc |= feed(l, n, TDC_LINK_KIND_MOTION);
    }
    return rc ? -1 : 0;
}

int tdc_sim_link_layers(tdc_sim_link_t *l, int eye, uint32_t frame, const tdc_layer_frame_t *src,
                        const uint8_t *pattern)
{
    const uint32_t flags = src->present;
    if (!l->layers[eye]) {
        return -1;
    }
    link_priv_t *p = l->priv;
    int rc = 0;
    double t0 = now_s();
    size_t n;
    if (pattern) {
        rc |= send_pattern(l, eye, frame, pattern);
        t0 = now_s();
    }
    uint8_t kinds[TDC_LAYER_MAX] = {0, 0, 0, 0};
    for (unsigned i = 0; i < src->hdr.count && i < TDC_LAYER_MAX; i++) {
        kinds[src->hdr.type[i] - 1u] = src->hdr.mv_kind[i];
    }
    n = tdc_link_encode_layers(&p->enc, p->pkt, p->cap, (uint32_t)eye, frame, src, flags, kinds, (uint32_t)l->w,
                               (uint32_t)l->h);
    l->encode_s += now_s() - t0;
    rc |= feed(l, n, TDC_LINK_KIND_LAYERS);
    return rc ? -1 : 0;
}

int tdc_sim_link_foveated(tdc_sim_link_t *l, int eye, uint32_t frame, const tdc_fov_params_t *fp, uint16_t delta_q15,
                          const uint8_t *samples, const int16_t *mv, tdc_fov_hdr_t *hdr)
{
    return tdc_sim_link_foveated_slot(l, eye, frame, 0, fp, delta_q15, samples, mv, hdr);
}

int tdc_sim_link_foveated_slot(tdc_sim_link_t *l, int eye, uint32_t frame, int reduced, const tdc_fov_params_t *fp,
                               uint16_t delta_q15, const uint8_t *samples, const int16_t *mv, tdc_fov_hdr_t *hdr)
{
    link_priv_t *p = l->priv;
    double t0 = now_s();
    size_t n = tdc_link_encode_foveated_slot(&p->enc, p->pkt, p->cap,
                                             reduced ? TDC_LINK_KIND_REDUCED : TDC_LINK_KIND_FULL, (uint32_t)eye,
                                             frame, fp, delta_q15, samples, mv, NULL);
    l->encode_s += now_s() - t0;
    const int rc = feed(l, n, TDC_LINK_KIND_FOVEATED);
    const tdc_fov_hdr_t *h = tdc_link_fov(&p->dec, (uint32_t)eye);
    if (rc == 0 && hdr && h) {
        *hdr = *h;
    }
    return rc == 0 && h ? 0 : -1;
}

void tdc_sim_link_count_raw(tdc_sim_link_t *l, size_t payload)
{
    l->bytes += TDC_LINK_HEADER_BYTES + payload;
    l->packets++;
}
