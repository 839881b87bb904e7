/*
 * tdc_render.h - the companion CPU renderer (docs/design.md §5, issue 6): Whitted
 * ray tracing on Intel Embree 3, frame by frame, for the simulator.
 *
 *   tdc_render_t *r = tdc_render_open(scene, &cfg, err, sizeof err);
 *   tdc_render_frame(r, frame, TDC_RENDER_FULL, &out, &stats);   // per refresh
 *   tdc_render_close(r);
 *
 * Frame f is the scene at time f / fps; motion vectors of frame f point to
 * frame f - 1.  All colours are linear light (scene radiance, 1.0 = the
 * panel's white); tdc_render_linear_to_rgb888() encodes for 8-bit panels.
 *
 * Motion vectors (common interface): per traced sample an interleaved
 * int16 pair (dx, dy) in Q4 px (1/16 px, clamped to +-2047.9375 px),
 * BACKWARD: the surface point now at sample position p was at p + (dx, dy)
 * in the previous frame.  Pixel (i, j) covers [i, i+1) x [j, j+1); its
 * centre is (i + 0.5, j + 0.5).  Float copies are available for tests.
 *
 * Output sizes per mode (tdc_render_output_size):
 *   FULL          W x H pixels, samples at pixel centres
 *   REDUCED       round(W r) x round(H r), each pixel a Gaussian resolve of a
 *                 supersampled grid (TRM §4.3: not aliased)
 *   SUBFRAME      ceil(W/2) x ceil(H/2) tiles, one traced pixel per 2x2 tile:
 *                 position tdc_ordering_pixel(tile ordering, frame mod 4);
 *                 static pixels jittered by tdc_jitter_offset_q4(frame),
 *                 dynamic ones (a non-zero MV in the pixel's 3x3
 *                 neighbourhood of the renderer's MV history) at the centre.
 *                 Orderings are updated by tdc_ordering_update() at every
 *                 frame = 0 mod 4 (see tdc_render_pattern_bits()).
 *   GROUND_TRUTH  W x H, N stratified samples per pixel (box filter).
 *   FOVEATED      n x 1 samples (thesis §4.2, docs/design.md §4.5; set with
 *                 tdc_render_set_foveation): first the kernel log-polar
 *                 buffer, rows j = 0..h-1 (angle) of columns u0..w-1
 *                 (radius), each a ray through the exact inverse of eq. 2.2
 *                 (r = e^(L K(u / w)), K(x) = x^alpha) of (i + jx, j + jy);
 *                 then the foveal disk, one ray per display pixel centre in
 *                 the disk, rows top to bottom (tdc_fov_disk_span).  This is
 *                 the link payload order; MVs as for FULL.  The geometry (u0,
 *                 the disk) is the firmware's (tdc_fov_geom), so both sides
 *                 agree on every sample.
 */
#ifndef TDC_RENDER_H
#define TDC_RENDER_H

#include <stddef.h>
#include <stdint.h>

#include "ref_fov.h" /* TDC_FOV_LOD_*, ref_fov_lod_cone (ref/ref_fov.c: the one footprint definition) */
#include "tdc_scene.h"

typedef enum {
    TDC_RENDER_FULL = 0,
    TDC_RENDER_REDUCED = 1,
    TDC_RENDER_SUBFRAME = 2,
    TDC_RENDER_GROUND_TRUTH = 3,
    TDC_RENDER_FOVEATED = 4
} tdc_render_mode_t;

/* Foveation of the FOVEATED mode (per frame: the gaze moves). */
typedef struct {
    double gaze_x, gaze_y; /* display pixels; rounded to Q8 like the link header */
    double alpha;          /* K(x) = x^alpha, [1, 8], default 4 */
    double delta;          /* buffer downscale, default 0.555: quantised up to Q15 like the link header,
                               w = floor(delta_q15 W / 2^15) (tdc_fov_lp_size) */
    double disk;           /* disk radius / distance to the farthest corner, [0, 1]; default 0.12443 */
    double jx, jy;         /* sub-sample jitter of the log-polar samples (Halton 2,3 where TAA follows) */
    int jitter;            /* how (jx, jy) moves a sample (ref_fov_lp_jitter): TDC_FOV_JITTER_TEXEL (0,
                              half a buffer texel) or _PIXEL (at most half a display pixel too) */
} tdc_render_fov_t;

typedef struct {
    int width, height;     /* output size; 0 = the scene's resolution */
    int threads;           /* worker threads (pthreads), >= 1 */
    uint32_t seed;         /* all randomness (jitter, light samples) derives from it */
    int max_bounces;       /* mirror / glossy bounces, 0..3 (default 3) */
    int reflect_mv;        /* reflected MVs for mirror hits (TDRT §3.1.2), default 1 */
    int shadow_mv;         /* shadow MVs (Zeng §4.1), default 0 */
    int dual_mv;           /* dual MVs for disocclusions (Zeng §4.3), default 0 */
    int dual_trace;        /* 1: the dual pass (and the shadow pass's falloff) traces a previous-frame ray
                              per candidate even where the previous FULL frame's G-buffer could be read
                              (the check of the lookup, tdc_render_trace.c); default 0 */
    double reduced_factor; /* r of REDUCED frames, (0, 1], default 0.5 */
    int reduced_ss;        /* supersamples per reduced pixel per axis, default 2 */
    double reduced_sigma;  /* Gaussian resolve sigma in full-res px, default 2.5 (TRM §4.3) */
    double reduced_gamma[3]; /* > 0: resolve the supersamples as gamma-coded values v = I^(1/gamma)
                              (clamped to [0, 1]) and return v^gamma, so that the displayed code is the
                              filtered code, as the firmware's D filters codes (TRM §4.2-4.3; pairing
                              the reduced frame with the full frame's compensation needs the same
                              domain); 0 (default): resolve in linear light */
    int gt_samples;        /* N of GROUND_TRUTH, default 64 */
    int record_rays;       /* keep every traced ray of the last frame (benchmark) */
    int tex_filter;        /* box-filter textures over each sample's ray-cone footprint (TDRT §3.1.1,
                              [AMNA*19]), default 1; 0: point-sampled as before */
    int indirect;          /* one diffuse indirect bounce per sample, 6-cone record (Zeng §4.3), default 0 */
    int indirect_reuse;    /* FULL frames: reuse the previous frame's cones at the dual MV (eqs. 9-11), default 0 */
    int fov_lod;           /* FOVEATED, with tex_filter: texture LOD of each log-polar sample (thesis
                              §4.1.2, eqs. 4.1-4.3; tdc_render_fov.c): TDC_FOV_LOD_FOOTPRINT (default), _THESIS
                              or _OFF (one display pixel's cone, as before) */
} tdc_render_config_t;

/* cfg.fov_lod: the cone of a log-polar sample is one display pixel's times
 *  OFF        1;
 *  FOOTPRINT  the sample's cell on the display, max(1, the longer side of
 *             eq. 2.3's cell: radial r L alpha (u/w)^(alpha-1) / w, tangential
 *             2 pi r / h, in display pixels per buffer texel): the texture is
 *             box-filtered over what the sample stands for, so the periphery
 *             does not alias before eq. 4.4 blurs it;
 *  THESIS     2^phi with the thesis's heuristic bias phi = 3 S1((u/w)^alpha)^3
 *             (eq. 4.3, S1 = smoothstep on [0, 1]); without its base bias 0.3
 *             of eq. 4.2, which our full-rate frames do not have either.
 * Disk samples keep one pixel's cone in every mode.  The factor is
 * ref_fov_lod_cone (ref/ref_fov.c), which the simulator's photograph and
 * procedural sources use as their footprint prefilter's box side. */

/* Caller-owned outputs; any pointer may be NULL (that output is not
 * written).  Sizes: n = output pixels (or tiles) of the mode.  FULL and
 * SUBFRAME write all of them; REDUCED and GROUND_TRUTH only rgb.  Primary
 * MVs are computed whenever something moved since the previous frame, even
 * if `mv` is NULL: they feed the MV history that drives the subframe
 * orderings and pixel classes.  Shadow and dual MVs only with their option. */
typedef struct {
    float *rgb;           /* n x 3 linear RGB */
    int16_t *mv;          /* n x 2 Q4 backward MVs (primary, or reflected for mirror hits) */
    float *mv_f;          /* n x 2 the same in float px (before rounding) */
    int16_t *mv_shadow;   /* n x 2 Q4 shadow MVs (= mv where not in a tracked shadow) */
    float *shadow_weight; /* n: Zeng eq. 4 falloff G(theta - pi/2; 0, 0.1), 0 where no shadow MV */
    int16_t *mv_dual;     /* n x 2 Q4 dual MVs (= mv where not disoccluded) */
    float *depth;         /* n: camera-space depth of the primary hit, INFINITY for misses */
    /* Layers (Zeng §4: the frame as separate components, each reused with
     * its own vector; FULL and SUBFRAME).  rgb = vis * shade + refl: exact
     * for grey lights; with coloured lights vis is the luminance ratio and
     * the recombination is off by the lights' colour difference. */
    float *shade;        /* n x 3: local radiance without shadows ((1 - k) base (ambient + all light samples)) */
    float *vis;          /* n: visibility, luminance of shadowed / unshadowed local radiance, [0, 1] (1 unlit, sky) */
    float *refl;         /* n x 3: reflection / glossy layer (k times the reflected radiance, 0 if not reflective) */
    int16_t *mv_surf;    /* n x 2 Q4: primary surface MV (never the reflected one) */
    int16_t *mv_refl;    /* n x 2 Q4: reflected MV (mirror: TDRT §3.1.2; glossy: stochastic, Zeng eq. 5),
                             = mv_surf where there is no reflected hit */
    uint8_t *shadow_src; /* n: 1 = a tracked shadow (blocker and shadow MV valid): shadow-splatting source (§4.1) */
    float *indirect;     /* n x 3: diffuse indirect layer (option indirect; rgb = vis shade + refl + indirect) */
} tdc_render_out_t;

typedef enum {
    TDC_STAGE_SCENE = 0,  /* animation + Embree instance update/commit */
    TDC_STAGE_PRIMARY,    /* primary rays */
    TDC_STAGE_SHADE,      /* textures + direct light + shadow rays */
    TDC_STAGE_REFLECT,    /* mirror bounces (rays, shading of reflected hits) */
    TDC_STAGE_MV,         /* primary motion vectors */
    TDC_STAGE_MV_REFLECT, /* reflected motion vectors */
    TDC_STAGE_MV_SHADOW,  /* shadow motion vectors (+ previous-frame rays for the falloff) */
    TDC_STAGE_MV_DUAL,    /* dual motion vectors (G-buffer lookup, or previous-frame rays) */
    TDC_STAGE_RESOLVE,    /* Gaussian resolve (reduced) / sample averaging (ground truth) */
    TDC_STAGE_ORDERING,   /* tile-ordering update (subframes, frame = 0 mod 4) */
    TDC_STAGE_INDIRECT,   /* option indirect: diffuse bounce, cones, reuse (its rays count as reflect rays) */
    TDC_STAGE_COUNT
} tdc_render_stage_t;

typedef enum { TDC_RAY_PRIMARY = 0, TDC_RAY_SHADOW, TDC_RAY_REFLECT, TDC_RAY_MV, TDC_RAY_KIND_COUNT } tdc_ray_kind_t;

typedef struct {
    double ms[TDC_STAGE_COUNT]; /* CPU milliseconds per stage, summed over threads */
    int ran[TDC_STAGE_COUNT];   /* 1 if the stage ran this frame, 0 if skipped */
    uint64_t rays[TDC_RAY_KIND_COUNT];
    double wall_ms;   /* whole call, wall clock */
    int out_w, out_h; /* output size of the mode */
    int frame_static; /* nothing moved between frame - 1 and frame */
    uint64_t dual_culled; /* samples the dual pass decided without a ray (still camera, outside moving objects) */
    int dual_lookup;      /* 1: the dual and shadow passes read the previous frame's G-buffer (no
                             previous-frame rays) */
} tdc_render_stats_t;

/* What the scene needs (detected at open); stages it does not need are skipped. */
typedef struct {
    int mirrors; /* a visible object has a mirror material -> reflection rays/MVs */
    int motion;  /* something moves (camera, object or light) -> MV work */
    int camera_moves;
    int objects_move;
    int moving_blocker; /* lit scene and an object or light moves -> shadow MVs useful */
    int lights;         /* point/rect lights present -> shadow rays */
    int area_lights;
    uint64_t triangles; /* triangles + quads*2 over all objects */
} tdc_render_features_t;

typedef struct tdc_render tdc_render_t;

void tdc_render_default_config(tdc_render_config_t *cfg);
/* Builds the Embree scenes (copies *scene).  NULL on error with a message. */
tdc_render_t *tdc_render_open(const tdc_scene_t *scene, const tdc_render_config_t *cfg, char *err, size_t errlen);
void tdc_render_close(tdc_render_t *r);
/* Changes the worker thread count (1..64) for the following frames. */
int tdc_render_set_threads(tdc_render_t *r, int threads);
/* Turns ray recording (benchmark) on or off for the following frames. */
void tdc_render_set_record(tdc_render_t *r, int on);
/* Sub-pixel offset (px, |j| <= 0.5) of every FULL sample of the following
 * frames: TAA's per-frame jitter.  Default 0 (pixel centres). */
void tdc_render_set_jitter(tdc_render_t *r, double jx, double jy);
/* Reflected MVs at mirror hits (TDRT §3.1.2) on or off for the following frames (cfg.reflect_mv). */
void tdc_render_set_reflect_mv(tdc_render_t *r, int on);
/* cfg.fov_lod (TDC_FOV_LOD_*) from the next tdc_render_set_foveation on. */
void tdc_render_set_fov_lod(tdc_render_t *r, int mode);
/* The ray cone of FOVEATED sample k (output order: log-polar, then disk) in
 * display pixels' cones (cfg.fov_lod); 0 for k out of range. */
float tdc_render_fov_cone(const tdc_render_t *r, int k);
/* Seed of every random number of the following frames (cfg.seed): glossy
 * lobe samples, area-light samples, ground-truth and reduced-frame
 * stratification, the indirect bounce. */
void tdc_render_set_seed(tdc_render_t *r, uint32_t seed);

/* Renders frame `frame` in `mode`.  Returns 0, or -1 on a bad argument. */
int tdc_render_frame(tdc_render_t *r, uint32_t frame, tdc_render_mode_t mode, const tdc_render_out_t *out,
                     tdc_render_stats_t *stats);

void tdc_render_output_size(const tdc_render_t *r, tdc_render_mode_t mode, int *w, int *h);
/* Sets the foveation of the following FOVEATED frames.  Returns 0, or -1 on
 * parameters the firmware would refuse (alpha, disk, gaze more than one
 * screen outside).  *lp_samples / *disk_pixels (may be NULL): the counts. */
int tdc_render_set_foveation(tdc_render_t *r, const tdc_render_fov_t *f, int *lp_samples, int *disk_pixels);
/* Sets the positions (image px, x y pairs, n >= 1) the following FOVEATED
 * frames trace instead of the foveation's: any sample set, e.g. the
 * simulator's subframe positions for layered sources.  Outputs per sample
 * as for FOVEATED, plus the layers and the shadow and dual MVs.  0, or -1
 * for a bad argument (positions beyond 1e6 px). */
int tdc_render_set_samples(tdc_render_t *r, const double *xy, int n);
/* Halton(2,3) jitter of frame f in [-0.5, 0.5)^2 (the thesis's sub-pixel jitter, §4.3.2). */
void tdc_render_halton(uint32_t f, double *jx, double *jy);
void tdc_render_get_features(const tdc_render_t *r, tdc_render_features_t *f);
/* 1 if nothing moves between frame - 1 and frame (the stream can say static). */
int tdc_render_frame_static(tdc_render_t *r, uint32_t frame);
const tdc_scene_t *tdc_render_scene(const tdc_render_t *r);

/* Tile orderings (1 bit per tile, tdc_ordering.h layout) used by subframes,
 * and the full-res Q4 MV history they are decided from (W x H x 2). */
const uint8_t *tdc_render_pattern_bits(const tdc_render_t *r);
void tdc_render_set_pattern_bits(tdc_render_t *r, const uint8_t *bits);
const int16_t *tdc_render_mv_history(const tdc_render_t *r);

/* One ray through image position (x, y) of `frame`, for tests and tools. */
typedef struct {
    int hit;     /* primary ray hit an object */
    int obj;     /* object index */
    double q[3]; /* hit point in the object's local space */
    double world[3];
    double mv[2];   /* the MV the renderer outputs (float px) */
    int mirror_hit; /* primary surface is a mirror and a reflected object was hit */
    int refl_obj;   /* last reflected non-mirror object */
    double refl_q[3];
    int in_shadow; /* a light (sample) is blocked: the first such one is tracked */
    int blocker_obj;
    double blocker_q[3];
    double shadow_mv[2];
    double shadow_weight;
    double dual_mv[2];
    int disoccluded;
    double rgb[3]; /* linear radiance of the sample */
    /* reflected / glossy MV (the layers' mv_refl): refl_mv_ok = 1 when the
     * sample has one; for glossy surfaces refl_mv is the stochastic eq. 5
     * sample, refl_mu its centre (the previous virtual image, as an MV) and
     * refl_axes the two image half-axes (x, y, x, y) of its Gaussian */
    int refl_mv_ok;
    double refl_mv[2], refl_mu[2], refl_axes[4];
    double shade[3], vis, refl[3]; /* layers */
    double indirect[3];            /* option indirect, without reuse */
} tdc_render_probe_t;
int tdc_render_probe(tdc_render_t *r, uint32_t frame, double x, double y, tdc_render_probe_t *p);

/* Screen position at `frame` of a point given in object `obj`'s local space
 * (obj = -1: world space).  Returns 0, or -1 if behind the camera. */
int tdc_render_project(tdc_render_t *r, uint32_t frame, int obj, const double q[3], double *x, double *y);
/* Screen position of the mirror image of object point q seen through the
 * mirror plane (mirror object mobj, local point mq, local normal from the
 * renderer); for reflection tests. */
int tdc_render_project_reflected(tdc_render_t *r, uint32_t frame, int mobj, const double mq[3], int obj,
                                 const double q[3], double *x, double *y);

/* Linear light -> 8-bit code: code = round(255 * clamp(v, 0, 1)^(1/2.2))
 * (the "2.2 display" transfer the panels approximate). n = pixels. */
void tdc_render_linear_to_rgb888(const float *lin, size_t n, uint8_t *rgb);
int tdc_render_write_png(const char *path, const float *lin, int w, int h, char *err, size_t errlen);

/* Rays of the last frame rendered with record_rays (benchmark replay). */
typedef struct {
    float org[3], tnear;
    float dir[3], tfar; /* tfar: the ray's original extent */
    uint32_t kind;      /* tdc_ray_kind_t */
    uint32_t flags;     /* TDC_RAY_PREV_FRAME, TDC_RAY_OCCLUSION */
} tdc_render_ray_t;
#define TDC_RAY_PREV_FRAME 1u /* traced in the previous frame's scene (MV rays) */
#define TDC_RAY_OCCLUSION 2u  /* rtcOccluded1 query (else rtcIntersect1) */
const tdc_render_ray_t *tdc_render_recorded_rays(const tdc_render_t *r, size_t *count);
/* The committed Embree scene (RTCScene) of `frame`, for bare-Embree comparisons. */
void *tdc_render_embree_scene(tdc_render_t *r, uint32_t frame);

const char *tdc_render_stage_name(tdc_render_stage_t s);
const char *tdc_render_mode_name(tdc_render_mode_t m);

#endif /* TDC_RENDER_H */
