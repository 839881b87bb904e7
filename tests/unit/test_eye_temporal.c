/*
 * test_eye_temporal.c - the temporal visibility model (sim/eye/tdc_eye_temporal.h),
 * in double precision:
 *   - the box-sampled taps at a fine rate have the closed-form frequency
 *     response |H(f)| (Watson 1986) to 1e-3 from 0 to 100 Hz;
 *   - the peak is 1 at the reported frequency, band-pass shape (DC ~ 1 - zeta
 *     of the unnormalised filter, a few per cent above 40 Hz);
 *   - zeta = 0 is a low-pass with DC gain exactly 1 and a sum of taps of 1;
 *   - the filter run on images: a temporal sinusoid of the error at 90 Hz
 *     comes out with the RMS the discrete response predicts (1e-6), at
 *     8 Hz and at 45 Hz (the TRM alternation), so 45 Hz is attenuated;
 *   - motion compensation: a pattern moving with the gaze is filtered as if
 *     it were static;
 *   - bad parameters are refused.
 */
#include <complex.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "eye/tdc_eye_temporal.h"

/* Discrete-time response of taps at rate R. */
static double complex discrete(const double *t, int k, double rate, double f)
{
    double complex s = 0.0;
    for (int i = 0; i < k; i++) {
        s += t[i] * cexp(-I * 2.0 * M_PI * f * (i + 0.5) / rate);
    }
    return s;
}

static void test_response_closed_form(void **state)
{
    (void)state;
    /* D(f) = sum_k [integral of h over [k/R, (k+1)/R)] e^{-i w (k + 1/2) / R}
     * is the midpoint rule of H(f) = integral h(t) e^{-i w t} dt: equal up
     * to O((w / R)^2) and the tail beyond the support (0.25 s here) */
    static const double rates[] = {150.0, 160.0};
    for (int ri = 0; ri < 2; ri++) {
        const double rate = rates[ri];
        tdc_tcsf_t p;
        tdc_tcsf_default(&p);
        p.support_s = 0.25;
        double taps[TDC_TCSF_MAX_TAPS];
        int n = tdc_tcsf_taps(&p, rate, taps, TDC_TCSF_MAX_TAPS);
        assert_int_equal(n, (int)ceil(0.25 * rate - 1e-9));
        double worst = 0.0, wf = 0.0;
        for (double f = 0.0; f <= 0.3 * rate; f += 0.5) {
            double e = fabs(cabs(discrete(taps, n, rate, f)) - tdc_tcsf_gain(&p, f));
            double tol = 1e-3 + 0.05 * pow(2.0 * M_PI * f / rate, 2.0);
            if (e / tol > worst) {
                worst = e / tol;
                wf = f;
            }
            assert_true(e <= tol);
        }
        print_message("  rate %.0f Hz, %d taps: ||D(f)| - |H(f)|| at most %.2f of the tolerance (at %.1f Hz)\n", rate, n,
                      worst, wf);
    }
}

static void test_shape(void **state)
{
    (void)state;
    tdc_tcsf_t p;
    tdc_tcsf_default(&p);
    double xi;
    double fp = tdc_tcsf_peak_hz(&p, &xi);
    assert_true(fp > 4.0 && fp < 12.0);
    assert_true(fabs(tdc_tcsf_gain(&p, fp) - 1.0) < 1e-12);
    for (double f = 0.0; f < 100.0; f += 0.5) {
        assert_true(tdc_tcsf_gain(&p, f) <= 1.0 + 1e-12);
    }
    /* DC: xi (1 - zeta) */
    assert_true(fabs(tdc_tcsf_gain(&p, 0.0) - xi * (1.0 - p.zeta)) < 1e-12);
    assert_true(tdc_tcsf_gain(&p, 0.0) < 0.35);
    assert_true(tdc_tcsf_gain(&p, 45.0) < 0.05);
    print_message("  peak %.2f Hz; |H| at 0 / 8 / 20 / 45 Hz: %.3f %.3f %.3f %.4f\n", fp, tdc_tcsf_gain(&p, 0.0),
                  tdc_tcsf_gain(&p, 8.0), tdc_tcsf_gain(&p, 20.0), tdc_tcsf_gain(&p, 45.0));
    /* zeta = 0: low-pass, DC gain 1, taps sum to 1 (all of h's mass in the support) */
    p.zeta = 0.0;
    p.support_s = 0.3;
    assert_true(fabs(tdc_tcsf_gain(&p, 0.0) - 1.0) < 1e-12);
    assert_true(tdc_tcsf_peak_hz(&p, NULL) < 0.3);
    double t[TDC_TCSF_MAX_TAPS];
    int n = tdc_tcsf_taps(&p, 120.0, t, TDC_TCSF_MAX_TAPS);
    double s = 0.0;
    for (int i = 0; i < n; i++) {
        s += t[i];
    }
    assert_true(fabs(s - 1.0) < 1e-9);
}

/* The filter on images: the error E_j(x) = a sin(2 pi f j / R) everywhere. */
static double run_sine(double f, double rate, int *k_out, double *pred)
{
    tdc_tcsf_t p;
    tdc_tcsf_default(&p);
    tdc_eye_temporal_t t;
    const int w = 8, h = 6;
    assert_int_equal(tdc_eye_temporal_init(&t, &p, rate, w, h), 0);
    static double err[8 * 6 * 3];
    double last = -1.0, sum2 = 0.0;
    int cnt = 0;
    for (int j = 0; j < 400; j++) {
        double e = 0.1 * sin(2.0 * M_PI * f * j / rate);
        for (int i = 0; i < w * h * 3; i++) {
            err[i] = e;
        }
        last = tdc_eye_temporal_push(&t, err, 0.0, 0.0);
        if (j >= 200) {
            sum2 += last * last;
            cnt++;
        }
    }
    /* predicted steady-state RMS over a long run: 255 * 0.1 |D(f)| / sqrt 2
     * (float storage of the ring: relative 1e-7) */
    *pred = 255.0 * 0.1 * cabs(discrete(t.taps, t.k, rate, f)) / sqrt(2.0);
    *k_out = t.k;
    tdc_eye_temporal_free(&t);
    return sqrt(sum2 / cnt);
}

static void test_filter_on_images(void **state)
{
    (void)state;
    int k;
    double pred;
    /* 9 and 18 Hz: the 200 instants averaged hold whole periods */
    double rms8 = run_sine(9.0, 90.0, &k, &pred);
    assert_int_equal(k, 11);
    assert_true(fabs(rms8 - pred) < 2e-3 * pred + 1e-6);
    double pred8 = pred;
    double rms20 = run_sine(18.0, 90.0, &k, &pred);
    assert_true(fabs(rms20 - pred) < 2e-3 * pred + 1e-6);
    /* the TRM alternation: (-1)^j */
    tdc_tcsf_t p;
    tdc_tcsf_default(&p);
    tdc_eye_temporal_t t;
    assert_int_equal(tdc_eye_temporal_init(&t, &p, 90.0, 4, 4), 0);
    static double err[4 * 4 * 3];
    double alt = -1.0;
    for (int j = 0; j < 40; j++) {
        for (int i = 0; i < 48; i++) {
            err[i] = (j & 1) ? 0.1 : -0.1;
        }
        alt = tdc_eye_temporal_push(&t, err, 0.0, 0.0);
    }
    double dalt = 0.0;
    for (int i = 0; i < t.k; i++) {
        dalt += t.taps[i] * ((i & 1) ? -1.0 : 1.0);
    }
    assert_true(fabs(alt - 255.0 * 0.1 * fabs(dalt)) < 1e-4);
    print_message("  90 Hz: 9 Hz sine RMS %.4f (predicted %.4f), 18 Hz %.4f; +-0.1 alternation (45 Hz) %.4f of 25.5\n",
                  rms8, pred8, rms20, alt);
    assert_true(alt < 0.1 * rms8 * sqrt(2.0));
    tdc_eye_temporal_free(&t);
}

/* A pattern that moves 2 px per instant (whole pixels: the lookups are
 * exact), seen by an eye that follows it, is filtered exactly like the
 * static pattern, up to the clamped left edge (<= 20 of 960 columns); a
 * fixating eye sees it crawl at 15 Hz and gets another figure. */
static void test_motion_compensation(void **state)
{
    (void)state;
    tdc_tcsf_t p;
    tdc_tcsf_default(&p);
    enum { w = 960, h = 2 };
    tdc_eye_temporal_t a, b, c;
    assert_int_equal(tdc_eye_temporal_init(&a, &p, 90.0, w, h), 0);
    assert_int_equal(tdc_eye_temporal_init(&b, &p, 90.0, w, h), 0);
    assert_int_equal(tdc_eye_temporal_init(&c, &p, 90.0, w, h), 0);
    static double es[w * h * 3], em[w * h * 3];
    double rs = 0, rm = 0, rf = 0;
    for (int j = 0; j < 20; j++) {
        double g = 2.0 * j;
        double env = 0.05 * (1.0 + sin(2.0 * M_PI * 6.0 * j / 90.0)); /* a 6 Hz modulation of the error */
        for (int y = 0; y < h; y++) {
            for (int x = 0; x < w; x++) {
                for (int ch = 0; ch < 3; ch++) {
                    es[3 * (y * w + x) + ch] = env * sin(2.0 * M_PI * x / 6.0);
                    em[3 * (y * w + x) + ch] = env * sin(2.0 * M_PI * (x - g) / 6.0);
                }
            }
        }
        rs = tdc_eye_temporal_push(&a, es, 0.0, 0.0);
        rm = tdc_eye_temporal_push(&b, em, g, 0.0);  /* tracking */
        rf = tdc_eye_temporal_push(&c, em, 0.0, 0.0); /* fixating */
    }
    assert_true(rs > 0.1);
    assert_true(fabs(rm - rs) < 0.02 * rs);
    assert_true(fabs(rf - rs) > 0.2 * rs);
    print_message("  6 Hz-modulated pattern: static %.4f, tracked %.4f, fixated (crawling at 30 Hz) %.4f\n", rs, rm, rf);
    tdc_eye_temporal_free(&a);
    tdc_eye_temporal_free(&b);
    tdc_eye_temporal_free(&c);
}

static void test_bad_params(void **state)
{
    (void)state;
    tdc_tcsf_t p;
    tdc_tcsf_default(&p);
    double t[4];
    tdc_eye_temporal_t s;
    assert_int_equal(tdc_tcsf_taps(&p, 0.0, t, 4), 0);
    assert_int_equal(tdc_tcsf_taps(&p, 90.0, NULL, 4), 0);
    assert_int_equal(tdc_tcsf_taps(&p, 90.0, t, 4), 4); /* capped at max */
    p.zeta = 1.0;                                        /* DC exactly 0 makes no filter */
    assert_int_equal(tdc_tcsf_taps(&p, 90.0, t, 4), 0);
    assert_true(isnan(tdc_tcsf_gain(&p, 1.0)));
    assert_int_equal(tdc_eye_temporal_init(&s, &p, 90.0, 4, 4), -1);
    tdc_tcsf_default(&p);
    p.n1 = 0;
    assert_int_equal(tdc_eye_temporal_init(&s, &p, 90.0, 4, 4), -1);
    tdc_tcsf_default(&p);
    assert_int_equal(tdc_eye_temporal_init(&s, &p, 90.0, 0, 4), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_response_closed_form),
        cmocka_unit_test(test_shape),
        cmocka_unit_test(test_filter_on_images),
        cmocka_unit_test(test_motion_compensation),
        cmocka_unit_test(test_bad_params),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
