/*
 * tdc_fvvdp_display.c - FovVideoVDP's display model: photometry (display-
 * encoded value -> emitted + reflected luminance) and geometry (pixels per
 * degree, view direction of a pixel, resolution magnification off-axis).
 *
 * Photometry (paper section 3.1, "display model"): L = (Y_peak - Y_black) *
 * EOTF(V) + Y_black with Y_black = Y_peak / contrast + E_amb / pi * k_refl
 * (the screen as a Lambertian reflector of the ambient light).
 *
 * Geometry: a flat screen of width_m seen from distance_m, square pixels.
 * The view direction of a point is (atan(x_m / d), atan(y_m / d)) in
 * degrees, and the eccentricity the metric uses is the Euclidean distance
 * between two such direction pairs (as the reference implementation does;
 * within 0.3 deg of the great-circle angle up to 30 deg off-axis).
 */
#include <math.h>

#include "metrics/tdc_fvvdp.h"

#define RAD2DEG (180.0 / M_PI)
#define DEG2RAD (M_PI / 180.0)

double tdc_fvvdp_black(const tdc_fvvdp_photometry_t *p)
{
    return p->y_peak / p->contrast + p->e_ambient / M_PI * p->k_refl;
}

/* IEC 61966-2-1 sRGB decoding. */
static double srgb2lin(double v)
{
    return v > 0.04045 ? pow((v + 0.055) / 1.055, 2.4) : v / 12.92;
}

double tdc_fvvdp_lum(const tdc_fvvdp_photometry_t *p, int c, double v)
{
    double yb = tdc_fvvdp_black(p);
    v = v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
    double e = p->eotf == TDC_FVVDP_EOTF_SRGB ? srgb2lin(v) : pow(v, p->gamma[c]);
    return (p->y_peak - yb) * e + yb;
}

double tdc_fvvdp_lum_rgb(const tdc_fvvdp_photometry_t *p, const double v[3])
{
    return p->rgb2y[0] * tdc_fvvdp_lum(p, 0, v[0]) + p->rgb2y[1] * tdc_fvvdp_lum(p, 1, v[1]) +
           p->rgb2y[2] * tdc_fvvdp_lum(p, 2, v[2]);
}

tdc_fvvdp_geometry_t tdc_fvvdp_geometry_ppd(int width, int height, double ppd)
{
    /* ppd = 1 / (2 atan(w_px / 2 / d) in deg), w_px = width_m / width. */
    tdc_fvvdp_geometry_t g = { width, height, 0.0, 1.0 };
    g.width_m = 2.0 * width * tan(0.5 / ppd * DEG2RAD);
    return g;
}

double tdc_fvvdp_ppd(const tdc_fvvdp_geometry_t *g)
{
    return 1.0 / (2.0 * RAD2DEG * atan(0.5 * g->width_m / g->width / g->distance_m));
}

void tdc_fvvdp_view_dir(const tdc_fvvdp_geometry_t *g, double w, double h, double x, double y, double out[2])
{
    double height_m = g->width_m * g->height / g->width;
    double xm = (x - w / 2.0) * g->width_m / w;
    double ym = -(y - h / 2.0) * height_m / h;
    out[0] = RAD2DEG * atan(xm / g->distance_m);
    out[1] = RAD2DEG * atan(ym / g->distance_m);
}

double tdc_fvvdp_res_mag(const tdc_fvvdp_geometry_t *g, const double dir[2])
{
    /* Pixels per degree at view angle a: one pixel (1/ppd deg at the centre)
     * spans tan(a + delta) - tan(a) of the screen, delta half a pixel. */
    double ppd = tdc_fvvdp_ppd(g);
    double a = sqrt(dir[0] * dir[0] + dir[1] * dir[1]);
    a = a < 89.9 ? a : 89.9;
    double delta = 0.5 / ppd;
    double r = (tan((a + delta) * DEG2RAD) - tan(a * DEG2RAD)) / tan(delta * DEG2RAD);
    return r;
}
