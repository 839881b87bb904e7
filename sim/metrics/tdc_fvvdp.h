/*
 * tdc_fvvdp.h - FovVideoVDP (Mantiuk, Denes, Chapiro, Kaplanyan, Rufo,
 * Bachy, Lian, Patney: "FovVideoVDP: A visible difference predictor for
 * wide field-of-view video", ACM TOG 40(4) 49, 2021), written by this
 * project from the paper's equations; the simulator's judge of temporal and
 * peripheral differences.  Host code, double precision (masking and band
 * contrasts in float: tdc_fvvdp.c).
 *
 * The stages, one per file:
 *   tdc_fvvdp_display.c   photometry (drive code -> cd/m^2) and geometry
 *                         (pixels per degree, gaze -> eccentricity)
 *   tdc_fvvdp_pyr.c       the decimated Laplacian / contrast pyramid
 *   tdc_fvvdp_temporal.c  sustained and transient channels (FIR over frames)
 *   tdc_fvvdp_csf.c       the CSF over rho, omega, adapting L and eccentricity
 *   tdc_fvvdp.c           masking, pooling, the JOD regression, the frame loop
 *
 * Parameter values are the published calibration of FovVideoVDP v1.2
 * (fvvdp_parameters.json "version 1.2.3" of github.com/gfxdisp/FovVideoVDP at
 * 31254d0, and the CSF sub-models that paper section 3 cites); every constant
 * names its source where it is defined.  docs/visual-model.md has the
 * equations, the validation table against the reference implementation and
 * what differs.
 */
#ifndef TDC_FVVDP_H
#define TDC_FVVDP_H

#include <stddef.h>

/* ---- photometry (tdc_fvvdp_display.c) ---- */
typedef enum { TDC_FVVDP_EOTF_SRGB = 0, TDC_FVVDP_EOTF_GAMMA = 1 } tdc_fvvdp_eotf_t;

typedef struct {
    double y_peak;      /* cd/m^2 of the full drive */
    double contrast;    /* y_peak / emitted black (panel contrast ratio) */
    double e_ambient;   /* ambient illuminance, lux */
    double k_refl;      /* display reflectivity (black += e_ambient/pi * k_refl) */
    tdc_fvvdp_eotf_t eotf;
    double gamma[3];    /* per channel when eotf == GAMMA */
    double rgb2y[3];    /* luminance weights of the primaries (sum 1) */
} tdc_fvvdp_photometry_t;

double tdc_fvvdp_black(const tdc_fvvdp_photometry_t *p);
/* Luminance (cd/m^2) of a display-encoded value v in [0,1] on channel c. */
double tdc_fvvdp_lum(const tdc_fvvdp_photometry_t *p, int c, double v);
/* Luminance of an RGB pixel (three channels, each v in [0,1]). */
double tdc_fvvdp_lum_rgb(const tdc_fvvdp_photometry_t *p, const double v[3]);

/* ---- geometry (tdc_fvvdp_display.c) ---- */
typedef struct {
    int width, height;  /* pixels */
    double width_m;     /* physical width (square pixels: height_m = width_m*height/width) */
    double distance_m;  /* viewing distance */
} tdc_fvvdp_geometry_t;

/* A geometry whose centre pixel density is ppd at 1 m. */
tdc_fvvdp_geometry_t tdc_fvvdp_geometry_ppd(int width, int height, double ppd);
double tdc_fvvdp_ppd(const tdc_fvvdp_geometry_t *g);
/* Visual angles (deg, x right, y up) of position (x, y) in a grid of w x h
 * samples covering the display (pixel centres at i + 0.5). */
void tdc_fvvdp_view_dir(const tdc_fvvdp_geometry_t *g, double w, double h, double x, double y, double out[2]);
/* Pixel density at a view direction relative to the centre's (>= 1 off-axis
 * on a flat screen). */
double tdc_fvvdp_res_mag(const tdc_fvvdp_geometry_t *g, const double dir[2]);

/* ---- the pyramid (tdc_fvvdp_pyr.c) ---- */
#define TDC_FVVDP_MAX_LEVELS 14

typedef struct {
    int levels;                          /* Gaussian levels (bands + 1 baseband) */
    int w[TDC_FVVDP_MAX_LEVELS], h[TDC_FVVDP_MAX_LEVELS];
    double rho[TDC_FVVDP_MAX_LEVELS];    /* band peak frequency, cpd */
} tdc_fvvdp_pyr_t;

/* The band layout for an image of w x h at ppd (bands down to 0.5 cpd). */
int tdc_fvvdp_pyr_layout(tdc_fvvdp_pyr_t *p, int w, int h, double ppd);
/* One reduce step (5-tap kernel a = 0.4, half-sample symmetric edges):
 * src w x h -> dst ceil(w/2) x ceil(h/2).  tmp holds w*ceil(h/2). */
void tdc_fvvdp_reduce(const double *src, int w, int h, double *dst, double *tmp);
/* One expand step: src (ceil(w/2) x ceil(h/2)) -> dst w x h.  tmp holds
 * ceil(w/2)*h. */
void tdc_fvvdp_expand(const double *src, int w, int h, double *dst, double *tmp);
/* Row i of that expand into o (w), with t (ceil(w/2)) as scratch: callers
 * that use the row at once expand inside their own row loop (no barrier,
 * the row still in cache; the same bits as tdc_fvvdp_expand). */
void tdc_fvvdp_expand_row(const double *src, int w, int h, int i, double *t, double *o);

/* ---- temporal channels (tdc_fvvdp_temporal.c) ---- */
#define TDC_FVVDP_MAX_TAPS 256  /* ceil(fps/4): 1000 Hz at most */
/* The history's 16-bit code of a luminance (cd/m^2): an unsigned float of
 * 5 exponent and 11 mantissa bits (no sign: light is never negative),
 * 2^-16 .. 2^15 (2 - 2^-11) = 65520 cd/m^2, rounded to nearest (ties to even).
 * Relative rounding error <= 2^-12 = 0.024 % (a float's 24 bits cut to 12),
 * half that of IEEE half precision, whose sign bit is wasted here;
 * luminance below 2^-16 = 1.5e-5 cd/m^2 (a dark step) reads as 2^-16,
 * beyond the top as the top.  Both ends: integer arithmetic on the float's
 * bits, no table, so the FIR's loop vectorises (tdc_fvvdp.c).
 * docs/visual-model.md gives the JOD change (validation set). */
#define TDC_FVVDP_L16_EXP0 111u /* float exponent field of code 0: 2^(111-127) */
static inline unsigned short tdc_fvvdp_l16(float v)
{
    union { float f; unsigned int u; } b;
    const float lo = 1.52587890625e-05f, hi = 65520.0f; /* 2^-16, 2^15 (2 - 2^-11) */
    b.f = v > lo ? (v < hi ? v : hi) : lo; /* NaN -> lo */
    unsigned int u = b.u - (TDC_FVVDP_L16_EXP0 << 23);
    return (unsigned short)((u + 0x7FFu + ((u >> 12) & 1u)) >> 12);
}
static inline float tdc_fvvdp_l16_value(unsigned short c)
{
    union { float f; unsigned int u; } b;
    b.u = ((unsigned int)c << 12) + (TDC_FVVDP_L16_EXP0 << 23);
    return b.f;
}
/* Taps of the sustained (ch 0) and transient (ch 1) filters at fps; tap 0
 * weighs the newest frame.  Returns the length (ceil(250 ms * fps)). */
int tdc_fvvdp_temporal_filters(double fps, double f[2][TDC_FVVDP_MAX_TAPS]);

/* ---- the CSF (tdc_fvvdp_csf.c) ---- */
/* The spatio-temporal, foveated CSF (sensitivity = 1/threshold Weber
 * contrast) at spatial frequency rho (cpd), temporal frequency omega (Hz),
 * adapting luminance L (cd/m^2) and eccentricity ecc (deg), without the
 * metric's sensitivity correction. */
double tdc_fvvdp_csf(double rho, double omega, double lum, double ecc);
/* The same through the 32^3 table the metric uses (log2 rho, log2 L,
 * sqrt ecc, trilinear in log2 S), channel 0 (omega 0) or 1 (omega 5 Hz). */
double tdc_fvvdp_csf_lut(int ch, double rho, double lum, double ecc);

/* ---- the metric (tdc_fvvdp.c) ---- */
typedef struct tdc_fvvdp tdc_fvvdp_t;

/* fps == 0: images (one sustained channel, no temporal filtering).
 * fps > 0: video; the first frame pads the history ("replicate").
 * Returns NULL with a one-line reason in why (>= 128 bytes) on bad input. */
tdc_fvvdp_t *tdc_fvvdp_new(const tdc_fvvdp_geometry_t *g, double fps, char *why, size_t why_len);
/* A metric judging another test against the same reference as owner: it
 * keeps no reference history, pyramids or scratch planes of its own but
 * reads and reuses owner's, so each frame must be fed to owner first (the
 * reference argument of tdc_fvvdp_frame is then ignored, may be NULL), the
 * metrics of one owner must not run frames at the same time, and owner must
 * outlive them.  Results are the same bits as an unshared metric's. */
tdc_fvvdp_t *tdc_fvvdp_new_shared(tdc_fvvdp_t *owner, char *why, size_t why_len);
/* A metric with its own test and reference beside other (the same geometry
 * and rate: the other eye of a stereo pair): it holds its histories and
 * reference pyramids but works in other's scratch planes (the test's
 * pyramids, contrasts, adaptation), so the metrics sharing them must not run
 * frames at the same time and other must outlive it.  Results are the same
 * bits as a metric of its own; each further metric saves about 7 planes of
 * doubles (165 MB at 1440x1600). */
tdc_fvvdp_t *tdc_fvvdp_new_beside(tdc_fvvdp_t *other, char *why, size_t why_len);
void tdc_fvvdp_free(tdc_fvvdp_t *m);

/* Feed one frame of linear luminance (cd/m^2, row-major w*h) of the test
 * and the reference.  gaze: fixation in pixels (may lie off-screen) for
 * foveated judging, or NULL for foveal sensitivity everywhere.  Returns the
 * JOD of this frame alone. */
double tdc_fvvdp_frame(tdc_fvvdp_t *m, const float *test, const float *ref, const double *gaze);
/* The JOD of every frame fed (since the last reset_pool), pooled as the
 * paper does; 10 before any. */
double tdc_fvvdp_jod(const tdc_fvvdp_t *m);

/* JODs of the whole view and of its regions: within the foveal radius of
 * the gaze and beyond it (NAN without a gaze, or where a region has no
 * pixel).  Regional JODs are tdc's extension: the paper's pooling
 * restricted to the region's pixels (the CSF still sees every pixel's
 * eccentricity); the reference has none, so they are not in the validation. */
typedef struct {
    double all, fovea, periphery;
} tdc_fvvdp_jods_t;
void tdc_fvvdp_pooled(const tdc_fvvdp_t *m, tdc_fvvdp_jods_t *j);
/* The same for the last frame fed. */
void tdc_fvvdp_last(const tdc_fvvdp_t *m, tdc_fvvdp_jods_t *j);
/* Foveal radius in degrees (default 5: fovea and parafovea); -1 if out of
 * (0, 90]. */
int tdc_fvvdp_set_fovea(tdc_fvvdp_t *m, double deg);
/* Forget the pooled frames, keep the temporal history: call once after a
 * warm-up of 250 ms (the filters' length), so that the start-up of a clip,
 * whose history is its first frame repeated, is not judged
 * (docs/visual-model.md). */
void tdc_fvvdp_reset_pool(tdc_fvvdp_t *m);
/* Heat-map hook: with bands non-NULL, every later frame adds its masked
 * difference D of band l (before pooling; transient channel weighted as in
 * pooling) to bands[l], w[l] x h[l] of the pyramid layout, for l < levels - 1.
 * The caller zeroes and collapses them (simulator/tdc_sim_jod.c); NULL stops. */
void tdc_fvvdp_set_dmap(tdc_fvvdp_t *m, double *const *bands);
/* Frames fed so far. */
int tdc_fvvdp_frames(const tdc_fvvdp_t *m);
/* Bytes the metric holds (the temporal history dominates). */
size_t tdc_fvvdp_bytes(const tdc_fvvdp_t *m);
/* The pooling's JOD of a quality Q (0 -> 10). */
double tdc_fvvdp_q2jod(double q);

#endif
