/*
 * fuzz_bands.c - libFuzzer target of the row-band mode (firmware/
 * tdc_band_link.h, docs/link-protocol.md §2.3) through the real decoder, on
 * a 12 x 10 stereo TRM stream (r = 1/2) whose staging buffer holds one band
 * of at most 4 rows.  The input is a recipe of 4-byte operations: a band
 * (any eye, kind, frame step, format, band height, index), the same with
 * one byte of its band header or pixels changed (CRC left bad or fixed),
 * raw bytes, a stream header (repeated or new).  Each packet is fed whole;
 * after it:
 *   - the decoder accepts a band exactly when the band check does
 *     (tdc_band_hdr_parse, then tdc_band_seq_check against a model of the
 *     eye's picture in flight kept here), and refuses it with that reason;
 *   - a refused packet writes nothing (every buffer byte as before); an
 *     accepted band writes exactly its rows, the rows its payload decodes to;
 *     a refusal is counted under exactly one code (and one band reason);
 *   - a refused band that names the picture in flight drops it (one
 *     BAND_DROPPED event);
 *   - a completed picture (its last band accepted) had every band accepted
 *     in order and no drop: only then it is "swapped in" (copied to a front
 *     buffer), and the buffer then equals what its bands carried.
 * ASan + UBSan catch the rest.  Seeds: tests/fuzz/corpus-bands.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_crc32.h"
#include "tdc_link.h"
#include "tdc_link_encode.h"
#include "fuzz_link_rig.h"

#define FW 12
#define FH 10
#define RW TDC_REDUCED_DIM(FW, 1u, 2u)
#define RH TDC_REDUCED_DIM(FH, 1u, 2u)
#define BR 4 /* largest band this build stages */

static uint8_t staging[TDC_LINK_STAGING_BAND_BYTES(FW, BR, 4u)];
static uint8_t full[2][FW * FH * 3];
static uint8_t reduced[2][RW * RH * 3];
static uint8_t snap_full[sizeof full], snap_red[sizeof reduced];
static uint8_t shadow[2][FW * FH * 3]; /* what the accepted bands of the eye's picture carried */
static uint8_t front[2][FW * FH * 3];  /* "swapped in" pictures */
static uint8_t src[FW * FH * 3];
static uint8_t rows_rgb[FW * FH * 3];
static uint8_t pkt[64 + FW * FH * 4 + TDC_BAND_HDR_BYTES];

static tdc_link_decoder_t dec;
static tdc_link_encoder_t enc;

/* the model of each eye's picture in flight, and what the harness saw of it */
static tdc_band_seq_t model[2];
static uint32_t got[2];  /* bit i: band i of the picture in flight accepted */
static uint8_t dead[2];  /* a drop event named the picture in flight */

#define CHECK(c)                                                                                                   \
    do {                                                                                                           \
        if (!(c)) {                                                                                                \
            abort();                                                                                               \
        }                                                                                                          \
    } while (0)

static void stream_header(uint16_t id)
{
    tdc_link_stream_info_t info = {TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_BANDS, 1, 2, FW, FH, 2, 0, 90};
    tdc_link_encoder_init(&enc, id, &info);
}

static int is_band_pkt(const tdc_link_header_t *h)
{
    return (h->kind == TDC_LINK_KIND_FULL || h->kind == TDC_LINK_KIND_REDUCED) && (h->flags & TDC_LINK_PKT_BAND) &&
           h->eye < 2 && h->stream_id == dec.stream_id && h->version == TDC_LINK_VERSION;
}

static uint32_t err_sum(const tdc_link_counters_t *c)
{
    uint32_t s = 0;
    for (int k = 1; k < TDC_LINK_ERR_COUNT; k++) {
        /* companions that are not a refusal of this packet */
        if (k != TDC_LINK_ERR_BAND_DROPPED && k != TDC_LINK_ERR_MISSING_REDUCED && k != TDC_LINK_ERR_GARBAGE &&
            k != TDC_LINK_ERR_MAGIC && k != TDC_LINK_ERR_HEADER_CRC) {
            s += c->errors[k];
        }
    }
    return s;
}

/* Feeds one packet (n bytes; `band` = built as a band, header h) and checks it. */
static void feed_packet(const uint8_t *p, size_t n, int band, const tdc_link_header_t *h)
{
    memcpy(snap_full, full, sizeof full);
    memcpy(snap_red, reduced, sizeof reduced);
    const uint32_t err0 = err_sum(tdc_link_counters(&dec));
    uint32_t berr0 = 0;
    for (int r = 1; r < TDC_BAND_ERR_N; r++) {
        berr0 += tdc_link_counters(&dec)->band_errors[r];
    }
    const int was_open = band && model[h->eye].state == TDC_BAND_OPEN &&
                         tdc_band_seq_is(&model[h->eye], h->kind, h->frame_index);
    int accepted = 0, drops_named = 0, refusal_names_open = 0;
    size_t used = 0;
    for (;;) {
        tdc_link_event_t ev;
        used += tdc_link_feed(&dec, p + used, n - used, &ev);
        if (ev.type == TDC_LINK_EV_NONE) {
            break;
        }
        if (ev.type == TDC_LINK_EV_ERROR && ev.error == TDC_LINK_ERR_BAND_DROPPED) {
            CHECK(ev.eye < 2 && (ev.kind == TDC_LINK_KIND_FULL || ev.kind == TDC_LINK_KIND_REDUCED));
            CHECK(ev.detail > 0 && ev.detail < TDC_BAND_DROP_N);
            /* the model follows the decoder's drop (its rules are checked below) */
            tdc_band_seq_t *m = &model[ev.eye];
            if (m->state != TDC_BAND_IDLE && tdc_band_seq_is(m, ev.kind, ev.frame_index)) {
                dead[ev.eye] = 1;
            }
            memset(m, 0, sizeof *m);
            m->state = TDC_BAND_DEAD;
            m->kind = ev.kind;
            m->frame = ev.frame_index;
            got[ev.eye] = 0;
            drops_named += band && ev.eye == h->eye && ev.kind == h->kind && ev.frame_index == h->frame_index;
            continue;
        }
        if (!band || ev.eye != h->eye || ev.kind != h->kind || ev.frame_index != h->frame_index) {
            continue;
        }
        const uint8_t *pay = p + TDC_LINK_HEADER_BYTES;
        if (ev.type == TDC_LINK_EV_ERROR && ev.error == TDC_LINK_ERR_BAND) {
            /* the band check must refuse it for the same reason */
            tdc_band_hdr_t bh;
            tdc_band_err_t r = tdc_band_hdr_parse(pay, (tdc_pixfmt_t)h->format, h->width, h->height, h->payload_len, &bh);
            if (r == TDC_BAND_OK) {
                r = tdc_band_seq_check(&model[h->eye], h->kind, h->frame_index, h->format, &bh);
            }
            CHECK(r != TDC_BAND_OK && (uint32_t)r == ev.detail);
            refusal_names_open = r != TDC_BAND_ERR_FRAME && r != TDC_BAND_ERR_DROPPED;
        } else if (ev.type == TDC_LINK_EV_ERROR && ev.error == TDC_LINK_ERR_CRC) {
            refusal_names_open = 1;
        } else if (ev.type == TDC_LINK_EV_PACKET) {
            /* accepted: the band check accepts it too */
            const tdc_band_hdr_t *dh = tdc_link_band(&dec, h->eye);
            CHECK(dh != NULL);
            tdc_band_hdr_t bh;
            CHECK(tdc_band_hdr_parse(pay, (tdc_pixfmt_t)h->format, h->width, h->height, h->payload_len, &bh) ==
                  TDC_BAND_OK);
            CHECK(!memcmp(&bh, dh, sizeof bh));
            CHECK(tdc_band_seq_check(&model[h->eye], h->kind, h->frame_index, h->format, &bh) == TDC_BAND_OK);
            if (bh.index == 0) {
                got[h->eye] = 0;
                dead[h->eye] = 0;
            }
            got[h->eye] |= 1u << bh.index;
            const int done = tdc_band_seq_accept(&model[h->eye], h->kind, h->frame_index, h->format, &bh);
            CHECK(done == (bh.index + 1u == bh.count));
            /* exactly its rows written, with what the payload decodes to */
            uint8_t *buf = h->kind == TDC_LINK_KIND_FULL ? full[h->eye] : reduced[h->eye];
            const uint8_t *snap = h->kind == TDC_LINK_KIND_FULL ? snap_full + h->eye * sizeof full[0]
                                                                : snap_red + h->eye * sizeof reduced[0];
            const size_t stride = (size_t)h->width * 3u, bytes = stride * h->height;
            tdc_pixfmt_unpack((tdc_pixfmt_t)h->format, pay + TDC_BAND_HDR_BYTES, h->width, bh.rows, rows_rgb, (uint32_t)stride);
            CHECK(!memcmp(buf + bh.first_row * stride, rows_rgb, stride * bh.rows));
            CHECK(!memcmp(buf, snap, bh.first_row * stride));
            CHECK(!memcmp(buf + (bh.first_row + bh.rows) * stride, snap + (bh.first_row + bh.rows) * stride,
                          bytes - (bh.first_row + bh.rows) * stride));
            memcpy(shadow[h->eye] + bh.first_row * stride, rows_rgb, stride * bh.rows);
            if (done) {
                /* the swap: only a picture with every band, in order, never dropped */
                CHECK(!dead[h->eye] && got[h->eye] == (1u << bh.count) - 1u);
                CHECK(!memcmp(buf, shadow[h->eye], bytes));
                memcpy(front[h->eye], buf, bytes);
                got[h->eye] = 0;
            }
            accepted = 1;
        }
    }
    CHECK(used == n);
    const tdc_link_counters_t *c = tdc_link_counters(&dec);
    if (band && !accepted) {
        CHECK(!memcmp(snap_full, full, sizeof full) && !memcmp(snap_red, reduced, sizeof reduced));
        CHECK(err_sum(c) - err0 <= 1u); /* at most one refusal (a packet split by garbage: hunting, none) */
        uint32_t berr = 0;
        for (int r = 1; r < TDC_BAND_ERR_N; r++) {
            berr += c->band_errors[r];
        }
        CHECK(berr - berr0 <= 1u);
        if (was_open && refusal_names_open) {
            CHECK(drops_named == 1); /* the picture in flight is dropped, once */
        }
    }
    if (band && accepted) {
        CHECK(err_sum(c) == err0);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    tdc_link_config_t cfg = {FW, FH, 2};
    tdc_link_buffers_t b = fuzz_frame_buffers(staging, sizeof staging, FW, (uint8_t *[2]){full[0], full[1]},
                                              (uint8_t *[2]){reduced[0], reduced[1]}, sizeof reduced[0]);
    memset(full, 0, sizeof full);
    memset(reduced, 0, sizeof reduced);
    memset(model, 0, sizeof model);
    memset(got, 0, sizeof got);
    memset(dead, 0, sizeof dead);
    if (tdc_link_decoder_init(&dec, &cfg, &b) != TDC_OK) {
        abort();
    }
    uint16_t id = 1;
    stream_header(id);
    tdc_link_header_t sh = {0};
    size_t n = tdc_link_encode_stream(&enc, pkt, sizeof pkt);
    feed_packet(pkt, n, 0, &sh);
    uint32_t frame = 0;
    /* at most 24 operations (a clean frame pair is 10): every case needs a few; longer inputs would
     * only make each execution slower */
    if (size > 24u * 4u) {
        size = 24u * 4u;
    }
    for (size_t i = 0; i + 4 <= size; i += 4) {
        const uint8_t b0 = data[i], b1 = data[i + 1], b2 = data[i + 2], b3 = data[i + 3];
        const unsigned op = b0 & 3u;
        if (op == 2u) { /* raw bytes: up to 31 of the input, then resync */
            const size_t k = (b1 & 31u) < size - i - 4 ? (b1 & 31u) : size - i - 4;
            size_t used = 0;
            for (;;) {
                tdc_link_event_t ev;
                used += tdc_link_feed(&dec, data + i + 4 + used, k - used, &ev);
                if (ev.type == TDC_LINK_EV_NONE) {
                    break;
                }
                if (ev.type != TDC_LINK_EV_ERROR || (ev.error != TDC_LINK_ERR_GARBAGE && ev.error != TDC_LINK_ERR_MAGIC &&
                                                     ev.error != TDC_LINK_ERR_HEADER_CRC)) {
                    return 0; /* raw bytes made a packet: the model no longer knows the decoder's state */
                }
            }
            tdc_link_decoder_resync(&dec);
            i += k;
            continue;
        }
        if (op == 3u) { /* stream header: the same again, or a new stream */
            if (b1 & 1u) {
                stream_header(++id);
            }
            n = tdc_link_encode_stream(&enc, pkt, sizeof pkt);
            feed_packet(pkt, n, 0, &sh);
            if (b1 & 1u) {
                memset(model, 0, sizeof model); /* the decoder forgets its pictures in flight */
                memset(got, 0, sizeof got);
                memset(dead, 0, sizeof dead);
                frame = 0;
            }
            continue;
        }
        const uint32_t eye = (b0 >> 2) & 1u;
        const tdc_pixfmt_t fmt = (tdc_pixfmt_t)(((b0 >> 3) & 3u) + 1u);
        const uint32_t step = (b0 >> 5) & 7u;
        frame = step == 7u ? (frame ? frame - 1u : 0u) : frame + (step > 3u ? 0u : step);
        tdc_link_kind_t kind = tdc_link_trm_kind(frame, eye);
        if (op == 0u && (b2 & 0x40u)) {
            kind = kind == TDC_LINK_KIND_FULL ? TDC_LINK_KIND_REDUCED : TDC_LINK_KIND_FULL; /* not due */
        }
        const uint32_t w = kind == TDC_LINK_KIND_FULL ? FW : RW, h = kind == TDC_LINK_KIND_FULL ? FH : RH;
        uint32_t br = ((b1 >> 4) & 3u) + 1u + ((b1 & 0x80u) ? 4u : 0u); /* 1..8: above 4 does not fit staging */
        if (fmt == TDC_PIXFMT_YCBCR420 && (br & 1u) && br < h) {
            br++;
        }
        const uint32_t index = (b1 & 15u) % (tdc_band_count(h, br) + 1u); /* count itself: invalid */
        for (size_t k = 0; k < (size_t)w * h * 3u; k++) {
            src[k] = (uint8_t)(b3 * 37u + k * 11u + frame);
        }
        n = tdc_link_encode_band(&enc, pkt, sizeof pkt, kind, eye, frame, fmt, src, w, h, FW * 3u, br, index);
        if (n == 0) {
            continue; /* invalid geometry: the encoder refuses it */
        }
        if (op == 1u) {
            /* one byte changed: in the band header (b2 < 16) or the pixels; CRC
             * fixed when b2 bit 7 is set (the band check must catch it) */
            const size_t len = n - TDC_LINK_HEADER_BYTES;
            pkt[TDC_LINK_HEADER_BYTES + (b2 & 0x7Fu) % len] ^= (uint8_t)(b3 | 1u);
            if (b2 & 0x80u) {
                tdc_link_header_t hh;
                (void)tdc_link_header_unpack(pkt, &hh);
                hh.payload_crc = tdc_crc32(pkt + TDC_LINK_HEADER_BYTES, (uint32_t)len);
                tdc_link_header_pack(pkt, &hh);
            }
        }
        tdc_link_header_t hh;
        (void)tdc_link_header_unpack(pkt, &hh);
        feed_packet(pkt, n, is_band_pkt(&hh), &hh);
    }
    return 0;
}
