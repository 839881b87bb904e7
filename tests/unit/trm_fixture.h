/* trm_fixture.h - a TRM instance with its arena, for tests (host, malloc). */
#ifndef TDC_TRM_FIXTURE_H
#define TDC_TRM_FIXTURE_H

#include <stdlib.h>

#include "tdc_panels.h"
#include "tdc_trm.h"

typedef struct {
    tdc_trm_t trm;
    void *mem;
    int w, h;
    uint8_t *in, *out, *red;
} trm_fix_t;

static inline tdc_status_t trm_fix_open(trm_fix_t *f, const tdc_trm_config_t *cfg, const tdc_panel_t *panel)
{
    size_t n = tdc_trm_get_size(cfg);
    f->mem = malloc(n ? n : 1);
    f->w = cfg->width;
    f->h = cfg->height;
    f->in = calloc((size_t)f->w * f->h * 3, 1);
    f->out = calloc((size_t)f->w * f->h * 3, 1);
    f->red = calloc((size_t)f->w * f->h * 3, 1);
    return tdc_trm_init(&f->trm, cfg, panel, f->mem, n);
}

static inline void trm_fix_close(trm_fix_t *f)
{
    free(f->mem);
    free(f->in);
    free(f->out);
    free(f->red);
}

/* Full frame f->in -> f->out. */
static inline tdc_status_t trm_fix_full(trm_fix_t *f)
{
    return tdc_trm_full(&f->trm, f->in, (uint32_t)f->w * 3u, f->out, (uint32_t)f->w * 3u);
}

/* The renderer's reduced frame of f->in (firmware D), then the reduced step. */
static inline tdc_status_t trm_fix_reduced_of_in(trm_fix_t *f)
{
    tdc_status_t s = tdc_trm_downsample(&f->trm, f->in, (uint32_t)f->w * 3u, f->red, (uint32_t)f->trm.rw * 3u);
    if (s != TDC_OK) {
        return s;
    }
    return tdc_trm_reduced(&f->trm, f->red, (uint32_t)f->trm.rw * 3u, f->out, (uint32_t)f->w * 3u);
}

#endif
