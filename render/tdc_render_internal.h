/*
 * tdc_render_internal.h - shared internals of the renderer (not a public API).
 */
#ifndef TDC_RENDER_INTERNAL_H
#define TDC_RENDER_INTERNAL_H

#include <embree3/rtcore.h>
#include <math.h>
#include <pthread.h>

#include "tdc_render.h"

#define TDC_R_MAX_BOUNCES 3

/* Camera of one frame: pinhole, y down in the image. */
typedef struct {
    double pos[3], fwd[3], right[3], up[3];
    double tan_half, aspect; /* tan(fov/2), W/H */
    int w, h;
    /* precomputed: image (x, y) -> screen-plane (sx, sy) = (x ax + bx, y ay + by),
     * and back: x = u kx + w/2, y = h/2 - v ky for u, v = plane coordinates / depth */
    double ax, bx, ay, by, kx, ky;
} rcam_t;

/* Everything that depends on the frame time. */
typedef struct {
    long frame; /* -1 = invalid */
    double t;
    rcam_t cam;
    double m[TDC_SCENE_MAX_OBJECTS][12];    /* object -> world */
    double minv[TDC_SCENE_MAX_OBJECTS][12]; /* world -> object */
    double nm[TDC_SCENE_MAX_OBJECTS][9];    /* normal matrix (inverse transpose of the 3x3) */
    double light_pos[TDC_SCENE_MAX_LIGHTS][3];
} rframe_t;

/* Per-object data the shader needs. */
typedef struct {
    RTCScene scene; /* the object's geometry in local space */
    int animated;
    uint64_t prims;
} robj_t;

typedef struct {
    RTCScene top;
    RTCGeometry inst[TDC_SCENE_MAX_OBJECTS];
    long frame; /* frame the instances are committed for, -1 none */
} rtop_t;

/* Per-material texture data prepared at open (tdc_r_tex_prepare): the
 * glyph of every character position of a text texture, so the per-sample
 * lookup needs neither strlen() nor the character switch. */
typedef struct {
    long text_len1;      /* strlen(text) + 1: the text repeats with one space */
    double text_cell6;   /* 6 * (scale / 8): glyph cell width */
    uint64_t text_mod_m; /* floor((2^64 - 1) / text_len1) + 1: remainder by multiplication */
    long text_mod_k;     /* smallest multiple of text_len1 >= 2^30 */
    /* 5x7 glyph rows (bit 4 = leftmost column) of each character position,
     * row 7 = 0 (the gap row), so the lookup needs no range test */
    unsigned char rows[TDC_SCENE_TEXT_LEN + 1][8];
} rtex_t;

/* One pixel of a FULL frame's G-buffer (option dual_mv): the primary
 * hit's camera depth (INFINITY: sky) and object (-1: sky).  Zeng eq. 6
 * reads the previous frame's (tdc_r_pass_mv_dual). */
typedef struct {
    float depth;
    int32_t obj;
} tdc_r_gpix_t;

struct tdc_render {
    tdc_scene_t *scene;
    tdc_render_config_t cfg;
    float full_jx, full_jy; /* FULL sample offset (tdc_render_set_jitter) */
    int W, H;
    tdc_render_features_t feat;
    RTCDevice dev;
    robj_t obj[TDC_SCENE_MAX_OBJECTS];
    rtex_t tex[TDC_SCENE_MAX_MATERIALS];
    rtop_t top[2];
    rframe_t fr[2]; /* cache of evaluated frames */
    /* motion between the frame being rendered and the previous one: pixels
     * of unmoved objects under an unmoved camera get MV = 0 without math */
    int cam_moved;
    uint8_t obj_moved[TDC_SCENE_MAX_OBJECTS];
    /* 1: the object's matrices of the two frames are bitwise equal, so its
     * previous world position is the current one without a second transform */
    uint8_t obj_same_m[TDC_SCENE_MAX_OBJECTS];
    /* 1: only the translation column differs (a translating object): the
     * rotation-scale product of a point is shared by both frames */
    uint8_t obj_same_rs[TDC_SCENE_MAX_OBJECTS];
    /* 1: the world normal of a primary hit is used (lit or mirror material);
     * unlit, non-mirror surfaces skip its transform and normalisation */
    uint8_t obj_needs_n[TDC_SCENE_MAX_OBJECTS];
    /* 1: unlit, textured, and its texture coordinates need atan2 (sphere,
     * cylinder): the shade pass computes them in a loop of their own */
    uint8_t obj_uv_first[TDC_SCENE_MAX_OBJECTS];
    int any_uv_first;
    int16_t *mv_hist;      /* W*H*2 */
    int16_t *mv_hist_prev; /* snapshot at the start of a subframe (pixel classes) */
    uint8_t *pattern;      /* ordering bits */
    void *sbuf[64];        /* per-thread sample buffers, kept between frames */
    size_t sbuf_cap[64];   /* in samples */
    float *fov_xy;         /* FOVEATED: sample positions, fov_n x 2 */
    float *fov_cone;       /* FOVEATED: each sample's cone in display pixels (>= 1, cfg.fov_lod), fov_n */
    int fov_n, fov_lp;     /* samples, of which log-polar */
    tdc_render_ray_t *rec; /* recorded rays (merged) */
    size_t nrec;
    /* option indirect_reuse: per-pixel 6-cone history of two frames
     * (TDC_R_CONE_FLOATS each), cone_frame = the frame in cone_hist[frame & 1] */
    float *cone_hist[2];
    long cone_frame;
    /* option dual_mv: the G-buffers of the last two FULL frames, gbuf[k]
     * holding frame gbuf_frame[k] (-2: none) sampled at pixel + 0.5 +
     * gbuf_j[k] (the frame's jitter) */
    tdc_r_gpix_t *gbuf[2];
    long gbuf_frame[2];
    float gbuf_j[2][2];
};

/* per-pixel cone record: 6 x RGB mean radiance, 6 weights, the normal */
#define TDC_R_CONE_FLOATS 27

/* Geometry (tdc_render_geom.c): builds obj's local Embree scene. */
int tdc_r_build_object(tdc_render_t *r, int i, char *err, size_t errlen);

/* Frames (tdc_render_core.c). */
const rframe_t *tdc_r_frame(tdc_render_t *r, long frame);
/* Fills cam_moved / obj_moved for frame vs frame - 1; returns 1 if anything
 * (camera, object or light) moved. */
int tdc_r_update_motion(tdc_render_t *r, long frame);
RTCScene tdc_r_top(tdc_render_t *r, long frame);


/* Small geometry helpers, inline: they run several times per sample. */
static inline void tdc_r_xform_point(const double m[12], const double p[3], double out[3])
{
    double x = m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3];
    double y = m[4] * p[0] + m[5] * p[1] + m[6] * p[2] + m[7];
    double z = m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11];
    out[0] = x; /* out may alias p */
    out[1] = y;
    out[2] = z;
}

static inline void tdc_r_xform_normal(const double nm[9], const double n[3], double out[3])
{
    /* in locals (writing out[] then reading it back stalled on store
     * forwarding), one reciprocal instead of three divisions */
    double x = nm[0] * n[0] + nm[1] * n[1] + nm[2] * n[2];
    double y = nm[3] * n[0] + nm[4] * n[1] + nm[5] * n[2];
    double z = nm[6] * n[0] + nm[7] * n[1] + nm[8] * n[2];
    double l2 = x * x + y * y + z * z;
    double il = l2 > 0 ? 1.0 / sqrt(l2) : 0.0;
    out[0] = x * il;
    out[1] = y * il;
    out[2] = z * il;
}

/* Tangent frame of a unit normal (Duff et al. 2017, branchless): T, B, n
 * orthonormal, depending only on n (GGX sampling, indirect bounce, cones). */
static inline void tdc_r_onb(const double n[3], double t[3], double b[3])
{
    double sg = n[2] >= 0 ? 1.0 : -1.0, aa = -1.0 / (sg + n[2]), bb = n[0] * n[1] * aa;
    t[0] = 1 + sg * n[0] * n[0] * aa;
    t[1] = sg * bb;
    t[2] = -sg * n[0];
    b[0] = bb;
    b[1] = sg + n[1] * n[1] * aa;
    b[2] = -n[1];
}

static inline void tdc_r_cam_ray(const rcam_t *c, double x, double y, double dir[3])
{
    double sx = x * c->ax + c->bx, sy = y * c->ay + c->by;
    /* not normalised: Embree and every use downstream (hit = org + t dir,
     * reflection, projection of directions) work with any length, and the
     * square root and division cost more than the rest of the ray setup */
    double x0 = c->fwd[0] + sx * c->right[0] + sy * c->up[0];
    double x1 = c->fwd[1] + sx * c->right[1] + sy * c->up[1];
    double x2 = c->fwd[2] + sx * c->right[2] + sy * c->up[2];
    dir[0] = x0; /* in locals: no store-forwarding stall when the ray is set up */
    dir[1] = x1;
    dir[2] = x2;
}

static inline int tdc_r_project_dir(const rcam_t *c, const double d[3], double *x, double *y)
{
    double z = d[0] * c->fwd[0] + d[1] * c->fwd[1] + d[2] * c->fwd[2];
    if (!(z > 1e-12)) return -1;
    double iz = 1.0 / z;
    double u = (d[0] * c->right[0] + d[1] * c->right[1] + d[2] * c->right[2]) * iz;
    double v = (d[0] * c->up[0] + d[1] * c->up[1] + d[2] * c->up[2]) * iz;
    *x = u * c->kx + 0.5 * c->w;
    *y = 0.5 * c->h - v * c->ky;
    return 0;
}

static inline int tdc_r_project(const rcam_t *c, const double p[3], double *x, double *y)
{
    double d[3] = {p[0] - c->pos[0], p[1] - c->pos[1], p[2] - c->pos[2]};
    return tdc_r_project_dir(c, d, x, y);
}

/* Textures (tdc_render_texture.c): per-material tables at open; base
 * colour at a local point, box-filtered over a footprint fw (object-space
 * length; 0 = point-sampled). */
void tdc_r_tex_prepare(tdc_render_t *r);
void tdc_r_base_color(const tdc_render_t *r, const tdc_object_t *o, const double q[3], const double nq[3], double fw,
                      double out[3]);
/* The two halves of tdc_r_base_color for a textured material: texture
 * coordinates of a local point, then the colour at (u, v). */
void tdc_r_tex_uv(const tdc_object_t *o, const double q[3], const double nq[3], double *u, double *v);
void tdc_r_tex_color(const tdc_render_t *r, const tdc_object_t *o, double u, double v, double fw, double out[3]);
/* Ray cones (TDRT §3.1.1 uses ray differentials for texture filtering; the
 * cone formulation of [AMNA*19]): the spread angle of one sample of a mode
 * with sw samples across the width and spp samples per slot (a pixel's
 * angle 2 tan(fov/2) / H, times the sample spacing in pixels: 1 for full
 * frames and subframes, W / sw for reduced frames' supersamples,
 * 1 / sqrt(spp) for the ground truth's), 0 with cfg.tex_filter off. */
double tdc_r_sample_cone(const tdc_render_t *r, int mode, int sw, int spp, double tan_half);
/* The footprint of a cone of angle `cone` after `dist` world units (summed
 * over mirror bounces: planar mirrors keep the spread) on a surface of
 * normal n hit along d: cone dist / |cos| (the longer axis of the ellipse,
 * as mip-mapping's isotropic LOD), |cos| floored at 1/16 (grazing hits).
 * minv (world -> object 3x4, or NULL): n is in object space (the raw
 * normal every hit has; unlit hits have no world normal), d is taken there
 * and the width scaled to object lengths (cube root of |det minv|). */
double tdc_r_tex_footprint(double cone, double dist, const double d[3], const double n[3], const double *minv);

#endif
