/*
 * tdc_lcd_model.h - double-precision reference of the LCD temporal model
 * M(v_t, v_{t-1}) (TRM paper eq. 7) and of its inverse, written straight
 * from the equations, with the same case rules as the firmware
 * (firmware/tdc_lcd.h): increasing-branch root first, roots count when in
 * [-h, 1 + h], unreachable targets go to the nearest of {0, 1, vertex}.
 * Header-only so that the host tools (tdc-tablegen, tdc-calib) use the very
 * same code without linking the simulator library.
 */
#ifndef TDC_LCD_MODEL_H
#define TDC_LCD_MODEL_H

#include <math.h>

enum { TDC_LCDM_ROOT = 0, TDC_LCDM_CLAMP_LOW = 1, TDC_LCDM_CLAMP_HIGH = 2 };

/* M(v, u) = p1 (v^2 + u^2) + p2 v u + p3 (v + u) + p4. */
static inline double tdc_lcdm_M(const double p[4], double v, double u)
{
    return p[0] * (v * v + u * u) + p[1] * v * u + p[2] * (v + u) + p[3];
}

/* Root of a v^2 + b v + c = 0 in [-h, 1 + h], increasing branch first;
 * returns 1 and *v clamped to [0, 1], or 0. */
static inline int tdc_lcdm_quad_root(double a, double b, double c, double h, double *v)
{
    double cand[2];
    int n = 0;
    if (a == 0.0) {
        if (b != 0.0) {
            cand[n++] = -c / b;
        }
    } else {
        double disc = b * b - 4.0 * a * c;
        if (disc < 0.0) {
            return 0;
        }
        double s = sqrt(disc);
        double q2 = b >= 0.0 ? -(b + s) : (s - b);
        double r_qa = q2 / (2.0 * a);
        if (b >= 0.0) {
            if (q2 != 0.0) {
                cand[n++] = 2.0 * c / q2;
            }
            cand[n++] = r_qa;
        } else {
            cand[n++] = r_qa;
            if (q2 != 0.0) {
                cand[n++] = 2.0 * c / q2;
            }
        }
    }
    for (int k = 0; k < n; k++) {
        if (cand[k] >= -h && cand[k] <= 1.0 + h) {
            *v = cand[k] < 0.0 ? 0.0 : (cand[k] > 1.0 ? 1.0 : cand[k]);
            return 1;
        }
    }
    return 0;
}

/* Unreachable: nearest of {0, 1, vertex}; steady evaluates M(v, v). */
static inline double tdc_lcdm_nearest(const double p[4], double u, int steady, double a, double b, double m, int *kind)
{
    double cand[3] = {0.0, 1.0, -1.0};
    if (a != 0.0) {
        double vx = -b / (2.0 * a);
        if (vx > 0.0 && vx < 1.0) {
            cand[2] = vx;
        }
    }
    double best = 0.0, best_err = INFINITY, best_m = 0.0;
    for (int k = 0; k < 3; k++) {
        if (cand[k] < 0.0) {
            continue;
        }
        double mv = tdc_lcdm_M(p, cand[k], steady ? cand[k] : u);
        if (fabs(mv - m) < best_err) {
            best_err = fabs(mv - m);
            best = cand[k];
            best_m = mv;
        }
    }
    if (kind) {
        *kind = best_m > m ? TDC_LCDM_CLAMP_LOW : TDC_LCDM_CLAMP_HIGH;
    }
    return best;
}

/* v with M(v, u) = m; h = half an output code (0.5 / (C-1)). */
static inline double tdc_lcdm_solve(const double p[4], double u, double m, double h, int *kind)
{
    double a = p[0], b = p[1] * u + p[2], c = p[0] * u * u + p[2] * u + p[3] - m;
    double v;
    if (tdc_lcdm_quad_root(a, b, c, h, &v)) {
        if (kind) {
            *kind = TDC_LCDM_ROOT;
        }
        return v;
    }
    return tdc_lcdm_nearest(p, u, 0, a, b, m, kind);
}

/* v with M(v, v) = m (first frame, no history). */
static inline double tdc_lcdm_solve_steady(const double p[4], double m, double h, int *kind)
{
    double a = 2.0 * p[0] + p[1], b = 2.0 * p[2], c = p[3] - m;
    double v;
    if (tdc_lcdm_quad_root(a, b, c, h, &v)) {
        if (kind) {
            *kind = TDC_LCDM_ROOT;
        }
        return v;
    }
    return tdc_lcdm_nearest(p, 0.0, 1, a, b, m, kind);
}

/*
 * Overdrive table of n x n deltas (convention in firmware/tdc_overdrive.h:
 * row = previous drive u_i = i/(n-1), column = target m_j = j/(n-1),
 * entry = round(16 (C-1) (v*(u_i, m_j) - m_j)), int16) for coefficients p
 * (normally the Q24-quantised ones as doubles) and a panel of `bits` bits.
 * Used by tdc-tablegen and by the tests, so both make the same tables.
 */
static inline void tdc_lcdm_make_od(const double p[4], int n, int bits, short *out)
{
    const double max = (double)((1 << bits) - 1);
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) {
            double u = i / (double)(n - 1), m = j / (double)(n - 1);
            double v = tdc_lcdm_solve(p, u, m, 0.5 / max, 0);
            long d = lround((v - m) * max * 16.0);
            out[i * n + j] = (short)(d > 32767 ? 32767 : (d < -32768 ? -32768 : d));
        }
    }
}

#endif /* TDC_LCD_MODEL_H */
