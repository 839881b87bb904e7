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

#define LW 45
#define LH 27

static uint8_t g_staging[TDC_LINK_STAGING_BYTES(LW, LH)];
static uint8_t g_full[2][TDC_LINK_FRAME_BYTES(LW, LH)];
static uint8_t g_reduced[2][TDC_LINK_FRAME_BYTES(LW, LH)];
static uint8_t g_sub[2][TDC_LINK_SUBFRAME_BYTES(LW, LH)];
static int16_t g_mv[2][TDC_LINK_MOTION_COUNT(LW, LH)];
static int16_t g_smv[2][TDC_LINK_SAMPLE_MOTION_COUNT(LW, LH)];
static uint8_t g_pat[2][TDC_PATTERN_BYTES(LW, LH)];
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
    for (int e = 0; e < 2; e++) {
        b.full[e] = g_full[e];
        b.reduced[e] = g_reduced[e];
        b.subframe[e] = g_sub[e];
        b.motion[e] = g_mv[e];
        b.sample_motion[e] = g_smv[e];
        b.pattern[e] = g_pat[e];
        for (size_t i = 0; i < sizeof g_full[e]; i++) {
            g_full[e][i] = 0;
            g_reduced[e][i] = 0;
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
}
