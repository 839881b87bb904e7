/*
 * ref_trm_gaze.h - double-precision reference of gaze-aware TRM's strength
 * (firmware/tdc_trm_gaze.h), straight from its definition:
 *     k(u) = 1 for |u|^2 <= u0^2, kmin for |u|^2 >= u1^2,
 *            1 - (1 - kmin) (|u|^2 - u0^2) / (u1^2 - u0^2) between,
 * u = m - g the retinal motion in px per frame; the frames through
 * ref_trm.h with tdc_ref_trm_t.strength set to the per-pixel map.
 */
#ifndef TDC_REF_TRM_GAZE_H
#define TDC_REF_TRM_GAZE_H

double tdc_ref_trm_gaze_strength(double u0, double u1, double kmin, double udx, double udy);

/* Per-pixel map (w*h) of tiles tile x tile from per-tile motion (mvx, mvy,
 * px/frame, tx*ty each) and gaze (gx, gy). */
void tdc_ref_trm_gaze_map(int w, int h, int tile, double u0, double u1, double kmin, const double *mvx,
                          const double *mvy, double gx, double gy, double *k);

#endif
