/*
 * tdc_retina.h - the retinal signal a visible-difference predictor judges:
 * the panel's emitted light, resolved in time, in photometric units
 * (cd/m^2), stabilised along the eye's movement, at the physical frame rate.
 * No fused window: the eye's temporal integration is the metric's business
 * (its temporal channels), not a box over a number of refreshes.
 *
 * Time: the run's refresh clock R is cut into N equal steps per refresh
 * (N = --retina-steps, or automatic: enough to resolve an OLED's low
 * persistence pulse, N = round(1 / persistence) up to 8, and an LCD's four
 * transition slices); the signal has R N frames per second.  Step k covers
 * [k / (R N), (k + 1) / (R N)) and its image is the mean over that interval
 *     S_k(x) = (R N) integral L(x + D(t), t) dt,
 * L the emitted luminance of every channel (below) and D(t) the eye's
 * displacement since its last saccade (below): a point the eye tracks stays
 * at the same x.  Sub-steps of the integral are at most 0.5 px of retinal
 * motion apart (bilinear lookups, edges clamped; tdc_eye_accumulate).
 *
 * Light: during a panel slice (tdc_panel_sim.h) a channel of linear value v
 * emits (Y_black + (Y_peak - Y_black) v) * norm cd/m^2, norm = 1 / duty of
 * an OLED's persistence (a low-persistence panel drives the pulse brighter
 * so that its time average is the nominal level; black-frame insertion then
 * halves the mean, as it does on a real panel), 0 between slices.  Y_peak,
 * Y_black and the per-channel gamma (EOTF v = (code / 255)^gamma) come from
 * the panel profile (peak_cdm2, black_cdm2, gamma: boards/panels/).
 *
 * The eye: a table of its screen position p(t) (0.5 ms steps, independent
 * of the refresh rate) from the gaze schedule (tdc_sim_gaze.h):
 *   pursuit  from the centre at gain x the pursued velocity delayed by the
 *            pursuit lag (0 before the lag has passed: the retinal slip of
 *            pursuit onset); a saccade back to the centre when it leaves the
 *            central half of the screen (the gaze table's rule)
 *   fixed    the --gaze-at point; saccade: the gaze table's fixations
 * --pursuit fixate makes the pursued velocity 0: fixation.  D(t) = p(t) -
 * a(t), a the position at the last saccade, so between saccades the gaze
 * point in the stabilised image is a(t) (pixels, centres at i + 0.5).
 * Tracker latency and noise move what the renderer and controller foveate
 * around (the modes), not the eye.
 *
 * Reference and test go through the same path: the reference is the scene's
 * ground truth rendered for each refresh of the run clock (at the middle of
 * its emission, as the modes render), encoded to drive codes with the
 * panel's gamma and shown on its own copy of the same panel simulation
 * (same persistence, LCD model and backlight), then the same integral.
 */
#ifndef TDC_RETINA_H
#define TDC_RETINA_H

#include <stddef.h>

#include "eye/tdc_eye.h"
#include "simulator/tdc_sim_gaze.h"
#include "tdc_panel.h"

/* Geometry and photometry of the view, from the panel profile. */
typedef struct {
    const char *panel;
    double ppd;           /* pixels per degree at the view centre */
    const char *ppd_from; /* "profile", "--ppd" or "default" (FLIP's desktop 67.02) */
    double distance_m;    /* viewing distance (HMD: the lens's virtual image) */
    double width_m;       /* physical width of the simulated view: 2 d tan(w / 2 / ppd) */
    double peak_cdm2, black_cdm2;
    double gamma[3];      /* EOTF per channel: (code / 255)^gamma */
    double rgb2y[3];      /* luminance of the primaries (Rec. 709 weights) */
} tdc_retina_display_t;

/* Fills d from profile p for a view w pixels wide.  0, or -1 with one line
 * naming the missing or inconsistent profile key in why. */
int tdc_retina_display_from_panel(const tdc_panel_t *p, double ppd, const char *ppd_from, int w,
                                  tdc_retina_display_t *d, char *why, size_t why_len);

/* The eye's trajectory. */
typedef struct {
    int schedule;      /* tdc_gaze_schedule_t */
    double gain, lag_s;
    int w, h;
    double step;       /* table step, s */
    int n;
    double *p;         /* 2n: screen position */
    double *a;         /* 2n: position at the last saccade */
} tdc_retina_eye_t;

/* Tabulates the eye over [0, duration + 1 s].  gaze: the run's gaze table
 * (fixed and saccade schedules); src: the pursued velocity.  0 or -1. */
int tdc_retina_eye_init(tdc_retina_eye_t *e, const tdc_sim_gaze_t *gaze, tdc_source_t *src, double gain,
                        double lag_s, int w, int h, double duration_s);
void tdc_retina_eye_free(tdc_retina_eye_t *e);
/* Position at t (continuous between saccades) and the last saccade's landing point. */
void tdc_retina_eye_at(const tdc_retina_eye_t *e, double t, double pos[2], double anchor[2]);

/* One step of the signal, handed to a consumer (the metric, --dump). */
typedef struct {
    const char *mode;        /* the test's mode name */
    int eye;                 /* 0, or 1 (right) in stereo */
    long step, refresh;      /* step index and the run-clock refresh it lies in */
    double t0, t1;           /* seconds */
    double fps;              /* steps per second: R N */
    int width, height;
    const float *test, *ref;     /* w*h*3, cd/m^2 per channel; NULL unless --dump writes them */
    const float *test_y, *ref_y; /* w*h, luminance cd/m^2 (rgb2y) */
    int test_dark, ref_dark;     /* 1: no light in the step, the planes are all zero */
    double gaze[2];              /* true gaze in the stabilised image, pixels */
    double gaze_screen[2];       /* true gaze on the screen at the step's middle */
    double shift[2];             /* D at the step's middle: image x shows screen x + D */
    const tdc_retina_display_t *display;
} tdc_retina_frame_t;

/* A consumer: called per step, mode and eye in time order.  Non-zero stops
 * the run (it is reported as an output failure). */
typedef int (*tdc_retina_cb_t)(void *ctx, const tdc_retina_frame_t *f);

/* Mean emitted luminance over [a, b) of n slices as S_k above; eye NULL: no
 * stabilisation (the light on the screen).  rgb (w*h*3) and y (w*h, may be
 * NULL) receive cd/m^2; acc: w*h*3 doubles of scratch.  rgb NULL: the
 * luminance alone into y (non-NULL then), integrated as one plane (a third
 * of the work; acc 2 w*h doubles).  0; 1 when no slice emits in [a, b)
 * (the planes are zero: a consumer may skip them); -1 (memory). */
int tdc_retina_sample(const tdc_retina_eye_t *eye, const tdc_eye_slice_t *sl, int n, double a, double b, double norm,
                      const tdc_retina_display_t *d, int w, int h, double *acc, float *rgb, float *y);

/* Steps per refresh: N if N > 0, else automatic (above). */
int tdc_retina_steps(int n, int lcd, double persistence);

#endif
