/*
 * tdc_fvvdp_csf.c - the contrast sensitivity function FovVideoVDP divides
 * every band by (paper section 3.3, eq. 4): sensitivity over spatial
 * frequency rho, temporal frequency omega, adapting luminance L and
 * eccentricity e,
 *
 *     S(rho, omega, L, e) = S_sp(rho / M, L, A) * S_st(rho / M, omega)
 *
 * with the parts, each from the model the paper names:
 *   - cortical magnification (Dougherty et al. 2003, J. Vision 3(10)):
 *     M(e) = 29.2 / (e + 3.67) mm/deg; the relative M_rel = (M(e)/M(0))^k_cm,
 *     k_cm = 0.604562 (fvvdp_parameters.json v1.2.3), scales frequency
 *     (rho / M_rel) and stimulus size;
 *   - stimulus area A = pi (sigma M_rel)^2 with sigma = 1.5 / rho deg, a
 *     fixed 1.5 cycles (csf_sigma = -1.5 of the parameters file);
 *   - S_sp: the achromatic detection of the spatio-chromatic CSF of Mantiuk,
 *     Ashraf & Chapiro (2020, "Practical colour contrast sensitivity
 *     functions"): three mechanisms (achromatic, red-green, yellow-violet),
 *     each a log-parabola in frequency with luminance-dependent peak and
 *     Rovamo's area summation, combined with a 2-norm over the cone
 *     contrasts of a D65 luminance modulation; the fitted values of
 *     16/09/2020 (SCCSF_ConeContrastMat.get_default_par of the reference's
 *     matlab/utils, version 1.2.3);
 *   - S_st: the temporal part as the ratio of Daly's spatio-velocity CSF
 *     (Laird, Rosen, Pelz, Montag & Daly 2006 fit: c0 0.6329, c1 0.8404,
 *     c2 0.7986, s1 6.1, s2 7.3, p1 45.9) at velocity omega/rho to its value
 *     at rest (velocity floored at 0.1 deg/s, the drift of fixation).
 *
 * The metric evaluates S per pixel through a 32^3 table over log2 rho
 * (2^-4..64 cpd), log2 L (1e-3..1e4 cd/m^2) and sqrt e (0..120 deg),
 * trilinear in log2 S, for omega = 0 (sustained) and 5 Hz (transient), as
 * the reference does; the table is built here from the equations.
 */
#include <math.h>
#include <pthread.h>

#include "metrics/tdc_fvvdp.h"
#include "tdc_par.h"

#define K_CM 0.604562
#define CSF_SIGMA 1.5

/* Daly's spatio-velocity CSF, Laird et al. 2006 fit. */
static double csf_spatiovel(double rho, double vel)
{
    const double c0 = 0.6329, c1 = 0.8404, c2 = 0.7986, s1 = 6.1, s2 = 7.3, p1 = 45.9;
    double v = vel > 0.1 ? vel : 0.1;
    double l = fabs(log10(c2 * v / 3.0));
    double k = s1 + s2 * l * l * l;
    double rho_max = p1 / (c2 * v + 2.0);
    double a = c1 * 2.0 * M_PI * rho;
    return k * (c0 * c1 * c2) * v * a * a * exp(-(c1 * 4.0 * M_PI * rho) / rho_max);
}

/* Luminance dependence of a mechanism parameter (SCCSF get_lum_dep). */
static double lum_dep(const double *p, int n, double l)
{
    switch (n) {
    case 1:
        return p[0];
    case 3:
        return p[0] * pow(1.0 + p[1] / l, -p[2]);
    default: /* 5 */
        return p[0] * pow(1.0 + p[1] / l, -p[2]) * (1.0 - pow(1.0 + p[3] / l, -p[4]));
    }
}

typedef struct {
    double s_max[5];
    int n_s_max;
    double f_max[3];
    int n_f_max;
    double bw, gamma, ac_prime;
} mech_t;

/* Mantiuk, Ashraf & Chapiro 2020, fitted 16/09/2020. */
static const mech_t MECH[3] = {
    { { 356404, 6.2726, 0.320031, 895943, 7.77919e-05 }, 5, { 2.3021, 3317.45, 0.186215 }, 3, 1.07516, 1.1107, 52.9768 },
    { { 423.978, 15.4032, 0.50343, 0, 0 }, 3, { 0.122699, 0, 0 }, 1, 2.70669, 1.72903, 1.38437 },
    { { 11811.9, 196.342, 0.339396, 0, 0 }, 3, { 7.1099e-08, 0, 0 }, 1, 5.3416, 1.47263, 0.282573 },
};

/* Cone contrast -> mechanism matrix (colmat of the same fit, signs of the
 * opponent channels applied). */
static const double M_LMS2ACC[3][3] = {
    { 1.0, 0.256197, 6.42477e-07 },
    { 1.0, -0.933541, 0.00373304 },
    { -0.00130319, -1.1504, 1.0 },
};

/* CIE 1931 XYZ -> CIE 2006 LMS for an LED LCD spectrum (xyz2lms2006). */
static const double M_XYZ_LMS[3][3] = {
    { 0.187596268556126, 0.585168649077728, -0.026384263306304 },
    { -0.133397430663221, 0.405505777260049, 0.034502127690364 },
    { 0.000244379021663, -0.000542995890619, 0.019406849066323 },
};
static const double D65[3] = { 0.95047, 1.0, 1.08883 };
/* The achromatic modulation direction in LMS (SCCSF sensitivity_coldir 1). */
static const double LMS_ACH[3] = { 0.698, 0.302, 0.019613 };

static double mech_csf(int c, double f, double area, double lum)
{
    const mech_t *m = &MECH[c];
    double s_max = lum_dep(m->s_max, m->n_s_max, lum);
    double f_max = lum_dep(m->f_max, m->n_f_max, lum);
    double d = log10(f) - log10(f_max);
    double s_peak = s_max / pow(10.0, d * d / (0.5 * pow(2.0, m->bw)));
    if (c > 0 && f < f_max) {
        s_peak = s_max; /* chromatic mechanisms are low-pass */
    }
    double k = m->ac_prime + area * 0.65;
    double ag = pow(area, m->gamma) * f * f;
    return s_peak * sqrt(ag / (k + ag));
}

/* Achromatic sensitivity of the spatio-chromatic CSF (SCCSF_ConeContrastMat
 * sensitivity for the luminance direction): 1 / threshold cone contrast. */
static double csf_achromatic(double f, double lum, double area)
{
    double lms[3], cc[3], acc[3];
    for (int i = 0; i < 3; i++) {
        lms[i] = lum * (M_XYZ_LMS[i][0] * D65[0] + M_XYZ_LMS[i][1] * D65[1] + M_XYZ_LMS[i][2] * D65[2]);
        cc[i] = LMS_ACH[i] / lms[i];
    }
    double y = lms[0] + lms[1];
    double c2 = 0.0;
    for (int i = 0; i < 3; i++) {
        acc[i] = fabs(M_LMS2ACC[i][0] * cc[0] + M_LMS2ACC[i][1] * cc[1] + M_LMS2ACC[i][2] * cc[2]);
        double cn = acc[i] * mech_csf(i, f, area, y);
        c2 += cn * cn;
    }
    double ncc = sqrt(cc[0] * cc[0] + cc[1] * cc[1] + cc[2] * cc[2]);
    return sqrt(3.0) * sqrt(c2) / ncc;
}

double tdc_fvvdp_csf(double rho, double omega, double lum, double ecc)
{
    double m_rel = pow((29.2 / (ecc + 3.67)) / (29.2 / 3.67), K_CM);
    double sigma = CSF_SIGMA / rho;
    double area = M_PI * (sigma * m_rel) * (sigma * m_rel);
    double rho_cm = rho / m_rel;
    double s_st = csf_spatiovel(rho_cm, omega / rho_cm) / (csf_spatiovel(rho_cm, 0.0) + 1e-5);
    return csf_achromatic(rho_cm, lum, area) * s_st;
}

/* ---- the table ---- */
#define N 32
#define Y_LO (log2(1e-3))
#define Y_HI (log2(1e4))
#define R_LO (-4.0)
#define R_HI 6.0
#define E_HI (sqrt(120.0))

static float lut[2][N][N][N]; /* [ch][Y][rho][ecc], log2 S */
static pthread_once_t lut_once = PTHREAD_ONCE_INIT;

static void lut_build(void)
{
    for (int c = 0; c < 2; c++) {
        for (int j = 0; j < N; j++) {
            double y = pow(10.0, log10(1e-3) + (log10(1e4) - log10(1e-3)) * j / (N - 1));
            for (int i = 0; i < N; i++) {
                double r = pow(10.0, log10(0.0625) + (log10(64.0) - log10(0.0625)) * i / (N - 1));
                for (int k = 0; k < N; k++) {
                    double es = E_HI * k / (N - 1);
                    double s = tdc_fvvdp_csf(r, c ? 5.0 : 0.0, y, es * es);
                    lut[c][j][i][k] = (float)log2(s > 1e-4 ? s : 1e-4);
                }
            }
        }
    }
}

void tdc_fvvdp_csf_init(void);
void tdc_fvvdp_csf_lut_log2(const double *log2_rho, const double *log2_lum, const double *sqrt_ecc, int n,
                            double *s0, double *s1);
void tdc_fvvdp_csf_init(void)
{
    pthread_once(&lut_once, lut_build);
}

/* log2 S of both channels (0: omega 0, 1: 5 Hz) at n points (log2 rho,
 * log2 L, sqrt ecc): one set of trilinear weights per point, in a loop that
 * vectorises (AVX2 gathers) with the same bits as the plain clone;
 * after tdc_fvvdp_csf_init. */
TDC_SIMD_CLONES void tdc_fvvdp_csf_lut_log2(const double *log2_rho, const double *log2_lum, const double *sqrt_ecc,
                                            int n, double *s0, double *s1)
{
    const float *v0 = &lut[0][0][0][0], *v1 = &lut[1][0][0][0];
    TDC_SIMD
    for (int x = 0; x < n; x++) {
        double ur = (log2_rho[x] - R_LO) / (R_HI - R_LO) * (N - 1);
        double uy = (log2_lum[x] - Y_LO) / (Y_HI - Y_LO) * (N - 1);
        double ue = sqrt_ecc[x] / E_HI * (N - 1);
        ur = ur < 0.0 ? 0.0 : (ur > N - 1 ? N - 1 : ur);
        uy = uy < 0.0 ? 0.0 : (uy > N - 1 ? N - 1 : uy);
        ue = ue < 0.0 ? 0.0 : (ue > N - 1 ? N - 1 : ue);
        int i = (int)ur, j = (int)uy, k = (int)ue;
        i = i > N - 2 ? N - 2 : i;
        j = j > N - 2 ? N - 2 : j;
        k = k > N - 2 ? N - 2 : k;
        double fr = ur - i, fy = uy - j, fe = ue - k;
        int o = (j * N + i) * N + k; /* [Y][rho][ecc] */
        const int di = N, dj = N * N;
        s0[x] = ((v0[o] * (1 - fr) + v0[o + di] * fr) * (1 - fy) + (v0[o + dj] * (1 - fr) + v0[o + dj + di] * fr) * fy) *
                    (1 - fe) +
                ((v0[o + 1] * (1 - fr) + v0[o + di + 1] * fr) * (1 - fy) +
                 (v0[o + dj + 1] * (1 - fr) + v0[o + dj + di + 1] * fr) * fy) * fe;
        s1[x] = ((v1[o] * (1 - fr) + v1[o + di] * fr) * (1 - fy) + (v1[o + dj] * (1 - fr) + v1[o + dj + di] * fr) * fy) *
                    (1 - fe) +
                ((v1[o + 1] * (1 - fr) + v1[o + di + 1] * fr) * (1 - fy) +
                 (v1[o + dj + 1] * (1 - fr) + v1[o + dj + di + 1] * fr) * fy) * fe;
    }
}

double tdc_fvvdp_csf_lut(int ch, double rho, double lum, double ecc)
{
    double lr = log2(rho), ly = log2(lum), se = sqrt(ecc > 0.0 ? ecc : 0.0), a[2];
    tdc_fvvdp_csf_init();
    tdc_fvvdp_csf_lut_log2(&lr, &ly, &se, 1, &a[0], &a[1]);
    return exp2(a[ch]);
}
