/*
 * test_link_fov_trm.c - foveated TRM streams (issue 14 item 5,
 * docs/link-protocol.md §2.2): FOVEATED packets in both slots of a TRM
 * stream.  Round trips (mono and stereo, ratios 1/2 and 3/4, both slots,
 * gaze centre / corner / outside, alpha 1/4/8, disks 0 / 12.4 % / 1, mixed
 * with plain FULL and REDUCED packets, random chunking): the samples land
 * in fov_lp, the disk in the slot's picture (full or reduced, at the
 * reduced grid's stride), nothing else changes, no reduced frame counts as
 * missing.  The decoded buffers through tdc_fov_trm equal tdc_fov_frame fed
 * by hand, for both slots.  Every refusal (the slot flag against TRM's
 * schedule, sizes against the slot, the foveation header against the
 * reduced grid, vectors, duplicates, a stream without REDUCED, stream
 * headers) gives its event and counter, writes nothing, and the next packet
 * is accepted.
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
#include "tdc_fov_trm.h"
#include "tdc_link.h"
#include "tdc_link_encode.h"
#include "test_link_util.h"

#define W 64
#define H 48
#define DELTA_Q15 18187u /* 0.555, quantised up (tdc_fov_link.h) */
#define FOV TDC_LINK_STREAM_FOVEATED
#define TRM TDC_LINK_STREAM_REDUCED

static lt_rig_t rig;
static uint8_t stream[1 << 18], pkt[1 << 16], payload[1 << 16];
static uint8_t samples[2 * W * H * 3]; /* lp samples + a whole-screen disk */
static int16_t mvs[W * H * 2];

typedef struct {
    uint16_t w, h; /* the slot's grid */
    int red;       /* the reduced slot */
} slot_t;

static tdc_link_encoder_t encoder(uint32_t flags, uint8_t eyes, uint16_t r_num, uint16_t r_den)
{
    const tdc_link_stream_info_t in = lt_info(flags, W, H, eyes, r_num, r_den, 90);
    tdc_link_encoder_t enc;
    tdc_link_encoder_init(&enc, 7, &in);
    return enc;
}

static slot_t slot_of(const tdc_link_encoder_t *enc, int red)
{
    slot_t s = {W, H, red};
    if (red) {
        s.w = (uint16_t)TDC_REDUCED_DIM(W, enc->info.r_num, enc->info.r_den);
        s.h = (uint16_t)TDC_REDUCED_DIM(H, enc->info.r_num, enc->info.r_den);
    }
    return s;
}

/* Parameters on the slot's grid; the gaze as fractions of it (Q8 of 1/256). */
static tdc_fov_params_t params(const slot_t *s, int32_t fx, int32_t fy, uint16_t alpha_q8, uint16_t disk_q15)
{
    tdc_fov_params_t p;
    memset(&p, 0, sizeof p);
    p.gaze_x_q8 = fx * s->w;
    p.gaze_y_q8 = fy * s->h;
    p.alpha_q8 = alpha_q8;
    p.disk_q15 = disk_q15;
    p.lp_w = tdc_fov_lp_size(DELTA_Q15, s->w);
    p.lp_h = tdc_fov_lp_size(DELTA_Q15, s->h);
    return p;
}

static size_t fill_samples(const tdc_fov_geom_t *g, uint32_t frame, uint32_t eye)
{
    return lt_fov_samples(g, 0x85EBCA6Bu * (frame * 2u + eye + 1u), samples, mvs);
}

static size_t put(size_t at, const uint8_t *p, size_t n)
{
    assert_true(n > 0 && at + n <= sizeof stream);
    memcpy(stream + at, p, n);
    return at + n;
}

static size_t put_stream_header(size_t at, const tdc_link_encoder_t *enc)
{
    return put(at, pkt, tdc_link_encode_stream(enc, pkt, sizeof pkt));
}

/* A foveated picture for a slot (the encoder's slot call). */
static size_t put_fov(size_t at, const tdc_link_encoder_t *enc, const slot_t *s, uint32_t eye, uint32_t frame,
                      const tdc_fov_params_t *p, int with_mv)
{
    tdc_fov_geom_t g;
    assert_int_equal(tdc_fov_geom(&g, s->w, s->h, p), TDC_OK);
    fill_samples(&g, frame, eye);
    const size_t n =
        tdc_link_encode_foveated_slot(enc, pkt, sizeof pkt, s->red ? TDC_LINK_KIND_REDUCED : TDC_LINK_KIND_FULL, eye,
                                      frame, p, DELTA_Q15, samples, with_mv ? mvs : NULL, NULL);
    return put(at, pkt, n);
}

/* A plain FULL or REDUCED picture (every byte v). */
static size_t put_plain(size_t at, const tdc_link_encoder_t *enc, const slot_t *s, uint32_t eye, uint32_t frame,
                        uint8_t v)
{
    static uint8_t rgb[W * H * 3];
    memset(rgb, v, sizeof rgb);
    const size_t n =
        tdc_link_encode_frame(enc, pkt, sizeof pkt, s->red ? TDC_LINK_KIND_REDUCED : TDC_LINK_KIND_FULL, eye, frame,
                              TDC_PIXFMT_RGB888, rgb, s->w, s->h, (uint32_t)s->w * 3u);
    return put(at, pkt, n);
}

/* Eye e's buffers hold frame `frame` of p in slot s exactly: fov_lp's
 * columns [u0, lp_w) and the disk at the slot picture's stride; every other
 * byte of every pipeline buffer is as in `before` (a copy of the rig). */
static void check_decoded(const lt_rig_t *before, const slot_t *s, uint32_t e, uint32_t frame,
                          const tdc_fov_params_t *p)
{
    tdc_fov_geom_t g;
    assert_int_equal(tdc_fov_geom(&g, s->w, s->h, p), TDC_OK);
    fill_samples(&g, frame, e);
    const tdc_fov_hdr_t *fh = tdc_link_fov(&rig.dec, e);
    assert_non_null(fh);
    assert_memory_equal(&fh->p, p, sizeof *p);
    assert_int_equal(fh->g.width, s->w);
    assert_int_equal(fh->g.height, s->h);
    assert_int_equal(fh->flags, 0);
    /* expected buffers: before, with the packet's bytes placed by hand */
    static lt_rig_t want;
    memcpy(want.full, before->full, sizeof want.full);
    memcpy(want.reduced, before->reduced, sizeof want.reduced);
    memcpy(want.fov_lp, before->fov_lp, sizeof want.fov_lp);
    const size_t cols = (size_t)(g.lp_w - g.u0);
    size_t k = 0;
    for (uint32_t j = 0; j < g.lp_h; j++, k += cols) {
        memcpy(want.fov_lp[e] + ((size_t)j * g.lp_w + g.u0) * 3u, samples + k * 3u, cols * 3u);
    }
    uint8_t *pic = s->red ? want.reduced[e] : want.full[e];
    for (int32_t j = 0; j < s->h; j++) {
        int32_t x0;
        const uint32_t span = tdc_fov_disk_span(&g, j, &x0);
        memcpy(pic + ((size_t)j * s->w + (size_t)x0) * 3u, samples + k * 3u, span * 3u);
        k += span;
    }
    assert_memory_equal(rig.full, want.full, sizeof want.full);
    assert_memory_equal(rig.reduced, want.reduced, sizeof want.reduced);
    assert_memory_equal(rig.fov_lp, want.fov_lp, sizeof want.fov_lp);
    assert_memory_equal(rig.fov_mv, before->fov_mv, sizeof rig.fov_mv);
    assert_memory_equal(rig.motion, before->motion, sizeof rig.motion);
}

/* ------------------------------------------------------------------------
 * Round trips.
 * ---------------------------------------------------------------------- */
static void test_round_trip(void **state)
{
    (void)state;
    static const uint16_t alphas[] = {256, 1024, 2048};
    static const int32_t gazes[][2] = {{128, 128}, {0, 0}, {256, 256}, {-200, 300}, {77, 181}};
    static const uint16_t disks[] = {0, 4077, 32768};
    static const uint16_t ratios[][2] = {{1, 2}, {3, 4}};
    static lt_rig_t before;
    for (int r = 0; r < 2; r++) {
        for (uint8_t eyes = 1; eyes <= 2; eyes++) {
            const tdc_link_encoder_t enc = encoder(FOV | TRM, eyes, ratios[r][0], ratios[r][1]);
            assert_int_equal(lt_init(&rig, W, H, eyes), TDC_OK);
            size_t n = put_stream_header(0, &enc);
            assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
            uint32_t packets = 1, fov_packets = 0;
            for (uint32_t frame = 0; frame < 45; frame++) {
                for (uint32_t e = 0; e < eyes; e++) {
                    const int red = tdc_link_trm_kind(frame, e) == TDC_LINK_KIND_REDUCED;
                    const slot_t s = slot_of(&enc, red);
                    const uint32_t k = frame * 2u + e;
                    memcpy(&before, &rig, offsetof(lt_rig_t, dec));
                    const uint32_t ev0 = rig.nev;
                    if (k % 7u == 3u) { /* a plain picture now and then: both kinds share the slots */
                        n = put_plain(0, &enc, &s, e, frame, (uint8_t)(k * 13u));
                        assert_int_equal(lt_feed(&rig, stream, n, -61, k), n);
                        assert_int_equal(rig.ev[ev0].type, TDC_LINK_EV_PACKET);
                        assert_int_equal(rig.ev[ev0].kind, red ? TDC_LINK_KIND_REDUCED : TDC_LINK_KIND_FULL);
                    } else {
                        const tdc_fov_params_t p =
                            params(&s, gazes[k % 5u][0], gazes[k % 5u][1], alphas[(k / 5u) % 3u], disks[(k / 3u) % 3u]);
                        n = put_fov(0, &enc, &s, e, frame, &p, 0);
                        assert_int_equal(lt_feed(&rig, stream, n, -97, k), n);
                        assert_int_equal(rig.nev, ev0 + 1);
                        assert_int_equal(rig.ev[ev0].type, TDC_LINK_EV_PACKET);
                        assert_int_equal(rig.ev[ev0].kind, TDC_LINK_KIND_FOVEATED);
                        assert_int_equal(rig.ev[ev0].flags, red ? TDC_LINK_PKT_FOV_REDUCED : 0u);
                        assert_int_equal(rig.ev[ev0].width, s.w);
                        assert_int_equal(rig.ev[ev0].eye, e);
                        check_decoded(&before, &s, e, frame, &p);
                        fov_packets++;
                    }
                    packets++;
                }
            }
            /* every slot was filled: nothing missing, nothing refused */
            for (int k = 1; k < TDC_LINK_ERR_COUNT; k++) {
                assert_int_equal(tdc_link_error_count(&rig.dec, (tdc_link_err_t)k), 0);
            }
            assert_int_equal(tdc_link_counters(&rig.dec)->missing_reduced_frames, 0);
            assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, packets);
            assert_int_equal(tdc_link_counters(&rig.dec)->packets_by_kind[TDC_LINK_KIND_FOVEATED], fov_packets);
        }
    }
}

/* A skipped foveated reduced frame counts as missing like a REDUCED one. */
static void test_missing_reduced(void **state)
{
    (void)state;
    const tdc_link_encoder_t enc = encoder(FOV | TRM, 1, 1, 2);
    const slot_t sf = slot_of(&enc, 0), sr = slot_of(&enc, 1);
    const tdc_fov_params_t pf = params(&sf, 128, 128, 1024, 4077), pr = params(&sr, 128, 128, 1024, 4077);
    assert_int_equal(lt_init(&rig, W, H, 1), TDC_OK);
    size_t n = put_stream_header(0, &enc);
    n = put_fov(n, &enc, &sf, 0, 0, &pf, 0);
    n = put_fov(n, &enc, &sr, 0, 1, &pr, 0);
    n = put_fov(n, &enc, &sf, 0, 2, &pf, 0); /* frame 3's reduced frame never comes */
    n = put_fov(n, &enc, &sf, 0, 4, &pf, 0);
    assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_MISSING_REDUCED), 1);
    assert_int_equal(tdc_link_counters(&rig.dec)->missing_reduced_frames, 1);
    assert_int_equal(lt_count(&rig, 0, TDC_LINK_EV_PACKET, 0), 5);
}

/* The decoded buffers through tdc_fov_trm = tdc_fov_frame fed by hand on
 * buffers of its own, for both slots, in place. */
static void test_stage_on_decoded_buffers(void **state)
{
    (void)state;
    static uint8_t lp[W * H * 3], pic[W * H * 3], out[W * H * 3];
    static uint64_t arena[TDC_FOV_TRM_MEM_BYTES(W, H, W, H) / 8u];
    static uint64_t arena_f[TDC_FOV_MEM_BYTES(W, H, 0) / 8u], arena_r[TDC_FOV_MEM_BYTES(W, H, 0) / 8u];
    const tdc_link_encoder_t enc = encoder(FOV | TRM, 2, 1, 2);
    const slot_t sf = slot_of(&enc, 0), sr = slot_of(&enc, 1);
    const size_t need = tdc_fov_trm_get_size(W, H, sr.w, sr.h);
    assert_true(need > 0 && need <= TDC_FOV_TRM_MEM_BYTES(W, H, sr.w, sr.h) && need <= sizeof arena);
    tdc_fov_trm_t st;
    assert_int_equal(tdc_fov_trm_init(&st, W, H, sr.w, sr.h, arena, need - 8u), TDC_ERR_SIZE);
    assert_int_equal(tdc_fov_trm_init(&st, W, H, W + 1, sr.h, arena, sizeof arena), TDC_ERR_SIZE);
    assert_int_equal(tdc_fov_trm_init(&st, W, H, sr.w, sr.h, arena, need), TDC_OK);
    const tdc_fov_config_t cf = {W, H, 0}, cr = {sr.w, sr.h, 0};
    tdc_fov_t hf, hr;
    assert_int_equal(tdc_fov_init(&hf, &cf, arena_f, sizeof arena_f), TDC_OK);
    assert_int_equal(tdc_fov_init(&hr, &cr, arena_r, sizeof arena_r), TDC_OK);
    assert_int_equal(lt_init(&rig, W, H, 2), TDC_OK);
    size_t n = put_stream_header(0, &enc);
    assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
    for (uint32_t f = 0; f < 8; f++) {
        for (uint32_t e = 0; e < 2; e++) {
            const int red = tdc_link_trm_kind(f, e) == TDC_LINK_KIND_REDUCED;
            const slot_t *s = red ? &sr : &sf;
            /* the gaze drifts, a saccade at frame 5 */
            const tdc_fov_params_t p =
                params(s, 90 + (int32_t)f * 9 + (f >= 5 ? 100 : 0) - (int32_t)e * 20, 130, (uint16_t)(768 + 128 * e), 4077);
            tdc_fov_geom_t g;
            assert_int_equal(tdc_fov_geom(&g, s->w, s->h, &p), TDC_OK);
            n = put_fov(0, &enc, s, e, f, &p, 0);
            const uint32_t ev0 = rig.nev;
            assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
            assert_int_equal(lt_count(&rig, ev0, TDC_LINK_EV_PACKET, 0), 1);
            /* by hand: the payload's samples where the layout puts them */
            const size_t cols = (size_t)(g.lp_w - g.u0), stride = (size_t)s->w * 3u;
            size_t k = 0;
            memset(lp, 0, sizeof lp);
            for (uint32_t j = 0; j < g.lp_h; j++, k += cols) {
                memcpy(lp + ((size_t)j * g.lp_w + g.u0) * 3u, samples + k * 3u, cols * 3u);
            }
            memset(pic, 0, sizeof pic);
            for (int32_t j = 0; j < s->h; j++) {
                int32_t x0;
                const uint32_t span = tdc_fov_disk_span(&g, j, &x0);
                memcpy(pic + (size_t)j * stride + (size_t)x0 * 3u, samples + k * 3u, span * 3u);
                k += span;
            }
            assert_int_equal(tdc_fov_frame(red ? &hr : &hf, &p, lp, (size_t)g.lp_w * 3u, NULL, 0, pic, stride, 0, out,
                                           stride),
                             TDC_OK);
            const tdc_fov_hdr_t *fh = tdc_link_fov(&rig.dec, e);
            assert_non_null(fh);
            uint8_t *dpic = red ? rig.reduced[e] : rig.full[e];
            /* the other slot's instance refuses this grid, nothing written */
            const uint64_t h0 = lt_hash_all(&rig);
            assert_int_equal(tdc_fov_trm_frame(&st, fh, !red, rig.fov_lp[e], dpic, stride), TDC_ERR_SIZE);
            assert_true(lt_hash_all(&rig) == h0);
            assert_int_equal(tdc_fov_trm_frame(&st, fh, red, rig.fov_lp[e], dpic, stride), TDC_OK);
            assert_memory_equal(dpic, out, (size_t)s->h * stride);
        }
    }
    assert_int_equal(st.full.frames, 8);
    assert_int_equal(st.reduced.frames, 8);
}

/* ------------------------------------------------------------------------
 * Refusals: a TRM stream with frames 0 (full) and 1 (reduced) accepted
 * (mono), the bad packet, nothing changed, then frame 3's reduced and
 * frame 4's full foveated pictures accepted.
 * ---------------------------------------------------------------------- */
static void expect_refused(const uint8_t *bad, size_t nbad, uint32_t flags, tdc_link_err_t err,
                           tdc_fov_hdr_err_t reason)
{
    static uint8_t badcopy[1 << 16];
    assert_true(nbad > 0 && nbad <= sizeof badcopy);
    memcpy(badcopy, bad, nbad);
    const tdc_link_encoder_t enc = encoder(flags, 1, (flags & TRM) ? 1 : 1, (flags & TRM) ? 2 : 1);
    const int trm = (flags & TRM) != 0;
    const slot_t sf = slot_of(&enc, 0), sr = slot_of(&enc, 1);
    const tdc_fov_params_t pf = params(&sf, 90, 140, 1024, 4077), pr = params(&sr, 90, 140, 1024, 4077);
    assert_int_equal(lt_init(&rig, W, H, 1), TDC_OK);
    size_t n = put_stream_header(0, &enc);
    n = put_fov(n, &enc, &sf, 0, 0, &pf, 0);
    if (trm) {
        n = put_fov(n, &enc, &sr, 0, 1, &pr, 0);
    }
    assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
    assert_int_equal(lt_count(&rig, 0, TDC_LINK_EV_PACKET, 0), trm ? 3 : 2);
    const tdc_fov_hdr_t kept = *tdc_link_fov(&rig.dec, 0);
    const uint64_t h0 = lt_hash_all(&rig);
    const uint32_t ev0 = rig.nev;
    assert_int_equal(lt_feed(&rig, badcopy, nbad, 0, 0), nbad);
    lt_expect_fov_refused(&rig, ev0, err, (int)reason, h0, &kept);
    /* the next valid packets are accepted */
    const uint32_t ev1 = rig.nev;
    n = trm ? put_fov(0, &enc, &sr, 0, 3, &pr, 0) : 0;
    n = put_fov(n, &enc, &sf, 0, 4, &pf, 0);
    assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
    assert_int_equal(lt_count(&rig, ev1, TDC_LINK_EV_PACKET, 0), trm ? 2 : 1);
    assert_int_equal(rig.ev[rig.nev - 1].kind, TDC_LINK_KIND_FOVEATED);
    assert_int_equal(rig.ev[rig.nev - 1].frame_index, 4);
}

/* A foveated packet of p on grid gw x gh with packet width x height and
 * flags as given, optionally one foveation-header byte changed; CRCs valid. */
static size_t raw_fov(const tdc_fov_params_t *p, uint16_t gw, uint16_t gh, uint32_t frame, uint16_t width,
                      uint16_t height, uint16_t flags, int byte_at, uint8_t byte_val, int with_mv)
{
    tdc_fov_geom_t g;
    uint8_t fh[TDC_FOV_HDR_BYTES];
    assert_int_equal(tdc_fov_geom(&g, gw, gh, p), TDC_OK);
    fill_samples(&g, frame, 0);
    assert_int_equal(tdc_fov_hdr_pack(fh, gw, gh, p, DELTA_Q15, with_mv ? TDC_FOV_FLAG_MV : 0u), TDC_OK);
    memcpy(payload, fh, sizeof fh);
    tdc_fov_pack_payload(&g, samples, with_mv ? mvs : NULL, payload + TDC_FOV_HDR_BYTES);
    if (byte_at >= 0) {
        payload[byte_at] = byte_val;
    }
    const tdc_link_header_t f = lt_fov_header(0, TDC_PIXFMT_RGB888, flags, frame, width, height);
    return tdc_link_encode_raw(pkt, sizeof pkt, &f, payload,
                               TDC_FOV_HDR_BYTES + tdc_fov_payload_bytes(&g, with_mv));
}

static void test_refusals(void **state)
{
    (void)state;
    const tdc_link_encoder_t enc = encoder(FOV | TRM, 1, 1, 2);
    const slot_t sf = slot_of(&enc, 0), sr = slot_of(&enc, 1);
    assert_int_equal(sr.w, W / 2);
    assert_int_equal(sr.h, H / 2);
    const tdc_fov_params_t pf = params(&sf, 128, 128, 1024, 4077), pr = params(&sr, 128, 128, 1024, 4077);
    const uint16_t R = TDC_LINK_PKT_FOV_REDUCED;
    const tdc_link_err_t E = TDC_LINK_ERR_FOVEATION;
    size_t n;
    /* frame 2 is a full slot, frame 3 a reduced one (mono) */
    /* the slot flag against TRM's schedule */
    n = raw_fov(&pr, sr.w, sr.h, 2, sr.w, sr.h, R, -1, 0, 0); /* a reduced picture in a full slot */
    expect_refused(pkt, n, FOV | TRM, TDC_LINK_ERR_UNEXPECTED, TDC_FOV_HDR_OK);
    n = raw_fov(&pf, W, H, 3, W, H, 0, -1, 0, 0); /* a full picture in a reduced slot */
    expect_refused(pkt, n, FOV | TRM, TDC_LINK_ERR_UNEXPECTED, TDC_FOV_HDR_OK);
    /* the packet's size against its slot */
    n = raw_fov(&pf, W, H, 3, W, H, R, -1, 0, 0); /* reduced slot, the full size */
    expect_refused(pkt, n, FOV | TRM, TDC_LINK_ERR_DIMENSIONS, TDC_FOV_HDR_OK);
    n = raw_fov(&pr, sr.w, sr.h, 2, sr.w, sr.h, 0, -1, 0, 0); /* full slot, the reduced size */
    expect_refused(pkt, n, FOV | TRM, TDC_LINK_ERR_DIMENSIONS, TDC_FOV_HDR_OK);
    n = raw_fov(&pr, sr.w, sr.h, 3, sr.w, (uint16_t)(sr.h + 1u), R, -1, 0, 0);
    expect_refused(pkt, n, FOV | TRM, TDC_LINK_ERR_DIMENSIONS, TDC_FOV_HDR_OK);
    /* the foveation header against the reduced grid: the full grid's buffer
     * and geometry in a packet sized for the reduced slot */
    n = raw_fov(&pf, W, H, 3, sr.w, sr.h, R, -1, 0, 0);
    expect_refused(pkt, n, FOV | TRM, E, TDC_FOV_HDR_BUFFER);
    /* lp_w one column off (byte 14), the disk count off (byte 22) */
    n = raw_fov(&pr, sr.w, sr.h, 3, sr.w, sr.h, R, 14, (uint8_t)(pr.lp_w + 1u), 0);
    expect_refused(pkt, n, FOV | TRM, E, TDC_FOV_HDR_BUFFER);
    n = raw_fov(&pr, sr.w, sr.h, 3, sr.w, sr.h, R, 22, 1, 0);
    expect_refused(pkt, n, FOV | TRM, E, TDC_FOV_HDR_GEOMETRY);
    /* a gaze more than one reduced screen outside (fine on the full grid) */
    {
        tdc_fov_params_t q = pr;
        q.gaze_x_q8 = -(int32_t)sr.w * 256 * 3 / 2;
        n = raw_fov(&pr, sr.w, sr.h, 3, sr.w, sr.h, R, -1, 0, 0);
        payload[0] = (uint8_t)((uint32_t)q.gaze_x_q8 & 0xFFu);
        payload[1] = (uint8_t)(((uint32_t)q.gaze_x_q8 >> 8) & 0xFFu);
        payload[2] = (uint8_t)(((uint32_t)q.gaze_x_q8 >> 16) & 0xFFu);
        payload[3] = (uint8_t)(((uint32_t)q.gaze_x_q8 >> 24) & 0xFFu);
        tdc_link_header_t f;
        assert_int_equal(tdc_link_header_unpack(pkt, &f), TDC_LINK_OK);
        n = tdc_link_encode_raw(pkt, sizeof pkt, &f, payload, f.payload_len);
        expect_refused(pkt, n, FOV | TRM, E, TDC_FOV_HDR_GAZE);
    }
    /* a payload one byte short (CRC valid) */
    {
        n = raw_fov(&pr, sr.w, sr.h, 3, sr.w, sr.h, R, -1, 0, 0);
        tdc_link_header_t f;
        assert_int_equal(tdc_link_header_unpack(pkt, &f), TDC_LINK_OK);
        n = tdc_link_encode_raw(pkt, sizeof pkt, &f, payload, f.payload_len - 1u);
        expect_refused(pkt, n, FOV | TRM, E, TDC_FOV_HDR_PAYLOAD);
    }
    /* vectors in a TRM stream, either slot */
    n = raw_fov(&pr, sr.w, sr.h, 3, sr.w, sr.h, R, -1, 0, 1);
    expect_refused(pkt, n, FOV | TRM, TDC_LINK_ERR_UNEXPECTED, TDC_FOV_HDR_OK);
    n = raw_fov(&pf, W, H, 2, W, H, 0, -1, 0, 1);
    expect_refused(pkt, n, FOV | TRM, TDC_LINK_ERR_UNEXPECTED, TDC_FOV_HDR_OK);
    /* the reduced slot of frame 1 again: foveated, and as a plain REDUCED */
    n = raw_fov(&pr, sr.w, sr.h, 1, sr.w, sr.h, R, -1, 0, 0);
    expect_refused(pkt, n, FOV | TRM, TDC_LINK_ERR_DUPLICATE, TDC_FOV_HDR_OK);
    {
        static uint8_t rgb[W * H * 3];
        n = tdc_link_encode_frame(&enc, pkt, sizeof pkt, TDC_LINK_KIND_REDUCED, 0, 1, TDC_PIXFMT_RGB888, rgb, sr.w,
                                  sr.h, (uint32_t)sr.w * 3u);
        expect_refused(pkt, n, FOV | TRM, TDC_LINK_ERR_DUPLICATE, TDC_FOV_HDR_OK);
    }
    /* a corrupted byte: the payload CRC */
    n = raw_fov(&pr, sr.w, sr.h, 3, sr.w, sr.h, R, -1, 0, 0);
    pkt[TDC_LINK_HEADER_BYTES + TDC_FOV_HDR_BYTES + 3] ^= 0x40;
    expect_refused(pkt, n, FOV | TRM, TDC_LINK_ERR_CRC, TDC_FOV_HDR_OK);
    /* the slot flag in a stream without REDUCED (r = 1: the grid is the panel) */
    {
        const tdc_link_encoder_t plain = encoder(FOV, 1, 1, 1);
        const tdc_fov_params_t p1 = params(&sf, 128, 128, 1024, 4077);
        n = tdc_link_encode_foveated_slot(&plain, pkt, sizeof pkt, TDC_LINK_KIND_REDUCED, 0, 3, &p1, DELTA_Q15,
                                          samples, NULL, NULL);
        tdc_link_header_t f;
        assert_int_equal(tdc_link_header_unpack(pkt, &f), TDC_LINK_OK);
        assert_int_equal(f.flags, R);
        assert_int_equal(f.width, W);
        expect_refused(pkt, n, FOV, TDC_LINK_ERR_UNEXPECTED, TDC_FOV_HDR_OK);
    }
    /* the encoder refuses a slot that is neither FULL nor REDUCED */
    assert_int_equal(tdc_link_encode_foveated_slot(&enc, pkt, sizeof pkt, TDC_LINK_KIND_MOTION, 0, 3, &pr, DELTA_Q15,
                                                   samples, NULL, NULL),
                     0);
    /* a packet flag FOVEATED does not know */
    n = raw_fov(&pr, sr.w, sr.h, 3, sr.w, sr.h, R | TDC_LINK_PKT_BAND, -1, 0, 0);
    expect_refused(pkt, n, FOV | TRM, TDC_LINK_ERR_FORMAT, TDC_FOV_HDR_OK);
}

static void test_stream_headers(void **state)
{
    (void)state;
    /* foveated with subframes: still undefined, refused; with REDUCED fine */
    const uint32_t flags[] = {FOV | TDC_LINK_STREAM_SUBFRAMES, FOV | TRM | TDC_LINK_STREAM_SUBFRAMES, FOV | TRM};
    for (int k = 0; k < 3; k++) {
        const tdc_link_encoder_t enc = encoder(flags[k], 1, (flags[k] & TRM) ? 1 : 1, (flags[k] & TRM) ? 2 : 1);
        assert_int_equal(lt_init(&rig, W, H, 1), TDC_OK);
        const size_t n = put_stream_header(0, &enc);
        assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
        assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_STREAM_HEADER), k < 2 ? 1 : 0);
        if (k < 2) {
            assert_null(tdc_link_stream(&rig.dec));
        } else {
            assert_non_null(tdc_link_stream(&rig.dec));
        }
    }
    /* a build without reduced buffers or without the foveation buffers refuses it */
    for (int k = 0; k < 2; k++) {
        const tdc_link_encoder_t enc = encoder(FOV | TRM, 2, 1, 2);
        assert_int_equal(lt_init(&rig, W, H, 2), TDC_OK);
        if (k == 0) {
            rig.dec.buf.reduced[1] = NULL;
        } else {
            rig.dec.buf.fov_lp[0] = NULL;
        }
        const size_t n = put_stream_header(0, &enc);
        assert_int_equal(lt_feed(&rig, stream, n, 0, 0), n);
        assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_STREAM_HEADER), 1);
    }
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_round_trip),
    cmocka_unit_test(test_missing_reduced),
    cmocka_unit_test(test_stage_on_decoded_buffers),
    cmocka_unit_test(test_refusals),
    cmocka_unit_test(test_stream_headers),
)
