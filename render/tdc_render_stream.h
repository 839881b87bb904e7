/*
 * tdc_render_stream.h - renderer output as a .tdcs link stream (the bytes
 * the link carries), through the link encoder (firmware/tdc_link_encode.h):
 * a STREAM packet whose flags say which stages the stream uses (no motion
 * flag, and no MOTION packets, when nothing in the scene moves), then per
 * refresh: FULL or REDUCED frames + MOTION (per pixel), or SUBFRAME +
 * MOTION (per sample) with a PATTERN bitmap at every frame = 0 mod 4.
 * Pixels: linear light -> RGB888 with tdc_render_linear_to_rgb888 (2.2).
 *
 * Layered subframes (TDC_RSTREAM_LAYERS, issue 16, docs/link-protocol.md
 * §2.1): per SUBFRAME render one LAYERS packet instead of SUBFRAME +
 * MOTION, with the layers the scene needs (stage elision):
 *   SHADING     always: the unshadowed shading (`shade`) when VISIBILITY
 *               is sent, else everything the other layers do not carry;
 *               vectors DUAL with the dual option (the dual MV where the
 *               pixel was disoccluded, the surface MV elsewhere), else SURFACE
 *   VISIBILITY  with shadow MVs on a scene with a moving blocker: round(255
 *               vis), vectors SHADOW (the shadow MV at tracked shadows, the
 *               surface MV elsewhere: the controller splats), + the FALLOFF
 *               plane (eq. 4 weight in Q15 at tracked shadows, 1 elsewhere)
 *   GLOSSY      with mirror or glossy materials: `refl`, vectors GLOSSY (a
 *               material with roughness > 0) or MIRROR (mv_refl)
 *   INDIRECT    with the indirect option: `indirect`, vectors DUAL / SURFACE
 * A scene that needs none of VISIBILITY, GLOSSY, INDIRECT sends SHADING
 * alone (the SUBFRAME + MOTION bytes plus a 16-byte header in one packet).
 */
#ifndef TDC_RENDER_STREAM_H
#define TDC_RENDER_STREAM_H

#include <stdint.h>

#include "tdc_render.h"

typedef struct tdc_render_stream tdc_render_stream_t;

typedef enum {
    TDC_RSTREAM_FULL = 0,     /* full frames only */
    TDC_RSTREAM_TRM = 1,      /* full and reduced frames (r of the renderer config) */
    TDC_RSTREAM_SUBFRAMES = 2, /* tile-ordered subframes */
    TDC_RSTREAM_LAYERS = 3     /* layered subframes (LAYERS packets) */
} tdc_rstream_kind_t;

/* Creates the file and writes the STREAM packet.  NULL + message on error. */
tdc_render_stream_t *tdc_render_stream_create(const char *path, tdc_render_t *r, tdc_rstream_kind_t kind, char *err,
                                              size_t errlen);
/* Packets of one rendered refresh: `mode` and the outputs of that
 * tdc_render_frame call (rgb: linear, output size of the mode; mv: Q4, may
 * be NULL for reduced frames).  0, or -1 if the encoder or the file failed. */
int tdc_render_stream_frame(tdc_render_stream_t *s, uint32_t frame, tdc_render_mode_t mode, const float *rgb,
                            const int16_t *mv);
/* Packets of one layered subframe (TDC_RSTREAM_LAYERS): `out` from the
 * SUBFRAME render of that frame with the planes the layer set needs
 * (tdc_render_stream_layer_set): rgb, mv, mv_surf, and per layer shade +
 * vis + mv_shadow + shadow_weight + shadow_src, refl + mv_refl, indirect,
 * and mv_dual with the dual option.  0, or -1 if a plane is missing or the
 * encoder or the file failed. */
int tdc_render_stream_layers(tdc_render_stream_t *s, uint32_t frame, const tdc_render_out_t *out);
/* The LAYERS packet flags (TDC_LAYER_PKT_*) of a layered stream, 0 for
 * the other kinds. */
uint32_t tdc_render_stream_layer_set(const tdc_render_stream_t *s);
/* Stream flags written in the STREAM packet (TDC_LINK_STREAM_*). */
uint32_t tdc_render_stream_flags(const tdc_render_stream_t *s);
/* Flushes and closes; returns 0 or -1; packets/bytes written if not NULL. */
int tdc_render_stream_close(tdc_render_stream_t *s, uint32_t *packets, uint64_t *bytes);

#endif
