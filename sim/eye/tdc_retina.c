/* tdc_retina.c - the retinal signal: emitted light in cd/m^2 per time step,
 * stabilised along the eye's movement (see tdc_retina.h). */
#include "eye/tdc_retina.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_par.h"

#define DEG2RAD (M_PI / 180.0)
#define EYE_STEP_S 0.0005 /* 2 kHz: finer than any refresh step (<= 1000 Hz x 8) needs for 0.5 px at 1000 px/s */
#define MAX_SUB 64

int tdc_retina_display_from_panel(const tdc_panel_t *p, double ppd, const char *ppd_from, int w,
                                  tdc_retina_display_t *d, char *why, size_t why_len)
{
    memset(d, 0, sizeof(*d));
    const char *missing = !p->peak_mcdm2 ? "peak_cdm2" : (!p->distance_mm ? "distance_m" : NULL);
    if (missing) {
        snprintf(why, why_len, "panel profile %s has no photometry: key '%s' missing (boards/panels/%s.panel)",
                 p->name, missing, p->name);
        return -1;
    }
    if (p->black_ucdm2 >= 1000u * (uint64_t)p->peak_mcdm2) {
        snprintf(why, why_len, "panel profile %s: black_cdm2 must be below peak_cdm2", p->name);
        return -1;
    }
    if (!(ppd >= 1.0 && ppd <= 1000.0) || w < 1) {
        snprintf(why, why_len, "pixels per degree %g out of range 1 .. 1000", ppd);
        return -1;
    }
    d->panel = p->name;
    d->ppd = ppd;
    d->ppd_from = ppd_from;
    d->distance_m = p->distance_mm / 1e3;
    d->width_m = 2.0 * d->distance_m * tan(0.5 * w / ppd * DEG2RAD);
    d->peak_cdm2 = p->peak_mcdm2 / 1e3;
    d->black_cdm2 = p->black_ucdm2 / 1e6;
    for (int c = 0; c < 3; c++) {
        d->gamma[c] = p->gamma_micro[c] / 1e6;
    }
    d->rgb2y[0] = 0.2126; /* ITU-R BT.709 */
    d->rgb2y[1] = 0.7152;
    d->rgb2y[2] = 0.0722;
    return 0;
}

int tdc_retina_steps(int n, int lcd, double persistence)
{
    if (n > 0) {
        return n;
    }
    if (lcd) {
        return 4; /* the LCD simulation's transition slices (TDC_PANEL_SIM_MAX_SLICES) */
    }
    int k = persistence > 0.0 ? (int)floor(1.0 / persistence + 0.5) : 1;
    return k < 1 ? 1 : (k > 8 ? 8 : k);
}

int tdc_retina_eye_init(tdc_retina_eye_t *e, const tdc_sim_gaze_t *gaze, tdc_source_t *src, double gain,
                        double lag_s, int w, int h, double duration_s)
{
    memset(e, 0, sizeof(*e));
    e->schedule = gaze->schedule;
    e->gain = gain;
    e->lag_s = lag_s;
    e->w = w;
    e->h = h;
    e->step = EYE_STEP_S;
    e->n = (int)ceil((duration_s + 1.0) / e->step) + 2;
    e->p = malloc(sizeof(double) * 2 * (size_t)e->n);
    e->a = malloc(sizeof(double) * 2 * (size_t)e->n);
    if (!e->p || !e->a) {
        tdc_retina_eye_free(e);
        return -1;
    }
    double x = w / 2.0, y = h / 2.0, ax = x, ay = y;
    for (int k = 0; k < e->n; k++) {
        const double t = k * e->step;
        if (e->schedule != TDC_GAZE_PURSUIT) {
            double g[2];
            tdc_sim_gaze_true(gaze, t, g);
            if (k == 0 || g[0] != x || g[1] != y) {
                ax = g[0]; /* a new fixation: a saccade */
                ay = g[1];
            }
            x = g[0];
            y = g[1];
        } else if (k > 0) {
            /* velocity over the step just ended, at its start, delayed by the lag */
            double v[2] = {0.0, 0.0}, tv = t - e->step - lag_s;
            if (tv >= 0.0 && src && src->pursuit) {
                src->pursuit(src, tv, v);
            }
            x += gain * v[0] * e->step;
            y += gain * v[1] * e->step;
            if (fabs(x - w / 2.0) > w / 4.0 || fabs(y - h / 2.0) > h / 4.0) {
                x = ax = w / 2.0;
                y = ay = h / 2.0;
            }
        }
        e->p[2 * k] = x;
        e->p[2 * k + 1] = y;
        e->a[2 * k] = ax;
        e->a[2 * k + 1] = ay;
    }
    return 0;
}

void tdc_retina_eye_free(tdc_retina_eye_t *e)
{
    free(e->p);
    free(e->a);
    e->p = e->a = NULL;
}

void tdc_retina_eye_at(const tdc_retina_eye_t *e, double t, double pos[2], double anchor[2])
{
    double u = t / e->step;
    long k = (long)floor(u);
    k = k < 0 ? 0 : (k >= e->n - 1 ? e->n - 2 : k);
    double f = u - k;
    f = f < 0.0 ? 0.0 : (f > 1.0 ? 1.0 : f);
    const double *p0 = e->p + 2 * k, *p1 = p0 + 2, *a0 = e->a + 2 * k, *a1 = a0 + 2;
    const int same = a0[0] == a1[0] && a0[1] == a1[1]; /* no saccade inside the step: glide */
    for (int c = 0; c < 2; c++) {
        pos[c] = same ? p0[c] + (p1[c] - p0[c]) * f : p0[c];
        anchor[c] = a0[c];
    }
}

/* Retinal shift D(t) = p(t) - a(t). */
static void shift_at(const tdc_retina_eye_t *e, double t, double s[2])
{
    double p[2], a[2];
    if (!e) {
        s[0] = s[1] = 0.0;
        return;
    }
    tdc_retina_eye_at(e, t, p, a);
    s[0] = p[0] - a[0];
    s[1] = p[1] - a[1];
}

int tdc_retina_sample(const tdc_retina_eye_t *eye, const tdc_eye_slice_t *sl, int n, double a, double b, double norm,
                      const tdc_retina_display_t *d, int w, int h, double *acc, float *rgb, float *y)
{
    const size_t np = (size_t)w * h;
    const double T = b - a, gain = d->peak_cdm2 - d->black_cdm2;
    double black = 0.0; /* the black level times the emitting share of [a, b) */
    int lit = 0;
    for (int i = 0; i < n && !lit; i++) {
        lit = sl[i].t0 < b && sl[i].t1 > a;
    }
    if (!lit) {
        /* no light in the step (4 of an OLED's 5 at 20 % persistence): all
         * zero bits are 0.0f */
        if (rgb) {
            memset(rgb, 0, sizeof(float) * 3 * np);
        }
        if (y) {
            memset(y, 0, sizeof(float) * np);
        }
        return 1;
    }
    memset(acc, 0, sizeof(double) * (rgb ? 3 : 1) * np);
    for (int i = 0; i < n; i++) {
        const double a1 = sl[i].t0 > a ? sl[i].t0 : a, b1 = sl[i].t1 < b ? sl[i].t1 : b;
        if (b1 <= a1 || (!sl[i].lin && (!sl[i].codes || !sl[i].lut))) {
            continue;
        }
        black += d->black_cdm2 * norm * (b1 - a1) / T;
        double *plane = acc + np; /* the luminance alone: the slice's, decoded once */
        if (!rgb) {
            tdc_eye_slice_luminance(&sl[i], d->rgb2y, w, h, plane);
        }
        /* sub-steps: at most 0.5 px of retinal motion apart (the eye's
         * displacement over the overlap, sampled at its ends and middle) */
        double s0[2], s1[2], sm[2];
        shift_at(eye, a1, s0);
        shift_at(eye, b1, s1);
        shift_at(eye, 0.5 * (a1 + b1), sm);
        double dist = fmax(hypot(sm[0] - s0[0], sm[1] - s0[1]) + hypot(s1[0] - sm[0], s1[1] - sm[1]), 0.0);
        int nsub = (int)ceil(dist / 0.5);
        nsub = nsub < 1 ? 1 : (nsub > MAX_SUB ? MAX_SUB : nsub);
        const double dt = (b1 - a1) / nsub;
        double sxy[2 * MAX_SUB], wgt[MAX_SUB];
        for (int k = 0; k < nsub; k++) {
            shift_at(eye, a1 + (k + 0.5) * dt, sxy + 2 * k);
            wgt[k] = gain * norm * dt / T;
        }
        if (tdc_eye_accumulate_steps(acc, &sl[i], rgb ? NULL : plane, w, h, nsub, sxy, wgt)) {
            return -1;
        }
    }
    if (!rgb) {
        /* the luminance alone: the black level's is black times the sum of
         * the weights */
        const double yb = black * (d->rgb2y[0] + d->rgb2y[1] + d->rgb2y[2]);
        TDC_PAR_FOR(np)
        for (int yy = 0; yy < h; yy++) {
            for (size_t j = (size_t)yy * w; j < (size_t)(yy + 1) * w; j++) {
                y[j] = (float)(acc[j] + yb);
            }
        }
        return 0;
    }
    TDC_PAR_FOR(np)
    for (int yy = 0; yy < h; yy++) {
        for (size_t j = (size_t)yy * w; j < (size_t)(yy + 1) * w; j++) {
            const double r = acc[3 * j] + black, g = acc[3 * j + 1] + black, bl = acc[3 * j + 2] + black;
            rgb[3 * j] = (float)r;
            rgb[3 * j + 1] = (float)g;
            rgb[3 * j + 2] = (float)bl;
            if (y) {
                y[j] = (float)(d->rgb2y[0] * r + d->rgb2y[1] * g + d->rgb2y[2] * bl);
            }
        }
    }
    return 0;
}
