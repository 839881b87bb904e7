/*
 * fuzz_link.c - libFuzzer harness for the streaming link decoder
 * (firmware/tdc_link.c).  Built with clang -fsanitize=fuzzer,address,undefined
 * by mk/link.mk: `make fuzz FUZZ_SECONDS=600`, smoke run in `make test`.
 *
 * Input: byte 0 selects the chunking (bits 0..4: seed of the chunk sizes,
 * 0 = whole input at once), the panel and build (bit 5: 0 = stereo with
 * every buffer, 1 = mono without subframe/pattern/per-sample-motion buffers
 * and without the foveated motion-vector buffer),
 * random tdc_link_decoder_resync() calls between chunks (bit 6) and whether
 * CRCs are repaired first (bit 7):
 * mutated packets almost never keep a valid CRC, so half of the runs
 * recompute header and payload CRCs of everything that parses as a packet,
 * which lets the fuzzer reach the field checks, sequencing and unpacking.
 * The rest of the input is the link byte stream for the 19 x 13 panel.
 *
 * Checked on every event, beyond the sanitizers:
 *  - a buffer changes only with an accepted packet of its kind and eye
 *    (a rejected packet never touches frame state; FOVEATED writes the
 *    full frame -- with FOV_REDUCED the reduced frame, on the reduced
 *    grid, without vectors --, the log-polar buffer and its vectors);
 *  - an accepted FOVEATED packet leaves a foveation header whose geometry
 *    the stage accepts; the refusal reasons add up to the FOVEATION errors;
 *  - error counters equal the error events seen, packets_ok the packet events;
 *  - no event is ever dropped; every byte is consumed.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_crc32.h"
#include "tdc_link.h"
#include "fuzz_link_rig.h"

#define FW 19
#define FH 13

static uint8_t staging[TDC_LINK_STAGING_BYTES(FW, FH)];
static uint8_t full[2][TDC_LINK_FRAME_BYTES(FW, FH)];
static uint8_t reduced[2][TDC_LINK_FRAME_BYTES(FW, FH)];
static uint8_t subframe[2][TDC_LINK_SUBFRAME_BYTES(FW, FH)];
static int16_t motion[2][TDC_LINK_MOTION_COUNT(FW, FH)];
static int16_t sample_motion[2][TDC_LINK_SAMPLE_MOTION_COUNT(FW, FH)];
static uint8_t pattern[2][TDC_PATTERN_BYTES(FW, FH)];
static uint8_t fov_lp[2][TDC_LINK_FRAME_BYTES(FW, FH)];
static int16_t fov_mv[2][TDC_LINK_MOTION_COUNT(FW, FH)];
static uint8_t work[1 << 20];

/* Slots beyond the kinds: per-sample motion, the foveated buffers. */
#define SLOT_SAMPLE_MV (TDC_LINK_KIND_LAST + 1u)
#define SLOT_FOV_LP (TDC_LINK_KIND_LAST + 2u)
#define SLOT_FOV_MV (TDC_LINK_KIND_LAST + 3u)
#define SLOTS (TDC_LINK_KIND_LAST + 4u)

/* Every pipeline buffer, by slot (kind, or one of the SLOT_*) and eye, and a copy of what it held after its last accepted
 * packet. */
static uint8_t *slot_ptr(unsigned slot, unsigned e, size_t *n)
{
    switch (slot) {
    case TDC_LINK_KIND_FULL: *n = sizeof full[e]; return full[e];
    case TDC_LINK_KIND_REDUCED: *n = sizeof reduced[e]; return reduced[e];
    case TDC_LINK_KIND_SUBFRAME: *n = sizeof subframe[e]; return subframe[e];
    case TDC_LINK_KIND_MOTION: *n = sizeof motion[e]; return (uint8_t *)motion[e];
    case TDC_LINK_KIND_PATTERN: *n = sizeof pattern[e]; return pattern[e];
    case SLOT_SAMPLE_MV: *n = sizeof sample_motion[e]; return (uint8_t *)sample_motion[e];
    case SLOT_FOV_LP: *n = sizeof fov_lp[e]; return fov_lp[e];
    case SLOT_FOV_MV: *n = sizeof fov_mv[e]; return (uint8_t *)fov_mv[e];
    default: *n = 0; return NULL;
    }
}

static uint8_t snap[SLOTS][2][TDC_LINK_STAGING_BYTES(FW, FH)];

static void take_snap(unsigned slot, unsigned e)
{
    size_t n;
    uint8_t *p = slot_ptr(slot, e, &n);
    if (p) {
        memcpy(snap[slot][e], p, n);
    }
}

static int snap_differs(unsigned slot, unsigned e)
{
    size_t n;
    uint8_t *p = slot_ptr(slot, e, &n);
    return p && memcmp(snap[slot][e], p, n) != 0;
}

/* Recompute CRCs of everything that parses as a packet. */
static void repair_crcs(uint8_t *p, size_t n)
{
    size_t o = 0;
    while (o + TDC_LINK_HEADER_BYTES <= n) {
        tdc_link_header_t h;
        if (tdc_link_header_unpack(p + o, &h) == TDC_LINK_ERR_MAGIC) {
            o++;
            continue;
        }
        /* Every header byte is a field, so unpack + pack rewrites the same
         * bytes with a valid header CRC. */
        const uint32_t len = h.payload_len;
        if (len <= n - o - TDC_LINK_HEADER_BYTES) {
            h.payload_crc = tdc_crc32(p + o + TDC_LINK_HEADER_BYTES, len);
        }
        tdc_link_header_pack(p + o, &h);
        o += len <= n - o - TDC_LINK_HEADER_BYTES ? TDC_LINK_HEADER_BYTES + len : 1u;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size - 1 > sizeof work) {
        return 0;
    }
    const uint8_t mode = data[0];
    const size_t n = size - 1;
    memcpy(work, data + 1, n);
    if (mode & 0x80u) {
        repair_crcs(work, n);
    }

    static tdc_link_decoder_t dec;
    const int mono = (mode & 0x20u) != 0;
    tdc_link_config_t cfg = {FW, FH, (uint8_t)(mono ? 1 : 2)};
    tdc_link_buffers_t b = fuzz_frame_buffers(staging, sizeof staging, FW, (uint8_t *[2]){full[0], full[1]},
                                              (uint8_t *[2]){reduced[0], reduced[1]}, sizeof reduced[0]);
    for (int e = 0; e < 2; e++) {
        b.subframe[e] = mono ? NULL : subframe[e];
        b.motion[e] = motion[e];
        b.sample_motion[e] = mono ? NULL : sample_motion[e];
        b.pattern[e] = mono ? NULL : pattern[e];
        b.fov_lp[e] = fov_lp[e];
        b.fov_mv[e] = mono ? NULL : fov_mv[e];
    }
    b.fov_lp_bytes = sizeof fov_lp[0];
    b.fov_mv_count = sizeof fov_mv[0] / sizeof fov_mv[0][0];
    if (tdc_link_decoder_init(&dec, &cfg, &b) != TDC_OK) {
        abort();
    }
    for (unsigned k = 1; k < SLOTS; k++) {
        for (unsigned e = 0; e < 2; e++) {
            take_snap(k, e);
        }
    }

    uint32_t err_events[TDC_LINK_ERR_COUNT] = {0};
    uint32_t ok_events = 0;
    uint32_t rng = 0x9E3779B9u ^ (mode & 0x1Fu);
    size_t pos = 0;
    unsigned guard = 0;
    while (pos < n || dec.ev_count) {
        size_t chunk = n - pos;
        if ((mode & 0x1Fu) != 0) {
            rng ^= rng << 13;
            rng ^= rng >> 17;
            rng ^= rng << 5;
            const size_t c = 1u + rng % 97u;
            chunk = c < chunk ? c : chunk;
        }
        if ((mode & 0x40u) && (rng % 13u) == 0u) {
            tdc_link_decoder_resync(&dec); /* a cut-off transfer */
        }
        tdc_link_event_t ev;
        const size_t used = tdc_link_feed(&dec, work + pos, chunk, &ev);
        if (used > chunk) {
            abort();
        }
        pos += used;
        if (ev.type == TDC_LINK_EV_NONE) {
            if (used != chunk) {
                abort(); /* no event means the whole chunk was consumed */
            }
        }
        if (used > 0) {
            guard = 0;
        } else if (++guard > 64) {
            abort(); /* calls without progress: a livelock */
        }
        if (ev.type == TDC_LINK_EV_ERROR) {
            if (ev.error == 0 || ev.error >= TDC_LINK_ERR_COUNT) {
                abort();
            }
            err_events[ev.error]++;
        } else if (ev.type == TDC_LINK_EV_PACKET) {
            ok_events++;
            if (ev.kind < TDC_LINK_KIND_FIRST || ev.kind > TDC_LINK_KIND_LAST || ev.eye >= cfg.eyes) {
                abort();
            }
            if (ev.kind == TDC_LINK_KIND_FOVEATED) {
                /* the slot's grid: the panel, or a TRM stream's reduced grid */
                const int red = (ev.flags & TDC_LINK_PKT_FOV_REDUCED) != 0;
                uint32_t rw = 0, rh = 0;
                tdc_link_reduced_size(&dec, &rw, &rh);
                const tdc_fov_hdr_t *fh = tdc_link_fov(&dec, ev.eye);
                tdc_fov_geom_t g;
                if (!fh || (red && (!(tdc_link_stream(&dec)->flags & TDC_LINK_STREAM_REDUCED) || ev.width != rw ||
                                    ev.height != rh || (fh->flags & TDC_FOV_FLAG_MV))) ||
                    tdc_fov_geom(&g, red ? (uint16_t)rw : FW, red ? (uint16_t)rh : FH, &fh->p) != TDC_OK ||
                    g.l != fh->g.l || g.u0 != fh->g.u0 || g.r_disk2_q16 != fh->g.r_disk2_q16 ||
                    g.log2_r2max_q24 != fh->g.log2_r2max_q24) {
                    abort();
                }
                take_snap(red ? TDC_LINK_KIND_REDUCED : TDC_LINK_KIND_FULL, ev.eye); /* the disk pixels */
                take_snap(SLOT_FOV_LP, ev.eye);
                take_snap(SLOT_FOV_MV, ev.eye);
            } else {
                const unsigned slot =
                    (ev.kind == TDC_LINK_KIND_MOTION && (ev.flags & TDC_LINK_PKT_MV_PER_SAMPLE)) ? SLOT_SAMPLE_MV
                                                                                                 : ev.kind;
                take_snap(slot, ev.eye);
            }
        }
        /* Only the slot of an accepted packet may have changed.  Checked
         * once the events of this call are all delivered: a commit can
         * queue MISSING_REDUCED before its own PACKET event. */
        for (unsigned k = 1; dec.ev_count == 0 && k < SLOTS; k++) {
            for (unsigned e = 0; e < 2; e++) {
                if (snap_differs(k, e)) {
                    abort();
                }
            }
        }
    }
    const tdc_link_counters_t *c = tdc_link_counters(&dec);
    for (unsigned e = 1; e < TDC_LINK_ERR_COUNT; e++) {
        if (c->errors[e] != err_events[e]) {
            abort();
        }
    }
    if (c->packets_ok != ok_events || c->events_dropped != 0 || c->bytes_in != n) {
        abort();
    }
    uint32_t refused = 0;
    for (unsigned r = 1; r < TDC_FOV_HDR_COUNT; r++) {
        refused += c->fov_refused[r];
    }
    if (refused != c->errors[TDC_LINK_ERR_FOVEATION] || c->fov_refused[0] != 0) {
        abort();
    }
    return 0;
}
