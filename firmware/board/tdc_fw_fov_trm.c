/*
 * tdc_fw_fov_trm.c - the foveated TRM stream family of the board frame loop
 * (stream flags REDUCED | FOVEATED, docs/foveation.md "Foveated TRM";
 * tdc_fw_family.h): TRM's schedule, whose slots may come FOVEATED.  The
 * decoder's FOVEATED buffers (wired by the foveation family) start the
 * eye's foveated TRM block of the mode arena, TRM's arena follows them,
 * then tdc_fov_trm's two stage arenas (tdc_fw_memmap.h).  FULL and REDUCED
 * pictures, whole or as bands, go to TRM as in a plain TRM stream.
 */
#include "tdc_fw_family.h"

#if TDC_CFG_FOV_TRM
#include "tdc_fw_trm.h"

static tdc_fov_trm_t g_fovtrm[FW_EYES];
static uint32_t g_frames[2]; /* foveated pictures composed: full slot, reduced slot */

static int fovtrm_configure(const tdc_link_stream_info_t *si, uint16_t hz)
{
    uint32_t rw = 0, rh = 0;
    uint8_t *mem[FW_EYES];
    tdc_link_reduced_size(&tdc_fw.dec, &rw, &rh);
    const size_t need = tdc_fov_trm_get_size((uint16_t)FW_W, (uint16_t)FW_H, (uint16_t)rw, (uint16_t)rh);
    for (uint32_t e = 0; e < FW_EYES; e++) {
        if (need == 0 || need > FW_FOVTRM_STAGE_BYTES ||
            tdc_fov_trm_init(&g_fovtrm[e], (uint16_t)FW_W, (uint16_t)FW_H, (uint16_t)rw, (uint16_t)rh, FOVTRM_STAGE(e),
                             FW_FOVTRM_STAGE_BYTES) != TDC_OK) {
            tdc_board_log("foveation stage refused the foveated TRM stream (size)");
            return -1;
        }
        mem[e] = FOVTRM_TRM(e);
    }
    return tdc_fw_trm_setup(si, hz, mem, FW_TRM_BYTES);
}

/* the slot due; it may come FOVEATED (the decoder checked that the packet's
 * slot is the one due) */
static uint32_t fovtrm_needs(uint32_t e, uint32_t frame)
{
    return tdc_fw_trm_needs(e, frame) | KIND_BIT(TDC_LINK_KIND_FOVEATED);
}

/* A FOVEATED packet: tdc_fov_trm remaps the slot's picture in place -- the
 * full slot's disk frame (W x H) or the reduced slot's picture
 * tdc_fw_reduced[e] (rW x rH), where the decoder left the disk pixels --
 * then TRM runs on it as on a FULL or REDUCED picture.  A refusal by the
 * stage writes nothing in the frame buffer (counted as a stage error);
 * TRM's sequencing then shows the next reduced frame without residual, as
 * after a lost full frame. */
static int fovtrm_eye(uint32_t e, uint32_t frame, uint32_t kinds, uint8_t *fb, tdc_res_t **residual)
{
    if (!(kinds & KIND_BIT(TDC_LINK_KIND_FOVEATED))) {
        return tdc_fw_trm_eye(e, frame, kinds, fb, residual);
    }
    const tdc_fov_hdr_t *h = tdc_link_fov(&tdc_fw.dec, e);
    const int red = tdc_link_trm_kind(frame, e) == TDC_LINK_KIND_REDUCED;
    uint32_t rw = 0, rh = 0;
    tdc_link_reduced_size(&tdc_fw.dec, &rw, &rh);
    if (!h) {
        return FW_EYE_REFUSED;
    }
    uint8_t *pic = red ? tdc_fw_reduced[e] : FOV_DISK(e);
    const uint32_t stride = red ? rw * 3u : FW_W * 3u;
    if (tdc_fov_trm_frame(&g_fovtrm[e], h, red, FOV_LP(e), pic, stride) != TDC_OK) {
        return FW_EYE_REFUSED;
    }
    tdc_fw.fov_composed++;
    g_frames[red]++;
    const tdc_status_t st =
        red ? tdc_fw_trm_reduced(e, pic, stride, fb, frame) : tdc_fw_trm_full(e, pic, stride, fb, frame);
    *residual = tdc_trm_residual(&tdc_fw_trm[e]);
    return st == TDC_OK ? FW_EYE_UPDATED : FW_EYE_REFUSED;
}

static void fovtrm_log(const tdc_link_counters_t *c)
{
    (void)c;
    if (tdc_fw.fam == &tdc_fw_family_fov_trm) {
        tdc_fw_log_kv("foveated TRM pictures composed, full slot: ", g_frames[0]);
        tdc_fw_log_kv("foveated TRM pictures composed, reduced slot: ", g_frames[1]);
    }
}

/* (its decoder buffers are the foveation family's: wired there) */
const tdc_fw_family_t tdc_fw_family_fov_trm = {"fov-trm",
                                               TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_FOVEATED,
                                               NULL,
                                               fovtrm_configure,
                                               fovtrm_needs,
                                               fovtrm_eye,
                                               tdc_fw_trm_band,
                                               fovtrm_log};
#else
TDC_FW_FAMILY_NOT_BUILT(fov_trm);
#endif
