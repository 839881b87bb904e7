/* tdc_eye_temporal.c - temporal contrast-sensitivity filter of the retinal
 * error (see tdc_eye_temporal.h). */
#include "eye/tdc_eye_temporal.h"

#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_bilinear.h"
#include "tdc_par.h"

void tdc_tcsf_default(tdc_tcsf_t *p)
{
    p->n1 = 9;
    p->n2 = 10;
    p->tau_s = 0.0043;
    p->kappa = 1.33;
    p->zeta = 0.9;
    p->support_s = 0.12; /* h1, h2 peak at (n-1) tau = 34-52 ms; < 1e-3 of the peak after 120 ms */
}

static int params_ok(const tdc_tcsf_t *p)
{
    return p && p->n1 >= 1 && p->n2 >= 1 && p->n1 <= 30 && p->n2 <= 30 && p->tau_s > 0.0 && p->kappa > 0.0 &&
           p->zeta >= 0.0 && p->zeta < 1.0 && p->support_s > 0.0;
}

/* Unnormalised H(f). */
static double complex tcsf_h(const tdc_tcsf_t *p, double f)
{
    const double w = 2.0 * M_PI * f;
    double complex a = cpow(1.0 + I * w * p->tau_s, -(double)p->n1);
    double complex b = cpow(1.0 + I * w * p->kappa * p->tau_s, -(double)p->n2);
    return a - p->zeta * b;
}

double tdc_tcsf_peak_hz(const tdc_tcsf_t *p, double *xi)
{
    /* |H| is smooth and unimodal over f >= 0 for these filters: a fine scan
     * then golden-section refinement */
    double best_f = 0.0, best = cabs(tcsf_h(p, 0.0));
    for (double f = 0.25; f <= 200.0; f += 0.25) {
        double g = cabs(tcsf_h(p, f));
        if (g > best) {
            best = g;
            best_f = f;
        }
    }
    double lo = fmax(0.0, best_f - 0.25), hi = best_f + 0.25;
    const double phi = 0.5 * (sqrt(5.0) - 1.0);
    for (int i = 0; i < 60; i++) {
        double a = hi - phi * (hi - lo), b = lo + phi * (hi - lo);
        if (cabs(tcsf_h(p, a)) > cabs(tcsf_h(p, b))) {
            hi = b;
        } else {
            lo = a;
        }
    }
    best_f = 0.5 * (lo + hi);
    best = fmax(best, cabs(tcsf_h(p, best_f)));
    if (xi) {
        *xi = 1.0 / best;
    }
    return best_f;
}

double tdc_tcsf_gain(const tdc_tcsf_t *p, double f_hz)
{
    if (!params_ok(p)) {
        return NAN;
    }
    double xi;
    tdc_tcsf_peak_hz(p, &xi);
    return xi * cabs(tcsf_h(p, f_hz));
}

/* integral_0^t of the gamma density of order n, scale tau: the regularised
 * lower incomplete gamma P(n, t/tau) = 1 - e^-x sum_{i<n} x^i / i!. */
static double gamma_cdf(int n, double tau, double t)
{
    if (t <= 0.0) {
        return 0.0;
    }
    const double x = t / tau;
    double term = 1.0, sum = 1.0;
    for (int i = 1; i < n; i++) {
        term *= x / i;
        sum += term;
    }
    return 1.0 - exp(-x) * sum;
}

int tdc_tcsf_taps(const tdc_tcsf_t *p, double rate_hz, double *taps, int max)
{
    if (!params_ok(p) || !(rate_hz > 0.0) || !taps || max < 1) {
        return 0;
    }
    int k = (int)ceil(p->support_s * rate_hz - 1e-9);
    k = k < 1 ? 1 : (k > max ? max : k);
    double xi;
    tdc_tcsf_peak_hz(p, &xi);
    const double t2 = p->kappa * p->tau_s;
    for (int i = 0; i < k; i++) {
        double a = i / rate_hz, b = (i + 1) / rate_hz;
        double h1 = gamma_cdf(p->n1, p->tau_s, b) - gamma_cdf(p->n1, p->tau_s, a);
        double h2 = gamma_cdf(p->n2, t2, b) - gamma_cdf(p->n2, t2, a);
        /* the box-sampled integral carries the 1/R of the sum's dt: taps act
         * on samples as H acts on the signal (DC gain sum = xi (1 - zeta)) */
        taps[i] = xi * (h1 - p->zeta * h2);
    }
    return k;
}

int tdc_eye_temporal_init(tdc_eye_temporal_t *t, const tdc_tcsf_t *p, double rate_hz, int w, int h)
{
    memset(t, 0, sizeof(*t));
    if (w < 1 || h < 1) {
        return -1;
    }
    t->k = tdc_tcsf_taps(p, rate_hz, t->taps, TDC_TCSF_MAX_TAPS);
    if (t->k < 1) {
        return -1;
    }
    t->w = w;
    t->h = h;
    t->ring = malloc(sizeof(float) * (size_t)t->k * w * h);
    t->rows = malloc(sizeof(double) * (size_t)h);
    if (!t->ring || !t->rows) {
        tdc_eye_temporal_free(t);
        return -1;
    }
    return 0;
}

void tdc_eye_temporal_free(tdc_eye_temporal_t *t)
{
    free(t->ring);
    free(t->rows);
    t->ring = NULL;
    t->rows = NULL;
}

double tdc_eye_temporal_push(tdc_eye_temporal_t *t, const double *err, double gx, double gy)
{
    const int w = t->w, h = t->h;
    const size_t np = (size_t)w * h;
    float *slot = t->ring + (size_t)t->head * np;
    TDC_PAR_FOR(np)
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const double *e = err + 3 * ((size_t)y * w + x);
            slot[(size_t)y * w + x] = (float)(0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2]);
        }
    }
    t->gx[t->head] = gx;
    t->gy[t->head] = gy;
    const int newest = t->head;
    t->head = (t->head + 1) % t->k;
    if (t->count < t->k) {
        t->count++;
    }
    if (t->count < t->k) {
        return -1.0;
    }
    /* F(x) = sum_i taps[i] E_{j-i}(x + g_{j-i} - g_j): the retinal point at
     * x now was seen at x - (g_j - g_{j-i}) i instants ago */
    TDC_PAR_FOR(np)
    for (int y = 0; y < h; y++) {
        double se = 0.0;
        for (int x = 0; x < w; x++) {
            double f = 0.0;
            for (int i = 0; i < t->k; i++) {
                int s = (newest - i + t->k) % t->k;
                double dx = t->gx[s] - gx, dy = t->gy[s] - gy;
                const float *img = t->ring + (size_t)s * np;
                f += t->taps[i] * (dx == 0.0 && dy == 0.0 ? img[(size_t)y * w + x]
                                                          : tdc_bilinear_f(img, w, h, 1, x + dx, y + dy, 0));
            }
            se += f * f;
        }
        t->rows[y] = se;
    }
    return 255.0 * sqrt(tdc_par_sum_rows(t->rows, h) / (double)np);
}
