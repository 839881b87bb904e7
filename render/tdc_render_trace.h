/*
 * tdc_render_trace.h - per-sample tracing passes shared by the frame
 * driver (tdc_render_frame.c) and the probe.  Internal.
 */
#ifndef TDC_RENDER_TRACE_H
#define TDC_RENDER_TRACE_H

#include "tdc_render_internal.h"

/* One traced sample and everything the passes derive from it.  The fields
 * every sample goes through (placement, primary hit, shading, primary MV)
 * come first and fill 4 cache lines; shadow, dual and mirror-chain fields
 * follow and are only touched by the passes that need them. */
typedef struct {
    _Alignas(64) float x; /* image position, full-res px (every sample starts a cache line) */
    float y;
    uint32_t dst, k;                          /* output slot, sample index within the slot (GT) */
    int px, py;                               /* full-res pixel (MV history) */
    int obj;                                  /* primary hit object, -1 = miss */
    int in_shadow, nmir, mv_valid, refl_used; /* flags: tracked shadow, mirror chain length, MV */
    float hit_t, hit_ng[3];                   /* Embree's primary hit: ray parameter, raw object-space normal */
    float cone_k; /* this sample's ray cone in display pixels' cones (FOVEATED: cfg.fov_lod; else 1) */
    double dir[3];                            /* primary direction (not normalised, see tdc_r_cam_ray) */
    double P[3], Q[3];                        /* hit: world, object space */
    double N[3], NQ[3];                       /* normal: world (facing the ray), object space (raw) */
    double depth;
    double col[3];
    double mirror;
    double mv[2];  /* motion vector (float px) */
    double xc, yc; /* current-frame projection of the hit (= x, y up to rounding) */
    double tu, tv; /* texture coordinates of an unlit textured primary hit (shade pass) */
    /* rarely used: shadow and dual MVs, shadow tracking, mirror chain */
    double mvs[2], sw, mvd[2];
    int disocc;
    int blk_obj, blk_light; /* shadow tracking (first blocked light sample) */
    double BQ[3];
    double loff[3]; /* blocked light sample - light position (0 for point lights) */
    int mobj[TDC_R_MAX_BOUNCES];
    double mQ[TDC_R_MAX_BOUNCES][3], mNQ[TDC_R_MAX_BOUNCES][3];
    int robj; /* final reflected object, -1 = miss */
    double rQ[3], rdir[3];
    /* glossy reflection (Zeng §4.2): GGX alpha of the primary surface, the
     * reflected / stochastic glossy MV (eq. 5) with its centre and the image
     * half-axes of its Gaussian, and the primary MV it may replace in mv */
    double rough;
    double mvr[2], mvr_mu[2], mvr_ax[4], mvsurf[2];
    int mvr_ok;
    /* layers (Zeng §4): unshadowed local shading, visibility, reflection */
    double lshade[3], vis, refl[3];
    double ind[3]; /* option indirect: the diffuse indirect light added to col */
} rsample_t;

typedef struct {
    tdc_render_t *r;
    const rframe_t *cur, *prev;
    RTCScene top, top_prev;
    struct RTCIntersectContext ctx;
    uint32_t frame;
    int gt; /* ground truth: one light sample per pixel sample, stratified by k */
    uint32_t spp;
    int track_blockers;              /* shadow rays return the blocker (shadow MVs) */
    double cone;                     /* ray-cone spread angle of one sample, rad (0: point-sampled textures) */
    double tex_fw;                   /* texture footprint of the surface being shaded (tdc_r_tex_footprint) */
    int layers;                      /* fill the layer fields (unshadowed shading, visibility, reflection, mvr) */
    /* dual MVs under a still camera: screen rectangles (x0, y0, x1, y1) of
     * the moving objects in the previous frame; a still surface whose pixel
     * is outside all of them cannot have been occluded (no ray).  ndual_rect
     * < 0: no culling (camera moved, or a moving object behind the camera) */
    int ndual_rect;
    float dual_rect[TDC_SCENE_MAX_OBJECTS][4];
    uint64_t dual_culled; /* samples the rectangles spared a ray */
    /* the previous FULL frame's G-buffer (W x H) and its sample jitter:
     * the dual pass reads it instead of tracing; NULL: it traces */
    const tdc_r_gpix_t *gb_prev;
    float gb_jx, gb_jy;
    int have_mv, have_dual;         /* the MV / dual passes ran (indirect reuse follows mv / mvd) */
    float *cone_cur;                /* indirect_reuse: this frame's cone history (W x H), or NULL */
    const float *cone_prev;         /* the previous frame's, or NULL (no history) */
    uint64_t ticks[TDC_STAGE_COUNT]; /* stage time in stamp() ticks (tdc_render_frame.c) */
    uint64_t rays[TDC_RAY_KIND_COUNT];
    int record;
    tdc_render_ray_t *rec;
    size_t nrec, crec;
    /* the shadow rays of a tile's shade pass, traced in packets of 16
     * (tdc_r_pass_shade): the ray, its light's contribution if unblocked,
     * the answer; and how many rays each sample of the tile has */
    struct tdc_r_shadow *sq;
    size_t nsq, csq;
    int *sq_cnt;
    size_t csq_cnt;
    struct tdc_r_dual *dq; /* the dual pass's previous-frame rays of a tile */
    size_t cdq;
} rthread_t;

/* Frees what the passes allocated in t (recorded rays, shadow queue). */
void tdc_r_thread_free(rthread_t *t);

void tdc_r_pass_primary(rthread_t *t, rsample_t *s, int n);
void tdc_r_pass_shade(rthread_t *t, rsample_t *s, int n);
void tdc_r_pass_reflect(rthread_t *t, rsample_t *s, int n);
void tdc_r_pass_mv(rthread_t *t, rsample_t *s, int n);
void tdc_r_pass_mv_reflect(rthread_t *t, rsample_t *s, int n);
void tdc_r_pass_mv_shadow(rthread_t *t, rsample_t *s, int n);
void tdc_r_pass_mv_dual(rthread_t *t, rsample_t *s, int n);
void tdc_r_pass_indirect(rthread_t *t, rsample_t *s, int n);
/* Random-number key of a sample: its pixel (same light samples in every mode and in probes). */
/* Texture footprint of sample a's cone after dist along d on a surface of
 * object-space normal NQ (tdc_r_tex_footprint), with the sample's own cone
 * (cone_k: the FOVEATED log-polar LOD); 0 with point-sampled textures. */
static inline double tdc_r_sample_fw(const rthread_t *t, const rsample_t *a, double dist, const double d[3],
                                     const double NQ[3], const double *minv)
{
    return t->cone > 0 ? tdc_r_tex_footprint(t->cone * a->cone_k, dist, d, NQ, minv) : 0;
}

static inline uint32_t tdc_r_rng_key(const rsample_t *a)
{
    return (uint32_t)a->py * 65536u + (uint32_t)a->px;
}
/* One secondary ray from surface point P (normal N facing the ray's side)
 * along d: the local (direct) radiance of what it hits, with shadow rays
 * (random salt), or the background.  Counted as a reflect ray. */
void tdc_r_trace_local(rthread_t *t, const double P[3], const double N[3], const double d[3], const rsample_t *a,
                       uint32_t salt, double L[3]);
double tdc_r_ggx_sample(const double d[3], const double N[3], double alpha, double u1, double u2, double out[3]);
double tdc_r_rand(uint32_t seed, uint32_t frame, uint32_t dst, uint32_t k, uint32_t dim);
double tdc_r_now_ms(void);

#endif
