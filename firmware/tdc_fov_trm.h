/*
 * tdc_fov_trm.h - foveated TRM streams (
 * docs/link-protocol.md §2.2, docs/foveation.md "Foveated TRM"): the
 * remap of both pictures of a TRM stream whose frames are foveated.
 *
 * A FOVEATED packet fills the FULL slot (its geometry on the W x H panel)
 * or, with TDC_LINK_PKT_FOV_REDUCED, the REDUCED slot (geometry on the
 * rW x rH reduced grid).  The decoder leaves the log-polar samples in
 * fov_lp[eye] and the disk pixels in the slot's picture (full[eye], or
 * reduced[eye] with rows rW * 3 bytes apart); tdc_fov_trm_frame() remaps
 * over that picture in place (the stage reads each disk pixel before it
 * writes it), after which TRM runs exactly as for a FULL or REDUCED
 * packet (tdc_trm_full_seq / tdc_trm_reduced_seq).
 *
 * Two tdc_fov instances, one per grid, so that each keeps its radial table
 * and column reciprocals across frames (the tables are keyed on R, alpha
 * and lp_w, which differ between the grids: one shared instance would
 * rebuild them every frame).  No TAA: the decoder refuses vectors in a TRM
 * stream (each instance sees every other frame of its eye).
 *
 * Memory, compile time per panel: TDC_FOV_TRM_MEM_BYTES(W, H, rW, rH); the
 * reduced grid is never larger than the panel (TRM's r < 1), so
 * TDC_FOV_TRM_MEM_BYTES(W, H, W, H) bounds every ratio.  Stage elision: a
 * stream without foveated packets never calls any of this.
 */
#ifndef TDC_FOV_TRM_H
#define TDC_FOV_TRM_H

#include "tdc_fov.h"
#include "tdc_fov_link.h"

typedef struct {
    tdc_fov_t full;    /* W x H: the full slot's pictures */
    tdc_fov_t reduced; /* rW x rH: the reduced slot's */
} tdc_fov_trm_t;

#define TDC_FOV_TRM_MEM_BYTES(W, H, RW, RH) (TDC_FOV_MEM_BYTES(W, H, 0) + TDC_FOV_MEM_BYTES(RW, RH, 0))

/* Arena bytes for a W x H panel with an rw x rh reduced grid (rw <= w,
 * rh <= h); 0 for an invalid size. */
size_t tdc_fov_trm_get_size(uint16_t w, uint16_t h, uint16_t rw, uint16_t rh);
/* mem: caller-owned, TDC_ARENA_ALIGN-aligned, tdc_fov_trm_get_size() bytes.
 * TDC_ERR_ARG / TDC_ERR_SIZE as tdc_fov_init, or a reduced grid larger than
 * the panel (TDC_ERR_SIZE). */
TDC_MUST_CHECK tdc_status_t tdc_fov_trm_init(tdc_fov_trm_t *st, uint16_t w, uint16_t h, uint16_t rw, uint16_t rh,
                                             void *mem, size_t mem_bytes);
/* One foveated picture as the decoder left it: h = tdc_link_fov(dec, eye)
 * on the packet's event, reduced = the event's TDC_LINK_PKT_FOV_REDUCED,
 * lp = fov_lp[eye] (rows h->p.lp_w * 3 bytes apart), pic = the slot's
 * picture holding the disk (full[eye] or reduced[eye]), rows stride bytes
 * apart; the remap is written over pic.  TDC_ERR_SIZE if h's grid is not
 * the slot's, TDC_ERR_ARG for vectors (no TAA here) or as tdc_fov_frame. */
TDC_MUST_CHECK tdc_status_t tdc_fov_trm_frame(tdc_fov_trm_t *st, const tdc_fov_hdr_t *h, int reduced,
                                              const uint8_t *lp, uint8_t *pic, size_t stride);
/* Forget both instances' history (a new stream). */
void tdc_fov_trm_reset(tdc_fov_trm_t *st);

#endif /* TDC_FOV_TRM_H */
