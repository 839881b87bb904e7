/*
 * tdc_sim_jod.h - the simulator's judge: FovVideoVDP (metrics/tdc_fvvdp.h)
 * on the retinal signal (eye/tdc_retina.h), as a consumer of its steps
 * (cfg.retina_cb), one metric per mode and eye.
 *
 * Frames: the metric sees one frame per refresh of the run clock, the mean
 * of that refresh's retinal steps (the steps resolve the emission inside a
 * refresh; FovVideoVDP's channels at the refresh rate keep every
 * refresh-to-refresh change, e.g. TRM's R/2 alternation, and its history
 * then costs ceil(R/4) frames instead of ceil(R N / 4)).
 * Warm-up: the first 250 ms (the filters' length) fill the history and are
 * not pooled (docs/visual-model.md: the start-up would dominate).
 * Gaze: the true gaze in the stabilised image (foveated judging).
 *
 * Outputs: tdc_sim_jod_write: jod.csv, one row per mode and eye (JOD of the
 * whole view, the fovea within 5 deg of the gaze and the periphery beyond,
 * frames pooled); the per-refresh series (jod_series.csv: pooled 0 during
 * the warm-up) as the run goes.
 */
#ifndef TDC_SIM_JOD_H
#define TDC_SIM_JOD_H

#include <stdio.h>

#include "eye/tdc_retina.h"
#include "metrics/tdc_fvvdp.h"

typedef struct tdc_sim_jod tdc_sim_jod_t;

/* series: per-refresh rows (may be NULL). */
tdc_sim_jod_t *tdc_sim_jod_new(FILE *series);
/* The consumer (ctx: the judge).  Non-zero on failure (memory, refused
 * geometry: the reason is printed). */
int tdc_sim_jod_cb(void *ctx, const tdc_retina_frame_t *f);
/* After the run: feeds every judge's last refresh.  0 or -1. */
int tdc_sim_jod_finish(tdc_sim_jod_t *j);
/* Pooled JODs of mode on eye (NAN when the run was no longer than the
 * warm-up); -1 if that pair was never judged. */
int tdc_sim_jod_result(tdc_sim_jod_t *j, const char *mode, int eye, tdc_fvvdp_jods_t *out, int *frames);
/* jod.csv rows (with a header line).  0, or -1 if a write failed. */
int tdc_sim_jod_write(tdc_sim_jod_t *j, FILE *f);
void tdc_sim_jod_free(tdc_sim_jod_t *j);

#endif
