/*
 * test_lcd_sim.c - stability and accuracy of the physical LCD simulation
 * (sim/lcd/tdc_lcdsim.h), including the stiff ends.
 *
 * For tau from 0.05 ms to 50 ms and refresh rates 60, 120, 144, 165 and
 * 240 Hz (frame 4.2 .. 16.7 ms, so h/tau spans 0.08 .. 333), a sub-pixel
 * driven by a random code sequence is integrated by the simulator with
 * 1, 4 and 16 exact sub-steps per refresh and compared with the closed form
 *     x_{k+1} = T + (x_k - T) e^{-P/tau},
 *     mean_k  = T + (x_k - T) (tau / P) (1 - e^{-P/tau})
 * evaluated independently here in long double.  Error bound: 1e-6 of full
 * scale for the state and the per-refresh luminance.  The same checker fed
 * with explicit Euler at the same step must FAIL at the stiff end (it is
 * unstable for h/tau > 2), which shows the check bites.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "tdc_cmocka.h"

#include "lcd/tdc_lcdsim.h"

static const double k_taus_ms[] = {0.05, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 50.0};
static const double k_rates[] = {60, 120, 144, 165, 240};

/* A one-level-table panel: the same tau for every transition. */
static void const_panel(tdc_lcdsim_panel_t *p, double tau_ms)
{
    memset(p, 0, sizeof *p);
    p->gamma[0] = p->gamma[1] = p->gamma[2] = 2.2;
    p->nlev = 2;
    p->lev[0] = 0.0;
    p->lev[1] = 1.0;
    for (int i = 0; i < 2; i++) {
        for (int j = 0; j < 2; j++) {
            p->tau_ms[i][j] = tau_ms;
        }
    }
    p->strobe_duty = 1.0;
}

typedef double (*step_fn)(double x0, double target, double tau, double h, double *integral);

/* Explicit Euler with the integral by the left rectangle rule: what the
 * checker must reject at the stiff end. */
static double step_euler(double x0, double target, double tau, double h, double *integral)
{
    if (integral) {
        *integral += x0 * h;
    }
    return x0 + h / tau * (target - x0);
}

/*
 * Integrates `frames` refreshes of a random drive sequence with `sub`
 * steps per refresh using `step`, and returns the largest error (state and
 * per-refresh mean) against the long-double closed form.
 */
static double run_checker(step_fn step, double tau_ms, double rate, int sub, int frames)
{
    const double P = 1.0 / rate, tau = tau_ms * 1e-3;
    uint32_t rng = 12345u;
    double x = 0.0;
    long double xr = 0.0L;
    double maxerr = 0.0;
    for (int k = 0; k < frames; k++) {
        rng = rng * 1664525u + 1013904223u;
        const int code = (int)(rng >> 24);
        const double target = pow(code / 255.0, 2.2);
        double integral = 0.0;
        for (int s = 0; s < sub; s++) {
            x = step(x, target, tau, P / sub, &integral);
        }
        const long double e = expl(-(long double)P / (long double)tau);
        const long double mean_r = target + (xr - target) * ((long double)tau / P) * (1.0L - e);
        xr = target + (xr - target) * e;
        const double err_x = fabs(x - (double)xr);
        const double err_m = fabs(integral / P - (double)mean_r);
        const double err = err_x > err_m ? err_x : err_m;
        if (!(err <= maxerr)) {
            maxerr = isfinite(err) ? err : INFINITY;
        }
        if (!isfinite(x)) {
            return INFINITY;
        }
    }
    return maxerr;
}

static void test_exact_all_stiffness(void **state)
{
    (void)state;
    for (size_t r = 0; r < sizeof k_rates / sizeof k_rates[0]; r++) {
        for (size_t t = 0; t < sizeof k_taus_ms / sizeof k_taus_ms[0]; t++) {
            for (int sub = 1; sub <= 16; sub *= 4) {
                double e = run_checker(tdc_lcdsim_step_exact, k_taus_ms[t], k_rates[r], sub, 400);
                if (sub == 1 || k_taus_ms[t] == 0.05 || k_taus_ms[t] == 50.0) {
                    printf("exact  %3.0f Hz tau %5.2f ms (h/tau %7.3f) %2d sub-steps: max error %.2e of full scale\n",
                           k_rates[r], k_taus_ms[t], 1e3 / k_rates[r] / sub / k_taus_ms[t], sub, e);
                }
                assert_true(e < 1e-6);
            }
        }
    }
}

static void test_euler_fails_on_stiff_end(void **state)
{
    (void)state;
    /* Same checker, same steps: explicit Euler diverges for h/tau > 2. */
    for (size_t r = 0; r < sizeof k_rates / sizeof k_rates[0]; r++) {
        double e = run_checker(step_euler, 0.05, k_rates[r], 1, 400);
        printf("Euler  %3.0f Hz tau  0.05 ms (h/tau %7.1f)  1 sub-step : max error %.2e -> rejected\n", k_rates[r],
               1e3 / k_rates[r] / 0.05, e);
        assert_true(e > 1e-6);
        assert_true(e > 1.0); /* not just inaccurate: unstable */
    }
    /* Even at 16 sub-steps it is unstable at 0.05 ms (h/tau >= 5). */
    assert_true(run_checker(step_euler, 0.05, 60, 16, 400) > 1.0);
    /* And on the soft end it is merely inaccurate at this step (first order). */
    double soft = run_checker(step_euler, 50.0, 240, 1, 400);
    printf("Euler  240 Hz tau 50.00 ms: max error %.2e (inaccurate, stable)\n", soft);
    assert_true(soft > 1e-6 && soft < 1.0);
}

/* The frame-level simulator (tau table, backlight windows) against the
 * closed form, constant and strobed backlight. */
static void test_frame_sim_closed_form(void **state)
{
    (void)state;
    for (int strobe = 0; strobe <= 1; strobe++) {
        for (size_t t = 0; t < sizeof k_taus_ms / sizeof k_taus_ms[0]; t++) {
            tdc_lcdsim_panel_t p;
            const_panel(&p, k_taus_ms[t]);
            if (strobe) {
                p.strobe = 1;
                p.strobe_duty = 0.25;
                p.strobe_phase = 0.6;
            }
            for (size_t r = 0; r < sizeof k_rates / sizeof k_rates[0]; r++) {
                tdc_lcdsim_t s;
                assert_int_equal(tdc_lcdsim_init(&s, &p, 3), 0);
                s.substeps = 3;
                const double P = 1.0 / k_rates[r], tau = k_taus_ms[t] * 1e-3;
                const double t0 = strobe ? 0.6 * P : 0.0, t1 = strobe ? 0.85 * P : P;
                long double xr = 0.0L;
                double maxerr = 0.0;
                uint32_t rng = 777u;
                for (int k = 0; k < 200; k++) {
                    uint8_t d[3];
                    rng = rng * 1664525u + 1013904223u;
                    d[0] = d[1] = d[2] = (uint8_t)(rng >> 24);
                    double lum[3];
                    tdc_lcdsim_frame(&s, d, k_rates[r], lum);
                    const long double T = powl(d[0] / 255.0L, 2.2L);
                    /* mean over [t0, t1] of T + (x0 - T) e^{-t/tau} */
                    const long double mean = T + (xr - T) * (long double)tau / (t1 - t0) *
                                                     (expl(-(long double)t0 / tau) - expl(-(long double)t1 / tau));
                    xr = T + (xr - T) * expl(-(long double)P / tau);
                    double e = fabs(lum[0] - (double)mean);
                    double ex = fabs(s.x[0] - (double)xr);
                    maxerr = fmax(maxerr, fmax(e, ex));
                }
                assert_true(maxerr < 1e-6);
                tdc_lcdsim_free(&s);
            }
        }
    }
}

/* Physics: with one tau for every transition the system is linear, so the
 * time-averaged light of an alternating pair equals the mean of the two
 * static levels (the Fig. 7 deviation needs transition-dependent tau). */
static void test_symmetric_tau_no_pair_deviation(void **state)
{
    (void)state;
    tdc_lcdsim_panel_t p;
    const_panel(&p, 3.0);
    for (int a = 0; a <= 255; a += 51) {
        for (int b = 0; b <= 255; b += 85) {
            double y = tdc_lcdsim_measure_pair(&p, 0, a, b, 120, 0.5);
            double want = 0.5 * (pow(a / 255.0, 2.2) + pow(b / 255.0, 2.2));
            assert_true(fabs(y - want) < 1e-9);
        }
    }
}

/* The shipped simulated panels: rising from black is slower than the
 * black/white transitions, grey-to-grey slower than black/white, and the
 * Fig. 7 measurement deviates from the plain model (so there is something
 * for the temporal model to fit). */
static void test_shipped_panels(void **state)
{
    (void)state;
    const char *files[] = {"sim/lcd/panels/pg279q.lcdsim", "sim/lcd/panels/lcd-240.lcdsim"};
    for (int f = 0; f < 2; f++) {
        tdc_lcdsim_panel_t p;
        char err[256];
        assert_int_equal(tdc_lcdsim_load(files[f], &p, err, sizeof err), 0);
        const double bw = tdc_lcdsim_tau_ms(&p, 0.0, 1.0), wb = tdc_lcdsim_tau_ms(&p, 1.0, 0.0);
        const double g2g = tdc_lcdsim_tau_ms(&p, 0.25, 0.5);
        assert_true(g2g > bw && g2g > wb);
        assert_true(tdc_lcdsim_tau_ms(&p, 0.0, 0.25) > tdc_lcdsim_tau_ms(&p, 0.25, 0.0)); /* dark rise slow */
        /* bilinear: the midpoint of two levels is the mean of the corners */
        const double mid = tdc_lcdsim_tau_ms(&p, 0.5 * (p.lev[0] + p.lev[1]), p.lev[0]);
        assert_true(fabs(mid - 0.5 * (p.tau_ms[0][0] + p.tau_ms[1][0])) < 1e-9);
        double y = tdc_lcdsim_measure_pair(&p, 1, 0, 128, 120, 1.0);
        double plain = p.black + (1 - p.black) * 0.5 * pow(128 / 255.0, p.gamma[1]);
        printf("%s: tau b->w %.2f w->b %.2f g2g %.2f ms; pair (0,128) %.5f vs plain %.5f\n", p.name, bw, wb, g2g, y,
               plain);
        assert_true(fabs(y - plain) > 1e-3);
    }
    /* Bad files give an error, not a crash. */
    tdc_lcdsim_panel_t p;
    char err[256];
    assert_int_equal(tdc_lcdsim_load("sim/lcd/panels/does-not-exist.lcdsim", &p, err, sizeof err), -1);
    assert_int_equal(tdc_lcdsim_load("boards/panels/pg279q.panel", &p, err, sizeof err), -1);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_exact_all_stiffness),   cmocka_unit_test(test_euler_fails_on_stiff_end),
    cmocka_unit_test(test_frame_sim_closed_form), cmocka_unit_test(test_symmetric_tau_no_pair_deviation),
    cmocka_unit_test(test_shipped_panels),
)
