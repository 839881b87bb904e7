/*
 * tdc_render_trace.h - per-sample tracing passes shared by the frame
 * driver (tdc_render_frame.c) and the probe.  Internal.
 */
#ifndef TDC_RENDER_TRACE_H
#define TDC_RENDER_TRACE_H

#include "tdc_render_internal.h"

/* One traced sample and everything the passes derive from it. */
typedef struct {
    float x, y;             /* image position, full-res px */
    uint32_t dst, k;        /* output slot, sample index within the slot (GT) */
    int px, py;             /* full-res pixel (MV history) */
    int obj;                /* primary hit object, -1 = miss */
    double dir[3];          /* primary direction (not normalised, see tdc_r_cam_ray) */
    double P[3], Q[3];      /* hit: world, object space */
    double N[3], NQ[3];     /* normal: world (facing the ray), object space (raw) */
    double xc, yc;          /* current-frame projection of the hit (= x, y up to rounding) */
    double depth;
    double col[3];
    double mirror;
    /* motion vectors (float px); before the rarely used shadow and mirror
     * fields so the passes every sample goes through share cache lines */
    double mv[2], mvs[2], sw, mvd[2];
    int mv_valid, refl_used, disocc;
    /* shadow tracking (first blocked light sample) */
    int in_shadow, blk_obj, blk_light;
    double BQ[3];
    double loff[3];         /* blocked light sample - light position (0 for point lights) */
    /* mirror chain */
    int nmir;
    int mobj[TDC_R_MAX_BOUNCES];
    double mQ[TDC_R_MAX_BOUNCES][3], mNQ[TDC_R_MAX_BOUNCES][3];
    int robj;               /* final reflected object, -1 = miss */
    double rQ[3], rdir[3];
} rsample_t;

typedef struct {
    tdc_render_t *r;
    const rframe_t *cur, *prev;
    RTCScene top, top_prev;
    struct RTCIntersectContext ctx;
    uint32_t frame;
    int gt;                 /* ground truth: one light sample per pixel sample, stratified by k */
    uint32_t spp;
    int track_blockers;     /* shadow rays return the blocker (shadow MVs) */
    double ms[TDC_STAGE_COUNT];
    uint64_t rays[TDC_RAY_KIND_COUNT];
    int record;
    tdc_render_ray_t *rec;
    size_t nrec, crec;
} rthread_t;

void tdc_r_pass_primary(rthread_t *t, rsample_t *s, int n);
void tdc_r_pass_shade(rthread_t *t, rsample_t *s, int n);
void tdc_r_pass_reflect(rthread_t *t, rsample_t *s, int n);
void tdc_r_pass_mv(rthread_t *t, rsample_t *s, int n);
void tdc_r_pass_mv_reflect(rthread_t *t, rsample_t *s, int n);
void tdc_r_pass_mv_shadow(rthread_t *t, rsample_t *s, int n);
void tdc_r_pass_mv_dual(rthread_t *t, rsample_t *s, int n);
double tdc_r_rand(uint32_t seed, uint32_t frame, uint32_t dst, uint32_t k, uint32_t dim);
double tdc_r_now_ms(void);

#endif
