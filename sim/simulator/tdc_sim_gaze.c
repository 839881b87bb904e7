/* tdc_sim_gaze.c - gaze schedules and the eye tracker (tdc_sim_gaze.h). */
#include "simulator/tdc_sim_gaze.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const k_names[] = {"pursuit", "fixed", "saccade"};

int tdc_sim_gaze_from_name(const char *name)
{
    for (int i = 0; i < 3; i++) {
        if (strcmp(name, k_names[i]) == 0) {
            return i;
        }
    }
    return -1;
}

const char *tdc_sim_gaze_name(int schedule)
{
    return schedule >= 0 && schedule < 3 ? k_names[schedule] : "?";
}

/* The saccade schedule's fixations (fractions of the screen), 250 ms each. */
static const double k_fix[4][2] = {{0.32, 0.36}, {0.68, 0.42}, {0.62, 0.68}, {0.36, 0.62}};
#define FIX_S 0.25

int tdc_sim_gaze_init(tdc_sim_gaze_t *g, tdc_source_t *src, int w, int h, double hz, double duration_s)
{
    g->w = w;
    g->h = h;
    g->step = 1.0 / (hz > 0 ? hz : 90.0) / 4.0; /* 4 steps per refresh */
    g->n = (int)ceil((duration_s + 1.0) / g->step) + 2;
    g->xy = malloc(sizeof(double) * 2 * (size_t)g->n);
    if (!g->xy) {
        return -1;
    }
    double x = w / 2.0, y = h / 2.0;
    for (int k = 0; k < g->n; k++) {
        const double t = k * g->step;
        if (g->schedule == TDC_GAZE_FIXED) {
            x = g->at_x >= 0 ? g->at_x : w / 2.0;
            y = g->at_y >= 0 ? g->at_y : h / 2.0;
        } else if (g->schedule == TDC_GAZE_SACCADE) {
            const int i = (int)floor(t / FIX_S) % 4;
            x = k_fix[i][0] * w;
            y = k_fix[i][1] * h;
        } else if (k > 0) {
            double v[2] = {0, 0};
            if (src && src->pursuit) {
                src->pursuit(src, t - g->step, v);
            }
            x += v[0] * g->step;
            y += v[1] * g->step;
            if (fabs(x - w / 2.0) > w / 4.0 || fabs(y - h / 2.0) > h / 4.0) {
                x = w / 2.0; /* a saccade back to the centre */
                y = h / 2.0;
            }
        }
        g->xy[2 * k] = x;
        g->xy[2 * k + 1] = y;
    }
    return 0;
}

void tdc_sim_gaze_free(tdc_sim_gaze_t *g)
{
    free(g->xy);
    g->xy = NULL;
}

void tdc_sim_gaze_true(const tdc_sim_gaze_t *g, double t, double xy[2])
{
    /* the entry at or before t: a saccade is a jump, not a glide */
    long k = (long)floor(t / g->step + 1e-9);
    k = k < 0 ? 0 : (k >= g->n ? g->n - 1 : k);
    xy[0] = g->xy[2 * k];
    xy[1] = g->xy[2 * k + 1];
}

static double unit(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return (*s + 0.5) / 4294967296.0;
}

void tdc_sim_gaze_tracked(const tdc_sim_gaze_t *g, double t, uint32_t frame, int eye, double xy[2])
{
    tdc_sim_gaze_true(g, t - g->latency_ms * 1e-3, xy);
    if (g->noise_deg > 0) {
        uint32_t s = (g->seed * 2654435761u) ^ (frame * 40503u + 1u) ^ ((uint32_t)eye << 30);
        s = s ? s : 1u;
        for (int i = 0; i < 4; i++) {
            unit(&s);
        }
        const double r = sqrt(-2.0 * log(unit(&s))), a = 2.0 * M_PI * unit(&s); /* Box-Muller */
        const double sd = g->noise_deg * g->ppd;
        xy[0] += sd * r * cos(a);
        xy[1] += sd * r * sin(a);
    }
}

double tdc_sim_gaze_rmax(const tdc_sim_gaze_t *g, const double xy[2])
{
    const double ex = fmax(xy[0], g->w - xy[0]), ey = fmax(xy[1], g->h - xy[1]);
    return sqrt(ex * ex + ey * ey);
}
