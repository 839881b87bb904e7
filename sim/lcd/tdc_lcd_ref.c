/*
 * tdc_lcd_ref.c - double-precision reference of the LCD stage (see header).
 */
#include "lcd/tdc_lcd_ref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_lcd_model.h"

int tdc_lcd_ref_init(tdc_lcd_ref_t *r, const double p[4], const double gamma[3], size_t n)
{
    memset(r, 0, sizeof *r);
    memcpy(r->p, p, sizeof r->p);
    memcpy(r->gamma, gamma, sizeof r->gamma);
    r->n = n;
    r->prev_drive = calloc(n ? n : 1, 1);
    r->prev_light = calloc(n ? n : 1, sizeof(double));
    return r->prev_drive && r->prev_light ? 0 : -1;
}

void tdc_lcd_ref_free(tdc_lcd_ref_t *r)
{
    free(r->prev_drive);
    free(r->prev_light);
    memset(r, 0, sizeof *r);
}

void tdc_lcd_ref_frame(tdc_lcd_ref_t *r, const uint8_t *wanted, uint8_t *drive, double *residual_add, double *v_out,
                       int *kind_out)
{
    const double h = 0.5 / 255.0;
    for (size_t i = 0; i < r->n; i++) {
        const double g = r->gamma[i % 3];
        const double W = pow(wanted[i] / 255.0, g);
        int kind;
        double v, res = 0.0, E = W;
        if (!r->have_history) {
            v = tdc_lcdm_solve_steady(r->p, wanted[i] / 255.0, h, &kind);
        } else {
            const double P = 0.5 * (W + r->prev_light[i]);
            const double m = pow(P, 1.0 / g);
            const double u = r->prev_drive[i] / 255.0;
            v = tdc_lcdm_solve(r->p, u, m, h, &kind);
            if (kind != TDC_LCDM_ROOT) {
                double ms = tdc_lcdm_M(r->p, round(v * 255.0) / 255.0, u);
                ms = ms < 0.0 ? 0.0 : (ms > 1.0 ? 1.0 : ms);
                const double ls = pow(ms, g);
                res = W + r->prev_light[i] - 2.0 * ls;
                E = 2.0 * ls - r->prev_light[i];
                E = E < 0.0 ? 0.0 : (E > 1.0 ? 1.0 : E);
            }
        }
        const long code = lround(v * 255.0);
        drive[i] = (uint8_t)(code < 0 ? 0 : (code > 255 ? 255 : code));
        r->prev_drive[i] = drive[i];
        r->prev_light[i] = E;
        if (residual_add) {
            residual_add[i] = res;
        }
        if (v_out) {
            v_out[i] = v;
        }
        if (kind_out) {
            kind_out[i] = kind;
        }
    }
    r->have_history = 1;
}
