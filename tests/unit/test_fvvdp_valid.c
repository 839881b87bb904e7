/*
 * test_fvvdp_valid.c - tdc's FovVideoVDP against the reference
 * implementation's numbers stored in sim/metrics/validation/
 * fvvdp_reference.csv (40 conditions: blur, noise, contrast, flicker 5-60
 * Hz, judder, frame drops, TRM-like alternation at 45-120 Hz, foveated blur
 * at 5-30 deg, at 11.4, 20 and 56 px/deg, 60-240 Hz; docs/visual-model.md).
 *
 * Goals (the issue's): mean |dJOD| <= 0.1, max <= 0.3, Spearman >= 0.98.
 * Measured when the table was made: mean 0.00001, max 0.0001, Spearman 1
 * (the port evaluates the same equations in double where the reference
 * uses float32); with the masking in float, max 0.00003.  The test asserts the goals and, tighter, max |dJOD| <=
 * 0.01, so a change that moves any condition by a hundredth of a JOD is
 * seen here and must be explained in the doc.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

#include <cmocka.h>

#include "metrics/tdc_fvvdp.h"
#include "metrics/validation/fvvdp_conditions.h"

static void test_against_reference(void **state)
{
    (void)state;
    double ref[FVVDP_MAXCOND], secs[FVVDP_MAXCOND], tdc[FVVDP_MAXCOND];
    assert_true(fvvdp_ncond >= 30 && fvvdp_ncond <= FVVDP_MAXCOND);
    assert_int_equal(fvvdp_read_reference(FVVDP_REFERENCE_CSV, ref, secs), 0);
    double sum = 0.0, mx = 0.0;
    for (int i = 0; i < fvvdp_ncond; i++) {
        char why[160];
        tdc[i] = fvvdp_cond_run(&fvvdp_conds[i], why, sizeof why);
        assert_false(isnan(tdc[i]));
        double d = fabs(tdc[i] - ref[i]);
        if (d > 0.01) {
            print_message("%s: reference %.4f tdc %.4f\n", fvvdp_conds[i].name, ref[i], tdc[i]);
        }
        sum += d;
        mx = d > mx ? d : mx;
    }
    double rs = fvvdp_spearman(ref, tdc, fvvdp_ncond);
    print_message("%d conditions: mean |dJOD| %.5f, max %.5f, Spearman %.4f\n", fvvdp_ncond, sum / fvvdp_ncond, mx, rs);
    assert_true(sum / fvvdp_ncond <= 0.1);
    assert_true(mx <= 0.3);
    assert_true(rs >= 0.98);
    assert_true(mx <= 0.01);
}

/* The set spans the range it claims: identical inputs at JOD 10, and
 * conditions down to below 8 JOD (a set of invisible differences would
 * validate nothing). */
static void test_set_spans_range(void **state)
{
    (void)state;
    double ref[FVVDP_MAXCOND], secs[FVVDP_MAXCOND], lo = 10.0;
    assert_int_equal(fvvdp_read_reference(FVVDP_REFERENCE_CSV, ref, secs), 0);
    int tens = 0;
    for (int i = 0; i < fvvdp_ncond; i++) {
        lo = ref[i] < lo ? ref[i] : lo;
        tens += ref[i] == 10.0;
    }
    assert_int_equal(tens, 2);
    assert_true(lo < 7.5);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_against_reference),
        cmocka_unit_test(test_set_spans_range),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
