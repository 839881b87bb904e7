/*
 * tdc_calib_trans.h - fit of the stateful overdrive tables from transition
 * measurements (docs/lcd.md §5; tdc-calib --transitions).
 *
 * Per refresh rate and channel, from the (previous drive, drive) grid of
 * light-within-the-refresh and state-at-its-end measurements:
 *   OD[i][j]  the drive (Q4 code) that delivers the wanted light of code
 *             w_j = j (C-1) / (N-1) within one refresh when the pixel starts
 *             in state s_i = i (C-1) / (N-1) (a state is named by the code
 *             whose settled transmittance it is); clamped to 0 / C-1 where
 *             the wanted light is out of reach from that state;
 *   ST[i][k]  the state (Q4 code) reached at the end of a refresh at drive
 *             v_k from state s_i;
 *   LO/HI[i]  the light (as a Q4 code) drives 0 and C-1 deliver from s_i:
 *             the reachable range, used for the residual rho.
 * Between measured rows the state is interpolated in linear light (a first
 * order liquid crystal is linear in its start transmittance), along the drive
 * in the gamma-encoded light; the inverse is a bisection on that monotone
 * curve.  The data are refused (with file, line and field) when transitions
 * are missing, the grid is not the regular one, runs disagree (noise), the
 * light or the state falls with rising drive beyond the noise, or a settled
 * state cannot reproduce its own static light.
 */
#ifndef TDC_CALIB_TRANS_H
#define TDC_CALIB_TRANS_H

#include <stdio.h>

#include "tdc_meas.h"

#define TDC_ST_MAX_N 65
#define TDC_ST_MAX_RATES 3

typedef struct {
    int rate;
    unsigned short od[3][TDC_ST_MAX_N * TDC_ST_MAX_N];
    unsigned short st[3][TDC_ST_MAX_N * TDC_ST_MAX_N];
    unsigned short lo[3][TDC_ST_MAX_N], hi[3][TDC_ST_MAX_N];
    /* fit report: RMS per transition class (0 rise, 1 fall, 2 small step,
     * 3 full swing, 4 all): light error % of white, drive error in codes,
     * state error % of white; counts; noise (run-to-run RMS, % of white, or
     * -1 with one run); share of (state, wanted) nodes out of reach */
    double light_rms[5], drive_rms[5], state_rms[5];
    long count[5];
    double noise_pct, unreachable_share;
    double gamma[3];
    int grid;
} tdc_st_fit_t;

typedef struct {
    int n; /* table nodes per axis: 17, 33 or 65 */
    int nrates;
    int max_code;
    tdc_st_fit_t rate[TDC_ST_MAX_RATES];
} tdc_st_fits_t;

/* Fits every rate of m (a TDC_MEAS_TRANSITIONS file named path) to n x n
 * tables.  gamma: the profile's per-channel gamma (the code axes of the
 * tables are the firmware's codes, so they must use the gamma its tables
 * decode with), or NULL to fit it from the settled transitions.  smooth: 1
 * to smooth the cell means along both axes before the fit (measurement
 * noise; tdc_calib_trans.c).  0 on success; else -1 and one line in err
 * saying what is wrong and why the fit cannot be trusted. */
int tdc_st_fit(const tdc_meas_t *m, const char *path, int n, int smooth, const double *gamma, tdc_st_fits_t *out,
               char *err, size_t errlen);

/* Prints the per-class fit errors (stdout of tdc-calib). */
void tdc_st_print(const tdc_st_fits_t *fits, FILE *f);

/* Writes the profile lines (lcd_state_n, lcd_od, lcd_st, lcd_reach_lo/hi)
 * for the rates in `rates` (ascending, nr of them). */
void tdc_st_write_profile(const tdc_st_fits_t *fits, FILE *f);

#endif /* TDC_CALIB_TRANS_H */
