/*
 * tdc_sim_jod.c - FovVideoVDP on the retinal signal (tdc_sim_jod.h).
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "simulator/tdc_sim_heatmap.h"
#include "simulator/tdc_sim_jod.h"
#include "tdc_par.h"

#define MAX_JUDGES 128

typedef struct {
    char mode[64];
    int eye;
    tdc_fvvdp_t *m;       /* created at the first refresh's end (its step count gives the rate) */
    int own;              /* index of the judge whose reference m shares (the eye's first), or -1 */
    float *acc_t, *acc_r; /* this refresh's retinal luminance, summed over its steps (acc_r: the
                             reference, held by the eye's first judge only: the same for every mode) */
    int w, h, nacc;
    long refresh;         /* the refresh being accumulated */
    double gaze[2], t1;
    int fed, warmup;      /* frames fed; frames of the warm-up */
    tdc_fvvdp_geometry_t g;
    double fps;           /* retinal steps per second */
    double rate;          /* the metric's frame rate (refreshes per second) */
    tdc_sim_heatmap_t *hm; /* eye 0 with heat maps on */
    float *per;           /* per-refresh JOD (NAN in the warm-up), index: refresh */
    long nper;
} judge_t;

struct tdc_sim_jod {
    FILE *series;
    int heat;
    judge_t j[MAX_JUDGES];
    int n;
};

int tdc_sim_jod_warmup(double hz)
{
    return (int)ceil(TDC_SIM_JOD_WARMUP_S * hz);
}

tdc_sim_jod_t *tdc_sim_jod_new(FILE *series, int heatmaps)
{
    tdc_sim_jod_t *s = calloc(1, sizeof *s);
    if (s) {
        s->heat = heatmaps;
    }
    if (s && series) {
        s->series = series;
        fprintf(series, "mode,eye,refresh,t,pooled,jod,jod_fovea,jod_periphery\n");
    }
    return s;
}

static judge_t *find(tdc_sim_jod_t *s, const char *mode, int eye)
{
    for (int i = 0; i < s->n; i++) {
        if (s->j[i].eye == eye && strcmp(s->j[i].mode, mode) == 0) {
            return &s->j[i];
        }
    }
    return NULL;
}

/* Feeds the accumulated refresh (its mean) to the metric. */
static int flush(tdc_sim_jod_t *s, judge_t *j)
{
    if (j->nacc == 0) {
        return 0;
    }
    if (!j->m) {
        /* The first refresh's step count fixes the rate: R = steps/s / N. */
        char why[160];
        double rate = j->fps / j->nacc;
        if (j->own >= 0 && !s->j[j->own].m) {
            fprintf(stderr, "tdc-sim: jod: mode %s eye %d: the reference's judge (mode %s) has no metric\n", j->mode,
                    j->eye, s->j[j->own].mode);
            return -1;
        }
        /* The other eye's metric at the same size and rate lends its
         * scratch planes (the judges run one at a time). */
        const judge_t *o = NULL;
        for (int i = 0; i < s->n && !o; i++) {
            o = s->j[i].m && s->j[i].rate == rate && memcmp(&s->j[i].g, &j->g, sizeof j->g) == 0 ? &s->j[i] : NULL;
        }
        j->m = j->own >= 0 ? tdc_fvvdp_new_shared(s->j[j->own].m, why, sizeof why)
               : o         ? tdc_fvvdp_new_beside(o->m, why, sizeof why)
                           : tdc_fvvdp_new(&j->g, rate, why, sizeof why);
        if (!j->m) {
            fprintf(stderr, "tdc-sim: jod: mode %s eye %d: %s\n", j->mode, j->eye, why);
            return -1;
        }
        j->rate = rate;
        j->warmup = tdc_sim_jod_warmup(rate);
    }
    if (j->own >= 0 && tdc_fvvdp_frames(s->j[j->own].m) != j->fed + 1) {
        /* the judge holding the reference stopped (its mode failed): this
         * mode's reference would be stale */
        fprintf(stderr, "tdc-sim: jod: mode %s eye %d: the reference's judge (mode %s) has %d refreshes, not %d\n",
                j->mode, j->eye, s->j[j->own].mode, tdc_fvvdp_frames(s->j[j->own].m), j->fed + 1);
        return -1;
    }
    size_t np = (size_t)j->w * j->h;
    float inv = 1.0f / (float)j->nacc;
    float *acc_t = j->acc_t, *acc_r = j->acc_r;
    TDC_PAR_FOR(np)
    for (int y = 0; y < j->h; y++) {
        for (size_t i = (size_t)y * j->w; i < (size_t)(y + 1) * j->w; i++) {
            acc_t[i] *= inv;
            if (acc_r) {
                acc_r[i] *= inv;
            }
        }
    }
    const int pooled = j->fed >= j->warmup; /* the frame about to be fed is pooled */
    if (j->hm && pooled) {
        tdc_fvvdp_set_dmap(j->m, tdc_sim_heatmap_bands(j->hm));
    }
    double fr = tdc_fvvdp_frame(j->m, j->acc_t, j->acc_r, j->gaze);
    if (j->hm && pooled) {
        tdc_fvvdp_set_dmap(j->m, NULL);
    }
    if (isnan(fr)) {
        fprintf(stderr, "tdc-sim: jod: mode %s eye %d: out of memory for the metric's history\n", j->mode, j->eye);
        return -1;
    }
    if (j->hm && pooled) {
        tdc_sim_heatmap_add(j->hm, j->acc_r);
    }
    j->fed++;
    if (j->fed == j->warmup) {
        tdc_fvvdp_reset_pool(j->m);
    }
    tdc_fvvdp_jods_t r;
    tdc_fvvdp_last(j->m, &r);
    if (j->refresh >= 0 && j->refresh >= j->nper) {
        long cap = j->refresh + 64;
        float *p = realloc(j->per, (size_t)cap * sizeof(float));
        if (!p) {
            fprintf(stderr, "tdc-sim: jod: out of memory\n");
            return -1;
        }
        for (long k = j->nper; k < cap; k++) {
            p[k] = NAN;
        }
        j->per = p;
        j->nper = cap;
    }
    if (j->refresh >= 0) {
        j->per[j->refresh] = pooled ? (float)r.all : NAN;
    }
    if (s->series) {
        fprintf(s->series, "%s,%d,%ld,%.6f,%d,%.4f,%.4f,%.4f\n", j->mode, j->eye, j->refresh, j->t1,
                j->fed > j->warmup, r.all, r.fovea, r.periphery);
    }
    memset(j->acc_t, 0, np * sizeof(float));
    if (j->acc_r) {
        memset(j->acc_r, 0, np * sizeof(float));
    }
    j->nacc = 0;
    return 0;
}

int tdc_sim_jod_cb(void *ctx, const tdc_retina_frame_t *f)
{
    tdc_sim_jod_t *s = ctx;
    judge_t *j = find(s, f->mode, f->eye);
    size_t np = (size_t)f->width * f->height;
    if (!j) {
        if (s->n == MAX_JUDGES) {
            fprintf(stderr, "tdc-sim: jod: more than %d mode-eye pairs\n", MAX_JUDGES);
            return -1;
        }
        j = &s->j[s->n];
        snprintf(j->mode, sizeof j->mode, "%s", f->mode);
        j->eye = f->eye;
        j->w = f->width;
        j->h = f->height;
        j->g = (tdc_fvvdp_geometry_t){ f->width, f->height, f->display->width_m, f->display->distance_m };
        j->fps = f->fps;
        j->refresh = f->refresh;
        /* The eye's first judge holds the reference; the eye's other modes
         * share it (their refreshes are flushed after it, in mode order). */
        j->own = -1;
        for (int i = 0; i < s->n && j->own < 0; i++) {
            j->own = s->j[i].eye == j->eye ? i : -1;
        }
        j->acc_t = calloc(np, sizeof(float));
        if (s->heat && f->eye == 0) {
            j->hm = tdc_sim_heatmap_new(j->w, j->h, tdc_fvvdp_ppd(&j->g));
        }
        /* A heat map shows the reference under it: its judge keeps its own
         * sum of the reference even where the metric shares the owner's. */
        j->acc_r = j->own < 0 || j->hm ? calloc(np, sizeof(float)) : NULL;
        if (!j->acc_t || (!j->acc_r && (j->own < 0 || j->hm)) || (s->heat && f->eye == 0 && !j->hm)) {
            fprintf(stderr, "tdc-sim: jod: out of memory\n");
            free(j->acc_t);
            free(j->acc_r);
            tdc_sim_heatmap_free(j->hm);
            memset(j, 0, sizeof *j);
            return -1;
        }
        s->n++;
    }
    if (f->refresh != j->refresh) {
        if (flush(s, j)) {
            return -1;
        }
        j->refresh = f->refresh;
    }
    /* a dark step adds nothing (4 of an OLED's 5 at 20 % persistence) */
    float *acc_t = f->test_dark ? NULL : j->acc_t, *acc_r = f->ref_dark ? NULL : j->acc_r;
    const int rows = acc_t || acc_r ? f->height : 0;
    TDC_PAR_FOR(rows ? np : 0)
    for (int y = 0; y < rows; y++) {
        for (size_t i = (size_t)y * f->width; acc_t && i < (size_t)(y + 1) * f->width; i++) {
            acc_t[i] += f->test_y[i];
        }
        for (size_t i = (size_t)y * f->width; acc_r && i < (size_t)(y + 1) * f->width; i++) {
            acc_r[i] += f->ref_y[i];
        }
    }
    j->nacc++;
    j->gaze[0] = f->gaze[0];
    j->gaze[1] = f->gaze[1];
    j->t1 = f->t1;
    return 0;
}

int tdc_sim_jod_finish(tdc_sim_jod_t *s)
{
    for (int i = 0; i < s->n; i++) {
        if (flush(s, &s->j[i])) {
            return -1;
        }
    }
    return 0;
}

int tdc_sim_jod_result(tdc_sim_jod_t *s, const char *mode, int eye, tdc_fvvdp_jods_t *out, int *frames)
{
    judge_t *j = find(s, mode, eye);
    if (!j || !j->m) {
        return -1;
    }
    tdc_fvvdp_pooled(j->m, out);
    *frames = j->fed > j->warmup ? j->fed - j->warmup : 0;
    return 0;
}

int tdc_sim_jod_write(tdc_sim_jod_t *s, FILE *f)
{
    int bad = fprintf(f, "mode,eye,jod,jod_fovea,jod_periphery,frames_pooled\n") < 0;
    for (int i = 0; i < s->n; i++) {
        tdc_fvvdp_jods_t r = { NAN, NAN, NAN };
        const judge_t *j = &s->j[i];
        if (j->m) {
            tdc_fvvdp_pooled(j->m, &r);
        }
        int pooled = j->fed > j->warmup ? j->fed - j->warmup : 0;
        char v[3][24];
        const double x[3] = { r.all, r.fovea, r.periphery };
        for (int k = 0; k < 3; k++) {
            /* NAN (nothing pooled, a region without pixels): an empty field */
            v[k][0] = 0;
            if (isfinite(x[k])) {
                snprintf(v[k], sizeof v[k], "%.4f", x[k]);
            }
        }
        bad |= fprintf(f, "%s,%d,%s,%s,%s,%d\n", j->mode, j->eye, v[0], v[1], v[2], pooled) < 0;
    }
    return bad ? -1 : 0;
}

double tdc_sim_jod_at(tdc_sim_jod_t *s, const char *mode, int eye, long refresh)
{
    const judge_t *j = find(s, mode, eye);
    return j && refresh >= 0 && refresh < j->nper ? j->per[refresh] : NAN;
}

int tdc_sim_jod_heatmaps(tdc_sim_jod_t *s, const char *outdir)
{
    int bad = 0;
    for (int i = 0; i < s->n; i++) {
        const judge_t *j = &s->j[i];
        char path[1200], err[1400];
        if (!j->hm || !tdc_sim_heatmap_frames(j->hm)) {
            continue; /* eye 1, or no pooled refresh (a run within the warm-up) */
        }
        snprintf(path, sizeof path, "%s/heatmap_%s.png", outdir, j->mode);
        if (tdc_sim_heatmap_write(j->hm, path, err, sizeof err)) {
            fprintf(stderr, "tdc-sim: heat map: %s\n", err);
            bad = 1;
        }
    }
    return bad ? -1 : 0;
}

/* One series.csv line (no newline): "mode[.L|.R],eval,t,...," -> the JOD of
 * the refresh that ends at t appended. */
static int merge_line(tdc_sim_jod_t *s, FILE *out, char *line, int eyes, double hz)
{
    char mode[80];
    size_t k = strcspn(line, ",");
    if (k == 0 || k >= sizeof mode) {
        return -1;
    }
    memcpy(mode, line, k);
    mode[k] = 0;
    int eye = 0;
    if (eyes == 2 && k > 2 && mode[k - 2] == '.') {
        eye = mode[k - 1] == 'R';
        mode[k - 2] = 0;
    }
    const char *p = strchr(line + k + 1, ',');
    double t = p ? strtod(p + 1, NULL) : NAN;
    double v = isfinite(t) ? tdc_sim_jod_at(s, mode, eye, lround(t * hz) - 1) : NAN;
    if (isfinite(v)) {
        return fprintf(out, "%s%.4f\n", line, v) < 0 ? -1 : 0;
    }
    return fprintf(out, "%s\n", line) < 0 ? -1 : 0;
}

int tdc_sim_jod_series_merge(tdc_sim_jod_t *s, const char *path, int eyes, double hz)
{
    char tmp[1200], line[512];
    errno = 0;
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *in = fopen(path, "r"), *out = in ? fopen(tmp, "w") : NULL;
    int bad = !in || !out;
    for (int n = 0; !bad && fgets(line, sizeof line, in); n++) {
        line[strcspn(line, "\n")] = 0;
        bad = n == 0 ? fprintf(out, "%s\n", line) < 0 : merge_line(s, out, line, eyes, hz);
    }
    bad |= in && ferror(in);
    if (in) {
        fclose(in);
    }
    if (out) {
        bad |= ferror(out) | (fclose(out) != 0);
    }
    if (bad || rename(tmp, path) != 0) {
        fprintf(stderr, "tdc-sim: %s: cannot add the jod column: %s\n", path, strerror(errno ? errno : EIO));
        remove(tmp);
        return -1;
    }
    return 0;
}

void tdc_sim_jod_free(tdc_sim_jod_t *s)
{
    if (!s) {
        return;
    }
    for (int i = 0; i < s->n; i++) {
        tdc_fvvdp_free(s->j[i].m);
        tdc_sim_heatmap_free(s->j[i].hm);
        free(s->j[i].per);
        free(s->j[i].acc_t);
        free(s->j[i].acc_r);
    }
    free(s);
}
