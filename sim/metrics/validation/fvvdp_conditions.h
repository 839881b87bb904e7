/*
 * fvvdp_conditions.h - the validation set of the FovVideoVDP port
 * (docs/visual-model.md): small, deterministic test/reference clips whose
 * JOD the reference implementation computed once (fvvdp_reference.csv) and
 * tdc's metric recomputes in `make test`.
 *
 * Frames are linear luminance (cd/m^2, float) of a display of 100 cd/m^2
 * peak, 1000:1, gamma 2.2, so both implementations judge the same numbers.
 */
#ifndef FVVDP_CONDITIONS_H
#define FVVDP_CONDITIONS_H

#include <stddef.h>

/* Generators: test = reference (SAME), Gaussian blur of a px, static or
 * per-frame noise of amplitude a, contrast scaled by a, flicker of depth a at
 * b Hz, content held a refreshes (JUDDER) or every a-th refresh repeated
 * (DROP) while panning at b deg/s, TRM-like alternation (+/- the detail above
 * a Gaussian of a px, on alternate refreshes). */
enum {
    FVVDP_K_SAME, FVVDP_K_BLUR, FVVDP_K_NOISE, FVVDP_K_CONTRAST, FVVDP_K_FLICKER,
    FVVDP_K_JUDDER, FVVDP_K_DROP, FVVDP_K_ALT, FVVDP_K_DYNNOISE
};

typedef struct {
    const char *name;
    int w, h, frames;
    double fps;     /* 0: a still image */
    double ppd;
    double ecc_deg; /* > 0: foveated, the gaze this far left of the centre */
    int kind;       /* generator (fvvdp_conditions.c) */
    double a;       /* its strength */
    double b;       /* a second parameter (frequency, period, speed) */
} fvvdp_cond_t;

extern const fvvdp_cond_t fvvdp_conds[];
extern const int fvvdp_ncond;
#define FVVDP_MAXCOND 64

/* Frame f of test (t = 1) or reference (t = 0), w*h luminance. */
void fvvdp_cond_frame(const fvvdp_cond_t *c, int f, int t, float *out);
/* The gaze in pixels (foveated conditions), or 0 if none. */
int fvvdp_cond_gaze(const fvvdp_cond_t *c, double gaze[2]);

/* tdc's JOD of a condition (NAN and a reason in why on failure). */
double fvvdp_cond_run(const fvvdp_cond_t *c, char *why, size_t why_len);

/* Spearman's rank correlation of a and b (ties ranked by their mean). */
double fvvdp_spearman(const double *a, const double *b, int n);
/* Reads the reference table ("condition,jod,seconds" rows) into ref[] and
 * secs[] by condition index: 0, -1 unreadable, -2 - i condition i missing. */
int fvvdp_read_reference(const char *path, double *ref, double *secs);

#endif
