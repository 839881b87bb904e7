/*
 * tdc_band_link.c - row bands of FULL / REDUCED pictures (tdc_band_link.h,
 * docs/link-protocol.md §2.3): the band header, its geometry rules and the
 * per-eye order of bands.  Integer only, no state of its own.
 */
#include "tdc_band_link.h"

#include "tdc_bytes.h"

/* Geometry of band `index` of a height-row picture in bands of band_rows:
 * 0 and *first, *rows, *count set if valid. */
static int band_geometry(uint32_t index, uint32_t band_rows, uint32_t height, uint32_t fmt, uint32_t *first,
                         uint32_t *rows, uint32_t *count)
{
    if (band_rows == 0 || height == 0 || band_rows > 65535u) {
        return -1;
    }
    const uint32_t n = tdc_band_count(height, band_rows);
    /* YCbCr 4:2:0: a band boundary inside a chroma row would split it */
    if (index >= n || (fmt == TDC_PIXFMT_YCBCR420 && n > 1u && (band_rows & 1u))) {
        return -1;
    }
    *count = n;
    *first = index * band_rows;
    *rows = height - *first < band_rows ? height - *first : band_rows;
    return 0;
}

int tdc_band_hdr_pack(uint8_t out[TDC_BAND_HDR_BYTES], uint32_t index, uint32_t band_rows, uint32_t height,
                      tdc_pixfmt_t fmt)
{
    uint32_t first = 0, rows = 0, count = 0;
    if (band_geometry(index, band_rows, height, (uint32_t)fmt, &first, &rows, &count) != 0) {
        return -1;
    }
    out[0] = TDC_BAND_LAYOUT_VERSION;
    out[1] = 0;
    tdc_put_le16(out + 2, index);
    tdc_put_le16(out + 4, count);
    tdc_put_le16(out + 6, band_rows);
    tdc_put_le16(out + 8, first);
    tdc_put_le16(out + 10, rows);
    tdc_put_le32(out + 12, 0);
    return 0;
}

tdc_band_err_t tdc_band_hdr_parse(const uint8_t *in, tdc_pixfmt_t fmt, uint32_t width, uint32_t height,
                                  uint32_t payload_len, tdc_band_hdr_t *h)
{
    h->version = in[0];
    h->reserved = in[1];
    h->index = tdc_get_le16(in + 2);
    h->count = tdc_get_le16(in + 4);
    h->band_rows = tdc_get_le16(in + 6);
    h->first_row = tdc_get_le16(in + 8);
    h->rows = tdc_get_le16(in + 10);
    h->reserved2 = tdc_get_le32(in + 12);
    if (h->version != TDC_BAND_LAYOUT_VERSION || h->reserved != 0 || h->reserved2 != 0) {
        return TDC_BAND_ERR_HEADER;
    }
    uint32_t first = 0, rows = 0, count = 0;
    if (band_geometry(h->index, h->band_rows, height, (uint32_t)fmt, &first, &rows, &count) != 0 ||
        h->count != count || h->first_row != first || h->rows != rows ||
        payload_len != tdc_band_payload_bytes(fmt, width, rows)) {
        return TDC_BAND_ERR_GEOMETRY;
    }
    return TDC_BAND_OK;
}

tdc_band_err_t tdc_band_seq_check(const tdc_band_seq_t *s, uint32_t kind, uint32_t frame, uint32_t fmt,
                                  const tdc_band_hdr_t *h)
{
    const int same = tdc_band_seq_is(s, kind, frame);
    if (h->index == 0) {
        /* a new picture, unless this one is already in flight */
        if (!same) {
            return TDC_BAND_OK;
        }
        return s->state == TDC_BAND_DEAD ? TDC_BAND_ERR_DROPPED : TDC_BAND_ERR_ORDER;
    }
    if (!same) {
        return TDC_BAND_ERR_FRAME;
    }
    if (s->state == TDC_BAND_DEAD) {
        return TDC_BAND_ERR_DROPPED;
    }
    if (h->count != s->count || h->band_rows != s->band_rows || fmt != s->format) {
        return TDC_BAND_ERR_SIZE;
    }
    return h->index == s->next ? TDC_BAND_OK : TDC_BAND_ERR_ORDER;
}

int tdc_band_seq_accept(tdc_band_seq_t *s, uint32_t kind, uint32_t frame, uint32_t fmt, const tdc_band_hdr_t *h)
{
    if (h->index == 0) {
        s->kind = (uint8_t)kind;
        s->frame = frame;
        s->format = (uint8_t)fmt;
        s->count = h->count;
        s->band_rows = h->band_rows;
    }
    s->next = (uint16_t)(h->index + 1u);
    if (s->next >= s->count) {
        s->state = TDC_BAND_IDLE;
        return 1;
    }
    s->state = TDC_BAND_OPEN;
    return 0;
}

const char *tdc_band_err_name(tdc_band_err_t e)
{
    static const char *const n[TDC_BAND_ERR_N] = {"TDC_BAND_OK",          "TDC_BAND_ERR_HEADER", "TDC_BAND_ERR_GEOMETRY",
                                                  "TDC_BAND_ERR_ORDER",   "TDC_BAND_ERR_FRAME",  "TDC_BAND_ERR_SIZE",
                                                  "TDC_BAND_ERR_DROPPED"};
    return (unsigned)e < TDC_BAND_ERR_N ? n[e] : "TDC_BAND_ERR_?";
}

const char *tdc_band_drop_name(tdc_band_drop_t d)
{
    static const char *const n[TDC_BAND_DROP_N] = {"TDC_BAND_DROP_NONE", "TDC_BAND_DROP_CRC", "TDC_BAND_DROP_REFUSED",
                                                   "TDC_BAND_DROP_MISSING"};
    return (unsigned)d < TDC_BAND_DROP_N ? n[d] : "TDC_BAND_DROP_?";
}
