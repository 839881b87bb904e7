/*
 * tdc_fvvdp_temporal.c - FovVideoVDP's two temporal channels (paper section
 * 3.2, eqs. 1-2): a sustained low-pass with a log-normal impulse response
 *
 *     F_s(t) = exp(-(ln(t + 1e-4) - ln(beta_s))^2 / (2 sigma_s^2)),
 *     sigma_s = 0.5, beta_s = 0.06 s           (fvvdp_parameters.json v1.2.3)
 *
 * normalised to unit sum, and a transient band-pass, its derivative scaled by
 * k2 = 0.062170507756932 (the reference's constant, which makes the
 * transient channel's peak response match the omega = 5 Hz the CSF of that
 * channel is evaluated at).  The filters are sampled at the true frame rate
 * over 250 ms (ceil(fps / 4) taps; t spans [0, taps / fps] in taps points,
 * as the reference samples them) and run as FIR filters over the frame
 * history, so the history the metric keeps is taps frames of test and
 * reference (tdc_fvvdp.c bounds it).
 */
#include <math.h>

#include "metrics/tdc_fvvdp.h"

#define SUSTAINED_SIGMA 0.5
#define SUSTAINED_BETA 0.06
#define TRANSIENT_K2 0.062170507756932

int tdc_fvvdp_temporal_filters(double fps, double f[2][TDC_FVVDP_MAX_TAPS])
{
    int n = (int)ceil(250.0 / (1000.0 / fps));
    if (n < 2 || n > TDC_FVVDP_MAX_TAPS) {
        return -1;
    }
    double t[TDC_FVVDP_MAX_TAPS];
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        t[i] = (double)n / fps * i / (n - 1);
        double a = log(t[i] + 1e-4) - log(SUSTAINED_BETA);
        f[0][i] = exp(-a * a / (2.0 * SUSTAINED_SIGMA * SUSTAINED_SIGMA));
        sum += f[0][i];
    }
    for (int i = 0; i < n; i++) {
        f[0][i] /= sum;
    }
    double dt = t[1] - t[0];
    for (int i = 0; i + 1 < n; i++) {
        f[1][i] = TRANSIENT_K2 * (f[0][i + 1] - f[0][i]) / dt;
    }
    f[1][n - 1] = 0.0;
    return n;
}
