/* ref_trm_gaze.c - double reference of gaze-aware TRM's strength (ref_trm_gaze.h). */
#include "ref_trm_gaze.h"

#include <stddef.h>

double tdc_ref_trm_gaze_strength(double u0, double u1, double kmin, double udx, double udy)
{
    double s2 = udx * udx + udy * udy;
    if (s2 <= u0 * u0) {
        return 1.0;
    }
    if (s2 >= u1 * u1) {
        return kmin;
    }
    return 1.0 - (1.0 - kmin) * (s2 - u0 * u0) / (u1 * u1 - u0 * u0);
}

void tdc_ref_trm_gaze_map(int w, int h, int tile, double u0, double u1, double kmin, const double *mvx,
                          const double *mvy, double gx, double gy, double *k)
{
    int tx = (w + tile - 1) / tile;
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            int t = (y / tile) * tx + x / tile;
            k[(size_t)y * w + x] = tdc_ref_trm_gaze_strength(u0, u1, kmin, mvx[t] - gx, mvy[t] - gy);
        }
    }
}
