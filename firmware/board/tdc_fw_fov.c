/*
 * tdc_fw_fov.c - the foveated stream family of the board frame loop (stream
 * flag FOVEATED; tdc_fw_family.h): a FOVEATED packet (or a FULL picture,
 * shown as a plain stream's) per eye and frame.  The decoder leaves the
 * samples and (TAA) vectors in the eye's foveation block of the mode arena
 * and the disk pixels in its disk frame (tdc_fw_memmap.h); tdc_fov remaps
 * them into the eye's part of the frame buffer.
 */
#include "tdc_fw_family.h"

#if TDC_CFG_FOV
static tdc_fov_t g_fov[FW_EYES];
static tdc_fov_lr_t g_fov_lr[FW_EYES];
static uint8_t g_have; /* bit e: g_last[e] is eye e's last frame through the stage */
static uint32_t g_last[2];
static uint32_t g_dt_us;  /* frame time at the panel's rate (eq. 4.7) */
static uint32_t g_resets; /* TAA histories forgotten: a gap in the eye's frames, a refusal or a FULL picture */

/* The decoder's FOVEATED buffers (the disk frame: its full[], which FULL
 * payloads never reach, deferred as they are). */
static void fov_wire(tdc_link_buffers_t *b)
{
    for (uint32_t e = 0; e < FW_EYES; e++) {
        b->full[e] = FOV_DISK(e);
        b->fov_lp[e] = FOV_LP(e);
        b->fov_mv[e] = TDC_CFG_FOV_TAA ? FOV_MV(e) : NULL;
    }
    b->full_stride = FW_W * 3u;
    b->fov_lp_bytes = FW_LP_SAMPLES * 3u;
    b->fov_mv_count = TDC_CFG_FOV_TAA ? FW_LP_SAMPLES * 2u : 0u;
}

static int fov_configure(const tdc_link_stream_info_t *si, uint16_t hz)
{
    const tdc_fov_config_t cfg = {(uint16_t)FW_W, (uint16_t)FW_H, (uint8_t)TDC_CFG_FOV_TAA};
    (void)si;
    for (uint32_t e = 0; e < FW_EYES; e++) {
        const size_t need = tdc_fov_get_size(&cfg);
        if (need == 0 || need > FW_FOV_STAGE_BYTES ||
            tdc_fov_init(&g_fov[e], &cfg, FOV_STAGE(e), FW_FOV_STAGE_BYTES) != TDC_OK ||
            tdc_fov_lr_init(&g_fov_lr[e], (uint16_t)FW_W, FOV_LR_MEM(e), FW_FOV_LR_BYTES) != TDC_OK ||
            tdc_fov_lr_attach(&g_fov[e], &g_fov_lr[e]) != TDC_OK) {
            tdc_board_log("foveation stage refused the panel (size)");
            return -1;
        }
    }
    g_dt_us = hz ? 1000000u / hz : 0u;
    g_have = 0;
    return 0;
}

static uint32_t fov_needs(uint32_t e, uint32_t frame)
{
    (void)e, (void)frame;
    return PICTURE_KINDS; /* either fills the eye's picture slot */
}

/* Forgets eye e's TAA history (its next foveated frame is taken as is). */
static void fov_forget(uint32_t e)
{
    g_resets += (g_have >> e) & 1u;
    g_have = (uint8_t)(g_have & ~(1u << e));
    tdc_fov_reset(&g_fov[e]);
}

/* Peripheral TAA runs on packets that carry vectors (TDC_FOV_FLAG_MV), from
 * a history that is the eye's previous frame: after a lost, refused or late
 * frame, a FULL picture or a packet without vectors it is forgotten (the
 * frame is composed as the stage without TAA composes it), never applied
 * later.  The stage writes nothing if it refuses. */
static tdc_status_t fov_frame(uint32_t e, uint32_t frame, uint8_t *fb)
{
    const tdc_fov_hdr_t *h = tdc_link_fov(&tdc_fw.dec, e);
    if (!h) {
        return TDC_ERR_STATE;
    }
    const int taa = (h->flags & TDC_FOV_FLAG_MV) != 0; /* the sender asks for TAA by sending vectors */
    if (!taa || !(g_have & (1u << e)) || frame != g_last[e] + 1u) {
        fov_forget(e);
    }
    const tdc_status_t st =
        tdc_fov_frame(&g_fov[e], &h->p, FOV_LP(e), (size_t)h->p.lp_w * 3u, taa ? FOV_MV(e) : NULL,
                      (size_t)h->p.lp_w * 2u, FOV_DISK(e), (size_t)FW_W * 3u, g_dt_us, fb, FW_STRIDE);
    if (st == TDC_OK && taa) {
        g_have = (uint8_t)(g_have | (1u << e));
        g_last[e] = frame;
    } else if (st != TDC_OK) {
        fov_forget(e);
    }
    tdc_fw.fov_composed += st == TDC_OK;
    return st;
}

static int fov_eye(uint32_t e, uint32_t frame, uint32_t kinds, uint8_t *fb, tdc_res_t **residual)
{
    (void)residual;
    if (kinds & KIND_BIT(TDC_LINK_KIND_FOVEATED)) {
        return fov_frame(e, frame, fb) == TDC_OK ? FW_EYE_UPDATED : FW_EYE_REFUSED;
    }
    if (kinds & KIND_BIT(TDC_LINK_KIND_FULL)) {
        fov_forget(e); /* a whole picture: shown as it is, the history no longer matches it */
        return FW_EYE_UPDATED;
    }
    return FW_EYE_NOTHING;
}

/* a FULL picture in a foveated stream: shown as it is */
static tdc_status_t fov_band(uint32_t e, uint32_t frame, uint32_t kind, const tdc_band_hdr_t *bh, uint8_t *fb,
                             uint32_t *done, uint32_t *covered, tdc_res_t **residual)
{
    (void)frame, (void)kind, (void)fb, (void)done, (void)covered, (void)residual;
    if (bh->index == 0u) {
        fov_forget(e);
    }
    return TDC_OK;
}

static void fov_log(const tdc_link_counters_t *c)
{
    uint32_t refused = 0;
    for (unsigned i = 1; i < TDC_FOV_HDR_COUNT; i++) {
        refused += c->fov_refused[i];
    }
    tdc_fw_log_kv("foveated frames composed: ", tdc_fw.fov_composed);
    tdc_fw_log_kv("foveation headers refused: ", refused);
    tdc_fw_log_kv("foveated TAA histories forgotten (gap, refusal or full frame): ", g_resets);
}

const tdc_fw_family_t tdc_fw_family_fov = {
    "fov", TDC_LINK_STREAM_FOVEATED, fov_wire, fov_configure, fov_needs, fov_eye, fov_band, fov_log};
#else
TDC_FW_FAMILY_NOT_BUILT(fov);
#endif
