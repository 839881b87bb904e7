/*
 * tdc_link_sink.h - the firmware's link decoder (firmware/tdc_link.h) as the
 * bulk OUT sink of the USB protocol (tdc_usbp_config_t.sink), for emulated
 * boards: the umockdev board (tests/usb) and the FunctionFS gadget of
 * `make test-vm` (tests/vm).  Buffers are static, sized for a small test
 * panel of at most TDC_LINK_SINK_MAX_W x TDC_LINK_SINK_MAX_H, one eye,
 * for every kind a board takes, FOVEATED streams included (any delta up to
 * 1, with vectors; the disk pixels go into `full`).
 */
#ifndef TDC_LINK_SINK_H
#define TDC_LINK_SINK_H

#include <stdint.h>

#include "tdc_link.h"
#include "tdc_usbproto.h"

#define TDC_LINK_SINK_MAX_W 64u
#define TDC_LINK_SINK_MAX_H 64u

typedef struct {
    tdc_link_decoder_t dec;
    /* the largest payload: a FOVEATED one at delta 1 with vectors and a
     * disk covering the screen (header + 3 + 4 + 3 B/px) */
    uint8_t staging[TDC_LINK_STAGING_BYTES(TDC_LINK_SINK_MAX_W, TDC_LINK_SINK_MAX_H) + TDC_FOV_HDR_BYTES +
                    (size_t)TDC_LINK_SINK_MAX_W * TDC_LINK_SINK_MAX_H * 6u];
    uint8_t full[TDC_LINK_FRAME_BYTES(TDC_LINK_SINK_MAX_W, TDC_LINK_SINK_MAX_H)];
    uint8_t reduced[TDC_LINK_FRAME_BYTES(TDC_LINK_SINK_MAX_W, TDC_LINK_SINK_MAX_H)];
    uint8_t subframe[TDC_LINK_SUBFRAME_BYTES(TDC_LINK_SINK_MAX_W, TDC_LINK_SINK_MAX_H)];
    int16_t motion[TDC_LINK_MOTION_COUNT(TDC_LINK_SINK_MAX_W, TDC_LINK_SINK_MAX_H)];
    int16_t sample_motion[TDC_LINK_SAMPLE_MOTION_COUNT(TDC_LINK_SINK_MAX_W, TDC_LINK_SINK_MAX_H)];
    uint8_t pattern[TDC_PATTERN_BYTES(TDC_LINK_SINK_MAX_W, TDC_LINK_SINK_MAX_H)];
    uint8_t fov_lp[TDC_LINK_FRAME_BYTES(TDC_LINK_SINK_MAX_W, TDC_LINK_SINK_MAX_H)];
    int16_t fov_mv[TDC_LINK_MOTION_COUNT(TDC_LINK_SINK_MAX_W, TDC_LINK_SINK_MAX_H)];
} tdc_link_sink_t;

/* 0 on success, -1 if w x h exceeds the static buffers or the decoder refuses. */
int tdc_link_sink_init(tdc_link_sink_t *s, uint16_t w, uint16_t h);

/* The tdc_usbp_sink_fn: ctx is the tdc_link_sink_t.  CRC and header-CRC
 * rejections count as crc_errors, every other rejection as malformed, each
 * accepted FULL, REDUCED or FOVEATED frame packet as one frame. */
void tdc_link_sink_feed(void *ctx, const uint8_t *data, uint32_t len, tdc_usbp_sink_report_t *d);

#endif
