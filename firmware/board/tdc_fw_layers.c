/*
 * tdc_fw_layers.c - the layered tile-assembly stream family of the board
 * frame loop (stream flags SUBFRAMES | LAYERS; tdc_fw_family.h): a LAYERS
 * packet per eye and frame (tdc_layer_link.h: per layer type its samples
 * and their own vectors, the eq. 4 falloff), with the PATTERN packet of the
 * cycle, assembled by tdc_layers (Zeng et al. §4-§5: per-layer
 * reprojection, splatting, the 3 sigma clamp, the clean-up) and recombined
 * into the eye's part of the frame buffer.  Stream flag LAYER_HIST switches
 * on the per-layer exponential history (eq. 2; tdc_layers.h "History per
 * layer"); without it the assembly is as the stage's goldens without
 * history.  Every layer type is kept (the stream header does not say which
 * a stream sends): 148 B/px of arena per eye.
 */
#include <string.h>

#include "tdc_fw_family.h"

#if TDC_CFG_LAYERS
#define FW_TILES TDC_TILE_COUNT(FW_W, FW_H)
/* the decoder's planes, one set per eye (values 3 B a tile, 1 for
 * visibility; vectors 4 B; falloff 2 B) */
static uint8_t g_val[FW_EYES][TDC_LAYER_MAX][FW_TILES * 3u] TDC_EXTRAM;
static int16_t g_mv[FW_EYES][TDC_LAYER_MAX][FW_TILES * 2u] TDC_EXTRAM;
static uint16_t g_falloff[FW_EYES][FW_TILES] TDC_EXTRAM;
static tdc_layer_frame_t g_lf[FW_EYES];
static uint8_t g_lpattern[FW_EYES][TDC_PATTERN_BYTES(FW_W, FW_H)] TDC_EXTRAM;
static uint8_t g_lsub[FW_EYES][TDC_LINK_SUBFRAME_BYTES(FW_W, FW_H)] TDC_EXTRAM;
static const uint8_t *g_pattern[FW_EYES]; /* where the decoder writes PATTERN packets */
static tdc_lasm_t g_ls[FW_EYES];
static uint32_t g_skipped, g_resyncs, g_history_streams;

static void lasm_wire(tdc_link_buffers_t *b)
{
    for (uint32_t e = 0; e < FW_EYES; e++) {
        memset(&g_lf[e], 0, sizeof g_lf[e]);
        for (uint32_t t = 0; t < TDC_LAYER_MAX; t++) {
            g_lf[e].value[t] = g_val[e][t];
            g_lf[e].mv[t] = g_mv[e][t];
        }
        g_lf[e].falloff = g_falloff[e];
        b->layers[e] = &g_lf[e];
        /* the decoder takes a SUBFRAMES stream only with subframe and
         * pattern buffers: the assembly family's if it is built (a layered
         * stream sends no SUBFRAME packet), else these */
        if (!b->subframe[e]) {
            b->subframe[e] = g_lsub[e];
        }
        if (!b->pattern[e]) {
            b->pattern[e] = g_lpattern[e];
        }
        g_pattern[e] = b->pattern[e];
    }
}

static tdc_status_t lasm_init(uint32_t e, uint8_t history)
{
    const tdc_lasm_config_t cfg = {(uint16_t)FW_W,
                                   (uint16_t)FW_H,
                                   (uint16_t)TDC_LAYER_PKT_TYPES,
                                   TDC_LASM_CLAMP_ZENG,
                                   1u, /* the §5 clean-up */
                                   2u, /* splatting radius (a 5 x 5 neighbourhood) */
                                   history,
                                   3277u, /* alpha = 0.1 (Zeng §5) */
                                   &TDC_PANEL_SYMBOL};
    const size_t need = tdc_lasm_get_size(&cfg);
    if (need == 0 || need > sizeof tdc_fw_mode_arena[e]) {
        return TDC_ERR_SIZE;
    }
    return tdc_lasm_init(&g_ls[e], &cfg, tdc_fw_mode_arena[e], sizeof tdc_fw_mode_arena[e]);
}

static int lasm_configure(const tdc_link_stream_info_t *si, uint16_t hz)
{
    (void)hz;
    const uint8_t history = (si->flags & TDC_LINK_STREAM_LAYER_HIST) ? 1u : 0u;
    for (uint32_t e = 0; e < FW_EYES; e++) {
        const tdc_status_t s = lasm_init(e, history);
        if (s != TDC_OK) {
            tdc_board_log(s == TDC_ERR_PANEL ? "layered assembly refused the stream (panel not 8-bit)"
                                             : "layered assembly refused the stream (size)");
            return -1;
        }
    }
    g_history_streams += history;
    return 0;
}

static uint32_t lasm_needs(uint32_t e, uint32_t frame)
{
    (void)e, (void)frame;
    return KIND_BIT(TDC_LINK_KIND_LAYERS);
}

/* Frames run in order; frames without a packet are assembled from history
 * (up to 64 behind, beyond that the assembly restarts at the frame). */
static int lasm_eye(uint32_t e, uint32_t frame, uint32_t kinds, uint8_t *fb, tdc_res_t **residual)
{
    tdc_lasm_t *st = &g_ls[e];
    (void)residual;
    if (frame < st->next_frame) {
        g_skipped++;
        return FW_EYE_REFUSED;
    }
    if (frame - st->next_frame > 64u) {
        if (lasm_init(e, st->cfg.history) != TDC_OK) {
            return FW_EYE_REFUSED;
        }
        tdc_lasm_start_at(st, frame);
        g_resyncs++;
    }
    while (st->next_frame < frame) {
        if (tdc_lasm_assemble(st, st->next_frame) != TDC_OK) {
            return FW_EYE_REFUSED;
        }
    }
    if (kinds & KIND_BIT(TDC_LINK_KIND_LAYERS)) {
        const uint8_t *bits = (kinds & KIND_BIT(TDC_LINK_KIND_PATTERN)) ? g_pattern[e] : NULL;
        if (tdc_lasm_ingest(st, frame, &g_lf[e], bits) != TDC_OK) {
            return FW_EYE_REFUSED;
        }
    }
    if (tdc_lasm_assemble(st, frame) != TDC_OK) {
        return FW_EYE_REFUSED;
    }
    int stride = 0;
    const uint8_t *out = tdc_lasm_output(st, &stride);
    tdc_fw_put_eye(fb, out, stride);
    return FW_EYE_UPDATED;
}

static void lasm_log(const tdc_link_counters_t *c)
{
    (void)c;
    tdc_fw_log_kv("layered streams with history: ", g_history_streams);
    tdc_fw_log_kv("layered frames behind the assembly: ", g_skipped);
    tdc_fw_log_kv("layered assembly restarts (joined mid-stream): ", g_resyncs);
}

const tdc_fw_family_t tdc_fw_family_layers = {"layers",
                                              TDC_LINK_STREAM_SUBFRAMES | TDC_LINK_STREAM_LAYERS,
                                              lasm_wire,
                                              lasm_configure,
                                              lasm_needs,
                                              lasm_eye,
                                              NULL,
                                              lasm_log};
#else
TDC_FW_FAMILY_NOT_BUILT(layers);
#endif
