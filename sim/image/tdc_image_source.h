/*
 * tdc_image_source.h - a simulator source that pans, zooms and rotates
 * across a photograph, with exact area-sampled ground truth.
 *
 * The scene.  The photograph is a piecewise-constant field of linear light:
 * texel (i, j) covers [i, i+1) x [j, j+1) in image coordinates and emits the
 * linear value of its code (sRGB EOTF, IEC 61966-2-1; 16-bit PNGs keep their
 * 16 bits).  Beyond the image the field is mirrored (period 2W x 2H), so a
 * long pan never shows edge streaks and the field stays piecewise constant.
 * Screen point p (pixels, y down) sees image point
 *     q(p, t) = c(t) + R(-theta(t)) (p - p_c) / z(t)
 * with p_c the screen centre, z(t) = z0 exp(zoom_rate t) screen pixels per
 * texel, theta(t) = rotate * t (clockwise on screen for rotate > 0 since y
 * points down) and c(t) = c0 - u t the image point at the screen centre;
 * u = v / z0 along --angle, so the content at the centre moves at the pan
 * speed v (px/s) at t = 0.
 *
 * Ground truth (the filter, exactly).  Pixel (x, y) shifted by (ox, oy) is
 * the mean of the field over the pixel's preimage, the quadrilateral q([x+ox,
 * x+ox+1) x [y+oy, y+oy+1), t): a box filter in screen space of the exact
 * field, evaluated in closed form, not by supersampling.  By Green's theorem
 * the integral over the quad is the contour integral of F(x, y) dy with F the
 * running integral of the field along its row, F(x, j) = sum of the texels
 * left of x plus the fractional part of the texel under x.  Each edge is cut
 * where it crosses texel rows and columns; on each piece F is linear in the
 * parameter, so the midpoint rule is exact.  Per-row prefix sums (double)
 * give F in O(1); neighbouring pixels share edges, so each edge is computed
 * once.  mean = integral / det(dq/dp) = integral * z^2.  Only the time
 * integral of the eye's window is a quadrature (tdc_eye_ground_truth: one
 * instant when the content is rigid under pursuit, i.e. a pure pan, else
 * midpoint steps).
 *
 * Rendering.  samples() are point samples of the same field (nearest texel:
 * a renderer without texture prefiltering), spp > 1 stratified g x g in the
 * pixel as the procedural scenes do; MVs are the exact backward screen
 * displacement over dt of the image point seen (q(p', t - dt) = q(p, t)).
 */
#ifndef TDC_IMAGE_SOURCE_H
#define TDC_IMAGE_SOURCE_H

#include <stddef.h>

#include "simulator/tdc_sim_scene.h"

typedef struct {
    double zoom;       /* z0: screen pixels per texel at t = 0 (> 0; default 1) */
    double zoom_rate;  /* d ln z / dt, 1/s (0: no zoom) */
    double rotate_dps; /* degrees per second (0: no rotation) */
    double cx, cy;     /* c0: image point at the screen centre at t = 0; NAN: the image centre */
} tdc_image_motion_t;

void tdc_image_motion_default(tdc_image_motion_t *m);

/* Source over a photograph file (PNG or JPEG).  p gives the screen size, the
 * pan speed (< 0: 0) and angle, the seed (unused) and pursuit (1: the eye
 * tracks the content at the screen centre).  Returns NULL with one line in
 * err on bad input (file, size, parameters). */
tdc_source_t *tdc_image_source_open(const char *path, const tdc_scene_params_t *p, const tdc_image_motion_t *m,
                                    char *err, size_t errlen);

/* The same over a linear-light image iw x ih x 3 (copied), for tests. */
tdc_source_t *tdc_image_source_from_linear(const double *lin, int iw, int ih, const tdc_scene_params_t *p,
                                           const tdc_image_motion_t *m, char *err, size_t errlen);

/* The map at time t: q = A p + b (A row-major 2x2). */
void tdc_image_source_map(const tdc_source_t *s, double t, double A[4], double b[2]);

/* Largest pursuit speed (px/s, the content at the screen centre) over
 * [0, duration]: for the evaluation margin. */
double tdc_image_source_max_speed(const tdc_source_t *s, double duration);

#endif
