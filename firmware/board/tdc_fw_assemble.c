/*
 * tdc_fw_assemble.c - the tile-assembly stream family of the board frame
 * loop (stream flag SUBFRAMES; tdc_fw_family.h): a SUBFRAME packet per eye
 * and frame, with its sample motion vectors if the stream sends them,
 * assembled by tdc_assemble and copied into the eye's part of the frame
 * buffer.  FULL packets of such a stream are never unpacked (no kind it
 * needs).
 */
#include <string.h>

#include "tdc_fw_family.h"

#if TDC_CFG_ASSEMBLE
static uint8_t g_subframe[FW_EYES][TDC_LINK_SUBFRAME_BYTES(FW_W, FW_H)] TDC_EXTRAM;
static int16_t g_sample_mv[FW_EYES][TDC_LINK_SAMPLE_MOTION_COUNT(FW_W, FW_H)] TDC_EXTRAM;
static uint8_t g_pattern[FW_EYES][TDC_PATTERN_BYTES(FW_W, FW_H)] TDC_EXTRAM;
static tdc_asm_t g_as[FW_EYES];
static uint32_t g_skipped; /* frames behind assembly's counter */
static uint32_t g_resyncs; /* joined mid-stream / too far ahead: assembly restarted at the frame */

static void asm_wire(tdc_link_buffers_t *b)
{
    for (uint32_t e = 0; e < FW_EYES; e++) {
        b->subframe[e] = g_subframe[e];
        b->sample_motion[e] = g_sample_mv[e];
        b->pattern[e] = g_pattern[e];
    }
}

static tdc_status_t asm_init(uint32_t e)
{
    const tdc_asm_config_t cfg = {(uint16_t)FW_W, (uint16_t)FW_H};
    const size_t need = tdc_asm_get_size(&cfg);
    if (need == 0 || need > sizeof tdc_fw_mode_arena[e]) {
        return TDC_ERR_SIZE;
    }
    return tdc_asm_init(&g_as[e], &cfg, tdc_fw_mode_arena[e], sizeof tdc_fw_mode_arena[e]);
}

static int asm_configure(const tdc_link_stream_info_t *si, uint16_t hz)
{
    (void)si, (void)hz;
    for (uint32_t e = 0; e < FW_EYES; e++) {
        if (asm_init(e) != TDC_OK) {
            tdc_board_log("tile assembly refused the stream (size)");
            return -1;
        }
    }
    return 0;
}

static uint32_t asm_needs(uint32_t e, uint32_t frame)
{
    (void)e, (void)frame;
    const tdc_link_stream_info_t *si = tdc_link_stream(&tdc_fw.dec);
    return KIND_BIT(TDC_LINK_KIND_SUBFRAME) |
           ((si && (si->flags & TDC_LINK_STREAM_SAMPLE_MV)) ? KIND_BIT(TDC_LINK_KIND_MOTION) : 0u);
}

/* Assembly runs frames in order; frames without a subframe are assembled
 * from history (up to 64 behind, beyond that the frame is skipped). */
static int asm_eye(uint32_t e, uint32_t frame, uint32_t kinds, uint8_t *fb, tdc_res_t **residual)
{
    tdc_asm_t *st = &g_as[e];
    (void)residual;
    if (frame < st->next_frame) {
        g_skipped++;
        return FW_EYE_REFUSED;
    }
    if (frame - st->next_frame > 64u) {
        /* a late joiner (or a board reset mid-stream, or a long gap): the
         * history is gone either way; restart assembly at this frame */
        if (asm_init(e) != TDC_OK) {
            return FW_EYE_REFUSED;
        }
        tdc_asm_start_at(st, frame);
        g_resyncs++;
    }
    while (st->next_frame < frame) {
        if (tdc_asm_assemble(st, st->next_frame) != TDC_OK) {
            return FW_EYE_REFUSED;
        }
    }
    if (kinds & KIND_BIT(TDC_LINK_KIND_SUBFRAME)) {
        const int16_t *mv = (kinds & KIND_BIT(TDC_LINK_KIND_MOTION)) ? g_sample_mv[e] : NULL;
        const uint8_t *bits = (kinds & KIND_BIT(TDC_LINK_KIND_PATTERN)) ? g_pattern[e] : NULL;
        if (tdc_asm_ingest(st, frame, g_subframe[e], mv, bits) != TDC_OK) {
            return FW_EYE_REFUSED;
        }
    }
    if (tdc_asm_assemble(st, frame) != TDC_OK) {
        return FW_EYE_REFUSED;
    }
    int stride = 0;
    const uint8_t *out = tdc_asm_output(st, &stride);
    tdc_fw_put_eye(fb, out, stride);
    return FW_EYE_UPDATED;
}

static void asm_log(const tdc_link_counters_t *c)
{
    (void)c;
    tdc_fw_log_kv("assembly restarts (joined mid-stream): ", g_resyncs);
}

const tdc_fw_family_t tdc_fw_family_assemble = {
    "assemble", TDC_LINK_STREAM_SUBFRAMES, asm_wire, asm_configure, asm_needs, asm_eye, NULL, asm_log};
#else
TDC_FW_FAMILY_NOT_BUILT(assemble);
#endif
