/*
 * fuzz_layers.c - libFuzzer target of the layered subframe kind
 * (firmware/tdc_layer_link.h) for a 20 x 12 stereo panel.  Input: byte 0 =
 * the packet flags, byte 1 = the eye, the rest = a LAYERS payload.  It goes
 * through the real decoder (stream header, packet built with valid CRCs
 * around the fuzzed payload), then:
 *   - a refused packet must leave every plane as it was and be counted
 *     under exactly one reason;
 *   - an accepted one must equal tdc_layer_payload_check's verdict, and
 *     re-encoding the unpacked planes must give the payload back byte for
 *     byte (nothing lost or invented).
 * ASan + UBSan catch the rest.  Seeds: tests/fuzz/corpus-layers.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_crc32.h"
#include "tdc_link.h"
#include "tdc_link_encode.h"
#include "../golden/tdc_layer_content.h"

#define FW 20
#define FH 12
#define NT (TDC_TILES(FW) * TDC_TILES(FH))

static uint8_t staging[TDC_LINK_STAGING_LAYERS_BYTES(FW, FH)];
static uint8_t pattern[2][TDC_PATTERN_BYTES(FW, FH)];
static uint8_t subframe[2][NT * 3];
static uint8_t val[2][TDC_LAYER_MAX][NT * 3];
static int16_t mv[2][TDC_LAYER_MAX][NT * 2];
static uint16_t wt[2][NT];
static tdc_layer_frame_t lf[2];
static uint8_t snap_val[sizeof val];
static int16_t snap_mv[sizeof mv / 2];
static uint16_t snap_wt[sizeof wt / 2];
static uint8_t pkt[64 + sizeof staging];
static uint8_t again[64 + sizeof staging];

static size_t feed_all(tdc_link_decoder_t *dec, const uint8_t *p, size_t n, tdc_link_event_t *first)
{
    size_t used = 0;
    first->type = TDC_LINK_EV_NONE;
    for (;;) {
        tdc_link_event_t ev;
        used += tdc_link_feed(dec, p + used, n - used, &ev);
        if (ev.type == TDC_LINK_EV_NONE) {
            break;
        }
        if (first->type == TDC_LINK_EV_NONE) {
            *first = ev;
        }
    }
    return used;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 2 || size - 2 > sizeof staging) {
        return 0;
    }
    const uint32_t flags = data[0], eye = data[1] & 1u;
    const uint8_t *payload = data + 2;
    const uint32_t len = (uint32_t)(size - 2);

    tdc_link_decoder_t dec;
    tdc_link_config_t cfg = {FW, FH, 2};
    tdc_link_buffers_t b;
    memset(&b, 0, sizeof b);
    b.staging = staging;
    b.staging_bytes = sizeof staging;
    for (int e = 0; e < 2; e++) {
        TDC_LAYER_FRAME_WIRE(lf[e], val[e], mv[e], wt[e]);
        b.layers[e] = &lf[e];
        b.pattern[e] = pattern[e];
        b.subframe[e] = subframe[e];
    }
    if (tdc_link_decoder_init(&dec, &cfg, &b) != TDC_OK) {
        abort();
    }
    tdc_link_stream_info_t info = {TDC_LINK_STREAM_SUBFRAMES | TDC_LINK_STREAM_LAYERS, 1, 1, FW, FH, 2, 0, 240};
    tdc_link_encoder_t enc;
    tdc_link_encoder_init(&enc, 3, &info);
    tdc_link_event_t ev;
    size_t n = tdc_link_encode_stream(&enc, pkt, sizeof pkt);
    if (feed_all(&dec, pkt, n, &ev) != n || ev.type != TDC_LINK_EV_PACKET) {
        abort();
    }
    memset(val, 0x5A, sizeof val);
    memset(mv, 0x33, sizeof mv);
    memset(wt, 0x11, sizeof wt);
    memcpy(snap_val, val, sizeof val);
    memcpy(snap_mv, mv, sizeof mv);
    memcpy(snap_wt, wt, sizeof wt);

    tdc_link_header_t h = {TDC_LINK_VERSION, TDC_LINK_KIND_LAYERS, (uint8_t)eye, 0, 3, (uint16_t)flags, 1, FW, FH,
                           0, 0};
    n = tdc_link_encode_raw(pkt, sizeof pkt, &h, payload, len);
    if (n == 0 || feed_all(&dec, pkt, n, &ev) != n) {
        abort();
    }
    const uint32_t want = tdc_layer_payload_bytes(flags, NT);
    const int verdict = want != 0 && len == want ? (int)tdc_layer_payload_check(payload, len, flags, FW, FH) : -1;
    if (ev.type == TDC_LINK_EV_PACKET) {
        if (verdict != TDC_LAYER_OK || lf[eye].present != flags) {
            abort(); /* accepted what the check refuses */
        }
        uint8_t kinds[TDC_LAYER_MAX] = {0};
        for (unsigned i = 0; i < lf[eye].hdr.count; i++) {
            kinds[lf[eye].hdr.type[i] - 1u] = lf[eye].hdr.mv_kind[i];
        }
        const size_t m = tdc_link_encode_layers(&enc, again, sizeof again, eye, 1, &lf[eye], flags, kinds, FW, FH);
        if (m != n || memcmp(again + TDC_LINK_HEADER_BYTES, payload, len) != 0) {
            abort(); /* the planes do not hold the payload */
        }
    } else {
        if (ev.type != TDC_LINK_EV_ERROR || verdict == TDC_LAYER_OK) {
            abort();
        }
        if (memcmp(snap_val, val, sizeof val) || memcmp(snap_mv, mv, sizeof mv) || memcmp(snap_wt, wt, sizeof wt)) {
            abort(); /* a refused packet wrote */
        }
        if (ev.error == TDC_LINK_ERR_LAYERS) {
            uint32_t total = 0;
            for (int r = 1; r < TDC_LAYER_ERR_N; r++) {
                total += tdc_link_counters(&dec)->layer_errors[r];
            }
            if (verdict <= 0 || total != 1 || tdc_link_counters(&dec)->layer_errors[verdict] != 1) {
                abort();
            }
        }
    }
    return 0;
}
