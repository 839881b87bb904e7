/*
 * tdc_sim_scene.h - the simulator's scene source interface and the built-in
 * procedural scenes (analytic, exact motion, exact ground truth).
 *
 * A source answers three questions, which is all a renderer must do for the
 * simulator (the Embree renderer plugs in behind the same interface):
 *   - samples: trace n primary rays at given sub-pixel positions at time t
 *     and return panel drive codes (RGB888, encoded with the panel gamma so
 *     that the ideal panel shows the scene's linear light) and optionally the
 *     backward motion vector of each sample (Q4 pixels, see docs/design.md §4.4);
 *   - ground truth: linear light of every pixel at time t, box-filtered over
 *     the pixel with a dense supersampling grid;
 *   - motion: the velocity the eye pursues (paper TRM §3, smooth pursuit) and
 *     whether the stream is cut between two instants (stream reset).
 *
 * Units: positions in pixels (pixel (x, y) covers [x, x+1) x [y, y+1), its
 * centre is x + 0.5), time in seconds, velocities in pixels per second,
 * linear light in [0, 1] per channel.
 */
#ifndef TDC_SIM_SCENE_H
#define TDC_SIM_SCENE_H

#include <stdint.h>

typedef enum {
    TDC_SCENE_STATIC = 0, /* still detailed pattern: TRM eq. 3 check */
    TDC_SCENE_PAN,        /* panned panorama-like texture */
    TDC_SCENE_TEXT,       /* scrolling pseudo text (1-px strokes) */
    TDC_SCENE_DISCS,      /* discs moving over a static textured background */
    TDC_SCENE_THIN,       /* room with thin vertical features, horizontal pan */
    TDC_SCENE_FENCE,      /* static floor, moving fence shadow (shadow MVs) */
    TDC_SCENE_BLACK,
    TDC_SCENE_WHITE,
    TDC_SCENE_CUT, /* pan scene, then a cut to the text scene (stream reset) */
    TDC_SCENE_COUNT
} tdc_scene_kind_t;

/* Motion vector flavours a source can produce. */
typedef enum {
    TDC_MV_SURFACE = 0, /* motion of the visible surface point (standard) */
    TDC_MV_SHADOW = 1   /* + shadow MVs and dual MVs for disocclusions (TRMV §4.1, §4.3) */
} tdc_mv_kind_t;

typedef struct tdc_source tdc_source_t;

/* Layered samples (issue 16, firmware/tdc_layer_link.h): a source fills a
 * tdc_layer_frame_t whose planes hold n samples (value[t - 1], mv[t - 1],
 * falloff), its present set and its header's count / types / vector kinds. */
struct tdc_layer_frame;
/* Foveated sampling of one frame (the fov modes; tdc_render_fov_t's fields). */
typedef struct {
    double gaze_x, gaze_y; /* display pixels */
    double alpha, delta, disk;
    double jx, jy; /* jitter of the log-polar samples (Halton where TAA follows) */
    int jitter;    /* how it moves a sample: TDC_FOV_JITTER_* (ref_fov_lp_jitter) */
} tdc_fov_sampling_t;

struct tdc_source {
    const char *name;
    int width, height;
    double gamma[3]; /* panel gamma used to encode drive codes */
    int gt_ss;       /* ground-truth supersampling: gt_ss x gt_ss samples per pixel */
    int rigid;       /* 1: all content moves with the pursuit velocity (GT needs one sample in time) */
    void *ctx;
    /* n samples at (xy[2i], xy[2i+1]) at time t.  spp > 1: each sample is the
     * mean of spp stratified rays within its pixel (MSAA-like; xy is then the
     * pixel's corner + 0.5).  rgb: n*3 codes.  mv (optional, may be NULL):
     * n*2 backward MVs in Q4 over dt seconds. */
    void (*samples)(tdc_source_t *s, double t, int n, const double *xy, int spp, uint8_t *rgb, int16_t *mv, double dt,
                    tdc_mv_kind_t kind);
    /* Linear light W*H*3 (double) of the scene at time t, every pixel
     * sampled at (x + ox, y + oy) shifted by (ox, oy) pixels. */
    void (*ground_truth)(tdc_source_t *s, double t, double ox, double oy, double *lin);
    /* Optional fast path for whole frames without motion vectors: drive
     * codes of every pixel as samples() would give for the pixel grid
     * (spp > 1: g x g box samples; spp 1: the centre + (jx, jy)); lin:
     * W*H*3 doubles of scratch.  0, or -1 (then use samples()). */
    int (*frame)(tdc_source_t *s, double t, double jx, double jy, int spp, uint8_t *rgb, double *lin);
    void (*pursuit)(tdc_source_t *s, double t, double v[2]);
    /* 1 if the content changes discontinuously in (t0, t1]. */
    int (*cut)(tdc_source_t *s, double t0, double t1);
    void (*destroy)(tdc_source_t *s);
    /* Optional, for renderers that trace whole frames (the Embree renderer):
     * a full W x H frame at pixel centres for time t, drive codes (panel
     * gamma), MVs over dt if mv != NULL; *rays = primary rays traced, *ms =
     * renderer wall time.  NULL: the modes use samples().  Returns 0. */
    int (*full_frame)(tdc_source_t *s, double t, double dt, uint8_t *rgb, int16_t *mv, uint64_t *rays, double *ms);
    /* Optional: a renderer that traces subframes itself with its own
     * (adaptive) tile orderings.  slot: one renderer state per mode;
     * samples: tiles*3 codes, mv: tiles*2 Q4 over dt (shadow != 0: shadow
     * and dual MVs), pattern: receives the orderings of the current cycle.
     * Returns 0. */
    int (*subframe)(tdc_source_t *s, int slot, int shadow, uint32_t frame, double t, double dt, uint8_t *samples,
                    int16_t *mv, uint8_t *pattern, uint64_t *rays);
    /* Optional: a renderer that traces reduced frames itself (TRM §4.3):
     * rw x rh drive codes at ratio r, ss x ss rays per reduced pixel
     * resolved with a Gaussian of sigma full-res px (ss 1 and a tiny sigma:
     * point sampling, aliased).  slot: one renderer per mode.  rgb NULL:
     * only open that renderer (untimed set-up).  0, or -1 (the renderer's
     * reduced size is not rw x rh, or it failed). */
    int (*reduced_frame)(tdc_source_t *s, int slot, double t, double r, int ss, double sigma, int rw, int rh,
                         uint8_t *rgb, uint64_t *rays);
    /* Optional (NULL: no layers): layered samples at the n positions xy at
     * time t, vectors over dt.  zeng = 1: temporally reliable vectors
     * (Zeng §4: shadow vectors for in-shadow samples, glossy vectors, ...),
     * zeng = 0: every layer with the ordinary surface vector.  The source
     * fills the layers it has (at least SHADING: a scene without shadows
     * or reflections sends one layer).  Returns 0, or -1. */
    int (*layers)(tdc_source_t *s, double t, int n, const double *xy, double dt, int zeng,
                  struct tdc_layer_frame *out);
    /* Optional: a renderer that traces subframes itself (as `subframe`)
     * with layer outputs: the layered samples of every tile of subframe
     * `frame` into out (planes hold tiles samples), its orderings into
     * pattern; zeng as for `layers`.  Returns 0. */
    int (*layered_subframe)(tdc_source_t *s, int slot, int zeng, uint32_t frame, double t, double dt,
                            struct tdc_layer_frame *out, uint8_t *pattern, uint64_t *rays);
    /* Optional: a renderer that traces foveated frames itself (the Embree
     * renderer's FOVEATED mode, thesis §4.2): the samples of f in the
     * firmware's payload order (kernel log-polar columns [u0, w), then the
     * disk), codes; MVs over dt if mv != NULL; *rays = primary rays traced.
     * NULL: the fov modes trace their positions with samples().  Returns 0. */
    int (*foveated)(tdc_source_t *s, const tdc_fov_sampling_t *f, double t, double dt, uint8_t *rgb, int16_t *mv,
                    uint64_t *rays);
    const char *note; /* what this source does not support, for reports */
    /* Optional, with full_frame: the sub-pixel offset of the following
     * full frames' samples (TAA jitter); NULL: always pixel centres. */
    void (*jitter)(tdc_source_t *s, double jx, double jy);
};

/* Parameters of the built-in scenes. */
typedef struct {
    tdc_scene_kind_t kind;
    int width, height;
    double speed;     /* px/s of the main motion; < 0: scene default */
    double angle_deg; /* direction of the main motion (0 = +x) */
    double cut_time;  /* TDC_SCENE_CUT: seconds */
    uint32_t seed;
    int pursuit;    /* 1: eye tracks the main motion, 0: fixation */
    int gt_ss;      /* 0: default 4 */
    double shift_x; /* this eye's view: the scene seen shifted by shift_x px (stereo disparity) */
} tdc_scene_params_t;

const char *tdc_scene_name(tdc_scene_kind_t k);
/* -1 if unknown. */
int tdc_scene_from_name(const char *name);
/* Default speed of a scene in px/s. */
double tdc_scene_default_speed(tdc_scene_kind_t k);

/* The built-in procedural source (malloc'd; destroy with s->destroy(s)). */
tdc_source_t *tdc_scene_create(const tdc_scene_params_t *p, const double gamma[3]);

/* Linear light of scene kind k at point (x, y), time t (exposed for tests). */
void tdc_scene_radiance(const tdc_source_t *s, double x, double y, double t, double rgb[3]);

#endif
