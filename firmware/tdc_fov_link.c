/*
 * tdc_fov_link.c - foveation header of the foveated link kind; layout and
 * rules in tdc_fov_link.h.  Little-endian byte access only (no casts of the
 * buffer), so the bytes mean the same on every CPU.
 */
#include "tdc_fov_link.h"

#include "tdc_fov_lr.h" /* TDC_FOV_LR_K_MIN_Q4 */

#include "tdc_bytes.h"

uint16_t tdc_fov_lp_size(uint16_t delta_q15, uint16_t n)
{
    return (uint16_t)(((uint32_t)delta_q15 * n) >> 15);
}

uint32_t tdc_fov_payload_bytes(const tdc_fov_geom_t *g, int with_mv)
{
    const uint32_t lp = (uint32_t)(g->lp_w - g->u0) * g->lp_h;
    return 3u * lp + 3u * tdc_fov_disk_pixels(g) + (with_mv ? 4u * lp : 0u);
}

tdc_status_t tdc_fov_hdr_pack(uint8_t out[TDC_FOV_HDR_BYTES], uint16_t width, uint16_t height,
                              const tdc_fov_params_t *p, uint16_t delta_q15, uint8_t flags)
{
    tdc_fov_geom_t g;
    if (!out || !p || (flags & ~TDC_FOV_FLAG_MV) || tdc_fov_geom(&g, width, height, p) != TDC_OK) {
        return TDC_ERR_ARG;
    }
    for (unsigned i = 0; i < TDC_FOV_HDR_BYTES; i++) {
        out[i] = 0;
    }
    tdc_put_le32(out + 0, (uint32_t)p->gaze_x_q8);
    tdc_put_le32(out + 4, (uint32_t)p->gaze_y_q8);
    tdc_put_le16(out + 8, p->alpha_q8);
    tdc_put_le16(out + 10, delta_q15);
    tdc_put_le16(out + 12, p->disk_q15);
    tdc_put_le16(out + 14, p->lp_w);
    tdc_put_le16(out + 16, p->lp_h);
    tdc_put_le16(out + 18, g.u0);
    tdc_put_le32(out + 20, tdc_fov_disk_pixels(&g));
    out[24] = flags;
    out[25] = (uint8_t)p->transform;
    if (p->transform != TDC_FOV_KERNEL_LOG_POLAR) {
        tdc_put_le16(out + 26, p->lr_k_q4[0]);
        tdc_put_le16(out + 28, p->lr_k_q4[1]);
    }
    return TDC_OK;
}

tdc_fov_hdr_err_t tdc_fov_hdr_parse(const uint8_t in[TDC_FOV_HDR_BYTES], uint16_t width, uint16_t height,
                                    tdc_fov_hdr_t *h)
{
    tdc_fov_params_t *p = &h->p;
    p->gaze_x_q8 = tdc_get_le32s(in + 0);
    p->gaze_y_q8 = tdc_get_le32s(in + 4);
    p->alpha_q8 = tdc_get_le16(in + 8);
    h->delta_q15 = tdc_get_le16(in + 10);
    p->disk_q15 = tdc_get_le16(in + 12);
    p->lp_w = tdc_get_le16(in + 14);
    p->lp_h = tdc_get_le16(in + 16);
    h->flags = in[24];
    p->transform = in[25];
    p->zero = 0;
    p->lr_k_q4[0] = tdc_get_le16(in + 26);
    p->lr_k_q4[1] = tdc_get_le16(in + 28);
    h->payload_bytes = 0;
    const int lr = p->transform == TDC_FOV_LOG_RECT;
    if (p->transform > TDC_FOV_LOG_RECT) {
        return TDC_FOV_HDR_TRANSFORM;
    }
    if (p->alpha_q8 < TDC_FOV_ALPHA_MIN_Q8 || p->alpha_q8 > TDC_FOV_ALPHA_MAX_Q8 || (lr && p->alpha_q8 != 256u)) {
        return TDC_FOV_HDR_ALPHA;
    }
    if (h->delta_q15 == 0 || h->delta_q15 > 32768u) {
        return TDC_FOV_HDR_DELTA;
    }
    if (p->disk_q15 > 32768u) {
        return TDC_FOV_HDR_DISK;
    }
    const int32_t w8 = (int32_t)width * 256, h8 = (int32_t)height * 256;
    if (p->gaze_x_q8 < -w8 || p->gaze_x_q8 > 2 * w8 || p->gaze_y_q8 < -h8 || p->gaze_y_q8 > 2 * h8) {
        return TDC_FOV_HDR_GAZE;
    }
    if (lr && (p->lr_k_q4[0] < TDC_FOV_LR_K_MIN_Q4 || p->lr_k_q4[1] < TDC_FOV_LR_K_MIN_Q4)) {
        return TDC_FOV_HDR_SCALE;
    }
    if (p->lp_w != tdc_fov_lp_size(h->delta_q15, width) || p->lp_h != tdc_fov_lp_size(h->delta_q15, height) ||
        tdc_fov_geom(&h->g, width, height, p) != TDC_OK) {
        return TDC_FOV_HDR_BUFFER;
    }
    if (tdc_get_le16(in + 18) != h->g.u0 || tdc_get_le32(in + 20) != tdc_fov_disk_pixels(&h->g)) {
        return TDC_FOV_HDR_GEOMETRY;
    }
    if (h->flags & ~TDC_FOV_FLAG_MV) {
        return TDC_FOV_HDR_RESERVED;
    }
    if (!lr && (p->lr_k_q4[0] | p->lr_k_q4[1])) {
        return TDC_FOV_HDR_RESERVED; /* k belongs to the log-rectilinear kind */
    }
    for (unsigned i = 30; i < TDC_FOV_HDR_BYTES; i++) {
        if (in[i]) {
            return TDC_FOV_HDR_RESERVED;
        }
    }
    h->payload_bytes = tdc_fov_payload_bytes(&h->g, h->flags & TDC_FOV_FLAG_MV);
    return TDC_FOV_HDR_OK;
}

tdc_fov_hdr_err_t tdc_fov_payload_check(const tdc_fov_hdr_t *h, uint32_t len)
{
    return len == h->payload_bytes ? TDC_FOV_HDR_OK : TDC_FOV_HDR_PAYLOAD;
}

void tdc_fov_unpack(const tdc_fov_hdr_t *h, const uint8_t *payload, uint8_t *lp, size_t lp_stride, int16_t *mv,
                    size_t mv_stride, uint8_t *disk, size_t disk_stride)
{
    const tdc_fov_geom_t *g = &h->g;
    const uint32_t cols = (uint32_t)(g->lp_w - g->u0);
    const uint8_t *s = payload;
    for (uint32_t j = 0; j < g->lp_h; j++) {
        uint8_t *d = lp + (size_t)j * lp_stride + (size_t)g->u0 * 3u;
        for (uint32_t k = 0; k < cols * 3u; k++) {
            d[k] = s[k];
        }
        s += (size_t)cols * 3u;
    }
    for (int32_t j = 0; j < (int32_t)g->height; j++) {
        int32_t x0;
        const uint32_t span = tdc_fov_disk_span(g, j, &x0);
        uint8_t *d = disk + (size_t)j * disk_stride + (size_t)x0 * 3u;
        for (uint32_t k = 0; k < span * 3u; k++) {
            d[k] = s[k];
        }
        s += (size_t)span * 3u;
    }
    if (h->flags & TDC_FOV_FLAG_MV) {
        for (uint32_t j = 0; j < g->lp_h; j++) {
            int16_t *d = mv + (size_t)j * mv_stride + (size_t)g->u0 * 2u;
            for (uint32_t k = 0; k < cols * 2u; k++) {
                d[k] = tdc_get_le16s(s + 2u * k);
            }
            s += (size_t)cols * 4u;
        }
    }
}

void tdc_fov_pack_payload(const tdc_fov_geom_t *g, const uint8_t *samples, const int16_t *mv, uint8_t *out)
{
    const uint32_t lp = (uint32_t)(g->lp_w - g->u0) * g->lp_h;
    const size_t rgb = 3u * ((size_t)lp + tdc_fov_disk_pixels(g));
    for (size_t k = 0; k < rgb; k++) {
        out[k] = samples[k];
    }
    if (mv) {
        for (size_t k = 0; k < 2u * (size_t)lp; k++) {
            tdc_put_le16s(out + rgb + 2u * k, mv[k]);
        }
    }
}

const char *tdc_fov_hdr_err_name(tdc_fov_hdr_err_t e)
{
    static const char *const n[TDC_FOV_HDR_COUNT] = {
        "TDC_FOV_HDR_OK",     "TDC_FOV_HDR_ALPHA",    "TDC_FOV_HDR_DELTA",    "TDC_FOV_HDR_DISK",   "TDC_FOV_HDR_GAZE",
        "TDC_FOV_HDR_BUFFER", "TDC_FOV_HDR_GEOMETRY", "TDC_FOV_HDR_RESERVED", "TDC_FOV_HDR_PAYLOAD",
        "TDC_FOV_HDR_TRANSFORM", "TDC_FOV_HDR_SCALE"};
    return (unsigned)e < TDC_FOV_HDR_COUNT ? n[e] : "TDC_FOV_HDR_?";
}
