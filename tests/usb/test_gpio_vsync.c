/*
 * test_gpio_vsync.c - the vsync statistics of tdc-gpio on synthetic edge
 * timestamps with known refresh, jitter and dropped frames, and tdc-gpio's
 * error paths on a machine without the named GPIO chip.  The real-line tests
 * (gpio-sim) belong to `make test-vm`.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "tdc_vsync_stats.h"

#ifndef TDC_GPIO_BIN
#error "TDC_GPIO_BIN must be defined by the build"
#endif

/* n edges at refresh hz, deterministic jitter of +-amp_ns (triangle wave),
 * edges listed in drop[] left out (missed frames). */
static size_t make_edges(uint64_t *ts, size_t n, double hz, int64_t amp_ns, const size_t *drop, size_t ndrop)
{
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        int skip = 0;
        for (size_t j = 0; j < ndrop; j++) skip |= drop[j] == i;
        if (skip) continue;
        int64_t tri = (int64_t)(i % 4) - 1; /* -1, 0, 1, 2 -> mean 0.5 */
        ts[k++] = (uint64_t)(1000000000.0 + (double)i * 1e9 / hz) + (uint64_t)(amp_ns * (tri + 1));
    }
    return k;
}

static void test_clean_90hz(void **state)
{
    (void)state;
    uint64_t ts[200];
    size_t n = make_edges(ts, 200, 90.0, 0, NULL, 0);
    tdc_vsync_stats_t s;
    assert_int_equal(tdc_vsync_analyse(ts, n, 0, &s), 0);
    assert_true(fabs(s.refresh_hz - 90.0) < 1e-3);
    assert_int_equal(s.missed, 0);
    assert_true(s.jitter_rms_us < 0.01);
    assert_true(s.jitter_pp_us < 0.01);
}

static void test_jitter_and_missed(void **state)
{
    (void)state;
    uint64_t ts[1000];
    const size_t drop[] = {100, 101, 500, 777};
    size_t n = make_edges(ts, 1000, 240.0, 20000, drop, 4); /* +-20 us triangle */
    tdc_vsync_stats_t s, e;
    assert_int_equal(tdc_vsync_analyse(ts, n, 0, &s), 0);
    assert_int_equal(s.missed, 4);
    assert_true(fabs(s.refresh_hz - 240.0) < 0.05);
    /* offsets 0,20,40,60 us repeating: interval deviations +20,+20,+20,-60;
     * across the dropped edge 777 the interval 776->778 deviates +40: p-p 100 */
    assert_true(fabs(s.jitter_pp_us - 100.0) < 1.0);
    assert_true(s.jitter_rms_us > 20.0 && s.jitter_rms_us < 45.0);
    /* with the nominal rate given, the same answer */
    assert_int_equal(tdc_vsync_analyse(ts, n, 240.0, &e), 0);
    assert_int_equal(e.missed, 4);
    /* a nominal rate half the real one sees every interval as one frame: no
     * missed frames, and the refresh comes out low by 995/999 */
    assert_int_equal(tdc_vsync_analyse(ts, n, 120.0, &e), 0);
    assert_int_equal(e.missed, 0);
    assert_true(fabs(e.refresh_hz - 240.0 * 995.0 / 999.0) < 0.05);
}

static void test_bad_input(void **state)
{
    (void)state;
    uint64_t ts[3] = {100, 50, 200};
    tdc_vsync_stats_t s;
    assert_int_equal(tdc_vsync_analyse(ts, 1, 0, &s), -1);
    assert_int_equal(tdc_vsync_analyse(ts, 3, 0, &s), -1); /* not increasing */
    assert_int_equal(tdc_vsync_analyse(NULL, 3, 0, &s), -1);
}

static int run(const char *args, char *err, size_t cap)
{
    char cmd[512];
    snprintf(cmd, sizeof cmd, "timeout 20 %s %s 2>&1 >/dev/null", TDC_GPIO_BIN, args);
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    size_t n = fread(err, 1, cap - 1, p);
    err[n] = '\0';
    int st = pclose(p);
    printf("  $ tdc-gpio %s -> %d: %s", args, WEXITSTATUS(st), err);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static void test_cli_errors(void **state)
{
    (void)state;
    char err[1024];
    assert_int_equal(run("reset --chip tdc-no-such-chip --line 0", err, sizeof err), 2);
    assert_non_null(strstr(err, "cannot open GPIO chip 'tdc-no-such-chip'"));
    assert_int_equal(run("vsync --chip /dev/tdc-no-such-chip --line vsync", err, sizeof err), 2);
    assert_int_equal(run("reset --line 0", err, sizeof err), 1);
    assert_non_null(strstr(err, "needs --chip and --line"));
    assert_int_equal(run("boot --chip x --line 0", err, sizeof err), 1);
    assert_non_null(strstr(err, "--boot-line"));
    assert_int_equal(run("vsync --chip x --line 0 --edge sideways", err, sizeof err), 1);
    /* the shared convention (docs/tools.md): tool: what failed: why */
    assert_non_null(strstr(err, "tdc-gpio: bad value for --edge 'sideways': "));
    assert_int_equal(run("vsync --chip x --line 0 --count 4294967298", err, sizeof err), 1);
    assert_int_equal(run("vsync --chip x --line 0 --expect-hz nan", err, sizeof err), 1);
    assert_non_null(strstr(err, "--expect-hz 'nan'"));
    assert_int_equal(run("frob --chip x --line 0", err, sizeof err), 1);
    assert_int_equal(run("--help", err, sizeof err), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clean_90hz),
        cmocka_unit_test(test_jitter_and_missed),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_cli_errors),
    };
    return cmocka_run_group_tests_name("tdc-gpio vsync statistics and error paths", tests, NULL, NULL);
}
