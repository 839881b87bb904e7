/*
 * tdc_fov_link.h - the foveation header of a foveated link packet and its
 * payload layout (docs/foveation.md).  The packet kind itself (magic, CRC,
 * sequence, the decoder's states) belongs to the link decoder; this is the
 * kind-specific part it calls: 32 bytes after the common packet header,
 * little-endian:
 *
 *    0  int32   gaze x, Q8 display pixels
 *    4  int32   gaze y, Q8
 *    8  uint16  alpha, Q8 in [1, 8]          K(x) = x^alpha
 *   10  uint16  delta, Q15 in (0, 1]         buffer downscale: w = floor(delta_q15 W / 2^15), same for h;
 *                                            senders quantise delta up (0.555 -> 18187) so that
 *                                            w = floor(0.555 W) at every panel size here
 *   12  uint16  disk, Q15 in [0, 1]          disk radius / distance to the farthest corner
 *   14  uint16  w                            log-polar buffer width (must be floor(delta W))
 *   16  uint16  h                            log-polar buffer height (must be floor(delta H))
 *   18  uint16  u0                           first column carried (must equal the geometry's)
 *   20  uint32  disk pixels                  (must equal the geometry's count)
 *   24  uint8   flags                        bit 0: motion vectors follow (TAA); others 0
 *   25  uint8   transform                    0: kernel log-polar (above), 1: log-rectilinear
 *                                            (tdc_fov_lr.h); others refused
 *   26  uint16  k_x, Q4 display pixels       log-rectilinear foveal scale per axis, in
 *   28  uint16  k_y, Q4                      [1, 4096) px; 0 for kernel log-polar
 *   30  2 bytes reserved, 0
 *
 * Log-rectilinear: alpha must be 1 (256), w x h is the whole buffer (u0 = 0),
 * rows j = 0..h-1 of texels i = 0..w-1, each the area average of the picture
 * over its footprint (tdc_fov_lr.h); the disk and the vectors as above.
 * Kernel log-polar headers are byte for byte what they were before the
 * transform byte existed (it and k are 0).
 *
 * Payload: the log-polar samples, rows j = 0..h-1 of columns u0..w-1, RGB8;
 * the disk pixels, display rows top to bottom, each row's span
 * (tdc_fov_disk_span), RGB8; with flag bit 0 the motion vectors of the
 * log-polar samples, int16 (dx, dy) Q4, same order.  u0 and the disk count
 * are derived data: a header whose stated values disagree with the ones the
 * parameters give is corrupt (or from another geometry rule) and refused.
 */
#ifndef TDC_FOV_LINK_H
#define TDC_FOV_LINK_H

#include "tdc_fov.h"

#define TDC_FOV_HDR_BYTES 32u
#define TDC_FOV_FLAG_MV 1u

/* Why a foveation header was refused (a counter index: 0 = accepted). */
typedef enum {
    TDC_FOV_HDR_OK = 0,
    TDC_FOV_HDR_ALPHA,    /* alpha outside [1, 8] (log-rectilinear: not 1) */
    TDC_FOV_HDR_DELTA,    /* delta outside (0, 1] */
    TDC_FOV_HDR_DISK,     /* disk fraction above 1 */
    TDC_FOV_HDR_GAZE,     /* gaze more than one screen outside */
    TDC_FOV_HDR_BUFFER,   /* w, h disagree with delta and the configured panel */
    TDC_FOV_HDR_GEOMETRY, /* u0 or the disk count disagree with the parameters */
    TDC_FOV_HDR_RESERVED, /* unknown flag or a non-zero reserved byte */
    TDC_FOV_HDR_PAYLOAD,  /* payload length disagrees with the header */
    TDC_FOV_HDR_TRANSFORM, /* unknown transform */
    TDC_FOV_HDR_SCALE,     /* log-rectilinear foveal scale k outside [1, 4096) px */
    TDC_FOV_HDR_COUNT
} tdc_fov_hdr_err_t;

typedef struct {
    tdc_fov_params_t p;
    uint16_t delta_q15;
    uint8_t flags;
    tdc_fov_geom_t g;       /* the geometry of the parameters (valid when accepted) */
    uint32_t payload_bytes; /* what must follow */
} tdc_fov_hdr_t;

/* Writes the header of the parameters for a width x height panel (u0, the
 * disk count from the geometry).  Returns TDC_OK or TDC_ERR_ARG. */
TDC_MUST_CHECK tdc_status_t tdc_fov_hdr_pack(uint8_t out[TDC_FOV_HDR_BYTES], uint16_t width, uint16_t height,
                                             const tdc_fov_params_t *p, uint16_t delta_q15, uint8_t flags);
/* Checks a received header against the configured panel; fills *h.
 * Returns TDC_FOV_HDR_OK or the first reason it is refused. */
tdc_fov_hdr_err_t tdc_fov_hdr_parse(const uint8_t in[TDC_FOV_HDR_BYTES], uint16_t width, uint16_t height,
                                    tdc_fov_hdr_t *h);
/* The log-polar buffer side for a display side n: floor(delta_q15 n / 2^15). */
uint16_t tdc_fov_lp_size(uint16_t delta_q15, uint16_t n);
/* TDC_FOV_HDR_OK if a payload of len bytes is what the accepted header h
 * announces, else TDC_FOV_HDR_PAYLOAD (truncated or padded packet). */
tdc_fov_hdr_err_t tdc_fov_payload_check(const tdc_fov_hdr_t *h, uint32_t len);
/* Payload bytes of a geometry with or without motion vectors. */
uint32_t tdc_fov_payload_bytes(const tdc_fov_geom_t *g, int with_mv);
/* The payload after the foveation header of an accepted header h (len =
 * h->payload_bytes, checked by the caller) into the stage's buffers: the
 * log-polar samples into lp (rows lp_stride bytes apart, columns [u0, lp_w)
 * written, the others left alone), their motion vectors into mv (int16
 * pairs, rows mv_stride int16 apart; only read with TDC_FOV_FLAG_MV, mv may
 * be NULL without it), the disk pixels into disk (a W x H RGB8 frame, rows
 * disk_stride bytes apart; only the disk spans written).  The link decoder
 * calls it after the packet CRC matched; bounds are the caller's (lp holds
 * lp_h rows of lp_w samples, mv likewise, disk the panel). */
void tdc_fov_unpack(const tdc_fov_hdr_t *h, const uint8_t *payload, uint8_t *lp, size_t lp_stride, int16_t *mv,
                    size_t mv_stride, uint8_t *disk, size_t disk_stride);
/* The inverse, for the sender: payload bytes after the header from the
 * samples in payload order (samples: lp samples then disk pixels, RGB8
 * packed; mv: one int16 pair per lp sample, or NULL without
 * TDC_FOV_FLAG_MV).  Writes tdc_fov_payload_bytes(g, mv != NULL) bytes. */
void tdc_fov_pack_payload(const tdc_fov_geom_t *g, const uint8_t *samples, const int16_t *mv, uint8_t *out);
/* "TDC_FOV_HDR_ALPHA"; "TDC_FOV_HDR_?" outside the enum. */
const char *tdc_fov_hdr_err_name(tdc_fov_hdr_err_t e);

#endif
