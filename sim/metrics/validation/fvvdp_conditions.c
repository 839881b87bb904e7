/*
 * fvvdp_conditions.c - the validation set's generators (fvvdp_conditions.h).
 *
 * Content: a sum of gratings (periods 3.1 to 23 px, several orientations)
 * and a soft vertical edge, display-encoded in [0.04, 0.86], defined at any
 * real position so that panning content moves by sub-pixel steps.  The
 * distortions act on the encoded values; frames are then decoded with the
 * validation display (100 cd/m^2, 1000:1, gamma 2.2).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fvvdp_conditions.h"
#include "metrics/tdc_fvvdp.h"


/* The pan speed of moving conditions, deg/s. */
#define PAN 4.0

const fvvdp_cond_t fvvdp_conds[] = {
    { "identical-image", 64, 64, 1, 0, 20, 0, FVVDP_K_SAME, 0, 0 },
    { "blur-0.5px-20ppd", 64, 64, 1, 0, 20, 0, FVVDP_K_BLUR, 0.5, 0 },
    { "blur-1px-20ppd", 64, 64, 1, 0, 20, 0, FVVDP_K_BLUR, 1.0, 0 },
    { "blur-2px-20ppd", 64, 64, 1, 0, 20, 0, FVVDP_K_BLUR, 2.0, 0 },
    { "blur-1px-11.4ppd", 64, 64, 1, 0, 11.4, 0, FVVDP_K_BLUR, 1.0, 0 },
    { "blur-1px-56ppd", 64, 64, 1, 0, 56, 0, FVVDP_K_BLUR, 1.0, 0 },
    { "noise-0.01-20ppd", 64, 64, 1, 0, 20, 0, FVVDP_K_NOISE, 0.01, 0 },
    { "noise-0.03-20ppd", 64, 64, 1, 0, 20, 0, FVVDP_K_NOISE, 0.03, 0 },
    { "noise-0.1-20ppd", 64, 64, 1, 0, 20, 0, FVVDP_K_NOISE, 0.1, 0 },
    { "noise-0.03-56ppd", 64, 64, 1, 0, 56, 0, FVVDP_K_NOISE, 0.03, 0 },
    { "contrast-0.9-20ppd", 64, 64, 1, 0, 20, 0, FVVDP_K_CONTRAST, 0.9, 0 },
    { "contrast-0.7-20ppd", 64, 64, 1, 0, 20, 0, FVVDP_K_CONTRAST, 0.7, 0 },
    { "contrast-0.5-11.4ppd", 64, 64, 1, 0, 11.4, 0, FVVDP_K_CONTRAST, 0.5, 0 },
    { "flicker-5Hz-120fps", 64, 64, 40, 120, 20, 0, FVVDP_K_FLICKER, 0.05, 5 },
    { "flicker-10Hz-120fps", 64, 64, 40, 120, 20, 0, FVVDP_K_FLICKER, 0.05, 10 },
    { "flicker-20Hz-120fps", 64, 64, 40, 120, 20, 0, FVVDP_K_FLICKER, 0.05, 20 },
    { "flicker-30Hz-120fps", 64, 64, 40, 120, 20, 0, FVVDP_K_FLICKER, 0.05, 30 },
    { "flicker-60Hz-240fps", 64, 64, 80, 240, 20, 0, FVVDP_K_FLICKER, 0.05, 60 },
    { "flicker-20Hz-60fps-56ppd", 64, 64, 24, 60, 56, 0, FVVDP_K_FLICKER, 0.05, 20 },
    { "judder-hold2-120fps-11.4ppd", 64, 64, 40, 120, 11.4, 0, FVVDP_K_JUDDER, 2, PAN },
    { "judder-hold3-90fps-20ppd", 64, 64, 30, 90, 20, 0, FVVDP_K_JUDDER, 3, PAN },
    { "drop-every6-90fps-20ppd", 64, 64, 30, 90, 20, 0, FVVDP_K_DROP, 6, PAN },
    { "drop-every5-60fps-56ppd", 64, 64, 24, 60, 56, 0, FVVDP_K_DROP, 5, PAN },
    { "trm-alt45-90fps", 64, 64, 30, 90, 20, 0, FVVDP_K_ALT, 1.5, 0 },
    { "trm-alt60-120fps", 64, 64, 40, 120, 20, 0, FVVDP_K_ALT, 1.5, 0 },
    { "trm-alt72-144fps", 64, 64, 48, 144, 20, 0, FVVDP_K_ALT, 1.5, 0 },
    { "trm-alt120-240fps", 64, 64, 80, 240, 20, 0, FVVDP_K_ALT, 1.5, 0 },
    { "trm-alt45-90fps-pan-11.4ppd", 64, 64, 30, 90, 11.4, 0, FVVDP_K_ALT, 1.5, PAN },
    { "fovblur-2px-5deg", 64, 64, 1, 0, 20, 5, FVVDP_K_BLUR, 2.0, 0 },
    { "fovblur-2px-10deg", 64, 64, 1, 0, 20, 10, FVVDP_K_BLUR, 2.0, 0 },
    { "fovblur-2px-20deg", 64, 64, 1, 0, 20, 20, FVVDP_K_BLUR, 2.0, 0 },
    { "fovblur-2px-30deg", 64, 64, 1, 0, 20, 30, FVVDP_K_BLUR, 2.0, 0 },
    { "fovblur-2px-10deg-11.4ppd", 64, 64, 1, 0, 11.4, 10, FVVDP_K_BLUR, 2.0, 0 },
    { "fovblur-2px-10deg-56ppd", 64, 64, 1, 0, 56, 10, FVVDP_K_BLUR, 2.0, 0 },
    { "fovnoise-0.03-20deg-90fps", 64, 64, 30, 90, 20, 20, FVVDP_K_DYNNOISE, 0.03, 0 },
    { "dynnoise-0.03-60fps", 64, 64, 24, 60, 20, 0, FVVDP_K_DYNNOISE, 0.03, 0 },
    { "dynnoise-0.03-144fps", 64, 64, 48, 144, 20, 0, FVVDP_K_DYNNOISE, 0.03, 0 },
    { "dynnoise-0.03-240fps", 64, 64, 80, 240, 20, 0, FVVDP_K_DYNNOISE, 0.03, 0 },
    { "identical-video-pan-90fps", 64, 64, 30, 90, 20, 0, FVVDP_K_SAME, 0, PAN },
    { "blur-1px-video-pan-60fps", 64, 64, 24, 60, 20, 0, FVVDP_K_BLUR, 1.0, PAN },
};
const int fvvdp_ncond = (int)(sizeof fvvdp_conds / sizeof fvvdp_conds[0]);

static double pattern(double x, double y, int w)
{
    const double tp = 2.0 * M_PI;
    return 0.45 + 0.12 * sin(tp * x / 17.3 + 0.5) * sin(tp * y / 23.1) + 0.08 * sin(tp * (0.8 * x + 0.6 * y) / 5.3) +
           0.06 * sin(tp * (0.3 * x - 0.95 * y) / 3.1 + 1.0) + 0.05 * sin(tp * y / 8.7) +
           0.1 * tanh((x - 0.6 * w) / 1.5);
}

/* Uniform in [-1, 1] from a position and a seed (splitmix64). */
static double hash(int x, int y, int s)
{
    uint64_t z = ((uint64_t)(uint32_t)x << 40) ^ ((uint64_t)(uint32_t)y << 20) ^ (uint64_t)(uint32_t)s;
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return (double)(z >> 11) / (double)(1ull << 52) - 1.0;
}

#define MAXW 64
#define MAXR 12

/* The content shifted right by dx pixels, Gaussian-blurred (sigma px, 0 =
 * none; reflected edges), into v (w*h). */
static void content(int w, int h, double dx, double sigma, double *v)
{
    double k[2 * MAXR + 1];
    int r = sigma > 0.0 ? (int)ceil(3.0 * sigma) : 0;
    r = r > MAXR ? MAXR : r;
    double ks = 0.0;
    for (int i = -r; i <= r; i++) {
        k[i + r] = sigma > 0.0 ? exp(-0.5 * i * i / (sigma * sigma)) : 1.0;
        ks += k[i + r];
    }
    double tmp[MAXW * MAXW];
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            double s = 0.0;
            for (int i = -r; i <= r; i++) {
                int xx = x + i;
                xx = xx < 0 ? -1 - xx : xx >= w ? 2 * w - 1 - xx : xx;
                s += k[i + r] * pattern(xx - dx, y, w);
            }
            tmp[y * w + x] = s / ks;
        }
    }
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            double s = 0.0;
            for (int i = -r; i <= r; i++) {
                int yy = y + i;
                yy = yy < 0 ? -1 - yy : yy >= h ? 2 * h - 1 - yy : yy;
                s += k[i + r] * tmp[yy * w + x];
            }
            v[y * w + x] = s / ks;
        }
    }
}

void fvvdp_cond_frame(const fvvdp_cond_t *c, int f, int t, float *out)
{
    int w = c->w, h = c->h;
    double fps = c->fps > 0.0 ? c->fps : 1.0;
    double speed = c->b * c->ppd / fps; /* px per refresh for panning kinds */
    double pos = f;                     /* content time in refreshes */
    double v[MAXW * MAXW], lo[MAXW * MAXW];
    if (t && c->kind == FVVDP_K_JUDDER) {
        pos = floor(f / c->a) * c->a;
    } else if (t && c->kind == FVVDP_K_DROP && f > 0 && f % (int)c->a == 0) {
        pos = f - 1;
    }
    int moving = (c->kind == FVVDP_K_JUDDER || c->kind == FVVDP_K_DROP || c->kind == FVVDP_K_ALT || c->kind == FVVDP_K_SAME || c->kind == FVVDP_K_BLUR);
    double dx = moving ? speed * pos : 0.0;
    if (c->kind == FVVDP_K_SAME || c->kind == FVVDP_K_BLUR) {
        dx = c->b * c->ppd / fps * f;
    }
    content(w, h, dx, t && c->kind == FVVDP_K_BLUR ? c->a : 0.0, v);
    if (t && c->kind == FVVDP_K_ALT) {
        /* Alternating high-pass: the two-frame mean is the reference. */
        content(w, h, dx, c->a, lo);
        double s = (f & 1) ? -1.0 : 1.0;
        for (int i = 0; i < w * h; i++) {
            v[i] += s * (v[i] - lo[i]);
        }
    }
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            double e = v[y * w + x];
            if (t) {
                switch (c->kind) {
                case FVVDP_K_NOISE:
                    e += c->a * hash(x, y, 1);
                    break;
                case FVVDP_K_DYNNOISE:
                    e += c->a * hash(x, y, 1 + f);
                    break;
                case FVVDP_K_CONTRAST:
                    e = 0.45 + c->a * (e - 0.45);
                    break;
                case FVVDP_K_FLICKER:
                    e *= 1.0 + c->a * sin(2.0 * M_PI * c->b * f / fps);
                    break;
                default:
                    break;
                }
            }
            e = e < 0.0 ? 0.0 : e > 1.0 ? 1.0 : e;
            out[y * w + x] = (float)((100.0 - 0.1) * pow(e, 2.2) + 0.1);
        }
    }
}

int fvvdp_cond_gaze(const fvvdp_cond_t *c, double gaze[2])
{
    if (c->ecc_deg <= 0.0) {
        return 0;
    }
    /* Left of the centre by ecc_deg of visual angle on a 1 m screen whose
     * centre density is ppd. */
    double px = tan(c->ecc_deg * M_PI / 180.0) / (2.0 * tan(0.5 / c->ppd * M_PI / 180.0));
    gaze[0] = c->w / 2.0 - 0.5 - px;
    gaze[1] = c->h / 2.0 - 0.5;
    return 1;
}

double fvvdp_cond_run(const fvvdp_cond_t *c, char *why, size_t why_len)
{
    tdc_fvvdp_geometry_t g = tdc_fvvdp_geometry_ppd(c->w, c->h, c->ppd);
    tdc_fvvdp_t *m = tdc_fvvdp_new(&g, c->frames > 1 ? c->fps : 0.0, why, why_len);
    if (!m) {
        return NAN;
    }
    float t[MAXW * MAXW], r[MAXW * MAXW];
    double gaze[2];
    int fov = fvvdp_cond_gaze(c, gaze);
    for (int f = 0; f < c->frames; f++) {
        fvvdp_cond_frame(c, f, 1, t);
        fvvdp_cond_frame(c, f, 0, r);
        tdc_fvvdp_frame(m, t, r, fov ? gaze : NULL);
    }
    double jod = tdc_fvvdp_jod(m);
    tdc_fvvdp_free(m);
    return jod;
}

/* Ranks with ties averaged (1-based). */
static void ranks(const double *v, int n, double *r)
{
    for (int i = 0; i < n; i++) {
        int less = 0, eq = 0;
        for (int j = 0; j < n; j++) {
            less += v[j] < v[i];
            eq += v[j] == v[i];
        }
        r[i] = less + (eq + 1) / 2.0;
    }
}

double fvvdp_spearman(const double *a, const double *b, int n)
{
    double ra[FVVDP_MAXCOND], rb[FVVDP_MAXCOND], ma = 0, mb = 0, sab = 0, saa = 0, sbb = 0;
    ranks(a, n, ra);
    ranks(b, n, rb);
    for (int i = 0; i < n; i++) {
        ma += ra[i] / n;
        mb += rb[i] / n;
    }
    for (int i = 0; i < n; i++) {
        sab += (ra[i] - ma) * (rb[i] - mb);
        saa += (ra[i] - ma) * (ra[i] - ma);
        sbb += (rb[i] - mb) * (rb[i] - mb);
    }
    return sab / sqrt(saa * sbb);
}

/* Reads "name,jod[,seconds]" rows into ref[] by condition index. */
int fvvdp_read_reference(const char *path, double *ref, double *secs)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        return -1;
    }
    for (int i = 0; i < fvvdp_ncond; i++) {
        ref[i] = NAN;
        secs[i] = NAN;
    }
    char line[512];
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#' || strncmp(line, "condition,", 10) == 0) {
            continue;
        }
        char *c1 = strchr(line, ',');
        if (!c1) {
            continue;
        }
        *c1 = 0;
        for (int i = 0; i < fvvdp_ncond; i++) {
            if (strcmp(line, fvvdp_conds[i].name) == 0) {
                char *end;
                ref[i] = strtod(c1 + 1, &end);
                if (*end == ',') {
                    secs[i] = strtod(end + 1, NULL);
                }
            }
        }
    }
    int err = ferror(f);
    fclose(f);
    if (err) {
        return -1; /* a read error (a folder given as the table) */
    }
    for (int i = 0; i < fvvdp_ncond; i++) {
        if (isnan(ref[i])) {
            return -2 - i;
        }
    }
    return 0;
}

