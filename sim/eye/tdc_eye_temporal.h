/*
 * tdc_eye_temporal.h - the eye's temporal visibility model (issue 15): a
 * temporal contrast-sensitivity filter on the retinal error signal, in the
 * spirit of the window of visibility of TRM §6.1 (Watson, Ahumada and
 * Farrell 1986), so that what flickers or crawls on the retina is weighed
 * by how visible it is, not averaged away instant by instant.
 *
 * Filter (Watson 1986, "Temporal sensitivity", Handbook of Perception):
 *     h(t) = xi [h1(t) - zeta h2(t)],
 *     hi(t) = u(t) (t / tau_i)^(n_i - 1) e^(-t / tau_i) / (tau_i (n_i - 1)!),
 *     tau_1 = tau, tau_2 = kappa tau,
 *     H(f) = xi [(1 + i 2 pi f tau_1)^(-n1) - zeta (1 + i 2 pi f tau_2)^(-n2)].
 * Defaults n1 = 9, n2 = 10, tau = 4.3 ms, kappa = 1.33, zeta = 0.9: a
 * band-pass peaking near 8 Hz, down to ~1/10 at 0 Hz and to a few per cent
 * above 40 Hz; xi normalises the peak |H| to 1.
 *
 * The signal it runs on: the per-instant encoded error E_j = enc(P_j) -
 * enc(G_j) of the simulator (P_j the Talbot-Plateau fusion over the window:
 * the eye's first temporal stage), sampled at the evaluation rate R, in
 * retinal coordinates (the older errors are read where the pursuing eye saw
 * them), reduced to one luminance-like channel (Rec. 709 weights of the
 * encoded channel errors: 4 bytes per pixel per tap).  The discrete taps are
 * the box-sampled impulse response h_k = integral over [k/R, (k+1)/R) of h,
 * in closed form (regularised incomplete gamma of integer order); the filter
 * is the FIR F_j = sum_k h_k E_{j-k} over the support where h matters
 * (<= TDC_TCSF_MAX_TAPS taps).  The reported figure is the RMS of F_j in
 * code values (255 = full scale), like the simulator's flicker column.
 */
#ifndef TDC_EYE_TEMPORAL_H
#define TDC_EYE_TEMPORAL_H

#include <stddef.h>

#define TDC_TCSF_MAX_TAPS 40

typedef struct {
    int n1, n2;        /* stages of the two cascades */
    double tau_s;      /* tau_1, seconds */
    double kappa;      /* tau_2 / tau_1 */
    double zeta;       /* transience: weight of the second cascade (0: low-pass) */
    double support_s;  /* FIR length in seconds (taps = ceil(support * R)) */
} tdc_tcsf_t;

/* Watson's defaults (above), 120 ms of support. */
void tdc_tcsf_default(tdc_tcsf_t *p);

/* |H(f)| / max_f |H(f)|: 1 at the peak. */
double tdc_tcsf_gain(const tdc_tcsf_t *p, double f_hz);
/* Peak frequency of |H| (Hz) and xi = 1 / max |H| of the unnormalised filter. */
double tdc_tcsf_peak_hz(const tdc_tcsf_t *p, double *xi);

/* Box-sampled taps at rate R (Hz), normalised by the same xi: taps[k] =
 * xi * integral_{k/R}^{(k+1)/R} (h1 - zeta h2) dt.  Returns the count
 * (1..max), or 0 on bad parameters. */
int tdc_tcsf_taps(const tdc_tcsf_t *p, double rate_hz, double *taps, int max);

/* The filter state of one mode's eye: a ring of the last K luminance
 * errors with the gaze position each was seen at. */
typedef struct {
    int w, h, k;       /* image size, taps */
    double taps[TDC_TCSF_MAX_TAPS];
    float *ring;       /* k * w * h */
    double gx[TDC_TCSF_MAX_TAPS], gy[TDC_TCSF_MAX_TAPS];
    int head, count;
    double *rows;      /* h: per-row sums */
} tdc_eye_temporal_t;

/* 0, or -1 (bad parameters, out of memory). */
int tdc_eye_temporal_init(tdc_eye_temporal_t *t, const tdc_tcsf_t *p, double rate_hz, int w, int h);
void tdc_eye_temporal_free(tdc_eye_temporal_t *t);

/* Pushes the error image err (w*h*3, encoded units, 1 = full scale) seen
 * with the gaze at (gx, gy) px (cumulative pursuit displacement) and returns
 * the RMS of the filtered error in code values, or -1 while fewer than k
 * errors have been pushed. */
double tdc_eye_temporal_push(tdc_eye_temporal_t *t, const double *err, double gx, double gy);

#endif
