/*
 * tdc_render_stream.h - renderer output as a .tdcs link stream (the bytes
 * the link carries), through the link encoder (firmware/tdc_link_encode.h):
 * a STREAM packet whose flags say which stages the stream uses (no motion
 * flag, and no MOTION packets, when nothing in the scene moves), then per
 * refresh: FULL or REDUCED frames + MOTION (per pixel), or SUBFRAME +
 * MOTION (per sample) with a PATTERN bitmap at every frame = 0 mod 4.
 * Pixels: linear light -> RGB888 with tdc_render_linear_to_rgb888 (2.2).
 */
#ifndef TDC_RENDER_STREAM_H
#define TDC_RENDER_STREAM_H

#include <stdint.h>

#include "tdc_render.h"

typedef struct tdc_render_stream tdc_render_stream_t;

typedef enum {
    TDC_RSTREAM_FULL = 0,     /* full frames only */
    TDC_RSTREAM_TRM = 1,      /* full and reduced frames (r of the renderer config) */
    TDC_RSTREAM_SUBFRAMES = 2 /* tile-ordered subframes */
} tdc_rstream_kind_t;

/* Creates the file and writes the STREAM packet.  NULL + message on error. */
tdc_render_stream_t *tdc_render_stream_create(const char *path, tdc_render_t *r, tdc_rstream_kind_t kind, char *err,
                                              size_t errlen);
/* Packets of one rendered refresh: `mode` and the outputs of that
 * tdc_render_frame call (rgb: linear, output size of the mode; mv: Q4, may
 * be NULL for reduced frames).  0, or -1 if the encoder or the file failed. */
int tdc_render_stream_frame(tdc_render_stream_t *s, uint32_t frame, tdc_render_mode_t mode, const float *rgb,
                            const int16_t *mv);
/* Stream flags written in the STREAM packet (TDC_LINK_STREAM_*). */
uint32_t tdc_render_stream_flags(const tdc_render_stream_t *s);
/* Flushes and closes; returns 0 or -1; packets/bytes written if not NULL. */
int tdc_render_stream_close(tdc_render_stream_t *s, uint32_t *packets, uint64_t *bytes);

#endif
