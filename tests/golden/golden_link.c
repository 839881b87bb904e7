/*
 * golden_link.c - bit-exact golden vectors of the link decoder: synthetic
 * streams (sim/link/tdc_link_gen.c, integer-only and included here so the
 * ARM runner has it too, encoded by firmware/tdc_link_encode.c) in
 * every pixel format, for TRM streams (full/reduced, motion) and
 * tile-ordered subframe streams (pattern, subframes, per-sample motion),
 * plus one damaged stream.  One checksum per accepted packet: FNV-1a 64 of
 * the pipeline buffer it filled, folded with the event fields; error
 * events fold their code and detail into the next checksum; a final line
 * pins the counters.  Freestanding, static buffers (~140 KiB).
 */
#include "golden.h"

#include "../../sim/link/tdc_link_gen.c"
#include "tdc_crc32.h"

#define LW 45
#define LH 27

static uint8_t g_staging[TDC_LINK_STAGING_BYTES(LW, LH)];
static uint8_t g_full[2][TDC_LINK_FRAME_BYTES(LW, LH)];
static uint8_t g_reduced[2][TDC_LINK_FRAME_BYTES(LW, LH)];
static uint8_t g_sub[2][TDC_LINK_SUBFRAME_BYTES(LW, LH)];
static int16_t g_mv[2][TDC_LINK_MOTION_COUNT(LW, LH)];
static int16_t g_smv[2][TDC_LINK_SAMPLE_MOTION_COUNT(LW, LH)];
static uint8_t g_pat[2][TDC_PATTERN_BYTES(LW, LH)];
static uint8_t g_fov_lp[2][TDC_LINK_FRAME_BYTES(LW, LH)]; /* FOVEATED: delta <= 1 */
static int16_t g_fov_mv[2][TDC_LINK_MOTION_COUNT(LW, LH)];
static uint32_t g_scratch[LW * LH];
static uint8_t g_stream[72 * 1024];
static tdc_link_decoder_t g_dec;
static int g_dec_ok; /* init_decoder() succeeded */

static const char *const fmt_name[TDC_PIXFMT_COUNT] = {"none", "rgb888", "rgb565", "rgb30", "ycbcr420"};

static void init_decoder(void)
{
    tdc_link_config_t cfg = {LW, LH, 2};
    tdc_link_buffers_t b;
    for (size_t i = 0; i < sizeof b; i++) {
        ((uint8_t *)&b)[i] = 0;
    }
    b.staging = g_staging;
    b.staging_bytes = sizeof g_staging;
    b.full_stride = LW * 3u;
    b.reduced_bytes = sizeof g_reduced[0];
    b.fov_lp_bytes = sizeof g_fov_lp[0];
    b.fov_mv_count = sizeof g_fov_mv[0] / sizeof g_fov_mv[0][0];
    for (int e = 0; e < 2; e++) {
        b.full[e] = g_full[e];
        b.reduced[e] = g_reduced[e];
        b.subframe[e] = g_sub[e];
        b.motion[e] = g_mv[e];
        b.sample_motion[e] = g_smv[e];
        b.pattern[e] = g_pat[e];
        b.fov_lp[e] = g_fov_lp[e];
        b.fov_mv[e] = g_fov_mv[e];
        for (size_t i = 0; i < sizeof g_full[e]; i++) {
            g_full[e][i] = 0;
            g_reduced[e][i] = 0;
            g_fov_lp[e][i] = 0;
        }
        for (size_t i = 0; i < sizeof g_fov_mv[e] / sizeof g_fov_mv[e][0]; i++) {
            g_fov_mv[e][i] = 0;
        }
    }
    g_dec_ok = tdc_link_decoder_init(&g_dec, &cfg, &b) == TDC_OK;
}

static uint64_t fold_u32(uint64_t h, uint32_t v)
{
    uint8_t b[4] = {(uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24)};
    return tdc_fnv1a64(h, b, 4);
}

static uint64_t fold_i16s(uint64_t h, const int16_t *v, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        h = fold_u32(h, (uint32_t)(uint16_t)v[i]);
    }
    return h;
}

/* Feeds n bytes in `chunk`-byte pieces, emitting one line per accepted packet. */
static void run(tdc_golden_ctx_t *ctx, const char *vector, size_t n, size_t chunk)
{
    uint64_t pending = TDC_FNV64_INIT;
    uint32_t line = 0;
    size_t pos = 0;
    if (!g_dec_ok) {
        tdc_golden_emit(ctx, "link", vector, 9999, TDC_GOLDEN_FAILED);
        return;
    }
    while (pos < n || g_dec.ev_count) {
        const size_t c = n - pos < chunk ? n - pos : chunk;
        tdc_link_event_t ev;
        pos += tdc_link_feed(&g_dec, g_stream + pos, c, &ev);
        if (ev.type == TDC_LINK_EV_ERROR) {
            pending = fold_u32(fold_u32(pending, ev.error), ev.detail);
        } else if (ev.type == TDC_LINK_EV_PACKET) {
            const uint32_t e = ev.eye;
            uint64_t h = fold_u32(fold_u32(fold_u32(pending, ev.kind), ev.eye), ev.frame_index);
            const uint32_t tiles = TDC_TILES(LW) * TDC_TILES(LH);
            switch (ev.kind) {
            case TDC_LINK_KIND_FULL: h = tdc_fnv1a64(h, g_full[e], sizeof g_full[e]); break;
            case TDC_LINK_KIND_FOVEATED: { /* the disk in the frame, the log-polar samples, vectors, geometry */
                const tdc_fov_hdr_t *fh = tdc_link_fov(&g_dec, e);
                /* a TRM stream's reduced slot: the disk in the reduced frame */
                h = (ev.flags & TDC_LINK_PKT_FOV_REDUCED)
                        ? fold_u32(tdc_fnv1a64(h, g_reduced[e], (size_t)ev.width * ev.height * 3u), ev.flags)
                        : tdc_fnv1a64(h, g_full[e], sizeof g_full[e]);
                h = tdc_fnv1a64(h, g_fov_lp[e], sizeof g_fov_lp[e]);
                h = fold_i16s(h, g_fov_mv[e], sizeof g_fov_mv[e] / sizeof g_fov_mv[e][0]);
                h = fh ? fold_u32(fold_u32(h, fh->g.l), fh->g.u0) : TDC_GOLDEN_FAILED;
                break;
            }
            case TDC_LINK_KIND_REDUCED: h = tdc_fnv1a64(h, g_reduced[e], (size_t)ev.width * ev.height * 3u); break;
            case TDC_LINK_KIND_SUBFRAME: h = tdc_fnv1a64(h, g_sub[e], sizeof g_sub[e]); break;
            case TDC_LINK_KIND_MOTION:
                h = (ev.flags & TDC_LINK_PKT_MV_PER_SAMPLE) ? fold_i16s(h, g_smv[e], (size_t)tiles * 2u)
                                                            : fold_i16s(h, g_mv[e], (size_t)LW * LH * 2u);
                break;
            case TDC_LINK_KIND_PATTERN: h = tdc_fnv1a64(h, g_pat[e], sizeof g_pat[e]); break;
            default: break;
            }
            tdc_golden_emit(ctx, "link", vector, line++, h);
            pending = TDC_FNV64_INIT;
        }
    }
    const tdc_link_counters_t *k = tdc_link_counters(&g_dec);
    uint64_t h = pending;
    /* Codes up to STREAM_HEADER (those the vectors were recorded with); a
     * later code is folded only when it occurred, so the checksums of these
     * streams do not change when a kind adds a code (FOVEATION). */
    for (int i = 0; i < TDC_LINK_ERR_COUNT; i++) {
        /* codes added after these vectors were recorded fold in only when
         * they occur, so the checked-in checksums stay valid */
        if (i < TDC_LINK_ERR_LAYERS || k->errors[i]) {
            h = fold_u32(h, k->errors[i]);
        }
    }
    h = fold_u32(fold_u32(fold_u32(h, k->packets_ok), (uint32_t)k->garbage_bytes), k->missing_reduced_frames);
    tdc_golden_emit(ctx, "link", vector, 9999, h);
}

static size_t gen(uint32_t flags, tdc_pixfmt_t fmt, uint32_t frames, uint32_t seed)
{
    tdc_link_gen_opts_t o;
    tdc_link_gen_opts_plain(&o, 0x1D, LW, LH, 2, 144, fmt, frames, seed);
    o.info.flags = flags;
    o.info.r_den = (flags & TDC_LINK_STREAM_REDUCED) ? 2 : 1; /* r = 1/2 with reduced frames */
    return tdc_link_gen_stream(g_stream, sizeof g_stream, &o, (uint8_t *)g_scratch, sizeof g_scratch, NULL, 0, NULL);
}

/* The foveated stream of tdc_golden_link (samples from tdc_link_gen's
 * picture of each frame and eye, vectors a fixed pattern). */
static size_t gen_foveated(int damaged)
{
    tdc_link_stream_info_t in;
    for (size_t i = 0; i < sizeof in; i++) {
        ((uint8_t *)&in)[i] = 0;
    }
    in.flags = TDC_LINK_STREAM_FOVEATED;
    in.r_num = in.r_den = 1;
    in.width = LW;
    in.height = LH;
    in.eyes = 2;
    in.refresh_hz = 90;
    tdc_link_encoder_t enc;
    tdc_link_encoder_init(&enc, 0x2F, &in);
    size_t n = tdc_link_encode_stream(&enc, g_stream, sizeof g_stream);
    static const uint16_t alpha[3] = {256, 1024, 2048}, disk[4] = {0, 4077, 12000, 32768};
    static uint8_t samples[2 * LW * LH * 3];
    static int16_t mv[LW * LH * 2];
    for (uint32_t f = 0; f < 6; f++) {
        for (uint32_t e = 0; e < 2; e++) {
            tdc_fov_params_t p;
            p.transform = TDC_FOV_KERNEL_LOG_POLAR;
            p.lr_k_q4[0] = p.lr_k_q4[1] = 0;
            p.zero = 0;
            p.gaze_x_q8 = (int32_t)(f * 2900u + e * 700u) - 1500;
            p.gaze_y_q8 = 3000 + (int32_t)(f * 900u);
            p.alpha_q8 = alpha[(f + e) % 3u];
            p.disk_q15 = disk[f % 4u];
            p.lp_w = tdc_fov_lp_size(18187, LW);
            p.lp_h = tdc_fov_lp_size(18187, LH);
            tdc_link_gen_rgb(samples, LW, 2u * LH, f, e, 77u);
            for (size_t i = 0; i < sizeof mv / sizeof mv[0]; i++) {
                mv[i] = (int16_t)((int32_t)((i * 37u + f * 11u + e) % 257u) - 128);
            }
            const size_t at = n;
            n += tdc_link_encode_foveated(&enc, g_stream + n, sizeof g_stream - n, e, f, &p, 18187, samples,
                                          (f & 1u) ? mv : NULL, NULL);
            if (damaged && f == 2 && e == 1) {
                /* alpha 9.0 in the foveation header, both CRCs recomputed */
                tdc_link_header_t hh;
                (void)tdc_link_header_unpack(g_stream + at, &hh);
                g_stream[at + TDC_LINK_HEADER_BYTES + 9] = 9;
                hh.payload_crc = tdc_crc32(g_stream + at + TDC_LINK_HEADER_BYTES, hh.payload_len);
                tdc_link_header_pack(g_stream + at, &hh);
            }
        }
    }
    return n;
}

/* A foveated TRM stream (stereo, r = 1/2: the 23 x 14 reduced grid):
 * every slot a FOVEATED packet (FOV_REDUCED in the reduced slots, its
 * parameters on the reduced grid) but frame 4's reduced one, a plain
 * REDUCED packet; the gaze moving over and off the screen, alpha 1/4/8,
 * disks 0..1; before frame 3's eye-0 reduced picture a refused one (the
 * reduced slot's flag on a full-size packet, header CRC valid: DIMENSIONS),
 * folded into the next checksum. */
static size_t gen_foveated_trm(void)
{
    tdc_link_stream_info_t in;
    for (size_t i = 0; i < sizeof in; i++) {
        ((uint8_t *)&in)[i] = 0;
    }
    in.flags = TDC_LINK_STREAM_FOVEATED | TDC_LINK_STREAM_REDUCED;
    in.r_num = 1;
    in.r_den = 2;
    in.width = LW;
    in.height = LH;
    in.eyes = 2;
    in.refresh_hz = 90;
    tdc_link_encoder_t enc;
    tdc_link_encoder_init(&enc, 0x31, &in);
    size_t n = tdc_link_encode_stream(&enc, g_stream, sizeof g_stream);
    static const uint16_t alpha[3] = {256, 1024, 2048}, disk[4] = {0, 4077, 12000, 32768};
    static uint8_t samples[2 * LW * LH * 3];
    for (uint32_t f = 0; f < 6; f++) {
        for (uint32_t e = 0; e < 2; e++) {
            const int red = tdc_link_trm_kind(f, e) == TDC_LINK_KIND_REDUCED;
            const uint32_t gw = red ? TDC_REDUCED_DIM(LW, 1u, 2u) : LW, gh = red ? TDC_REDUCED_DIM(LH, 1u, 2u) : LH;
            tdc_link_gen_rgb(samples, gw, 2u * gh, f, e, 91u);
            if (red && f == 4) {
                n += tdc_link_encode_frame(&enc, g_stream + n, sizeof g_stream - n, TDC_LINK_KIND_REDUCED, e, f,
                                           TDC_PIXFMT_RGB888, samples, gw, gh, gw * 3u);
                continue;
            }
            tdc_fov_params_t p;
            p.transform = TDC_FOV_KERNEL_LOG_POLAR;
            p.lr_k_q4[0] = p.lr_k_q4[1] = 0;
            p.zero = 0;
            p.gaze_x_q8 = (int32_t)((f * 60u + e * 15u) * gw) - 20 * (int32_t)gw;
            p.gaze_y_q8 = (int32_t)((110u + f * 20u) * gh);
            p.alpha_q8 = alpha[(f + e) % 3u];
            p.disk_q15 = disk[(f + 2u * e) % 4u];
            p.lp_w = tdc_fov_lp_size(18187, (uint16_t)gw);
            p.lp_h = tdc_fov_lp_size(18187, (uint16_t)gh);
            if (red && f == 3 && e == 0) {
                /* the full slot's encoding with the reduced slot's flag */
                const size_t at = n;
                tdc_fov_params_t q = p;
                q.lp_w = tdc_fov_lp_size(18187, LW);
                q.lp_h = tdc_fov_lp_size(18187, LH);
                n += tdc_link_encode_foveated(&enc, g_stream + n, sizeof g_stream - n, e, f, &q, 18187, samples, NULL,
                                              NULL);
                tdc_link_header_t hh;
                (void)tdc_link_header_unpack(g_stream + at, &hh);
                hh.flags = TDC_LINK_PKT_FOV_REDUCED;
                tdc_link_header_pack(g_stream + at, &hh);
            }
            n += tdc_link_encode_foveated_slot(&enc, g_stream + n, sizeof g_stream - n,
                                               red ? TDC_LINK_KIND_REDUCED : TDC_LINK_KIND_FULL, e, f, &p, 18187,
                                               samples, NULL, NULL);
        }
    }
    return n;
}

static void name2(char *out, const char *a, const char *b)
{
    while (*a) {
        *out++ = *a++;
    }
    *out++ = '-';
    while (*b) {
        *out++ = *b++;
    }
    *out = 0;
}

void tdc_golden_link(tdc_golden_ctx_t *ctx);

void tdc_golden_link(tdc_golden_ctx_t *ctx)
{
    char vec[40];
    for (int f = TDC_PIXFMT_RGB888; f < TDC_PIXFMT_COUNT; f++) {
        size_t n = gen(TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_MOTION, (tdc_pixfmt_t)f, 3, 100u + (uint32_t)f);
        init_decoder();
        name2(vec, fmt_name[f], "trm");
        run(ctx, vec, n, 4096);
        n = gen(TDC_LINK_STREAM_SUBFRAMES | TDC_LINK_STREAM_SAMPLE_MV, (tdc_pixfmt_t)f, 5, 200u + (uint32_t)f);
        init_decoder();
        name2(vec, fmt_name[f], "subframes");
        run(ctx, vec, n, 1000);
    }
    /* Damaged stream, fed 7 bytes at a time: a flipped payload byte, a
     * corrupted header, garbage and a duplicated tail. */
    size_t n = gen(TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_MOTION, TDC_PIXFMT_YCBCR420, 4, 7);
    g_stream[200] ^= 0x20;
    g_stream[n / 2] ^= 0x01;
    g_stream[n / 3 + 5] = 'T';
    const size_t tail = 3000;
    for (size_t i = 0; i < tail && n + i < sizeof g_stream; i++) {
        g_stream[n + i] = g_stream[n - tail + i];
    }
    init_decoder();
    run(ctx, "damaged", n + tail, 7);
    /* Foveated stream (kind 7), stereo: the gaze moving over and off the
     * screen, alpha 1/4/8, disks 0..1, vectors on odd frames; then the same
     * with one packet's alpha out of range (CRC valid: refused by the
     * foveation header) fed 5 bytes at a time. */
    for (int damaged = 0; damaged < 2; damaged++) {
        init_decoder();
        n = gen_foveated(damaged);
        run(ctx, damaged ? "foveated-refused" : "foveated", n, damaged ? 5 : 4096);
    }
    /* Foveated TRM (issue 14 item 5): both slots foveated, fed 11 bytes at a time. */
    init_decoder();
    n = gen_foveated_trm();
    run(ctx, "foveated-trm", n, 11);
}
