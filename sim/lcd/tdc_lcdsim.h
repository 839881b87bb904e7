/*
 * tdc_lcdsim.h - physical LCD pixel response for the host simulator
 * (docs/design.md §5, TRM paper §2.2).
 *
 * Each sub-pixel's transmittance x (normalised linear light, 0..1) relaxes
 * toward the static level of its drive value, T(v) = v^gamma_c, as a
 * first-order liquid-crystal response
 *     dx/dt = -(x - T(v_t)) / tau(v_{t-1}, v_t),
 * where the time constant depends on the transition (previous drive ->
 * current drive, bilinear in a table from the panel's sim file; rising and
 * falling transitions differ and grey-to-grey is slower than black/white).
 * The drive is constant within a refresh, so the ODE is integrated EXACTLY:
 *     x(t)   = T + (x0 - T) e^{-t/tau}
 *     int_a^b x dt = T (b - a) + (x0 - T) tau e^{-a/tau} (1 - e^{-(b-a)/tau})
 * (1 - e^{-h/tau} through expm1, so tau >> h loses nothing and tau << h
 * underflows to the settled value: stable for any stiffness).
 * The backlight is constant or strobed (on for `duty` of the refresh from
 * phase `phase`, scaled 1/duty so the mean is unchanged).  Luminance seen
 * = black + (1 - black) * mean over the refresh of backlight(t) * x(t).
 *
 * The physical parameters live in a sim-side file (sim/lcd/panels/NAME.lcdsim):
 * they are the "truth" that the calibration (tdc-calib) must recover from
 * measurements, so they are kept out of the firmware panel profile.
 */
#ifndef TDC_LCDSIM_H
#define TDC_LCDSIM_H

#include <stddef.h>
#include <stdint.h>

#define TDC_LCDSIM_MAX_LEV 9

typedef struct {
    char name[64];
    double gamma[3];                                       /* static response T(v) = v^gamma per channel */
    double black;                                          /* black level as a fraction of white (LCD leakage) */
    double peak_cd[3];                                     /* luminance of each primary at full drive, cd/m^2 */
    int nlev;                                              /* tau table size */
    double lev[TDC_LCDSIM_MAX_LEV];                        /* drive levels, 0..1, increasing */
    double tau_ms[TDC_LCDSIM_MAX_LEV][TDC_LCDSIM_MAX_LEV]; /* [from][to] */
    int strobe;                                            /* 0 constant backlight, 1 strobed */
    double strobe_duty;                                    /* fraction of the refresh the backlight is on */
    double strobe_phase;                                   /* start of the flash as a fraction of the refresh */
} tdc_lcdsim_panel_t;

/* Loads a .lcdsim file; 0 on success, else -1 with a message in err. */
int tdc_lcdsim_load(const char *path, tdc_lcdsim_panel_t *p, char *err, size_t errlen);

/* Time constant in ms of a transition between normalised drives. */
double tdc_lcdsim_tau_ms(const tdc_lcdsim_panel_t *p, double from, double to);

/* One exact step of duration h (s) with constant target T and time
 * constant tau (s): returns x(h), adds int_0^h x dt to *integral. */
double tdc_lcdsim_step_exact(double x0, double target, double tau, double h, double *integral);

typedef struct {
    const tdc_lcdsim_panel_t *panel;
    size_t n;      /* sub-pixels (W*H*3 interleaved, channel = index % 3) */
    double *x;     /* transmittance state */
    uint8_t *prev; /* previous drive codes */
    int have_prev;
    int substeps; /* exact sub-steps per refresh (>= 1; time-resolved use) */
} tdc_lcdsim_t;

/* Allocates the state for n sub-pixels; the panel starts dark (x = 0). */
int tdc_lcdsim_init(tdc_lcdsim_t *s, const tdc_lcdsim_panel_t *p, size_t n);
void tdc_lcdsim_free(tdc_lcdsim_t *s);

/* Sets every sub-pixel to the settled state of a constant drive. */
void tdc_lcdsim_settle(tdc_lcdsim_t *s, const uint8_t *drive);

/*
 * Shows one refresh of drive codes (n, 8-bit) at refresh_hz; writes the
 * normalised luminance seen over the refresh (0..1 with the black level
 * included) per sub-pixel to lum (may be NULL).
 */
void tdc_lcdsim_frame(tdc_lcdsim_t *s, const uint8_t *drive, double refresh_hz, double *lum);

/* The Fig. 7 measurement: alternating codes a, b on a full-screen patch of
 * channel ch at refresh_hz, settled, then time-averaged luminance over
 * integration_s (normalised, black included). */
double tdc_lcdsim_measure_pair(const tdc_lcdsim_panel_t *p, int ch, int a, int b, double refresh_hz,
                               double integration_s);

/*
 * The transition measurement (docs/lcd.md §5, tdc-lcd-measure --transitions):
 * channel ch settled at drive `prev`, then ONE refresh at drive `code` at
 * refresh_hz with the panel's backlight timing.  *light = the normalised
 * luminance delivered within that refresh (backlight-weighted mean, black
 * included, as tdc_lcdsim_frame reports it); *end = the normalised luminance
 * the transmittance reached at the end of the refresh would show under a lit
 * backlight (black + (1 - black) x_end): the state the next refresh starts
 * from.  prev == code is the settled static patch (*light == *end).
 */
void tdc_lcdsim_measure_transition(const tdc_lcdsim_panel_t *p, int ch, int prev, int code, double refresh_hz,
                                   double *light, double *end);

#endif /* TDC_LCDSIM_H */
