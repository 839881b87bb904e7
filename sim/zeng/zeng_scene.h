/*
 * zeng_scene.h - the analytic double-precision scenes of the Zeng et al.
 * evaluation ("Temporally Reliable Motion Vectors for Real-time Ray
 * Tracing", EG 2021; sim/zeng/README.md): planes, boxes and spheres moving
 * by translation, a pinhole camera moving on a line, one rectangular area
 * light (three in the lights scene), traced by hand so that every quantity
 * the paper's vectors need (blocker and light sample positions, lobe hit
 * points, the previous frame's G-buffer) is exact, and so that a
 * 1024-sample ground truth at 160x120 takes seconds on one core.
 *
 * Each scene exercises one effect, as the paper's figures do (Fig. 8 shows
 * only the shadowed direct light, Fig. 11 the glossy reflection, Fig. 12 the
 * indirect light):
 *   fence     Fig. 8: a fence moving fast sideways between an area light and
 *             the floor; final = shading * visibility + ambient.  Noisy
 *             layer: visibility (one shadow ray to a random light point).
 *   glossy    Fig. 11: a glossy floor (Gaussian lobe, sigma 0.08 rad around
 *             the mirror direction) under textured boxes and spheres, the
 *             camera moving fast sideways; final = diffuse + glossy.  Noisy
 *             layer: glossy (one lobe sample).
 *   occlusion Figs. 1 right / 12 (PICA-like): boxes moving left to right in
 *             front of a wall, still camera; final = albedo * irradiance.
 *             Noisy layer: the indirect light (one cosine-weighted ray to a
 *             coloured sky, one diffuse bounce), filtered demodulated.
 *   pinkroom  Fig. 1 left (and Fig. 9's moving light): a pink room, a table
 *             on four legs, a stool, a shelf and two spheres (one rolling)
 *             under an area light sweeping sideways; soft shadows fall over the
 *             floor-wall corners and onto the spheres, where eq. 3's flat
 *             receiver does not hold.  Noisy layer: visibility, as fence.
 *   lights    Fig. 10: "another view of the fence scene with multiple
 *             moving light sources": the fence seen from higher and to the
 *             side under three area lights, each moving its own way, so the
 *             slats cast three shadows moving at three speeds that overlap.
 *             One shadow ray per pixel to one light chosen in proportion to
 *             its unshadowed light there (§4.1: "for each light sample, we
 *             compute its motion vector"); the visibility layer is the
 *             lights' visibilities weighted by their unshadowed light.
 *   apples    Fig. 9: apples on a cloth's folds (spheres on low domes) on a
 *             desk, a light on the right sweeping fast from back to front:
 *             the shadows fall on curved receivers, eq. 3's flat receiver
 *             fails almost everywhere and eq. 4's falloff must catch it.
 *             Noisy layer: visibility, as fence.
 */
#ifndef ZENG_SCENE_H
#define ZENG_SCENE_H

#include <stddef.h>
#include <stdint.h>

#define ZS_MAX_OBJ 24
#define ZS_MAX_LIGHTS 4

enum { ZS_PLANE, ZS_BOX, ZS_SPHERE };
enum { ZS_FENCE, ZS_GLOSSY, ZS_OCCLUSION, ZS_PINKROOM, ZS_LIGHTS, ZS_APPLES, ZS_NSCENES };
/* the layers the pipeline filters separately (Zeng §4: shading, visibility,
 * glossy, other indirect) */
enum { ZL_VIS, ZL_GLOSSY, ZL_INDIRECT, ZL_N };

typedef struct {
    int type;
    double a[3], b[3]; /* plane: point, unit normal; box: min, max; sphere: centre, b[0] radius (at frame 0) */
    double vel[3];     /* translation per frame */
    double albedo[3], albedo2[3];
    double tex_scale; /* stripes of albedo/albedo2 along x+z with this period (0: plain) */
    double ks, rough; /* glossy: weight and lobe angular sigma (rad) */
} zs_obj_t;

typedef struct {
    int kind, nobj;
    zs_obj_t obj[ZS_MAX_OBJ];
    double cam0[3], cam_vel[3], target[3], target_vel[3], vfov; /* radians */
    double light_c[3], light_e1[3], light_e2[3], light_vel[3], light_le[3];
    /* lights 1..nlights-1 (0 or 1: light 0 alone): the same size and
     * radiance as light 0, centred light_d[k] away from it at frame 0 and
     * moving by light_dv[k] a frame (light_d[0], light_dv[0] stay 0) */
    int nlights;
    double light_d[ZS_MAX_LIGHTS][3], light_dv[ZS_MAX_LIGHTS][3];
    double ambient;
    int noisy; /* ZL_* layer this scene renders with one sample per pixel */
    /* the glossy layer's spatial filter: 0 [LLK*19]'s lobe footprint
     * (zeng_pipe.c), 1 the fixed 15x15 joint bilateral, sigma 3 px, that
     * stood in for it before (kept to compare: tdc-zeng --glossy-filter) */
    int glossy_fixed;
    /* 1: eq. 4's alpha^V switched off (alpha everywhere): the cosine
     * falloff's share (tdc-zeng --no-falloff) */
    int no_falloff;
    /* eq. 5's spread along the footprint's axes, scaled (1: the paper's; 0:
     * the sampled hit's virtual image alone; tdc-zeng --spread) */
    double spread;
    /* 1: eq. 5's vectors weight-averaged over the glossy filter's kernel
     * before the fetch, as §4.1 does with the shadow vectors (§4.2: "The
     * usage of our stochastic glossy reflection motion vectors is similar to
     * the shadow motion vectors"); 0: one per pixel (tdc-zeng --glossy-mv) */
    int glossy_splat;
} zs_scene_t;

typedef struct {
    double pos[3], r[3], u[3], f[3];
    double fpx;
    int w, h;
} zs_cam_t;

/* One frame's G-buffer and layers (W*H; vectors are the previous frame's
 * continuous pixel position, pixel (i, j) covering [i, i+1) x [j, j+1)). */
typedef struct {
    int w, h;
    int *id;                         /* object hit by the primary ray, -1 sky */
    double *pos, *nrm, *alb, *depth; /* world position (3), normal (3), albedo (3), view depth */
    double *shade;                   /* unshadowed direct light (3) */
    double *layer;                   /* the noisy layer (3 channels; visibility repeats its value) */
    double *mv_trad;                 /* Zeng eq. 1: the surface's previous position (2) */
    double *mv_eff;                  /* effect vectors: shadow eq. 3 (splat input) / glossy eq. 5 (2) */
    double *mv_spec;                 /* glossy scene: the specular hit's virtual image (2) */
    uint8_t *in_shadow;              /* fence: the shadow ray found a blocker (mv_eff valid) */
    double *pen;                     /* fence, in-shadow pixels: the penumbra's width in pixels (PCSS) */
    double *hitd;                    /* glossy surface: the lobe sample's hit distance (INFINITY: sky) */
} zs_frame_t;

void zs_scene_init(zs_scene_t *s, int kind);
const char *zs_scene_name(int kind);
int zs_scene_by_name(const char *name);
void zs_camera(const zs_scene_t *s, int frame, int w, int h, zs_cam_t *c);
/* Projects world point p (w = 1) or direction p (w = 0) to continuous pixel
 * coordinates; returns 0 behind the camera. */
int zs_project(const zs_cam_t *c, const double p[3], int w, double xy[2]);

int zs_frame_alloc(zs_frame_t *f, int w, int h);
void zs_frame_free(zs_frame_t *f);

/* Renders frame `frame` with one sample per pixel of the scene's noisy layer
 * (random numbers from seed) and every motion vector. */
void zs_render(const zs_scene_t *s, int frame, uint64_t seed, zs_frame_t *f);
/* The noisy layer's one sample at pixel (x, y) of `frame` drawn with the
 * random numbers of (seed, rng_frame, rng_pixel): A-SVGF's temporal
 * gradient re-shades the previous frame's sample in this frame. */
void zs_sample(const zs_scene_t *s, int frame, int w, int h, int x, int y, uint64_t seed, int rng_frame,
               size_t rng_pixel, double out[3]);
/* Ground truth of the noisy layer: `spp` stratified samples per pixel
 * (spp a square), seed-independent; out: W*H*3. */
void zs_ground_truth(const zs_scene_t *s, int frame, int w, int h, int spp, double *out);
/* The displayed colour from a layer image (W*H*3, linear). */
void zs_composite(const zs_scene_t *s, const zs_frame_t *f, const double *layer, double *rgb);

/* Exposed for the tests. */
double zs_intersect(const zs_scene_t *s, int frame, const double o[3], const double d[3], double tmax, int *id,
                    double n[3]);
void zs_obj_offset(const zs_scene_t *s, int id, int frame, double off[3]);
void zs_light_offset(const zs_scene_t *s, int frame, double off[3]);
/* Light k's translation at `frame` (light 0: zs_light_offset). */
void zs_light_k_offset(const zs_scene_t *s, int k, int frame, double off[3]);
int zs_nlights(const zs_scene_t *s);
/* Visibility from p (normal n) of point (u, v) of light k at `frame`: 1
 * lit, 0 blocked (then the blocker's point bp and id *bid, else -1); lp:
 * the light point. */
double zs_light_vis(const zs_scene_t *s, int frame, int k, const double p[3], const double n[3], double u, double v,
                    double lp[3], double bp[3], int *bid);

/* Zeng eq. 3: the previous frame's position of a shadow: the line from the
 * light sample l through the blocker point b (both moved back by their own
 * translations dl, db) meets the receiver's plane (point s moved back by ds,
 * normal n).  Returns 0 when the line is parallel to the plane. */
int zs_shadow_prev(const double l[3], const double dl[3], const double b[3], const double db[3], const double s[3],
                   const double ds[3], const double n[3], double out[3]);
/* Zeng eq. 4: alpha^V = 1 - G(theta - pi/2; 0, 0.1) (1 - alpha), G peak 1. */
double zs_alpha_v(double theta, double alpha);
/* Mirror of p across the plane (point q, unit normal n). */
void zs_mirror(const double p[3], const double q[3], const double n[3], double out[3]);

#endif
