/*
 * tdc_fw_plain.c - the plain stream family of the board frame loop (no
 * family flag; tdc_fw_family.h): a FULL picture per eye and frame, unpacked
 * by the loop into the eye's part of the frame buffer and shown as it is.
 * In every build.
 */
#include "tdc_fw_family.h"

static uint32_t plain_needs(uint32_t e, uint32_t frame)
{
    (void)e, (void)frame;
    return KIND_BIT(TDC_LINK_KIND_FULL);
}

static int plain_eye(uint32_t e, uint32_t frame, uint32_t kinds, uint8_t *fb, tdc_res_t **residual)
{
    (void)e, (void)frame, (void)fb, (void)residual;
    return (kinds & KIND_BIT(TDC_LINK_KIND_FULL)) ? FW_EYE_UPDATED : FW_EYE_NOTHING;
}

/* (the loop unpacked the band: nothing else to do) */
static tdc_status_t plain_band(uint32_t e, uint32_t frame, uint32_t kind, const tdc_band_hdr_t *bh, uint8_t *fb,
                               uint32_t *done, uint32_t *covered, tdc_res_t **residual)
{
    (void)e, (void)frame, (void)kind, (void)bh, (void)fb, (void)done, (void)covered, (void)residual;
    return TDC_OK;
}

const tdc_fw_family_t tdc_fw_family_plain = {"plain", 0u, NULL, NULL, plain_needs, plain_eye, plain_band, NULL};
