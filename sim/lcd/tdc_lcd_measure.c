/*
 * tdc-lcd-measure - the paper's Fig. 7 measurement, on the simulated LCD:
 * full-screen patches of one primary alternating between two drive codes
 * (a, b) at a refresh rate, time-averaged luminance over an integration
 * window (the Specbos 1211 used 1 s).  Writes the measurement CSV that
 * tdc-calib reads (format in docs/lcd.md), optionally with multiplicative
 * and additive measurement noise from a seeded generator.
 *
 * With --transitions it measures instead what an overdrive calibration
 * needs (docs/lcd.md §5): for every (previous drive, drive) pair of an N x N
 * grid, the patch settled at the previous drive, then ONE refresh at the
 * drive with the panel's backlight timing: the light delivered within that
 * refresh and the state (transmittance, as the luminance it shows) reached
 * at its end; --runs R repeats every transition R times with independent
 * noise so the calibration can see the measurement noise.
 *
 * Usage: tdc-lcd-measure PANEL.lcdsim RATES [--grid N] [--integration S]
 *                        [--noise REL] [--seed N] [--transitions [--runs R]] [-o FILE]
 *   RATES: comma-separated refresh rates in Hz, e.g. 120,144,165
 * The output is written to a temporary file renamed onto FILE on success,
 * so an error never leaves a truncated file behind.
 */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lcd/tdc_lcdsim.h"
#include "tdc_meas.h"
#include "tdc_tool.h"

static uint64_t g_rng = 0x9e3779b97f4a7c15ull;

static double rnd_uniform(void)
{
    g_rng ^= g_rng << 13;
    g_rng ^= g_rng >> 7;
    g_rng ^= g_rng << 17;
    return ((g_rng >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

static double rnd_gauss(void)
{
    return sqrt(-2.0 * log(rnd_uniform())) * cos(6.283185307179586 * rnd_uniform());
}

static const char usage[] = "usage: tdc-lcd-measure PANEL.lcdsim RATES [--grid N] [--integration S] [--noise REL] "
                            "[--seed N] [--transitions [--runs R]] [-o FILE]";

static double noisy(double y, double noise)
{
    /* relative noise plus a floor of 1e-4 cd/m^2 (instrument dark noise) */
    return noise > 0.0 ? y + y * noise * rnd_gauss() + 1e-4 * rnd_gauss() : y;
}

int main(int argc, char **argv)
{
    tdc_tool_set_name("tdc-lcd-measure");
    if (argc == 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
        printf("%s\n"
               "Simulates the Fig. 7 luminance measurement of an LCD panel model (or, with\n"
               "--transitions, one-refresh transitions) at the refresh rates RATES (comma-separated Hz)\n"
               "and writes the CSV to FILE (stdout without -o) for tdc-calib.\n"
               "exit codes (docs/tools.md): 0 OK, 1 ARGS, 7 FILE, 13 INPUT (a malformed panel model)\n",
               usage);
        return TDC_EXIT_OK;
    }
    if (argc > 1 && argv[1][0] == '-') {
        return tdc_fail_usage(NULL, "unknown option '%s'", argv[1]);
    }
    if (argc < 3) {
        return tdc_fail_usage(NULL, "%s", usage);
    }
    const char *panel_path = argv[1];
    const char *rates_arg = argv[2];
    const char *out_path = NULL;
    int grid = 17, runs = 1, seed = 0;
    int transitions = 0;
    double integration = 1.0, noise = 0.0;
    for (int i = 3; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int bad = 0;
        if (!strcmp(a, "--grid") && v) {
            bad = tdc_parse_int(v, 2, 256, &grid);
            i++;
        } else if (!strcmp(a, "--runs") && v) {
            bad = tdc_parse_int(v, 1, 100, &runs);
            i++;
        } else if (!strcmp(a, "--integration") && v) {
            bad = tdc_parse_double(v, 1e-3, 100.0, &integration);
            i++;
        } else if (!strcmp(a, "--noise") && v) {
            bad = tdc_parse_double(v, 0.0, 1.0, &noise);
            i++;
        } else if (!strcmp(a, "--seed") && v) {
            bad = tdc_parse_int(v, 0, 2147483647L, &seed);
            i++;
        } else if (!strcmp(a, "--transitions")) {
            transitions = 1;
        } else if (!strcmp(a, "-o") && v) {
            out_path = v;
            i++;
        } else {
            const int needs = !v && strstr(" --grid --runs --integration --noise --seed -o ", a) && a[0] == '-';
            return tdc_fail_usage(NULL, needs ? "option '%s' needs a value" : "unknown option '%s'", a);
        }
        if (bad) {
            fprintf(stderr,
                    "tdc-lcd-measure: %s '%s': need --grid 2..256, --runs 1..100, --integration "
                    "0.001..100, --noise 0..1, --seed 0..2147483647\n",
                    a, v);
            return TDC_EXIT_ARGS;
        }
    }
    g_rng ^= (uint64_t)seed * 0x2545f4914f6cdd1dull;
    tdc_lcdsim_panel_t p;
    char err[256];
    if (tdc_in_check(panel_path) != 0) {
        return tdc_fail(TDC_EXIT_FILE, NULL, panel_path, "cannot read: %s", strerror(errno));
    }
    if (tdc_lcdsim_load(panel_path, &p, err, sizeof err) != 0) {
        fprintf(stderr, "tdc-lcd-measure: %s\n", err);
        return TDC_EXIT_INPUT;
    }
    int rates[8], nrates = 0;
    char rbuf[128];
    snprintf(rbuf, sizeof rbuf, "%s", rates_arg);
    for (char *tok = strtok(rbuf, ","); tok; tok = strtok(NULL, ",")) {
        int r;
        if (nrates == 8 || tdc_parse_int(tok, 1, 1000, &r)) {
            fprintf(stderr, "tdc-lcd-measure: bad rate list '%s' (1..8 rates in 1..1000 Hz, comma-separated)\n",
                    rates_arg);
            return TDC_EXIT_ARGS;
        }
        rates[nrates++] = r;
    }
    if (!nrates) {
        fprintf(stderr, "tdc-lcd-measure: bad rate list '%s'\n", rates_arg);
        return TDC_EXIT_ARGS;
    }
    tdc_out_t out;
    FILE *f = stdout;
    if (out_path) {
        if (tdc_out_open(&out, out_path, "w") != 0) {
            return tdc_fail(TDC_EXIT_FILE, NULL, out_path, "cannot write: %s", strerror(errno));
        }
        f = out.f;
    }
    static const char chname[3] = {'R', 'G', 'B'};
    if (!transitions) {
        fprintf(f, "# tdc LCD measurement v1 (docs/lcd.md): simulated panel %s, Fig. 7 alternating pairs,\n", p.name);
        fprintf(f, "# %g s integration, noise %g relative; generated by tdc-lcd-measure\n", integration, noise);
        fprintf(f, "rate_hz,channel,code_a,code_b,luminance_cd_m2\n");
    } else {
        fprintf(f, "# tdc LCD transition measurement v2 (docs/lcd.md): simulated panel %s, %s backlight;\n", p.name,
                p.strobe ? "strobed" : "constant");
        fprintf(f,
                "# settled at prev_code, one refresh at code: light within the refresh and the state at its\n"
                "# end (as luminance); %d x %d grid, %d run(s), noise %g relative; generated by "
                "tdc-lcd-measure\n",
                grid, grid, runs, noise);
        fprintf(f, "rate_hz,channel,prev_code,code,run,light_cd_m2,end_cd_m2\n");
    }
    for (int r = 0; r < nrates; r++) {
        for (int ch = 0; ch < 3; ch++) {
            for (int i = 0; i < grid; i++) {
                for (int j = 0; j < grid; j++) {
                    int a = (int)lround(i * 255.0 / (grid - 1));
                    int b = (int)lround(j * 255.0 / (grid - 1));
                    if (!transitions) {
                        double y = tdc_lcdsim_measure_pair(&p, ch, a, b, rates[r], integration) * p.peak_cd[ch];
                        fprintf(f, "%d,%c,%d,%d,%.6f\n", rates[r], chname[ch], a, b, noisy(y, noise));
                        continue;
                    }
                    double light, end;
                    tdc_lcdsim_measure_transition(&p, ch, a, b, rates[r], &light, &end);
                    for (int k = 0; k < runs; k++) {
                        fprintf(f, "%d,%c,%d,%d,%d,%.6f,%.6f\n", rates[r], chname[ch], a, b, k,
                                noisy(light * p.peak_cd[ch], noise), noisy(end * p.peak_cd[ch], noise));
                    }
                }
            }
        }
    }
    if (out_path && tdc_out_commit(&out) != 0) {
        return tdc_fail(TDC_EXIT_FILE, NULL, out_path, "cannot write: %s", strerror(errno));
    }
    return 0;
}
