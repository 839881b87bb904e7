/*
 * tdc_link_encode.c - link encoder (see tdc_link_encode.h and
 * docs/link-protocol.md).  Integer only and allocation-free.
 */
#include "tdc_link_encode.h"

#include <string.h>

#include "tdc_crc32.h"
#include "tdc_fixed.h"

/* BT.709 full-range RGB -> YCbCr, Q16 (rows sum to 65536, 0, 0). */
#define ENC_Y_R 13933
#define ENC_Y_G 46871
#define ENC_Y_B 4732
#define ENC_CB_R (-7509)
#define ENC_CB_G (-25259)
#define ENC_CB_B 32768
#define ENC_CR_R 32768
#define ENC_CR_G (-29763)
#define ENC_CR_B (-3005)

static uint8_t sat_u8(int32_t v)
{
    return (uint8_t)(v < 0 ? 0 : (v > 255 ? 255 : v));
}

void tdc_pixfmt_rgb_to_ycbcr(int32_t r, int32_t g, int32_t b, uint8_t ycc[3])
{
    ycc[0] = sat_u8(tdc_asr32(ENC_Y_R * r + ENC_Y_G * g + ENC_Y_B * b + 32768, 16));
    ycc[1] = sat_u8(128 + tdc_asr32(ENC_CB_R * r + ENC_CB_G * g + ENC_CB_B * b + 32768, 16));
    ycc[2] = sat_u8(128 + tdc_asr32(ENC_CR_R * r + ENC_CR_G * g + ENC_CR_B * b + 32768, 16));
}

static inline void pack_rgb565_px(const uint8_t *s, uint8_t *o)
{
    const uint32_t r5 = (s[0] * 31u + 127u) / 255u;
    const uint32_t g6 = (s[1] * 63u + 127u) / 255u;
    const uint32_t b5 = (s[2] * 31u + 127u) / 255u;
    tdc_put_le16(o, (r5 << 11) | (g6 << 5) | b5);
}

static inline void pack_rgb30_px(const uint8_t *s, uint8_t *o)
{
    uint32_t v = 0;
    for (uint32_t c = 0; c < 3; c++) {
        v |= ((s[c] * 1023u + 127u) / 255u) << (10u * c);
    }
    tdc_put_le32(o, v);
}

void tdc_pixfmt_pack(tdc_pixfmt_t fmt, const uint8_t *rgb, uint32_t w, uint32_t h, uint32_t stride, uint8_t *out)
{
    switch (fmt) {
    case TDC_PIXFMT_RGB888:
        for (uint32_t y = 0; y < h; y++) {
            memcpy(out + (size_t)w * 3u * y, rgb + (size_t)stride * y, (size_t)w * 3u);
        }
        break;
    case TDC_PIXFMT_RGB565: TDC_PIXFMT_ROWS(rgb, stride, 3u, out, w * 2u, 2u, w, h, pack_rgb565_px); break;
    case TDC_PIXFMT_RGB30: TDC_PIXFMT_ROWS(rgb, stride, 3u, out, w * 4u, 4u, w, h, pack_rgb30_px); break;
    case TDC_PIXFMT_YCBCR420: {
        const uint32_t cw = (w + 1u) / 2u, ch = (h + 1u) / 2u;
        uint8_t *cb = out + (size_t)w * h, *cr = cb + (size_t)cw * ch;
        for (uint32_t y = 0; y < h; y++) {
            for (uint32_t x = 0; x < w; x++) {
                const uint8_t *s = rgb + (size_t)stride * y + 3u * x;
                uint8_t ycc[3];
                tdc_pixfmt_rgb_to_ycbcr(s[0], s[1], s[2], ycc);
                out[(size_t)w * y + x] = ycc[0];
            }
        }
        /* Chroma of the mean colour of each 2x2 block (1, 2 or 4 pixels). */
        for (uint32_t j = 0; j < ch; j++) {
            for (uint32_t i = 0; i < cw; i++) {
                int32_t sr = 0, sg = 0, sb = 0;
                unsigned n = 0;
                for (uint32_t dy = 0; dy < 2u && 2u * j + dy < h; dy++) {
                    for (uint32_t dx = 0; dx < 2u && 2u * i + dx < w; dx++) {
                        const uint8_t *s = rgb + (size_t)stride * (2u * j + dy) + 3u * (2u * i + dx);
                        sr += s[0];
                        sg += s[1];
                        sb += s[2];
                        n++;
                    }
                }
                const unsigned sh = 16u + (n == 4u ? 2u : (n == 2u ? 1u : 0u));
                const int32_t half = (int32_t)1 << (sh - 1u);
                cb[(size_t)cw * j + i] =
                    sat_u8(128 + tdc_asr32(ENC_CB_R * sr + ENC_CB_G * sg + ENC_CB_B * sb + half, sh));
                cr[(size_t)cw * j + i] =
                    sat_u8(128 + tdc_asr32(ENC_CR_R * sr + ENC_CR_G * sg + ENC_CR_B * sb + half, sh));
            }
        }
        break;
    }
    default: break;
    }
}

void tdc_link_encoder_init(tdc_link_encoder_t *enc, uint16_t stream_id, const tdc_link_stream_info_t *info)
{
    enc->stream_id = stream_id;
    enc->info = *info;
}

/* Payload already written at out + HEADER_BYTES: add the header. */
static size_t finish(uint8_t *out, const tdc_link_header_t *f, uint32_t len)
{
    tdc_link_header_t h = *f;
    h.payload_len = len;
    h.payload_crc = tdc_crc32(out + TDC_LINK_HEADER_BYTES, len);
    tdc_link_header_pack(out, &h);
    return (size_t)TDC_LINK_HEADER_BYTES + len;
}

size_t tdc_link_encode_raw(uint8_t *out, size_t cap, const tdc_link_header_t *f, const uint8_t *payload,
                           uint32_t payload_len)
{
    if (!out || cap < (size_t)TDC_LINK_HEADER_BYTES + payload_len || (payload_len && !payload)) {
        return 0;
    }
    memmove(out + TDC_LINK_HEADER_BYTES, payload, payload_len);
    return finish(out, f, payload_len);
}

static void fields(const tdc_link_encoder_t *enc, tdc_link_header_t *f, tdc_link_kind_t kind, uint32_t eye,
                   uint32_t frame, tdc_pixfmt_t fmt, uint32_t w, uint32_t h, uint32_t flags)
{
    f->version = TDC_LINK_VERSION;
    f->kind = (uint8_t)kind;
    f->eye = (uint8_t)eye;
    f->format = (uint8_t)fmt;
    f->stream_id = enc->stream_id;
    f->flags = (uint16_t)flags;
    f->frame_index = frame;
    f->width = (uint16_t)w;
    f->height = (uint16_t)h;
    f->payload_len = 0; /* set by finish() */
    f->payload_crc = 0;
}

size_t tdc_link_encode_stream(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap)
{
    if (cap < (size_t)TDC_LINK_HEADER_BYTES + TDC_LINK_STREAM_HEADER_BYTES) {
        return 0;
    }
    const tdc_link_stream_info_t *in = &enc->info;
    tdc_link_stream_pack(out + TDC_LINK_HEADER_BYTES, in);
    tdc_link_header_t f;
    fields(enc, &f, TDC_LINK_KIND_STREAM, 0, 0, TDC_PIXFMT_NONE, in->width, in->height, 0);
    return finish(out, &f, TDC_LINK_STREAM_HEADER_BYTES);
}

size_t tdc_link_encode_frame(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, tdc_link_kind_t kind,
                             uint32_t eye, uint32_t frame, tdc_pixfmt_t fmt, const uint8_t *rgb, uint32_t w, uint32_t h,
                             uint32_t stride)
{
    if ((kind != TDC_LINK_KIND_FULL && kind != TDC_LINK_KIND_REDUCED) || !tdc_pixfmt_valid(fmt) || w == 0 || h == 0 ||
        w > 65535u || h > 65535u) {
        return 0;
    }
    const size_t total = tdc_link_packet_bytes(kind, fmt, w, h, 0);
    if (!out || !rgb || total == 0 || cap < total) {
        return 0;
    }
    tdc_pixfmt_pack(fmt, rgb, w, h, stride, out + TDC_LINK_HEADER_BYTES);
    tdc_link_header_t f;
    fields(enc, &f, kind, eye, frame, fmt, w, h, 0);
    return finish(out, &f, (uint32_t)(total - TDC_LINK_HEADER_BYTES));
}

size_t tdc_link_encode_band(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, tdc_link_kind_t kind,
                            uint32_t eye, uint32_t frame, tdc_pixfmt_t fmt, const uint8_t *rgb, uint32_t w, uint32_t h,
                            uint32_t stride, uint32_t band_rows, uint32_t index)
{
    if ((kind != TDC_LINK_KIND_FULL && kind != TDC_LINK_KIND_REDUCED) || !tdc_pixfmt_valid(fmt) ||
        tdc_link_packet_bytes(kind, fmt, w, h, 0) == 0 || !out || !rgb) {
        return 0;
    }
    uint8_t bh[TDC_BAND_HDR_BYTES];
    if (tdc_band_hdr_pack(bh, index, band_rows, h, fmt) != 0) {
        return 0;
    }
    const uint32_t first = tdc_get_le16(bh + 8), rows = tdc_get_le16(bh + 10);
    const uint32_t len = tdc_band_payload_bytes(fmt, w, rows);
    if (cap < (size_t)TDC_LINK_HEADER_BYTES + len) {
        return 0;
    }
    memcpy(out + TDC_LINK_HEADER_BYTES, bh, TDC_BAND_HDR_BYTES);
    tdc_pixfmt_pack(fmt, rgb + (size_t)first * stride, w, rows, stride,
                    out + TDC_LINK_HEADER_BYTES + TDC_BAND_HDR_BYTES);
    tdc_link_header_t f;
    fields(enc, &f, kind, eye, frame, fmt, w, h, TDC_LINK_PKT_BAND);
    return finish(out, &f, len);
}

size_t tdc_link_encode_subframe(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, uint32_t eye, uint32_t frame,
                                tdc_pixfmt_t fmt, const uint8_t *samples, uint32_t w, uint32_t h)
{
    if (!tdc_pixfmt_valid(fmt) || w == 0 || h == 0 || w > 65535u || h > 65535u) {
        return 0;
    }
    const size_t total = tdc_link_packet_bytes(TDC_LINK_KIND_SUBFRAME, fmt, w, h, 0);
    if (!out || !samples || total == 0 || cap < total) {
        return 0;
    }
    const uint32_t tx = TDC_TILES(w), ty = TDC_TILES(h);
    tdc_pixfmt_pack(fmt, samples, tx, ty, tx * 3u, out + TDC_LINK_HEADER_BYTES);
    tdc_link_header_t f;
    fields(enc, &f, TDC_LINK_KIND_SUBFRAME, eye, frame, fmt, w, h, 0);
    return finish(out, &f, (uint32_t)(total - TDC_LINK_HEADER_BYTES));
}

size_t tdc_link_encode_motion(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, uint32_t eye, uint32_t frame,
                              const int16_t *mv, uint32_t w, uint32_t h, int per_sample)
{
    const uint32_t flags = per_sample ? TDC_LINK_PKT_MV_PER_SAMPLE : 0u;
    if (w == 0 || h == 0 || w > 65535u || h > 65535u) {
        return 0;
    }
    const size_t total = tdc_link_packet_bytes(TDC_LINK_KIND_MOTION, TDC_PIXFMT_NONE, w, h, flags);
    if (!out || !mv || total == 0 || cap < total) {
        return 0;
    }
    const size_t count = (total - TDC_LINK_HEADER_BYTES) / 2u;
    uint8_t *p = out + TDC_LINK_HEADER_BYTES;
    for (size_t i = 0; i < count; i++) {
        tdc_put_le16s(p + 2u * i, mv[i]);
    }
    tdc_link_header_t f;
    fields(enc, &f, TDC_LINK_KIND_MOTION, eye, frame, TDC_PIXFMT_NONE, w, h, flags);
    return finish(out, &f, (uint32_t)(total - TDC_LINK_HEADER_BYTES));
}

size_t tdc_link_encode_pattern(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, uint32_t eye, uint32_t frame,
                               const uint8_t *bits, uint32_t w, uint32_t h)
{
    if (w == 0 || h == 0 || w > 65535u || h > 65535u) {
        return 0;
    }
    const size_t total = tdc_link_packet_bytes(TDC_LINK_KIND_PATTERN, TDC_PIXFMT_NONE, w, h, 0);
    if (!out || !bits || total == 0 || cap < total) {
        return 0;
    }
    const size_t n = total - TDC_LINK_HEADER_BYTES;
    memcpy(out + TDC_LINK_HEADER_BYTES, bits, n);
    /* Bits past the last tile are zero on the wire. */
    const uint32_t tiles = TDC_TILES(w) * TDC_TILES(h);
    if (tiles % 8u) {
        out[TDC_LINK_HEADER_BYTES + n - 1u] &= (uint8_t)((1u << (tiles % 8u)) - 1u);
    }
    tdc_link_header_t f;
    fields(enc, &f, TDC_LINK_KIND_PATTERN, eye, frame, TDC_PIXFMT_NONE, w, h, 0);
    return finish(out, &f, (uint32_t)(total - TDC_LINK_HEADER_BYTES));
}

size_t tdc_link_encode_layers(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, uint32_t eye, uint32_t frame,
                              const tdc_layer_frame_t *src, uint32_t flags, const uint8_t mv_kind[TDC_LAYER_MAX],
                              uint32_t w, uint32_t h)
{
    if (!out || !src || !mv_kind || w == 0 || h == 0 || w > 65535u || h > 65535u ||
        !tdc_layer_frame_accepts(src, flags)) {
        return 0;
    }
    const size_t total = tdc_link_packet_bytes(TDC_LINK_KIND_LAYERS, TDC_PIXFMT_NONE, w, h, flags);
    if (total == 0 || cap < total) {
        return 0;
    }
    uint8_t *p = out + TDC_LINK_HEADER_BYTES;
    if (tdc_layer_hdr_pack(p, flags, mv_kind, w, h) != 0) {
        return 0;
    }
    p += TDC_LAYER_HDR_BYTES;
    const uint32_t tiles = (uint32_t)TDC_TILES(w) * TDC_TILES(h);
    for (uint32_t t = 1; t <= TDC_LAYER_MAX; t++) {
        if (!(flags & TDC_LAYER_PKT_TYPE(t))) {
            continue;
        }
        const uint32_t nb = tiles * tdc_layer_value_bytes(t);
        memcpy(p, src->value[t - 1u], nb);
        p += nb;
        for (uint32_t k = 0; k < 2u * tiles; k++) {
            tdc_put_le16s(p + 2u * k, src->mv[t - 1u][k]);
        }
        p += (size_t)tiles * 4u;
    }
    if (flags & TDC_LAYER_PKT_FALLOFF) {
        for (uint32_t k = 0; k < tiles; k++) {
            tdc_put_le16(p + 2u * k, src->falloff[k]);
        }
    }
    tdc_link_header_t f;
    fields(enc, &f, TDC_LINK_KIND_LAYERS, eye, frame, TDC_PIXFMT_NONE, w, h, flags);
    return finish(out, &f, (uint32_t)(total - TDC_LINK_HEADER_BYTES));
}

size_t tdc_link_encode_foveated(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, uint32_t eye, uint32_t frame,
                                const tdc_fov_params_t *p, uint16_t delta_q15, const uint8_t *samples,
                                const int16_t *mv, tdc_fov_geom_t *g)
{
    return tdc_link_encode_foveated_slot(enc, out, cap, TDC_LINK_KIND_FULL, eye, frame, p, delta_q15, samples, mv, g);
}

size_t tdc_link_encode_foveated_slot(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, tdc_link_kind_t slot,
                                     uint32_t eye, uint32_t frame, const tdc_fov_params_t *p, uint16_t delta_q15,
                                     const uint8_t *samples, const int16_t *mv, tdc_fov_geom_t *g)
{
    if (!enc || (slot != TDC_LINK_KIND_FULL && slot != TDC_LINK_KIND_REDUCED) ||
        (slot == TDC_LINK_KIND_REDUCED && enc->info.r_den == 0)) {
        return 0;
    }
    const int red = slot == TDC_LINK_KIND_REDUCED;
    /* the slot's grid: the eye, or the reduced grid of the stream's ratio */
    const uint16_t w = red ? (uint16_t)TDC_REDUCED_DIM(enc->info.width, enc->info.r_num, enc->info.r_den)
                           : enc->info.width;
    const uint16_t h = red ? (uint16_t)TDC_REDUCED_DIM(enc->info.height, enc->info.r_num, enc->info.r_den)
                           : enc->info.height;
    tdc_fov_geom_t geom;
    uint8_t fh[TDC_FOV_HDR_BYTES];
    if (!out || !p || !samples || tdc_fov_geom(&geom, w, h, p) != TDC_OK ||
        tdc_fov_hdr_pack(fh, w, h, p, delta_q15, mv ? TDC_FOV_FLAG_MV : 0u) != TDC_OK) {
        return 0;
    }
    const uint32_t n = TDC_FOV_HDR_BYTES + tdc_fov_payload_bytes(&geom, mv != NULL);
    if (cap < (size_t)TDC_LINK_HEADER_BYTES + n) {
        return 0;
    }
    memcpy(out + TDC_LINK_HEADER_BYTES, fh, TDC_FOV_HDR_BYTES);
    tdc_fov_pack_payload(&geom, samples, mv, out + TDC_LINK_HEADER_BYTES + TDC_FOV_HDR_BYTES);
    if (g) {
        *g = geom;
    }
    tdc_link_header_t f;
    fields(enc, &f, TDC_LINK_KIND_FOVEATED, eye, frame, TDC_PIXFMT_RGB888, w, h, red ? TDC_LINK_PKT_FOV_REDUCED : 0u);
    return finish(out, &f, n);
}
