/*
 * tdc_fw_trm.h - what the foveated TRM family (tdc_fw_fov_trm.c) takes from
 * the TRM family (tdc_fw_trm.c): TRM's instances, their set-up in a given
 * arena, and TRM's per-eye and per-band work on FULL and REDUCED pictures.
 * Internal to firmware/board; only with TDC_CFG_TRM.
 */
#ifndef TDC_FW_TRM_H
#define TDC_FW_TRM_H

#include "tdc_fw_family.h"

extern tdc_trm_t tdc_fw_trm[FW_EYES];

/* TRM for the stream in each eye's mem[e] (bytes each); 0, or -1 (logged) */
int tdc_fw_trm_setup(const tdc_link_stream_info_t *si, uint16_t hz, uint8_t *const mem[], size_t bytes);
uint32_t tdc_fw_trm_needs(uint32_t e, uint32_t frame);
/* A whole FULL (in place allowed) or REDUCED picture of eye e through TRM
 * into fb: tdc_trm_full_seq / tdc_trm_reduced_seq, as row bands on the
 * board's row workers when the loop is built with several. */
tdc_status_t tdc_fw_trm_full(uint32_t e, const uint8_t *in, uint32_t stride, uint8_t *fb, uint32_t frame);
tdc_status_t tdc_fw_trm_reduced(uint32_t e, const uint8_t *in, uint32_t stride, uint8_t *fb, uint32_t frame);
int tdc_fw_trm_eye(uint32_t e, uint32_t frame, uint32_t kinds, uint8_t *fb, tdc_res_t **residual);
tdc_status_t tdc_fw_trm_band(uint32_t e, uint32_t frame, uint32_t kind, const tdc_band_hdr_t *bh, uint8_t *fb,
                             uint32_t *done, uint32_t *covered, tdc_res_t **residual);

#endif
