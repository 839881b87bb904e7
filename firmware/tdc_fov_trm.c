/*
 * tdc_fov_trm.c - foveated TRM streams: one tdc_fov instance per slot grid
 * (tdc_fov_trm.h).  No arithmetic of its own: the remap is tdc_fov_frame's.
 */
#include "tdc_fov_trm.h"

size_t tdc_fov_trm_get_size(uint16_t w, uint16_t h, uint16_t rw, uint16_t rh)
{
    const tdc_fov_config_t cf = {w, h, 0}, cr = {rw, rh, 0};
    const size_t a = tdc_fov_get_size(&cf), b = tdc_fov_get_size(&cr);
    /* both are multiples of TDC_ARENA_ALIGN (tdc_arena.h): the second
     * arena starts aligned */
    return a && b && rw <= w && rh <= h ? a + b : 0u;
}

tdc_status_t tdc_fov_trm_init(tdc_fov_trm_t *st, uint16_t w, uint16_t h, uint16_t rw, uint16_t rh, void *mem,
                              size_t mem_bytes)
{
    const tdc_fov_config_t cf = {w, h, 0}, cr = {rw, rh, 0};
    if (!st || !mem) {
        return TDC_ERR_ARG;
    }
    if (rw > w || rh > h) {
        return TDC_ERR_SIZE;
    }
    const size_t a = tdc_fov_get_size(&cf);
    if (!a) {
        return TDC_ERR_ARG;
    }
    if (mem_bytes < a) {
        return TDC_ERR_SIZE;
    }
    const tdc_status_t s = tdc_fov_init(&st->full, &cf, mem, a);
    return s != TDC_OK ? s : tdc_fov_init(&st->reduced, &cr, (uint8_t *)mem + a, mem_bytes - a);
}

tdc_status_t tdc_fov_trm_frame(tdc_fov_trm_t *st, const tdc_fov_hdr_t *h, int reduced, const uint8_t *lp,
                               uint8_t *pic, size_t stride)
{
    if (!st || !h) {
        return TDC_ERR_ARG;
    }
    tdc_fov_t *f = reduced ? &st->reduced : &st->full;
    if (h->g.width != f->cfg.width || h->g.height != f->cfg.height) {
        return TDC_ERR_SIZE;
    }
    if (h->flags & TDC_FOV_FLAG_MV) {
        return TDC_ERR_ARG;
    }
    return tdc_fov_frame(f, &h->p, lp, (size_t)h->p.lp_w * 3u, 0, 0, pic, stride, 0u, pic, stride);
}

void tdc_fov_trm_reset(tdc_fov_trm_t *st)
{
    tdc_fov_reset(&st->full);
    tdc_fov_reset(&st->reduced);
}
