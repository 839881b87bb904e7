/*
 * tdc_lcd_ref.h - double-precision reference of the firmware LCD stage
 * (firmware/tdc_lcd.h), straight from the equations: per sub-pixel
 *   W = (w/255)^g, P = (W + E_{t-1}) / 2, m = P^(1/g),
 *   v = the inverse of M(v, d_{t-1}) = m (common/tdc_lcd_model.h),
 *   unreachable: residual += W + E_{t-1} - 2 M(v, d)^g, E_t = 2 M^g - E_{t-1};
 *   first frame: v with M(v, v) = w/255, E = W.
 */
#ifndef TDC_LCD_REF_H
#define TDC_LCD_REF_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    double p[4];
    double gamma[3];
    size_t n;            /* sub-pixels W*H*3 */
    uint8_t *prev_drive; /* d_{t-1} codes */
    double *prev_light;  /* E_{t-1}, linear */
    int have_history;
} tdc_lcd_ref_t;

int tdc_lcd_ref_init(tdc_lcd_ref_t *r, const double p[4], const double gamma[3], size_t n);
void tdc_lcd_ref_free(tdc_lcd_ref_t *r);

/* One frame of n sub-pixels (contiguous): wanted codes -> drive codes;
 * residual_add (may be NULL) receives the unreached light (linear, not
 * accumulated: set per sub-pixel, 0 where reachable); v_out (may be NULL)
 * the continuous drive (0..1); kind_out (may be NULL) the case. */
void tdc_lcd_ref_frame(tdc_lcd_ref_t *r, const uint8_t *wanted, uint8_t *drive, double *residual_add, double *v_out,
                       int *kind_out);

#endif
