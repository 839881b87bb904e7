/*
 * tdc_sim_link.h - the link as the simulator uses it: every payload is
 * encoded into real packets by the host encoder (sim/link) and fed through
 * the firmware decoder (firmware/tdc_link.h), which fills the buffers the
 * firmware stages read.  Packets are counted in bytes on the wire.
 */
#ifndef TDC_SIM_LINK_H
#define TDC_SIM_LINK_H

#include <stdint.h>
#include <stddef.h>

#include "tdc_layer_link.h" /* tdc_layer_frame_t */
#include "tdc_fov_link.h"

typedef struct {
    int w, h, rw, rh;
    int eyes; /* 1, or 2: one stereo stream, packets carry the eye */
    uint32_t flags;
    uint16_t r_num, r_den, hz;
    uint16_t stream_id;
    uint64_t bytes; /* on the wire */
    uint32_t packets;
    uint32_t errors; /* decoder errors (should be 0) */
    double decode_s, encode_s;
    /* decoded buffers per eye (what the firmware reads) */
    uint8_t *full[2], *reduced[2], *subframe[2], *pattern[2];
    int16_t *motion[2], *sample_motion[2];
    tdc_layer_frame_t *layers[2]; /* LAYERS streams: every plane of the four types + falloff */
    uint8_t *fov_lp[2]; /* FOVEATED: the log-polar samples (lp_w x lp_h RGB8) */
    int16_t *fov_mv[2]; /* their motion vectors */
    void *priv;
} tdc_sim_link_t;

/* Stream flags (same bits as TDC_LINK_STREAM_*). */
#define TDC_SIM_LINK_REDUCED 0x0001u
#define TDC_SIM_LINK_SUBFRAMES 0x0002u
#define TDC_SIM_LINK_MOTION 0x0004u
#define TDC_SIM_LINK_SAMPLE_MV 0x0010u
#define TDC_SIM_LINK_LAYERS 0x0020u
#define TDC_SIM_LINK_FOVEATED 0x0040u

int tdc_sim_link_init(tdc_sim_link_t *l, int w, int h, int eyes, uint32_t flags, uint16_t r_num, uint16_t r_den,
                      uint16_t hz);
void tdc_sim_link_free(tdc_sim_link_t *l);
/* (Re)starts the stream: a STREAM packet with a new stream id. */
int tdc_sim_link_stream(tdc_sim_link_t *l);
/* Each returns 0 when the packet was accepted (decoded into l->...). */
int tdc_sim_link_full(tdc_sim_link_t *l, int eye, uint32_t frame, const uint8_t *rgb);
int tdc_sim_link_reduced(tdc_sim_link_t *l, int eye, uint32_t frame, const uint8_t *rgb);
int tdc_sim_link_subframe(tdc_sim_link_t *l, int eye, uint32_t frame, const uint8_t *samples, const int16_t *mv,
                          const uint8_t *pattern);
/* A layered subframe (LAYERS packet: the planes src->present names, vector
 * kinds from src->hdr) and, with pattern, the cycle's PATTERN packet. */
int tdc_sim_link_layers(tdc_sim_link_t *l, int eye, uint32_t frame, const tdc_layer_frame_t *src,
                        const uint8_t *pattern);
/* FOVEATED packet (the link decoder's kind 7): the foveation header of p
 * and the samples in payload order (tdc_fov_link.h), vectors if mv; the
 * decoder puts the disk pixels into full[eye], the rest into fov_lp/fov_mv.
 * 0 when accepted; then *hdr (if not NULL) is the decoder's parsed header.
 * Needs the link in the build (-1 without). */
int tdc_sim_link_foveated(tdc_sim_link_t *l, int eye, uint32_t frame, const tdc_fov_params_t *p, uint16_t delta_q15,
                          const uint8_t *samples, const int16_t *mv, tdc_fov_hdr_t *hdr);
/* The same for a slot of a TRM stream (docs/link-protocol.md §2.2):
 * reduced = 1 sends the reduced frame foveated (p and the samples on the
 * rw x rh grid, packet flag FOV_REDUCED; the decoder puts the disk pixels
 * into reduced[eye]); reduced = 0 is tdc_sim_link_foveated. */
int tdc_sim_link_foveated_slot(tdc_sim_link_t *l, int eye, uint32_t frame, int reduced, const tdc_fov_params_t *p,
                               uint16_t delta_q15, const uint8_t *samples, const int16_t *mv, tdc_fov_hdr_t *hdr);
/* Bytes of a payload sent without a packet kind of its own (interlaced
 * rows): counted as payload + header, not decoded. */
void tdc_sim_link_count_raw(tdc_sim_link_t *l, size_t payload);

#endif
