/*
 * tdc_link_sink.c - see tdc_link_sink.h.
 */
#include "tdc_link_sink.h"

#include <string.h>

int tdc_link_sink_init(tdc_link_sink_t *s, uint16_t w, uint16_t h)
{
    if (w == 0 || h == 0 || w > TDC_LINK_SINK_MAX_W || h > TDC_LINK_SINK_MAX_H) return -1;
    tdc_link_buffers_t b;
    memset(&b, 0, sizeof b);
    b.staging = s->staging;
    b.staging_bytes = sizeof s->staging;
    b.full[0] = s->full;
    b.full_stride = (uint32_t)w * 3u;
    b.reduced[0] = s->reduced;
    b.reduced_bytes = sizeof s->reduced;
    b.subframe[0] = s->subframe;
    b.motion[0] = s->motion;
    b.sample_motion[0] = s->sample_motion;
    b.pattern[0] = s->pattern;
    b.fov_lp[0] = s->fov_lp;
    b.fov_lp_bytes = sizeof s->fov_lp;
    b.fov_mv[0] = s->fov_mv;
    b.fov_mv_count = sizeof s->fov_mv / sizeof s->fov_mv[0];
    tdc_link_config_t cfg = {w, h, 1};
    return tdc_link_decoder_init(&s->dec, &cfg, &b) == TDC_OK ? 0 : -1;
}

void tdc_link_sink_feed(void *ctx, const uint8_t *data, uint32_t len, tdc_usbp_sink_report_t *d)
{
    tdc_link_sink_t *s = ctx;
    size_t off = 0;
    for (;;) {
        tdc_link_event_t ev;
        off += tdc_link_feed(&s->dec, data + off, len - off, &ev);
        if (ev.type == TDC_LINK_EV_NONE) break; /* every byte of this transfer consumed, no event pending */
        if (ev.type == TDC_LINK_EV_ERROR) {
            if (ev.error == TDC_LINK_ERR_CRC || ev.error == TDC_LINK_ERR_HEADER_CRC)
                d->crc_errors++;
            else
                d->malformed++;
        } else if (ev.kind == TDC_LINK_KIND_FULL || ev.kind == TDC_LINK_KIND_REDUCED ||
                   ev.kind == TDC_LINK_KIND_FOVEATED) {
            d->frames++;
        }
    }
}
