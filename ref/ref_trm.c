/* ref_trm.c - double-precision TRM reference (see ref_trm.h). */
#include "ref_trm.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_geom.h"

/* The firmware's size rule (tdc_geom.h): the reference works on the same
 * reduced grid, only its arithmetic is double. */
static int reduced_dim(int n, int num, int den)
{
    return (int)tdc_reduced_dim((uint32_t)n, (uint32_t)num, (uint32_t)den);
}

int tdc_ref_trm_init(tdc_ref_trm_t *r, int w, int h, int r_num, int r_den, double sigma, double s,
                     const double gamma[3])
{
    memset(r, 0, sizeof *r);
    r->w = w;
    r->h = h;
    r->rw = reduced_dim(w, r_num, r_den);
    r->rh = reduced_dim(h, r_num, r_den);
    r->sigma = sigma;
    r->s = s;
    memcpy(r->gamma, gamma, sizeof r->gamma);
    r->rho = calloc((size_t)w * h * 3, sizeof(double));
    r->dprev = calloc((size_t)r->rw * r->rh * 3, sizeof(double));
    r->tmp = calloc((size_t)h * r->rw * 3, sizeof(double));
    r->red = calloc((size_t)r->rw * r->rh * 3, sizeof(double));
    return (r->rho && r->dprev && r->tmp && r->red) ? 0 : -1;
}

void tdc_ref_trm_free(tdc_ref_trm_t *r)
{
    free(r->rho);
    free(r->dprev);
    free(r->tmp);
    free(r->red);
    memset(r, 0, sizeof *r);
}

static int clampi(int v, int lo, int hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

/* Gaussian-weighted mean of samples src[k*step] around centre x (full-res
 * units), support |k - x| <= 3 sigma, clamp to edge. */
static double gauss_at(const double *src, int n, int step, double x, double sigma)
{
    double R = 3.0 * sigma, sw = 0.0, acc = 0.0;
    for (int k = (int)ceil(x - R); k <= (int)floor(x + R); k++) {
        double d = k - x;
        double wgt = exp(-d * d / (2.0 * sigma * sigma));
        acc += wgt * src[(size_t)clampi(k, 0, n - 1) * step];
        sw += wgt;
    }
    return acc / sw;
}

void tdc_ref_trm_downsample(tdc_ref_trm_t *r, const uint8_t *in, double *out)
{
    int w = r->w, h = r->h, rw = r->rw, rh = r->rh;
    double *row = malloc(sizeof(double) * (size_t)w * 3);
    double *col = malloc(sizeof(double) * (size_t)h);
    for (int y = 0; y < h; y++) {
        for (int i = 0; i < w * 3; i++) {
            row[i] = in[(size_t)y * w * 3 + i] / 255.0;
        }
        for (int j = 0; j < rw; j++) {
            double x = (j + 0.5) * w / rw - 0.5;
            for (int c = 0; c < 3; c++) {
                r->tmp[((size_t)y * rw + j) * 3 + c] = gauss_at(row + c, w, 3, x, r->sigma);
            }
        }
    }
    for (int j = 0; j < rw; j++) {
        for (int c = 0; c < 3; c++) {
            for (int y = 0; y < h; y++) {
                col[y] = r->tmp[((size_t)y * rw + j) * 3 + c];
            }
            for (int jy = 0; jy < rh; jy++) {
                double yy = (jy + 0.5) * h / rh - 0.5;
                out[((size_t)jy * rw + j) * 3 + c] = gauss_at(col, h, 1, yy, r->sigma);
            }
        }
    }
    free(row);
    free(col);
}

/* Bilinear U of a reduced gamma-domain image at full-res pixel (x, y). */
static double upsample_at(const tdc_ref_trm_t *r, const double *src, int x, int y, int c)
{
    double u = (x + 0.5) * r->rw / r->w - 0.5, v = (y + 0.5) * r->rh / r->h - 0.5;
    u = u < 0 ? 0 : (u > r->rw - 1 ? r->rw - 1 : u);
    v = v < 0 ? 0 : (v > r->rh - 1 ? r->rh - 1 : v);
    int i0 = (int)floor(u), j0 = (int)floor(v);
    int i1 = i0 + 1 < r->rw ? i0 + 1 : i0, j1 = j0 + 1 < r->rh ? j0 + 1 : j0;
    double fu = u - i0, fv = v - j0;
#define S(i, j) src[((size_t)(j)*r->rw + (i)) * 3 + c]
    double a = S(i0, j0) + (S(i1, j0) - S(i0, j0)) * fu;
    double b = S(i0, j1) + (S(i1, j1) - S(i0, j1)) * fu;
#undef S
    return a + (b - a) * fv;
}

static uint8_t encode(double lin, double gamma)
{
    lin = lin < 0 ? 0 : (lin > 1 ? 1 : lin);
    return (uint8_t)floor(255.0 * pow(lin, 1.0 / gamma) + 0.5);
}

void tdc_ref_trm_full(tdc_ref_trm_t *r, const uint8_t *in, uint8_t *out_codes, double *out_lin)
{
    tdc_ref_trm_downsample(r, in, r->dprev);
    for (int y = 0; y < r->h; y++) {
        for (int x = 0; x < r->w; x++) {
            for (int c = 0; c < 3; c++) {
                size_t i = ((size_t)y * r->w + x) * 3 + c;
                double li = pow(in[i] / 255.0, r->gamma[c]);
                double lu = pow(upsample_at(r, r->dprev, x, y, c), r->gamma[c]);
                /* gaze-aware TRM (ref_trm_gaze.h): beta = I + k (I - U D I) */
                double k = r->strength ? r->strength[(size_t)y * r->w + x] : 1.0;
                double beta = r->strength ? li + k * (li - lu) : 2.0 * li - lu;
                double shown = beta < 0 ? 0 : (beta > 1 ? 1 : beta);
                r->rho[i] = beta - shown;
                out_codes[i] = encode(shown, r->gamma[c]);
                if (out_lin) {
                    out_lin[i] = shown;
                }
            }
        }
    }
    r->have_full = 1;
}

int tdc_ref_trm_reduced(tdc_ref_trm_t *r, const uint8_t *in_red, uint8_t *out_codes, double *out_lin)
{
    if (!r->have_full) {
        return -1;
    }
    for (size_t i = 0; i < (size_t)r->rw * r->rh * 3; i++) {
        r->red[i] = in_red[i] / 255.0;
    }
    for (int y = 0; y < r->h; y++) {
        for (int x = 0; x < r->w; x++) {
            for (int c = 0; c < 3; c++) {
                size_t i = ((size_t)y * r->w + x) * 3 + c;
                /* motion test at the link's precision: U(D(I_t)) moved half
                 * a code (gamma domain) towards U(i) */
                double ga = upsample_at(r, r->dprev, x, y, c), gb = upsample_at(r, r->red, x, y, c);
                double half = 0.5 / 255.0;
                ga = ga > gb + half ? ga - half : (gb > ga + half ? ga + half : gb);
                double a = pow(ga, r->gamma[c]);
                double alpha = pow(gb, r->gamma[c]);
                double cc = (a + alpha) > 0 ? fabs(a - alpha) / (a + alpha) : 0.0;
                double wgt = exp(-r->s * cc);
                double v = alpha + wgt * r->rho[i];
                double shown = v < 0 ? 0 : (v > 1 ? 1 : v);
                out_codes[i] = encode(shown, r->gamma[c]);
                if (out_lin) {
                    out_lin[i] = shown;
                }
            }
        }
    }
    return 0;
}
