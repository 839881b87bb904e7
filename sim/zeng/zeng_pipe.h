/*
 * zeng_pipe.h - the temporal pipelines compared by Zeng et al. §6, in
 * doubles, one layer (the scene's noisy one, zeng_scene.h) at a time:
 *
 *   trad        traditional vectors (eq. 1), history rejected where the
 *               previous frame shows another object, no clamp; eq. 2 with
 *               alpha = 0.1 on the spatially filtered frame.
 *   trad-clamp  traditional vectors, no rejection, the history clamped to
 *               mu +- 1 sigma of the current 1-sample frame's 5x5
 *               neighbourhood (Salvi 2016; Zeng §4.3).
 *   spec        glossy only: the specular ray's virtual-image vectors
 *               (Zimmer et al. 2015), 1-sigma clamp (Zeng §6, (3)).
 *   ours        the temporally reliable vectors: shadow (eq. 3, splatted
 *               over the 31x31 filter's in-shadow pixels, alpha^V of eq.
 *               4), stochastic glossy (eq. 5), dual (eq. 6, from the
 *               previous frame's object ids and positions: a lookup); the
 *               3-sigma clamp and the 9x9 clean-up with sigma =
 *               min(w_A + w_C, 5) (§5, eqs. 7-8).
 *   svgf        Schied et al. 2017 on the 1-sample frame: reprojection with
 *               an id/normal/depth test, colour and moments integrated with
 *               max(0.2, 1/n), variance from the moments (spatial 7x7 when n
 *               < 4), 5 variance-guided a-trous levels, the first level fed
 *               back as history.
 *   asvgf       Schied et al. 2018 on top: one sample per 3x3 stratum of
 *               the previous frame is forward-projected and re-shaded in
 *               this frame with its old random numbers; the normalised
 *               temporal gradient lambda = |delta| / max(old, new), averaged
 *               over 3x3 strata, raises the blend weight: a = (1 - lambda)
 *               a + lambda.
 *
 * Per-effect spatial filters (Zeng §5), applied before eq. 2:
 *   visibility  separable 31x31 joint bilateral (sigma 8 px)
 *   glossy      [LLK*19]: a joint bilateral on the glossy surface whose
 *               Gaussian is the lobe reflected below the surface and
 *               projected on the screen (its sigma from the hit distance
 *               and the roughness, zp_glossy_footprint), up to 31x31;
 *               s->glossy_fixed: the fixed 15x15, sigma 3 px, stand-in
 *   indirect    4-level a-trous (Dammertz), demodulated irradiance
 */
#ifndef ZENG_PIPE_H
#define ZENG_PIPE_H

#include "zeng/zeng_scene.h"

enum { ZM_TRAD, ZM_TRAD_CLAMP, ZM_SPEC, ZM_OURS, ZM_SVGF, ZM_ASVGF, ZM_N };

typedef struct {
    int method, w, h;
    double alpha;
    int clamp_r;  /* clamp window radius (2: 5x5) */
    /* 1: the clamp's mu and sigma over the spatially filtered current frame
     * (eq. 2's c~_i, "first filtered spatially per frame", then blended);
     * 0: over the 1-sample frame */
    int clamp_filtered;
    double clamp_k; /* ours' clamp: mu +- clamp_k sigma (3, §5; the others use 1) */
    int have;     /* history valid */
    double *hist; /* W*H*3 accumulated layer (eq. 2's c-bar) */
    double *out;  /* W*H*3 displayed layer */
    /* scratch */
    double *filt, *tmp, *tmp2, *sig, *mvx;
    /* SVGF */
    double *mom, *len, *var, *var2;
    /* A-SVGF: the renderer seed (to re-shade old samples), lambda per stratum */
    uint64_t seed;
    double *lam;
    /* diagnostics of the last step: pixels whose history was rejected, and
     * those that took a dual vector */
    long rejected, dual;
} zp_state_t;

const char *zp_method_name(int m);
int zp_init(zp_state_t *st, int method, int w, int h);
void zp_free(zp_state_t *st);
/* One frame: f (this frame), pf (the previous frame's buffers, ignored at
 * the first step). */
void zp_step(zp_state_t *st, const zs_scene_t *s, int frame, const zs_frame_t *f, const zs_frame_t *pf);

/* [LLK*19]'s kernel for the glossy layer: per pixel the Gaussian's sigma in
 * pixels, the glossy lobe reflected below the surface and projected on the
 * screen (0 off the glossy surface; zeng_pipe.c). */
void zp_glossy_footprint(const zs_scene_t *s, const zs_frame_t *f, double *sg);

/* The per-effect spatial filter of the scene's noisy layer (exposed for tests). */
void zp_spatial(const zs_scene_t *s, const zs_frame_t *f, const double *in, double *out, double *tmp);

/* The previous frame's view depth at continuous position (fx, fy) (pixel
 * centres at integers) from its sample (qx, qy) and the neighbour on the
 * object's side (linear; extrapolated from the other neighbour where the
 * one toward (fx, fy) is another object; the sample's own depth where
 * neither is): the depth a G-buffer read at y gives. */
double zp_depth_at(const zs_frame_t *f, int qx, int qy, double fx, double fy);

/* Eq. 6's dual vector of pixel (x, y): y = trad vector; when the previous
 * frame's sample at y saw something in front of this surface point (its
 * depth nearer by more than 1e-3 (1 + d) + 1 % of d: a disocclusion), z = that occluder's
 * previous point moved by its own motion and projected with this frame's
 * camera (cam; pc: the previous frame's), x^O = y + (x - z).  Returns 1 when the pixel is disoccluded (out =
 * x^O), 0 otherwise (out = the traditional vector). */
int zp_dual_vector(const zs_scene_t *s, int frame, const zs_frame_t *f, const zs_frame_t *pf, const zs_cam_t *cam,
                   const zs_cam_t *pc, int x, int y, double out[2]);

#endif
