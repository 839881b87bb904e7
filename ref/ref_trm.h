/*
 * ref_trm.h - double-precision reference of TRM, written straight from the
 * paper's equations (TRM §4, docs/design.md §4.1) with the same sampling geometry
 * as the firmware (reduced sample centres, clamp-to-edge, Gaussian support
 * 3 sigma, bilinear U) but no quantisation except the final 8-bit output:
 *   v = code / 255;  lin(v) = v^gamma  (per channel)
 *   beta = 2 lin(I) - lin(U(D(I)));  out = round(255 clamp(beta)^(1/gamma))
 *   rho = beta - clamp(beta)
 *   alpha = lin(U(i));  c = |A - B| / (A + B);  w = exp(-s c)
 *   with A = lin(g), g = U(D(I_t)) moved half a code towards U(i): the
 *   motion test works at the link's precision (whole codes), so a static
 *   pair (i = round(D(I))) has c = 0, as in the firmware
 *   out = round(255 clamp(alpha + w rho)^(1/gamma))
 */
#ifndef TDC_REF_TRM_H
#define TDC_REF_TRM_H

#include <stdint.h>

typedef struct {
    int w, h, rw, rh;
    double sigma, s;
    double gamma[3];
    double *rho;   /* w*h*3 */
    double *dprev; /* rw*rh*3, gamma domain in [0, 1] */
    double *tmp;   /* h*rw*3 */
    double *red;   /* rw*rh*3 */
    int have_full;
    /* gaze-aware TRM: compensation strength k per pixel (w*h, caller-owned,
     * ref_trm_gaze.h), NULL = 1 (plain TRM): beta = I + k (I - U D I) */
    const double *strength;
} tdc_ref_trm_t;

int tdc_ref_trm_init(tdc_ref_trm_t *r, int w, int h, int r_num, int r_den, double sigma, double s,
                     const double gamma[3]);
void tdc_ref_trm_free(tdc_ref_trm_t *r);

/* D of a full-res frame, gamma domain [0, 1], rw*rh*3. */
void tdc_ref_trm_downsample(tdc_ref_trm_t *r, const uint8_t *in, double *out);

/* Full-res frame; out_codes (w*h*3) and optionally the exact clamped linear
 * light shown (out_lin, may be NULL). */
void tdc_ref_trm_full(tdc_ref_trm_t *r, const uint8_t *in, uint8_t *out_codes, double *out_lin);

/* Reduced frame (rw*rh*3 codes) -> out_codes; out_lin optional. */
int tdc_ref_trm_reduced(tdc_ref_trm_t *r, const uint8_t *in_red, uint8_t *out_codes, double *out_lin);

#endif
