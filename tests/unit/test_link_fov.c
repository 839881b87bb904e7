/*
 * test_link_fov.c - the FOVEATED packet kind in the link decoder (issue 14
 * item 2, docs/link-protocol.md §2.7): encoder -> decoder round trips over
 * alpha, gaze, disk fraction and motion vectors on mono and stereo panels,
 * the decoded buffers remapped by the stage equal the stage fed directly;
 * every refusal (packet header, payload CRC, each foveation-header reason,
 * truncated and padded payloads, buffers this build lacks, sequencing,
 * stream headers) gives its error event and counter, leaves every pipeline
 * buffer unchanged, and the next valid packet is accepted; chunking does
 * not change anything.  The log-rectilinear transform (tdc_fov_lr.h) through
 * the same kind: round trips (the whole buffer, u0 = 0) and its own
 * refusals (unknown transform, foveal scale, alpha, k on a kernel
 * log-polar header, u0), each with the last good frame kept.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tdc_cmocka.h"

#include <stdio.h>
#include <stdlib.h>

#include "tdc_fov.h"
#include "tdc_fov_link.h"
#include "tdc_link.h"
#include "tdc_link_encode.h"
#include "test_link_util.h"

#define W 64
#define H 48
#define DELTA_Q15 18187u /* 0.555, quantised up (tdc_fov_link.h) */

static lt_rig_t rig;
static uint8_t stream[1 << 18], pkt[1 << 16], payload[1 << 16];
static uint8_t samples[2 * W * H * 3];
static int16_t mvs[W * H * 2];

static tdc_fov_params_t params(int32_t gx_q8, int32_t gy_q8, uint16_t alpha_q8, uint16_t disk_q15)
{
    const tdc_fov_params_t p = {
        .gaze_x_q8 = gx_q8,
        .gaze_y_q8 = gy_q8,
        .alpha_q8 = alpha_q8,
        .disk_q15 = disk_q15,
        .lp_w = tdc_fov_lp_size(DELTA_Q15, W),
        .lp_h = tdc_fov_lp_size(DELTA_Q15, H),
    };
    return p;
}

static tdc_link_encoder_t encoder(uint32_t flags, uint8_t eyes)
{
    const tdc_link_stream_info_t in = lt_info(flags, W, H, eyes, 1, 1, 90);
    tdc_link_encoder_t enc;
    tdc_link_encoder_init(&enc, 7, &in);
    return enc;
}

/* Samples of a frame (lp then disk, payload order) and their vectors,
 * different for every (frame, eye). */
static size_t fill_samples(const tdc_fov_geom_t *g, uint32_t frame, uint32_t eye)
{
    return lt_fov_samples(g, 0x9E3779B9u * (frame * 2u + eye + 1u), samples, mvs);
}

static size_t put(size_t at, const uint8_t *p, size_t n)
{
    assert_true(at + n <= sizeof stream);
    memcpy(stream + at, p, n);
    return at + n;
}

static size_t put_stream_header(size_t at, const tdc_link_encoder_t *enc)
{
    const size_t n = tdc_link_encode_stream(enc, pkt, sizeof pkt);
    assert_true(n > 0);
    return put(at, pkt, n);
}

static size_t put_foveated(size_t at, const tdc_link_encoder_t *enc, uint32_t eye, uint32_t frame,
                           const tdc_fov_params_t *p, int with_mv, tdc_fov_geom_t *g)
{
    tdc_fov_geom_t gg;
    assert_int_equal(tdc_fov_geom(&gg, W, H, p), TDC_OK);
    fill_samples(&gg, frame, eye);
    const size_t n =
        tdc_link_encode_foveated(enc, pkt, sizeof pkt, eye, frame, p, DELTA_Q15, samples, with_mv ? mvs : NULL, g);
    assert_true(n > 0);
    return put(at, pkt, n);
}

/* The decoded buffers of eye e hold frame `frame` of p exactly; columns
 * below u0 and pixels outside the disk are as before (`before_*`). */
static void check_decoded(uint32_t e, uint32_t frame, const tdc_fov_params_t *p, int with_mv, const uint8_t *before_lp,
                          const uint8_t *before_full)
{
    tdc_fov_geom_t g;
    assert_int_equal(tdc_fov_geom(&g, W, H, p), TDC_OK);
    fill_samples(&g, frame, e);
    const tdc_fov_hdr_t *fh = tdc_link_fov(&rig.dec, e);
    assert_non_null(fh);
    assert_memory_equal(&fh->p, p, sizeof *p);
    assert_int_equal(fh->delta_q15, DELTA_Q15);
    assert_int_equal(fh->flags, with_mv ? TDC_FOV_FLAG_MV : 0);
    assert_int_equal(fh->g.u0, g.u0);
    const size_t cols = (size_t)(g.lp_w - g.u0);
    size_t k = 0;
    for (uint32_t j = 0; j < g.lp_h; j++) {
        const uint8_t *row = rig.fov_lp[e] + (size_t)j * g.lp_w * 3u;
        assert_memory_equal(row, before_lp + (size_t)j * g.lp_w * 3u, (size_t)g.u0 * 3u);
        assert_memory_equal(row + (size_t)g.u0 * 3u, samples + k * 3u, cols * 3u);
        if (with_mv) {
            assert_memory_equal(rig.fov_mv[e] + ((size_t)j * g.lp_w + g.u0) * 2u, mvs + k * 2u,
                                cols * 2u * sizeof(int16_t));
        }
        k += cols;
    }
    for (int32_t j = 0; j < H; j++) {
        for (int32_t i = 0; i < W; i++) {
            const size_t o = ((size_t)j * W + (size_t)i) * 3u;
            if (tdc_fov_in_disk(&g, i, j)) {
                assert_memory_equal(rig.full[e] + o, samples + k * 3u, 3);
                k++;
            } else {
                assert_memory_equal(rig.full[e] + o, before_full + o, 3);
            }
        }
    }
}

/* ------------------------------------------------------------------------
 * Round trips.
 * ---------------------------------------------------------------------- */
static void test_round_trip(void **state)
{
    (void)state;
    static const uint16_t alphas[] = {256, 1024, 2048};
    static const int32_t gazes[][2] = {{W * 128, H * 128}, {0, 0}, {W * 256, H * 256}, {-W * 200, H * 300}};
    static const uint16_t disks[] = {0, 4077, 32768};
    static uint8_t before_lp[TDC_LINK_FRAME_BYTES(W, H)], before_full[TDC_LINK_FRAME_BYTES(W, H)];
    for (uint8_t eyes = 1; eyes <= 2; eyes++) {
        const tdc_link_encoder_t enc = encoder(TDC_LINK_STREAM_FOVEATED, eyes);
        assert_int_equal(lt_init(&rig, W, H, eyes), TDC_OK);
        size_t n = put_stream_header(0, &enc);
        assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
        uint32_t frame = 0, packets = 1;
        for (size_t a = 0; a < 3; a++) {
            for (size_t gz = 0; gz < 4; gz++) {
                for (size_t d = 0; d < 3; d++) {
                    for (uint32_t e = 0; e < eyes; e++) {
                        const int with_mv = (int)((a + gz + d + e) & 1u);
                        const tdc_fov_params_t p = params(gazes[gz][0], gazes[gz][1], alphas[a], disks[d]);
                        memcpy(before_lp, rig.fov_lp[e], sizeof before_lp);
                        memcpy(before_full, rig.full[e], sizeof before_full);
                        n = put_foveated(0, &enc, e, frame, &p, with_mv, NULL);
                        const uint32_t ev0 = rig.nev;
                        assert_int_equal(lt_feed(&rig, stream, n, -97, frame * 2u + e), n);
                        assert_int_equal(rig.nev, ev0 + 1);
                        assert_int_equal(rig.ev[ev0].type, TDC_LINK_EV_PACKET);
                        assert_int_equal(rig.ev[ev0].kind, TDC_LINK_KIND_FOVEATED);
                        assert_int_equal(rig.ev[ev0].eye, e);
                        assert_int_equal(rig.ev[ev0].frame_index, frame);
                        check_decoded(e, frame, &p, with_mv, before_lp, before_full);
                        packets++;
                    }
                    frame++;
                }
            }
        }
        for (int k = 1; k < TDC_LINK_ERR_COUNT; k++) {
            assert_int_equal(tdc_link_error_count(&rig.dec, (tdc_link_err_t)k), 0);
        }
        assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, packets);
        assert_int_equal(tdc_link_counters(&rig.dec)->packets_by_kind[TDC_LINK_KIND_FOVEATED], packets - 1u);
    }
}

/* The decoded buffers through the stage = the stage fed the samples
 * placed by hand (the decoder adds nothing and loses nothing). */
static void test_stage_on_decoded_buffers(void **state)
{
    (void)state;
    static uint8_t lp[TDC_LINK_FRAME_BYTES(W, H)], disk[TDC_LINK_FRAME_BYTES(W, H)], out_a[TDC_LINK_FRAME_BYTES(W, H)];
    static int16_t mv[TDC_LINK_MOTION_COUNT(W, H)];
    static uint64_t arena_a[TDC_FOV_MEM_BYTES(W, H, 1) / 8u], arena_b[TDC_FOV_MEM_BYTES(W, H, 1) / 8u];
    const tdc_fov_config_t cfg = {W, H, 1};
    assert_true(tdc_fov_get_size(&cfg) <= sizeof arena_a);
    tdc_fov_t sa, sb;
    assert_int_equal(tdc_fov_init(&sa, &cfg, arena_a, sizeof arena_a), TDC_OK);
    assert_int_equal(tdc_fov_init(&sb, &cfg, arena_b, sizeof arena_b), TDC_OK);
    const tdc_link_encoder_t enc = encoder(TDC_LINK_STREAM_FOVEATED, 1);
    assert_int_equal(lt_init(&rig, W, H, 1), TDC_OK);
    size_t n = put_stream_header(0, &enc);
    assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
    memset(lp, 0, sizeof lp);
    memset(mv, 0, sizeof mv);
    memset(rig.fov_lp, 0, sizeof rig.fov_lp);
    memset(rig.fov_mv, 0, sizeof rig.fov_mv);
    for (uint32_t f = 0; f < 6; f++) {
        /* the gaze drifts, then a saccade at frame 4 */
        const tdc_fov_params_t p = params(W * 100 + (int32_t)f * 300 + (f >= 4 ? W * 90 : 0), H * 130, 1024, 4077);
        tdc_fov_geom_t g;
        n = put_foveated(0, &enc, 0, f, &p, 1, &g);
        assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
        assert_int_equal(rig.ev[rig.nev - 1].type, TDC_LINK_EV_PACKET);
        /* by hand: the samples where the payload order puts them */
        const size_t cols = (size_t)(g.lp_w - g.u0);
        size_t k = 0;
        for (uint32_t j = 0; j < g.lp_h; j++, k += cols) {
            memcpy(lp + ((size_t)j * g.lp_w + g.u0) * 3u, samples + k * 3u, cols * 3u);
            memcpy(mv + ((size_t)j * g.lp_w + g.u0) * 2u, mvs + k * 2u, cols * 2u * sizeof(int16_t));
        }
        memset(disk, 0, sizeof disk);
        for (int32_t j = 0; j < H; j++) {
            int32_t x0;
            const uint32_t span = tdc_fov_disk_span(&g, j, &x0);
            memcpy(disk + ((size_t)j * W + (size_t)x0) * 3u, samples + k * 3u, span * 3u);
            k += span;
        }
        const tdc_fov_hdr_t *fh = tdc_link_fov(&rig.dec, 0);
        assert_non_null(fh);
        assert_int_equal(tdc_fov_frame(&sa, &p, lp, (size_t)g.lp_w * 3u, mv, (size_t)g.lp_w * 2u, disk, W * 3u, 11111,
                                       out_a, W * 3u),
                         TDC_OK);
        assert_int_equal(tdc_fov_frame(&sb, &fh->p, rig.fov_lp[0], (size_t)fh->p.lp_w * 3u, rig.fov_mv[0],
                                       (size_t)fh->p.lp_w * 2u, rig.full[0], W * 3u, 11111, rig.full[0], W * 3u),
                         TDC_OK);
        assert_memory_equal(out_a, rig.full[0], sizeof out_a);
    }
}

/* ------------------------------------------------------------------------
 * Refusals: a valid stream, the bad packet, then a valid packet that must
 * be accepted.  Returns nothing; checks event, counter, buffers.
 * ---------------------------------------------------------------------- */
typedef enum { BAD_RAW, BAD_FOV_BYTE, BAD_LEN } bad_how_t;

/* One FOVEATED packet of p with its foveation header or length altered
 * (the packet CRC recomputed, so only the kind-specific checks can see it). */
static size_t raw_foveated(const tdc_link_encoder_t *enc, uint32_t eye, uint32_t frame, const tdc_fov_params_t *p,
                           int with_mv, int byte_at, uint8_t byte_val, int len_delta, uint8_t fmt, uint16_t width)
{
    const size_t n0 = tdc_link_encode_foveated(enc, pkt, sizeof pkt, eye, frame, p, DELTA_Q15, samples,
                                               with_mv ? mvs : NULL, NULL);
    assert_true(n0 > TDC_LINK_HEADER_BYTES);
    uint32_t len = (uint32_t)(n0 - TDC_LINK_HEADER_BYTES);
    memcpy(payload, pkt + TDC_LINK_HEADER_BYTES, len);
    memset(payload + len, 0, 16);
    if (byte_at >= 0) {
        payload[byte_at] = byte_val;
    }
    len = (uint32_t)((int32_t)len + len_delta);
    const tdc_link_header_t f = lt_fov_header((uint8_t)eye, fmt, 0, frame, width, H);
    return tdc_link_encode_raw(pkt, sizeof pkt, &f, payload, len);
}

static void expect_refused(const uint8_t *bad, size_t nbad, tdc_link_err_t err, tdc_fov_hdr_err_t reason, uint8_t eyes,
                           uint32_t stream_flags, int drop_mv_buffer, size_t lp_bytes)
{
    const tdc_link_encoder_t enc = encoder(stream_flags, eyes);
    assert_int_equal(lt_init(&rig, W, H, eyes), TDC_OK);
    static uint8_t badcopy[1 << 16];
    memcpy(badcopy, bad, nbad);
    const tdc_fov_params_t good = params(W * 90, H * 140, 1024, 4077);
    size_t n = put_stream_header(0, &enc);
    n = put_foveated(n, &enc, 0, 0, &good, 0, NULL); /* frame 0: a good picture */
    assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
    assert_int_equal(rig.nev, 2);
    assert_int_equal(rig.ev[1].type, TDC_LINK_EV_PACKET);
    const tdc_fov_hdr_t kept = *tdc_link_fov(&rig.dec, 0);
    const uint64_t h0 = lt_hash_all(&rig);
    const uint32_t ev0 = rig.nev;
    /* a build with smaller buffers (for the bad packet only) */
    const tdc_link_buffers_t full_build = rig.dec.buf;
    if (drop_mv_buffer) {
        rig.dec.buf.fov_mv[0] = rig.dec.buf.fov_mv[1] = NULL;
    }
    if (lp_bytes) {
        rig.dec.buf.fov_lp_bytes = lp_bytes;
    }
    assert_int_equal(lt_feed(&rig, badcopy, nbad, 0, 0), nbad);
    rig.dec.buf = full_build;
    lt_expect_fov_refused(&rig, ev0, err, (int)reason, h0, &kept);
    /* the next valid packet is accepted */
    n = put_foveated(0, &enc, 0, 5, &good, 0, NULL);
    const uint32_t ev1 = rig.nev;
    assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
    assert_int_equal(lt_count(&rig, ev1, TDC_LINK_EV_PACKET, 0), 1);
    assert_int_equal(rig.ev[rig.nev - 1].kind, TDC_LINK_KIND_FOVEATED);
    assert_int_equal(rig.ev[rig.nev - 1].frame_index, 5);
}

#define FOV TDC_LINK_STREAM_FOVEATED
/* The refusal tests' packet: gaze at the centre, alpha 4, disk 4077/32768,
 * its geometry in g and its samples filled. */
static tdc_fov_params_t refusal_setup(tdc_fov_geom_t *g)
{
    const tdc_fov_params_t p = params(W * 128, H * 128, 1024, 4077);
    assert_int_equal(tdc_fov_geom(g, W, H, &p), TDC_OK);
    fill_samples(g, 1, 0);
    return p;
}

static void test_refusals_packet_header(void **state)
{
    (void)state;
    const tdc_link_encoder_t enc = encoder(FOV, 1);
    tdc_fov_geom_t g;
    const tdc_fov_params_t p = refusal_setup(&g);
    size_t n;
    /* a pixel format other than RGB888 */
    n = raw_foveated(&enc, 0, 1, &p, 0, -1, 0, 0, TDC_PIXFMT_RGB565, W);
    expect_refused(pkt, n, TDC_LINK_ERR_FORMAT, TDC_FOV_HDR_OK, 1, FOV, 0, 0);
    n = raw_foveated(&enc, 0, 1, &p, 0, -1, 0, 0, TDC_PIXFMT_NONE, W);
    expect_refused(pkt, n, TDC_LINK_ERR_FORMAT, TDC_FOV_HDR_OK, 1, FOV, 0, 0);
    /* dimensions other than the panel's */
    n = raw_foveated(&enc, 0, 1, &p, 0, -1, 0, 0, TDC_PIXFMT_RGB888, W - 1);
    expect_refused(pkt, n, TDC_LINK_ERR_DIMENSIONS, TDC_FOV_HDR_OK, 1, FOV, 0, 0);
    /* shorter than the foveation header */
    {
        const tdc_link_header_t f = lt_fov_header(0, TDC_PIXFMT_RGB888, 0, 1, W, H);
        memset(payload, 0, 31);
        n = tdc_link_encode_raw(pkt, sizeof pkt, &f, payload, 31);
        expect_refused(pkt, n, TDC_LINK_ERR_LENGTH, TDC_FOV_HDR_OK, 1, FOV, 0, 0);
    }
    /* eye 1 on a mono panel */
    n = raw_foveated(&enc, 1, 1, &p, 0, -1, 0, 0, TDC_PIXFMT_RGB888, W);
    expect_refused(pkt, n, TDC_LINK_ERR_EYE, TDC_FOV_HDR_OK, 1, FOV, 0, 0);
    /* a stream that did not announce foveated packets (stage elision) */
    n = raw_foveated(&enc, 0, 1, &p, 0, -1, 0, 0, TDC_PIXFMT_RGB888, W);
    {
        /* the refusal happens before any foveated packet is accepted: own rig */
        const tdc_link_encoder_t plain = encoder(0, 1);
        assert_int_equal(lt_init(&rig, W, H, 1), TDC_OK);
        memcpy(payload, pkt, n);
        size_t m = put_stream_header(0, &plain);
        m = put(m, payload, n);
        const uint64_t h0 = lt_hash_all(&rig);
        assert_int_equal(lt_feed(&rig, stream, m, 0, 0), m);
        assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_UNEXPECTED), 1);
        assert_true(lt_hash_all(&rig) == h0);
        assert_null(tdc_link_fov(&rig.dec, 0));
    }
    /* a corrupted payload byte: the packet CRC */
    n = tdc_link_encode_foveated(&enc, pkt, sizeof pkt, 0, 1, &p, DELTA_Q15, samples, NULL, NULL);
    pkt[TDC_LINK_HEADER_BYTES + TDC_FOV_HDR_BYTES + 5] ^= 0x10;
    expect_refused(pkt, n, TDC_LINK_ERR_CRC, TDC_FOV_HDR_OK, 1, FOV, 0, 0);
    /* ... and in the foveation header */
    n = tdc_link_encode_foveated(&enc, pkt, sizeof pkt, 0, 1, &p, DELTA_Q15, samples, NULL, NULL);
    pkt[TDC_LINK_HEADER_BYTES + 9] ^= 0x01;
    expect_refused(pkt, n, TDC_LINK_ERR_CRC, TDC_FOV_HDR_OK, 1, FOV, 0, 0);
    /* truncated on the wire (the next packet follows early): the CRC fails,
     * the rescan finds the next packet */
    {
        assert_int_equal(lt_init(&rig, W, H, 1), TDC_OK);
        size_t m = put_stream_header(0, &enc);
        m = put_foveated(m, &enc, 0, 0, &p, 0, NULL);
        assert_int_equal(lt_feed(&rig, stream, m, 0, 0), m);
        const uint64_t h0 = lt_hash_all(&rig);
        n = tdc_link_encode_foveated(&enc, pkt, sizeof pkt, 0, 1, &p, DELTA_Q15, samples, NULL, NULL);
        m = put(0, pkt, n - 40);
        m = put_foveated(m, &enc, 0, 2, &p, 0, NULL);
        const size_t good_at = n - 40;
        const uint32_t ev0 = rig.nev;
        assert_int_equal(lt_feed(&rig, stream, good_at, 0, 0), good_at); /* the cut packet alone: nothing yet */
        assert_true(lt_hash_all(&rig) == h0);
        assert_int_equal(lt_feed(&rig, stream + good_at, m - good_at, 0, 0), m - good_at);
        assert_int_equal(lt_count(&rig, ev0, TDC_LINK_EV_ERROR, TDC_LINK_ERR_CRC), 1);
        assert_int_equal(lt_count(&rig, ev0, TDC_LINK_EV_PACKET, 0), 1);
        assert_int_equal(rig.ev[rig.nev - 1].frame_index, 2);
    }
}

static void test_refusals_foveation_header(void **state)
{
    (void)state;
    const tdc_link_encoder_t enc = encoder(FOV, 1);
    tdc_fov_geom_t g;
    const tdc_fov_params_t p = refusal_setup(&g);
    const uint8_t F = TDC_PIXFMT_RGB888;
    size_t n;
    const tdc_link_err_t E = TDC_LINK_ERR_FOVEATION;
    /* alpha below 1 and above 8 (Q8 at bytes 8..9) */
    n = raw_foveated(&enc, 0, 1, &p, 0, 9, 0, 0, F, W); /* 1024 -> 0 */
    expect_refused(pkt, n, E, TDC_FOV_HDR_ALPHA, 1, FOV, 0, 0);
    n = raw_foveated(&enc, 0, 1, &p, 0, 9, 9, 0, F, W); /* 2304 = 9.0 */
    expect_refused(pkt, n, E, TDC_FOV_HDR_ALPHA, 1, FOV, 0, 0);
    /* delta 0 and above 1 (Q15 at 10..11) */
    {
        const int at[] = {10, 11};
        for (int k = 0; k < 2; k++) {
            const size_t n0 =
                tdc_link_encode_foveated(&enc, pkt, sizeof pkt, 0, 1, &p, DELTA_Q15, samples, NULL, NULL);
            memcpy(payload, pkt + TDC_LINK_HEADER_BYTES, n0 - TDC_LINK_HEADER_BYTES);
            payload[at[0]] = 0;
            payload[at[1]] = k ? 0x81 : 0; /* 0 or 33024 */
            tdc_link_header_t f;
            assert_int_equal(tdc_link_header_unpack(pkt, &f), TDC_LINK_OK);
            n = tdc_link_encode_raw(pkt, sizeof pkt, &f, payload, (uint32_t)(n0 - TDC_LINK_HEADER_BYTES));
            expect_refused(pkt, n, E, TDC_FOV_HDR_DELTA, 1, FOV, 0, 0);
        }
    }
    /* one header or payload byte changed (at, to v; or the payload len bytes
     * short or long, CRC valid): refused with the reason named */
    const struct {
        int at;
        uint8_t v;
        int len;
        tdc_fov_hdr_err_t why;
    } bad[] = {
        /* disk fraction above 1 (Q15 at 12..13: 4077 = 0x0FED -> 0x80ED) */
        {13, 0x80, 0, TDC_FOV_HDR_DISK},
        /* gaze far outside the screen (x, Q8 int32 at 0..3: top byte) */
        {3, 0x40, 0, TDC_FOV_HDR_GAZE},
        {3, 0xC0, 0, TDC_FOV_HDR_GAZE},
        /* buffer width disagreeing with delta and the panel (14..15) */
        {14, (uint8_t)(p.lp_w + 1u), 0, TDC_FOV_HDR_BUFFER},
        /* u0 (18..19) and the disk count (20..23) disagreeing with the parameters */
        {18, (uint8_t)(g.u0 - 1u), 0, TDC_FOV_HDR_GEOMETRY},
        {22, 1, 0, TDC_FOV_HDR_GEOMETRY},
        /* an unknown flag, a reserved byte */
        {24, 2, 0, TDC_FOV_HDR_RESERVED},
        {31, 1, 0, TDC_FOV_HDR_RESERVED},
        /* a payload one byte short or long of what the header states (CRC valid) */
        {-1, 0, -1, TDC_FOV_HDR_PAYLOAD},
        {-1, 0, 1, TDC_FOV_HDR_PAYLOAD},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        n = raw_foveated(&enc, 0, 1, &p, 0, bad[i].at, bad[i].v, bad[i].len, F, W);
        expect_refused(pkt, n, E, bad[i].why, 1, FOV, 0, 0);
    }
    /* the MV flag set but no vectors sent: the payload is short */
    n = raw_foveated(&enc, 0, 1, &p, 0, 24, TDC_FOV_FLAG_MV, 0, F, W);
    expect_refused(pkt, n, E, TDC_FOV_HDR_PAYLOAD, 1, FOV, 0, 0);
}

static void test_refusals_buffers_and_sequence(void **state)
{
    (void)state;
    const tdc_link_encoder_t enc = encoder(FOV, 2);
    tdc_fov_geom_t g;
    const tdc_fov_params_t p = refusal_setup(&g);
    size_t n;
    /* vectors for a build without the TAA buffer */
    n = tdc_link_encode_foveated(&enc, pkt, sizeof pkt, 0, 1, &p, DELTA_Q15, samples, mvs, NULL);
    expect_refused(pkt, n, TDC_LINK_ERR_UNEXPECTED, TDC_FOV_HDR_OK, 2, FOV, 1, 0);
    /* a log-polar buffer larger than this build holds */
    n = tdc_link_encode_foveated(&enc, pkt, sizeof pkt, 0, 1, &p, DELTA_Q15, samples, NULL, NULL);
    expect_refused(pkt, n, TDC_LINK_ERR_LENGTH, TDC_FOV_HDR_OK, 2, FOV, 0, (size_t)p.lp_w * p.lp_h * 3u - 1u);
    /* the same frame and eye twice, and a FULL frame after a foveated one */
    n = tdc_link_encode_foveated(&enc, pkt, sizeof pkt, 0, 0, &p, DELTA_Q15, samples, NULL, NULL);
    expect_refused(pkt, n, TDC_LINK_ERR_DUPLICATE, TDC_FOV_HDR_OK, 2, FOV, 0, 0);
    static uint8_t rgb[W * H * 3];
    memset(rgb, 9, sizeof rgb);
    n = tdc_link_encode_frame(&enc, pkt, sizeof pkt, TDC_LINK_KIND_FULL, 0, 0, TDC_PIXFMT_RGB888, rgb, W, H, W * 3u);
    expect_refused(pkt, n, TDC_LINK_ERR_DUPLICATE, TDC_FOV_HDR_OK, 2, FOV, 0, 0);
    /* ... but the other eye of the same frame is fine, and so is FULL later */
    {
        assert_int_equal(lt_init(&rig, W, H, 2), TDC_OK);
        size_t m = put_stream_header(0, &enc);
        m = put_foveated(m, &enc, 0, 3, &p, 0, NULL);
        m = put_foveated(m, &enc, 1, 3, &p, 0, NULL);
        m = put(m, pkt, tdc_link_encode_frame(&enc, pkt, sizeof pkt, TDC_LINK_KIND_FULL, 0, 4, TDC_PIXFMT_RGB888, rgb,
                                              W, H, W * 3u));
        assert_int_equal(lt_feed(&rig, stream, m, 0, 0), m);
        assert_int_equal(lt_count(&rig, 0, TDC_LINK_EV_PACKET, 0), 4);
        assert_memory_equal(rig.full[0], rgb, sizeof rgb);
    }
    /* an older frame */
    {
        assert_int_equal(lt_init(&rig, W, H, 2), TDC_OK);
        size_t m = put_stream_header(0, &enc);
        m = put_foveated(m, &enc, 0, 6, &p, 0, NULL);
        assert_int_equal(lt_feed(&rig, stream, m, 0, 0), m);
        const uint64_t h1 = lt_hash_all(&rig);
        m = put_foveated(0, &enc, 1, 5, &p, 0, NULL);
        assert_int_equal(lt_feed(&rig, stream, m, 0, 0), m);
        assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_ORDER), 1);
        assert_true(lt_hash_all(&rig) == h1);
        assert_null(tdc_link_fov(&rig.dec, 1));
    }
}

static void test_stream_headers(void **state)
{
    (void)state;
    /* foveated with subframes: not defined, refused (with reduced frames:
     * foveated TRM, tests/unit/test_link_fov_trm.c) */
    const uint32_t bad[] = {FOV | TDC_LINK_STREAM_SUBFRAMES, FOV | TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_SUBFRAMES};
    for (int k = 0; k < 2; k++) {
        tdc_link_encoder_t enc = encoder(bad[k], 1);
        if (bad[k] & TDC_LINK_STREAM_REDUCED) {
            enc.info.r_num = 1;
            enc.info.r_den = 2;
        }
        assert_int_equal(lt_init(&rig, W, H, 1), TDC_OK);
        const size_t n = put_stream_header(0, &enc);
        assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
        assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_STREAM_HEADER), 1);
        assert_null(tdc_link_stream(&rig.dec));
    }
    /* a build without the foveation buffers refuses a foveated stream */
    {
        const tdc_link_encoder_t enc = encoder(FOV, 2);
        assert_int_equal(lt_init(&rig, W, H, 2), TDC_OK);
        rig.dec.buf.fov_lp[1] = NULL;
        const size_t n = put_stream_header(0, &enc);
        assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
        assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_STREAM_HEADER), 1);
    }
    /* a new stream forgets the foveation headers */
    {
        const tdc_link_encoder_t enc = encoder(FOV, 1);
        const tdc_fov_params_t p = params(W * 128, H * 128, 1024, 4077);
        assert_int_equal(lt_init(&rig, W, H, 1), TDC_OK);
        size_t n = put_stream_header(0, &enc);
        n = put_foveated(n, &enc, 0, 2, &p, 0, NULL);
        assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
        assert_non_null(tdc_link_fov(&rig.dec, 0));
        assert_null(tdc_link_fov(&rig.dec, 1));
        tdc_link_encoder_t enc2 = encoder(FOV | TDC_LINK_STREAM_MOTION, 1);
        n = put_stream_header(0, &enc2);
        assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
        assert_null(tdc_link_fov(&rig.dec, 0));
    }
}

/* The same stream fed whole, byte by byte and in random chunks: the same
 * events and buffers. */
static void test_chunking(void **state)
{
    (void)state;
    const tdc_link_encoder_t enc = encoder(FOV, 2);
    size_t n = put_stream_header(0, &enc);
    for (uint32_t f = 0; f < 5; f++) {
        for (uint32_t e = 0; e < 2; e++) {
            const tdc_fov_params_t p = params(W * (40 + 40 * (int32_t)f), H * (200 - 30 * (int32_t)e), 768, 6000);
            n = put_foveated(n, &enc, e, f, &p, (int)((f + e) & 1u), NULL);
        }
    }
    uint64_t ref = 0;
    const int chunks[] = {0, 1, 7, -300, -5};
    for (int c = 0; c < 5; c++) {
        assert_int_equal(lt_init(&rig, W, H, 2), TDC_OK);
        assert_int_equal(lt_feed(&rig, stream, n, chunks[c], 99u + (uint32_t)c), n);
        assert_int_equal(rig.nev, 11);
        assert_int_equal(lt_count(&rig, 0, TDC_LINK_EV_PACKET, 0), 11);
        const uint64_t h = lt_hash_all(&rig);
        if (c == 0) {
            ref = h;
        }
        assert_true(h == ref);
    }
}

static tdc_fov_params_t lr_params(int32_t gx_q8, int32_t gy_q8, uint16_t disk_q15)
{
    tdc_fov_params_t p = params(gx_q8, gy_q8, 256, disk_q15);
    p.transform = TDC_FOV_LOG_RECT;
    p.lr_k_q4[0] = 0x0105; /* 16.3 px */
    p.lr_k_q4[1] = 0x00C8; /* 12.5 px */
    return p;
}

static void test_log_rect(void **state)
{
    (void)state;
    static uint8_t before_lp[TDC_LINK_FRAME_BYTES(W, H)], before_full[TDC_LINK_FRAME_BYTES(W, H)];
    const tdc_link_encoder_t enc = encoder(FOV, 1);
    assert_int_equal(lt_init(&rig, W, H, 1), TDC_OK);
    size_t n = put_stream_header(0, &enc);
    assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
    static const int32_t gazes[][2] = {{W * 128, H * 128}, {0, 0}, {-W * 200, H * 300}};
    for (uint32_t f = 0; f < 6; f++) {
        const tdc_fov_params_t p = lr_params(gazes[f % 3][0], gazes[f % 3][1], f < 3 ? 4077 : (f == 4 ? 32768 : 0));
        memcpy(before_lp, rig.fov_lp[0], sizeof before_lp);
        memcpy(before_full, rig.full[0], sizeof before_full);
        n = put_foveated(0, &enc, 0, f, &p, (int)(f & 1u), NULL);
        const uint32_t ev0 = rig.nev;
        assert_int_equal(lt_feed(&rig, stream, n, -97, f), n);
        assert_int_equal(rig.nev, ev0 + 1);
        if (rig.ev[ev0].type != TDC_LINK_EV_PACKET)
            fail_msg("frame %u: event %d error %d", f, rig.ev[ev0].type, rig.ev[ev0].error);
        check_decoded(0, f, &p, (int)(f & 1u), before_lp, before_full);
        assert_int_equal(tdc_link_fov(&rig.dec, 0)->g.u0, 0); /* the whole buffer */
    }
    /* the whole buffer with vectors (2.2 B/px at delta 0.555) and a whole-screen disk (3 B/px) exceed a
     * 4 B/px staging buffer: refused by length like any packet larger than the build's buffers */
    {
        const tdc_fov_params_t big = lr_params(W * 128, H * 128, 32768);
        n = put_foveated(0, &enc, 0, 6, &big, 1, NULL);
        const uint32_t ev0 = rig.nev;
        assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
        assert_int_equal(lt_count(&rig, ev0, TDC_LINK_EV_ERROR, TDC_LINK_ERR_LENGTH), 1);
    }
    const tdc_fov_params_t p = lr_params(W * 90, H * 140, 4077);
    tdc_fov_geom_t g;
    assert_int_equal(tdc_fov_geom(&g, W, H, &p), TDC_OK);
    fill_samples(&g, 1, 0);
    const uint8_t F = TDC_PIXFMT_RGB888;
    const tdc_link_err_t E = TDC_LINK_ERR_FOVEATION;
    n = raw_foveated(&enc, 0, 1, &p, 0, 25, 2, 0, F, W); /* transform 2: unknown */
    expect_refused(pkt, n, E, TDC_FOV_HDR_TRANSFORM, 1, FOV, 0, 0);
    n = raw_foveated(&enc, 0, 1, &p, 0, 25, 0xFF, 0, F, W);
    expect_refused(pkt, n, E, TDC_FOV_HDR_TRANSFORM, 1, FOV, 0, 0);
    n = raw_foveated(&enc, 0, 1, &p, 0, 27, 0, 0, F, W); /* k_x 0x0105 -> 5: below 1 px */
    expect_refused(pkt, n, E, TDC_FOV_HDR_SCALE, 1, FOV, 0, 0);
    n = raw_foveated(&enc, 0, 1, &p, 0, 28, 0, 0, F, W); /* k_y 0 */
    expect_refused(pkt, n, E, TDC_FOV_HDR_SCALE, 1, FOV, 0, 0);
    n = raw_foveated(&enc, 0, 1, &p, 0, 9, 4, 0, F, W); /* alpha 4: log-rectilinear has none */
    expect_refused(pkt, n, E, TDC_FOV_HDR_ALPHA, 1, FOV, 0, 0);
    n = raw_foveated(&enc, 0, 1, &p, 0, 18, 1, 0, F, W); /* u0 1: the whole buffer is carried */
    expect_refused(pkt, n, E, TDC_FOV_HDR_GEOMETRY, 1, FOV, 0, 0);
    n = raw_foveated(&enc, 0, 1, &p, 0, 30, 1, 0, F, W); /* reserved */
    expect_refused(pkt, n, E, TDC_FOV_HDR_RESERVED, 1, FOV, 0, 0);
    const tdc_fov_params_t q = params(W * 128, H * 128, 1024, 4077); /* a kernel log-polar header with a k */
    assert_int_equal(tdc_fov_geom(&g, W, H, &q), TDC_OK);
    fill_samples(&g, 1, 0);
    n = raw_foveated(&enc, 0, 1, &q, 0, 26, 1, 0, F, W);
    expect_refused(pkt, n, E, TDC_FOV_HDR_RESERVED, 1, FOV, 0, 0);
    n = raw_foveated(&enc, 0, 1, &q, 0, 25, 1, 0, F, W); /* transform 1 without k */
    expect_refused(pkt, n, E, TDC_FOV_HDR_ALPHA, 1, FOV, 0, 0);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_round_trip),
    cmocka_unit_test(test_stage_on_decoded_buffers),
    cmocka_unit_test(test_refusals_packet_header),
    cmocka_unit_test(test_refusals_foveation_header),
    cmocka_unit_test(test_refusals_buffers_and_sequence),
    cmocka_unit_test(test_stream_headers),
    cmocka_unit_test(test_chunking),
    cmocka_unit_test(test_log_rect),
)
