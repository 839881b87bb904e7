/*
 * fvvdp_validate.c - tdc-fvvdp-validate: the validation set of the
 * FovVideoVDP port against the reference implementation.
 *
 *   tdc-fvvdp-validate dump DIR     write the frames (DIR/<name>.f32: the
 *                                   test frames then the reference frames,
 *                                   float32 cd/m^2, row-major) and
 *                                   DIR/manifest.csv for fvvdp_reference.py
 *   tdc-fvvdp-validate bench        seconds tdc's metric spends on the set
 *                                   (frames made beforehand, untimed): the
 *                                   figure make bench-sim sets against the
 *                                   reference's on the same frames
 *   tdc-fvvdp-validate table CSV    tdc's JOD beside the reference's (CSV
 *                                   from fvvdp_reference.py): a markdown
 *                                   table, mean and max |dJOD|, Spearman
 *                                   rank correlation
 *
 * Exit codes (docs/tools.md): 0 OK, 1 ARGS usage, 7 FILE a file not read or
 * written, 13 INPUT the reference table lacks a condition, 14 REFUSED the
 * metric refused a condition.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "fvvdp_conditions.h"
#include "metrics/tdc_fvvdp.h"
#include "tdc_tool.h"

#define TOOL "tdc-fvvdp-validate"

static int dump(const char *dir)
{
    char path[4096];
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, TOOL ": dump: cannot create %s: %s\n", dir, strerror(errno));
        return TDC_EXIT_FILE;
    }
    snprintf(path, sizeof path, "%s/manifest.csv", dir);
    FILE *mf = fopen(path, "w");
    if (!mf) {
        fprintf(stderr, TOOL ": dump: cannot write %s: %s\n", path, strerror(errno));
        return TDC_EXIT_FILE;
    }
    fprintf(mf, "name,width,height,frames,fps,width_m,distance_m,gaze_x,gaze_y\n");
    float fr[64 * 64];
    int bad = 0;
    for (int i = 0; i < fvvdp_ncond; i++) {
        const fvvdp_cond_t *c = &fvvdp_conds[i];
        tdc_fvvdp_geometry_t g = tdc_fvvdp_geometry_ppd(c->w, c->h, c->ppd);
        double gz[2];
        int fov = fvvdp_cond_gaze(c, gz);
        fprintf(mf, "%s,%d,%d,%d,%.17g,%.17g,%.17g,", c->name, c->w, c->h, c->frames, c->frames > 1 ? c->fps : 0.0,
                g.width_m, g.distance_m);
        if (fov) {
            fprintf(mf, "%.17g,%.17g\n", gz[0], gz[1]);
        } else {
            fprintf(mf, "nan,nan\n");
        }
        snprintf(path, sizeof path, "%s/%s.f32", dir, c->name);
        FILE *f = fopen(path, "wb");
        if (!f) {
            fprintf(stderr, TOOL ": dump: cannot write %s: %s\n", path, strerror(errno));
            fclose(mf);
            return TDC_EXIT_FILE;
        }
        for (int t = 1; t >= 0; t--) {
            for (int k = 0; k < c->frames; k++) {
                fvvdp_cond_frame(c, k, t, fr);
                bad |= fwrite(fr, sizeof(float), (size_t)c->w * c->h, f) != (size_t)c->w * c->h;
            }
        }
        bad |= fclose(f) != 0;
    }
    bad |= fclose(mf) != 0;
    if (bad) {
        fprintf(stderr, TOOL ": dump: write to %s failed\n", dir);
        return TDC_EXIT_FILE;
    }
    printf("%d conditions written to %s\n", fvvdp_ncond, dir);
    return 0;
}

static int table(const char *csv)
{
    double ref[FVVDP_MAXCOND], secs[FVVDP_MAXCOND], tdc[FVVDP_MAXCOND] = { 0 };
    int rc = fvvdp_read_reference(csv, ref, secs);
    if (rc == -1) {
        fprintf(stderr, TOOL ": table: cannot read %s: %s\n", csv, strerror(errno));
        return TDC_EXIT_FILE;
    }
    if (rc < -1) {
        fprintf(stderr, TOOL ": table: %s has no row for condition %s\n", csv, fvvdp_conds[-2 - rc].name);
        return TDC_EXIT_INPUT;
    }
    double sum = 0, mx = 0;
    printf("| condition | reference JOD | tdc JOD | tdc - reference |\n|---|---:|---:|---:|\n");
    for (int i = 0; i < fvvdp_ncond; i++) {
        char why[160];
        tdc[i] = fvvdp_cond_run(&fvvdp_conds[i], why, sizeof why);
        if (isnan(tdc[i])) {
            fprintf(stderr, TOOL ": table: condition %s refused: %s\n", fvvdp_conds[i].name, why);
            return TDC_EXIT_REFUSED;
        }
        double d = tdc[i] - ref[i];
        sum += fabs(d);
        mx = fabs(d) > mx ? fabs(d) : mx;
        printf("| %s | %.4f | %.4f | %+.4f |\n", fvvdp_conds[i].name, ref[i], tdc[i], d);
    }
    printf("\n%d conditions: mean |dJOD| %.5f (goal <= 0.1), max |dJOD| %.5f (goal <= 0.3), Spearman %.4f (goal >= 0.98)\n",
           fvvdp_ncond, sum / fvvdp_ncond, mx, fvvdp_spearman(ref, tdc, fvvdp_ncond));
    return 0;
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static int bench(void)
{
    static float fr[2][512][64 * 64];
    double secs = 0.0, px = 0.0;
    int frames = 0;
    for (int i = 0; i < fvvdp_ncond; i++) {
        const fvvdp_cond_t *c = &fvvdp_conds[i];
        char why[160];
        for (int k = 0; k < c->frames && k < 512; k++) {
            fvvdp_cond_frame(c, k, 1, fr[0][k]);
            fvvdp_cond_frame(c, k, 0, fr[1][k]);
        }
        tdc_fvvdp_geometry_t g = tdc_fvvdp_geometry_ppd(c->w, c->h, c->ppd);
        double gz[2];
        int fov = fvvdp_cond_gaze(c, gz);
        double t0 = now();
        tdc_fvvdp_t *m = tdc_fvvdp_new(&g, c->frames > 1 ? c->fps : 0.0, why, sizeof why);
        if (!m) {
            fprintf(stderr, TOOL ": bench: condition %s refused: %s\n", c->name, why);
            return TDC_EXIT_REFUSED;
        }
        for (int k = 0; k < c->frames; k++) {
            tdc_fvvdp_frame(m, fr[0][k], fr[1][k], fov ? gz : NULL);
        }
        tdc_fvvdp_free(m);
        secs += now() - t0;
        frames += c->frames;
        px += (double)c->frames * c->w * c->h;
    }
    printf("tdc %d frames %.0f pixels %.4f s\n", frames, px, secs);
    return 0;
}

static void usage(FILE *f)
{
    fprintf(f, "usage: " TOOL " dump DIR | bench | table REFERENCE.csv\n"
               "  dump DIR     write the validation set's frames and manifest.csv for fvvdp_reference.py\n"
               "  bench        seconds tdc's FovVideoVDP spends on the set (make bench-sim)\n"
               "  table CSV    tdc's JOD beside the reference's, with the agreement statistics\n"
               "exit codes: 0 OK, 1 ARGS, 7 FILE, 13 INPUT (the table lacks a condition), 14 REFUSED\n");
}

int main(int argc, char **argv)
{
    if (argc == 2 && strcmp(argv[1], "--help") == 0) {
        usage(stdout);
        return TDC_EXIT_OK;
    }
    if (argc == 2 && strcmp(argv[1], "bench") == 0) {
        return bench();
    }
    if (argc == 3 && strcmp(argv[1], "dump") == 0) {
        return dump(argv[2]);
    }
    if (argc == 3 && strcmp(argv[1], "table") == 0) {
        return table(argv[2]);
    }
    fprintf(stderr, TOOL ": bad arguments: usage: " TOOL " dump DIR | bench | table REFERENCE.csv (--help)\n");
    return TDC_EXIT_ARGS;
}
