/*
 * tdc_wire.c - link wire format (tdc_wire.h): the one header packer and
 * unpacker, the STREAM payload, the table of packet kinds and their
 * payload sizes.  Integer only, no state, no allocation.
 */
#include "tdc_wire.h"

#include "tdc_crc32.h"
#include "tdc_layer_link.h"

const char *tdc_link_err_name(tdc_link_err_t e)
{
    static const char *const names[TDC_LINK_ERR_COUNT] = {
        "ok",    "magic",     "garbage",         "header-crc", "version",      "kind",
        "eye",   "format",    "dimensions",      "length",     "crc",          "stream",
        "order", "duplicate", "missing-reduced", "unexpected", "stream-header", "layers", "foveation",
        "band",  "band-dropped"};
    return (unsigned)e < (unsigned)TDC_LINK_ERR_COUNT ? names[e] : "?";
}

/* ------------------------------------------------------------------------
 * Packet header.
 * ---------------------------------------------------------------------- */
void tdc_link_header_pack(uint8_t out[TDC_LINK_HEADER_BYTES], const tdc_link_header_t *h)
{
    tdc_put_le32(out + TDC_LINK_OFF_MAGIC, TDC_LINK_MAGIC);
    out[TDC_LINK_OFF_VERSION] = h->version;
    out[TDC_LINK_OFF_KIND] = h->kind;
    out[TDC_LINK_OFF_EYE] = h->eye;
    out[TDC_LINK_OFF_FORMAT] = h->format;
    tdc_put_le16(out + TDC_LINK_OFF_STREAM_ID, h->stream_id);
    tdc_put_le16(out + TDC_LINK_OFF_FLAGS, h->flags);
    tdc_put_le32(out + TDC_LINK_OFF_FRAME, h->frame_index);
    tdc_put_le16(out + TDC_LINK_OFF_WIDTH, h->width);
    tdc_put_le16(out + TDC_LINK_OFF_HEIGHT, h->height);
    tdc_put_le32(out + TDC_LINK_OFF_PAYLOAD_LEN, h->payload_len);
    tdc_put_le32(out + TDC_LINK_OFF_PAYLOAD_CRC, h->payload_crc);
    tdc_put_le32(out + TDC_LINK_OFF_HEADER_CRC, tdc_crc32(out, TDC_LINK_OFF_HEADER_CRC));
}

tdc_link_err_t tdc_link_header_unpack(const uint8_t in[TDC_LINK_HEADER_BYTES], tdc_link_header_t *h)
{
    h->version = in[TDC_LINK_OFF_VERSION];
    h->kind = in[TDC_LINK_OFF_KIND];
    h->eye = in[TDC_LINK_OFF_EYE];
    h->format = in[TDC_LINK_OFF_FORMAT];
    h->stream_id = tdc_get_le16(in + TDC_LINK_OFF_STREAM_ID);
    h->flags = tdc_get_le16(in + TDC_LINK_OFF_FLAGS);
    h->frame_index = tdc_get_le32(in + TDC_LINK_OFF_FRAME);
    h->width = tdc_get_le16(in + TDC_LINK_OFF_WIDTH);
    h->height = tdc_get_le16(in + TDC_LINK_OFF_HEIGHT);
    h->payload_len = tdc_get_le32(in + TDC_LINK_OFF_PAYLOAD_LEN);
    h->payload_crc = tdc_get_le32(in + TDC_LINK_OFF_PAYLOAD_CRC);
    if (tdc_get_le32(in + TDC_LINK_OFF_MAGIC) != TDC_LINK_MAGIC) {
        return TDC_LINK_ERR_MAGIC;
    }
    if (tdc_crc32(in, TDC_LINK_OFF_HEADER_CRC) != tdc_get_le32(in + TDC_LINK_OFF_HEADER_CRC)) {
        return TDC_LINK_ERR_HEADER_CRC;
    }
    return TDC_LINK_OK;
}

/* ------------------------------------------------------------------------
 * STREAM payload.
 * ---------------------------------------------------------------------- */
void tdc_link_stream_pack(uint8_t out[TDC_LINK_STREAM_HEADER_BYTES], const tdc_link_stream_info_t *s)
{
    tdc_put_le32(out + TDC_LINK_STREAM_OFF_FLAGS, s->flags);
    tdc_put_le16(out + TDC_LINK_STREAM_OFF_R_NUM, s->r_num);
    tdc_put_le16(out + TDC_LINK_STREAM_OFF_R_DEN, s->r_den);
    tdc_put_le16(out + TDC_LINK_STREAM_OFF_WIDTH, s->width);
    tdc_put_le16(out + TDC_LINK_STREAM_OFF_HEIGHT, s->height);
    out[TDC_LINK_STREAM_OFF_EYES] = s->eyes;
    out[TDC_LINK_STREAM_OFF_RESERVED] = s->reserved;
    tdc_put_le16(out + TDC_LINK_STREAM_OFF_REFRESH, s->refresh_hz);
}

void tdc_link_stream_unpack(const uint8_t in[TDC_LINK_STREAM_HEADER_BYTES], tdc_link_stream_info_t *s)
{
    s->flags = tdc_get_le32(in + TDC_LINK_STREAM_OFF_FLAGS);
    s->r_num = tdc_get_le16(in + TDC_LINK_STREAM_OFF_R_NUM);
    s->r_den = tdc_get_le16(in + TDC_LINK_STREAM_OFF_R_DEN);
    s->width = tdc_get_le16(in + TDC_LINK_STREAM_OFF_WIDTH);
    s->height = tdc_get_le16(in + TDC_LINK_STREAM_OFF_HEIGHT);
    s->eyes = in[TDC_LINK_STREAM_OFF_EYES];
    s->reserved = in[TDC_LINK_STREAM_OFF_RESERVED];
    s->refresh_hz = tdc_get_le16(in + TDC_LINK_STREAM_OFF_REFRESH);
}

/* ------------------------------------------------------------------------
 * Kinds.  A new kind is one row here (and its case in the decoder).
 * ---------------------------------------------------------------------- */
static const tdc_link_kind_info_t kinds[TDC_LINK_KIND_LAST + 1] = {
    [TDC_LINK_KIND_STREAM] = {"stream", TDC_LINK_PAYLOAD_FIXED, TDC_LINK_GRID_NONE, TDC_LINK_STREAM_HEADER_BYTES, 0u},
    /* whole pictures, or with TDC_LINK_PKT_BAND one row band (band header + rows: tdc_band_link.h) */
    [TDC_LINK_KIND_FULL] = {"full", TDC_LINK_PAYLOAD_PIXELS, TDC_LINK_GRID_PIXELS, 0u, TDC_LINK_PKT_BAND},
    [TDC_LINK_KIND_REDUCED] = {"reduced", TDC_LINK_PAYLOAD_PIXELS, TDC_LINK_GRID_PIXELS, 0u, TDC_LINK_PKT_BAND},
    [TDC_LINK_KIND_SUBFRAME] = {"subframe", TDC_LINK_PAYLOAD_PIXELS, TDC_LINK_GRID_TILES, 0u, 0u},
    /* (dx, dy) int16 LE per pixel, or per tile with MV_PER_SAMPLE */
    [TDC_LINK_KIND_MOTION] = {"motion", TDC_LINK_PAYLOAD_PER_ELEM, TDC_LINK_GRID_MV, 4u, TDC_LINK_PKT_MV_PER_SAMPLE},
    [TDC_LINK_KIND_PATTERN] = {"pattern", TDC_LINK_PAYLOAD_BITS, TDC_LINK_GRID_TILES, 0u, 0u},
    /* RGB888 samples; the 32-byte foveation header states the rest; with
     * FOV_REDUCED the picture of a TRM stream's reduced slot (rW x rH) */
    [TDC_LINK_KIND_FOVEATED] = {"foveated", TDC_LINK_PAYLOAD_STATED, TDC_LINK_GRID_NONE, 0u, TDC_LINK_PKT_FOV_REDUCED},
    /* layer header + per layer value and vector planes (+ falloff), flags = the layer set */
    [TDC_LINK_KIND_LAYERS] = {"layers", TDC_LINK_PAYLOAD_LAYERS, TDC_LINK_GRID_TILES, 0u, TDC_LAYER_PKT_KNOWN},
};

const tdc_link_kind_info_t *tdc_link_kind_info(uint32_t kind)
{
    /* a value without a row (7, kept for the foveated kind) is unknown */
    return kind >= TDC_LINK_KIND_FIRST && kind <= TDC_LINK_KIND_LAST && kinds[kind].name ? &kinds[kind]
                                                                                          : (const tdc_link_kind_info_t *)0;
}

const char *tdc_link_kind_name(uint32_t kind)
{
    const tdc_link_kind_info_t *k = tdc_link_kind_info(kind);
    return k ? k->name : "?";
}

uint32_t tdc_link_payload_bytes(tdc_link_kind_t kind, tdc_pixfmt_t fmt, uint32_t width, uint32_t height,
                                uint32_t pkt_flags)
{
    const tdc_link_kind_info_t *k = tdc_link_kind_info((uint32_t)kind);
    if (!k) {
        return 0;
    }
    const int tiles =
        k->grid == TDC_LINK_GRID_TILES || (k->grid == TDC_LINK_GRID_MV && (pkt_flags & TDC_LINK_PKT_MV_PER_SAMPLE));
    const uint32_t gw = tiles ? TDC_TILES(width) : width;
    const uint32_t gh = tiles ? TDC_TILES(height) : height;
    switch (k->rule) {
    case TDC_LINK_PAYLOAD_FIXED: return k->unit;
    case TDC_LINK_PAYLOAD_PIXELS: return tdc_pixfmt_payload_bytes(fmt, gw, gh);
    case TDC_LINK_PAYLOAD_PER_ELEM: return gw * gh * k->unit;
    case TDC_LINK_PAYLOAD_LAYERS: return tdc_layer_payload_bytes(pkt_flags, gw * gh);
    case TDC_LINK_PAYLOAD_BITS: return (gw * gh + 7u) / 8u;
    default: /* STATED: not a function of the packet header */ return 0;
    }
}

size_t tdc_link_packet_bytes(tdc_link_kind_t kind, tdc_pixfmt_t fmt, uint32_t width, uint32_t height,
                             uint32_t pkt_flags)
{
    if (width == 0 || height == 0 || width > 65535u || height > 65535u ||
        (uint64_t)width * height > ((uint64_t)1 << 28)) {
        return 0;
    }
    const uint32_t n = tdc_link_payload_bytes(kind, fmt, width, height, pkt_flags);
    return n ? (size_t)n + TDC_LINK_HEADER_BYTES : 0;
}
