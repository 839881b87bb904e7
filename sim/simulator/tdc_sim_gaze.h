/*
 * tdc_sim_gaze.h - where the simulated eye looks (the gaze point of
 * foveated streams, issue 14) and what the eye tracker reports of it.
 *
 * Schedules (tdc-sim --gaze):
 *   pursuit  the gaze starts at the screen centre and moves with the
 *            velocity the eye pursues (the scene's main motion); when it
 *            leaves the central half of the screen it jumps back to the
 *            centre (a saccade)
 *   fixed    the screen centre (--gaze-at X,Y: that point, pixels)
 *   saccade  fixations on four points around the centre, 250 ms each,
 *            jumping between them
 * The tracker (what the renderer and the controller foveate around):
 * the true gaze at t - latency (--gaze-latency ms) plus Gaussian noise of
 * sigma --gaze-noise degrees per axis (pixels = degrees x the view's
 * pixels per degree), drawn per rendered frame from the run's seed.
 * The metrics weight errors by eccentricity around the TRUE gaze.
 *
 * Note: the legacy eye model's retinal motion compensation stays the run's
 * (--pursuit fixate / pursuit of the scene); the gaze point only decides
 * where the fovea is.  The retinal signal (eye/tdc_retina.h) follows the
 * schedule itself: its eye moves along this table's schedules (pursuit with
 * --pursuit-gain and --pursuit-lag).
 */
#ifndef TDC_SIM_GAZE_H
#define TDC_SIM_GAZE_H

#include <stdint.h>

#include "simulator/tdc_sim_scene.h"

typedef enum { TDC_GAZE_PURSUIT = 0, TDC_GAZE_FIXED = 1, TDC_GAZE_SACCADE = 2 } tdc_gaze_schedule_t;

typedef struct {
    int schedule; /* tdc_gaze_schedule_t */
    double at_x, at_y;   /* fixed: the point (< 0: the centre) */
    double latency_ms;   /* tracker latency */
    double noise_deg;    /* tracker noise, sigma per axis */
    double ppd;          /* pixels per degree */
    uint32_t seed;
    int w, h;
    double step;         /* table step, s */
    int n;               /* table entries */
    double *xy;          /* true gaze at k * step */
} tdc_sim_gaze_t;

/* "pursuit", "fixed", "saccade" -> schedule, -1 if unknown. */
int tdc_sim_gaze_from_name(const char *name);
const char *tdc_sim_gaze_name(int schedule);
/* Tabulates the true gaze over [0, duration + 1 s] at the source's
 * pursuit velocity (src may be NULL for fixed and saccade).  0 or -1 (memory). */
int tdc_sim_gaze_init(tdc_sim_gaze_t *g, tdc_source_t *src, int w, int h, double hz, double duration_s);
void tdc_sim_gaze_free(tdc_sim_gaze_t *g);
/* The true gaze at time t (pixels, centres at i + 0.5). */
void tdc_sim_gaze_true(const tdc_sim_gaze_t *g, double t, double xy[2]);
/* What the tracker reports for a frame rendered at t (frame = its index,
 * eye: the eye, for independent noise). */
void tdc_sim_gaze_tracked(const tdc_sim_gaze_t *g, double t, uint32_t frame, int eye, double xy[2]);
/* Distance from the gaze to the farthest screen corner. */
double tdc_sim_gaze_rmax(const tdc_sim_gaze_t *g, const double xy[2]);

#endif
