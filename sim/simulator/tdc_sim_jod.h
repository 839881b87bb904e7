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
 * the warm-up) as the run goes, and after it series.csv's jod column and
 * the heat maps.
 */
#ifndef TDC_SIM_JOD_H
#define TDC_SIM_JOD_H

#include <stdio.h>

#include "eye/tdc_retina.h"
#include "metrics/tdc_fvvdp.h"

/* Refreshes of the warm-up at a run clock of hz: the first 250 ms. */
#define TDC_SIM_JOD_WARMUP_S 0.25
int tdc_sim_jod_warmup(double hz);

typedef struct tdc_sim_jod tdc_sim_jod_t;

/* series: per-refresh rows (may be NULL); heatmaps: keep eye 0's
 * visible-difference maps (simulator/tdc_sim_heatmap.h). */
tdc_sim_jod_t *tdc_sim_jod_new(FILE *series, int heatmaps);
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
/* The JOD of mode's refresh on eye alone (NAN in the warm-up or unknown). */
double tdc_sim_jod_at(tdc_sim_jod_t *j, const char *mode, int eye, long refresh);
/* OUTDIR/heatmap_<mode>.png of eye 0 for every mode with a pooled refresh.
 * 0, or -1 (reason printed) if one was not written. */
int tdc_sim_jod_heatmaps(tdc_sim_jod_t *j, const char *outdir);
/* Fills series.csv's last column (jod, written empty by the run) with the
 * JOD of the refresh ending at each row's t (hz: the run clock); the
 * warm-up's rows stay empty.  0 or -1 (printed). */
int tdc_sim_jod_series_merge(tdc_sim_jod_t *j, const char *path, int eyes, double hz);
void tdc_sim_jod_free(tdc_sim_jod_t *j);

#endif
