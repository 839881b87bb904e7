/*
 * tdc_layer_link.c - the layered subframe payload (tdc_layer_link.h): header
 * pack/parse, the full-payload check the decoder runs after the CRC and
 * before it writes anything, and the unpack into planes by layer type.
 * Little-endian byte access only; no state, no allocation.
 */
#include "tdc_layer_link.h"

#include "tdc_bytes.h"

int tdc_layer_mv_valid(uint32_t type, uint32_t kind)
{
    switch (type) {
    case TDC_LAYER_SHADING: /* disocclusions: dual vectors */
    case TDC_LAYER_INDIRECT: return kind == TDC_LAYER_MV_SURFACE || kind == TDC_LAYER_MV_DUAL;
    case TDC_LAYER_VISIBILITY:
        return kind == TDC_LAYER_MV_SURFACE || kind == TDC_LAYER_MV_SHADOW || kind == TDC_LAYER_MV_DUAL;
    case TDC_LAYER_GLOSSY:
        return kind == TDC_LAYER_MV_SURFACE || kind == TDC_LAYER_MV_MIRROR || kind == TDC_LAYER_MV_GLOSSY;
    default: return 0;
    }
}

int tdc_layer_hdr_pack(uint8_t out[TDC_LAYER_HDR_BYTES], uint32_t flags, const uint8_t mv_kind[TDC_LAYER_MAX],
                       uint32_t width, uint32_t height)
{
    if (!tdc_layer_flags_valid(flags) || width == 0 || height == 0 || width > 65535u || height > 65535u) {
        return -1;
    }
    for (unsigned i = 0; i < TDC_LAYER_HDR_BYTES; i++) {
        out[i] = 0;
    }
    unsigned n = 0;
    for (uint32_t t = 1; t <= TDC_LAYER_MAX; t++) {
        if (flags & TDC_LAYER_PKT_TYPE(t)) {
            if (!tdc_layer_mv_valid(t, mv_kind[t - 1u])) {
                return -1;
            }
            out[2u + n] = (uint8_t)t;
            out[6u + n] = mv_kind[t - 1u];
            n++;
        }
    }
    out[0] = TDC_LAYER_LAYOUT_VERSION;
    out[1] = (uint8_t)n;
    out[10] = (flags & TDC_LAYER_PKT_FALLOFF) ? 1u : 0u;
    tdc_put_le16(out + 12, TDC_TILES(width));
    tdc_put_le16(out + 14, TDC_TILES(height));
    return 0;
}

tdc_layer_err_t tdc_layer_hdr_parse(const uint8_t in[TDC_LAYER_HDR_BYTES], uint32_t pkt_flags, uint32_t width,
                                    uint32_t height, tdc_layer_hdr_t *h)
{
    h->version = in[0];
    h->count = in[1];
    for (unsigned i = 0; i < TDC_LAYER_MAX; i++) {
        h->type[i] = in[2u + i];
        h->mv_kind[i] = in[6u + i];
    }
    h->flags = in[10];
    h->reserved = in[11];
    h->tiles_x = tdc_get_le16(in + 12);
    h->tiles_y = tdc_get_le16(in + 14);
    if (h->version != TDC_LAYER_LAYOUT_VERSION) {
        return TDC_LAYER_ERR_VERSION;
    }
    unsigned want = 0;
    for (uint32_t t = 1; t <= TDC_LAYER_MAX; t++) {
        want += (pkt_flags & TDC_LAYER_PKT_TYPE(t)) ? 1u : 0u;
    }
    if (h->count == 0 || h->count > TDC_LAYER_MAX || h->count != want) {
        return TDC_LAYER_ERR_COUNT;
    }
    /* types: the flags' set, ascending, then zeros */
    uint32_t t = 0;
    for (unsigned i = 0; i < TDC_LAYER_MAX; i++) {
        if (i < h->count) {
            do {
                t++;
            } while (t <= TDC_LAYER_MAX && !(pkt_flags & TDC_LAYER_PKT_TYPE(t)));
            if (h->type[i] != t) {
                return TDC_LAYER_ERR_TYPE;
            }
        } else if (h->type[i] != 0) {
            return TDC_LAYER_ERR_TYPE;
        }
    }
    for (unsigned i = 0; i < TDC_LAYER_MAX; i++) {
        if (i < h->count ? !tdc_layer_mv_valid(h->type[i], h->mv_kind[i]) : h->mv_kind[i] != 0) {
            return TDC_LAYER_ERR_VECTOR;
        }
    }
    if (h->tiles_x != TDC_TILES(width) || h->tiles_y != TDC_TILES(height)) {
        return TDC_LAYER_ERR_SIZE;
    }
    if ((h->flags & ~1u) || h->reserved || (h->flags != 0) != ((pkt_flags & TDC_LAYER_PKT_FALLOFF) != 0)) {
        return TDC_LAYER_ERR_RESERVED;
    }
    return TDC_LAYER_OK;
}

tdc_layer_err_t tdc_layer_payload_check(const uint8_t *payload, uint32_t len, uint32_t pkt_flags, uint32_t width,
                                        uint32_t height)
{
    tdc_layer_hdr_t h;
    const uint32_t tiles = (uint32_t)TDC_TILES(width) * TDC_TILES(height);
    if (len < TDC_LAYER_HDR_BYTES || len != tdc_layer_payload_bytes(pkt_flags, tiles)) {
        return TDC_LAYER_ERR_SIZE; /* the decoder checked this already; kept for direct callers */
    }
    const tdc_layer_err_t e = tdc_layer_hdr_parse(payload, pkt_flags, width, height, &h);
    if (e != TDC_LAYER_OK) {
        return e;
    }
    const uint8_t *p = payload + TDC_LAYER_HDR_BYTES;
    for (unsigned i = 0; i < h.count; i++) {
        p += (size_t)tiles * tdc_layer_value_bytes(h.type[i]);
        /* vectors: the high byte of a component is 0x80 and the low 0x00 */
        for (uint32_t k = 0; k < 2u * tiles; k++) {
            if (p[2u * k] == 0x00u && p[2u * k + 1u] == 0x80u) {
                return TDC_LAYER_ERR_SENTINEL;
            }
        }
        p += (size_t)tiles * 4u;
    }
    if (pkt_flags & TDC_LAYER_PKT_FALLOFF) {
        for (uint32_t k = 0; k < tiles; k++) {
            if (tdc_get_le16(p + 2u * k) > TDC_LAYER_W_ONE) {
                return TDC_LAYER_ERR_WEIGHT;
            }
        }
    }
    return TDC_LAYER_OK;
}

int tdc_layer_frame_accepts(const tdc_layer_frame_t *dst, uint32_t pkt_flags)
{
    if (!dst) {
        return 0;
    }
    for (uint32_t t = 1; t <= TDC_LAYER_MAX; t++) {
        if ((pkt_flags & TDC_LAYER_PKT_TYPE(t)) && (!dst->value[t - 1u] || !dst->mv[t - 1u])) {
            return 0;
        }
    }
    return !(pkt_flags & TDC_LAYER_PKT_FALLOFF) || dst->falloff != NULL;
}

void tdc_layer_unpack(const uint8_t *payload, uint32_t pkt_flags, uint32_t width, uint32_t height,
                      tdc_layer_frame_t *dst)
{
    const uint32_t tiles = (uint32_t)TDC_TILES(width) * TDC_TILES(height);
    (void)tdc_layer_hdr_parse(payload, pkt_flags, width, height, &dst->hdr); /* checked before */
    dst->present = (uint16_t)pkt_flags;
    const uint8_t *p = payload + TDC_LAYER_HDR_BYTES;
    for (unsigned i = 0; i < dst->hdr.count; i++) {
        const uint32_t t = dst->hdr.type[i];
        const uint32_t nb = tiles * tdc_layer_value_bytes(t);
        uint8_t *v = dst->value[t - 1u];
        for (uint32_t k = 0; k < nb; k++) {
            v[k] = p[k];
        }
        p += nb;
        int16_t *mv = dst->mv[t - 1u];
        for (uint32_t k = 0; k < 2u * tiles; k++) {
            mv[k] = tdc_get_le16s(p + 2u * k);
        }
        p += (size_t)tiles * 4u;
    }
    if (pkt_flags & TDC_LAYER_PKT_FALLOFF) {
        for (uint32_t k = 0; k < tiles; k++) {
            dst->falloff[k] = tdc_get_le16(p + 2u * k);
        }
    }
}

const char *tdc_layer_err_name(tdc_layer_err_t e)
{
    static const char *const n[TDC_LAYER_ERR_N] = {
        "TDC_LAYER_OK",         "TDC_LAYER_ERR_VERSION",  "TDC_LAYER_ERR_COUNT",    "TDC_LAYER_ERR_TYPE",
        "TDC_LAYER_ERR_VECTOR", "TDC_LAYER_ERR_SIZE",     "TDC_LAYER_ERR_RESERVED", "TDC_LAYER_ERR_SENTINEL",
        "TDC_LAYER_ERR_WEIGHT"};
    return (unsigned)e < TDC_LAYER_ERR_N ? n[e] : "TDC_LAYER_ERR_?";
}
