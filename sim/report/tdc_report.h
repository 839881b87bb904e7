/*
 * tdc_report.h - simulator outputs: summary CSV, markdown table, picture
 * strips (PNG via common/tdc_png.h).  Plots are drawn by sim/report/tdc_plots.py
 * (matplotlib) from the CSV files.
 */
#ifndef TDC_REPORT_H
#define TDC_REPORT_H

#include <stdio.h>
#include <stdint.h>

#include "simulator/tdc_sim.h"

/* PNG strip outdir/strip_<mode>.png: displayed drive codes | perceived |
 * perceived ground truth | FLIP error map (black = 0 .. white = 1), each
 * cw x ch (the evaluated interior, `margin` px in from the edges). */
int tdc_report_strip(const char *outdir, const char *mode, const uint8_t *codes, const double *perc_lin,
                     const double *gt_lin, const double *flipmap, int w, int h, int cw, int ch, int margin);

/* 1 once a strip could not be written (its message is on stderr): the
 * strips are written deep inside a run, the program's exit code says it. */
int tdc_report_write_failed(void);

/* Summary of one run: CSV header + rows (append = 0 writes the header). */
void tdc_report_csv(FILE *f, const tdc_sim_config_t *cfg, const tdc_sim_result_t *r, int n, int header);

/* Markdown table of one run. */
void tdc_report_markdown(FILE *f, const tdc_sim_config_t *cfg, const tdc_sim_result_t *r, int n);
/* The foveation figures of every available mode (gaze metrics, rays and
 * link bytes vs full rate): a markdown table (printed by
 * tdc_report_markdown when a foveated mode ran) or CSV with a header. */
void tdc_report_foveation(FILE *f, const tdc_sim_config_t *cfg, const tdc_sim_result_t *r, int n, int csv);

#endif
