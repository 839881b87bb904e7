/* tdc_run.h - modes of the tdc-run program (each in its own file). */
#ifndef TDC_RUN_H
#define TDC_RUN_H

#include <stdint.h>

#include "tdc_tool.h"

/* Exit codes: the shared table of every tdc program (tdc_tool.h,
 * docs/tools.md): OK, ARGS (usage), FILE (cannot read or write a file),
 * INPUT (a PNG or frame of the wrong size), REFUSED (the firmware refused
 * the frame or the configuration), NOMEM. */

/* Gaze-aware TRM inputs (run_gaze.c): gaze velocity and tile motion
 * vectors per frame, Q4 px per frame (the link's MOTION payload). */
#define TDC_RUN_GAZE_TILE 16 /* tile edge, px: tdc_trm_gaze's default */
typedef struct {
    int frames;
    unsigned tx, ty;        /* tiles of one frame */
    int16_t *gaze;          /* frames x (gx, gy) */
    unsigned char *have_gaze;
    int16_t *mv;            /* frames x ty x tx x (dx, dy) */
    unsigned char *have_mv; /* per tile */
    unsigned *tiles_of;     /* tiles given per frame */
} tdc_run_gaze_t;
/* Reads both files for frames of w x h; an exit code (messages printed). */
int tdc_run_gaze_load(tdc_run_gaze_t *g, const char *gaze_path, const char *mv_path, int frames, int w, int h);
/* Full frame `frame`'s tile MVs and gaze, or INPUT when the files lack them. */
int tdc_run_gaze_frame(const tdc_run_gaze_t *g, int frame, const char *gaze_path, const char *mv_path,
                       const int16_t **mv, int16_t *gx, int16_t *gy);
void tdc_run_gaze_free(tdc_run_gaze_t *g);

/* TRM mode (default): tdc_run.c */
int tdc_run_trm_main(int argc, char **argv);
/* Tile assembly mode: `tdc-run assemble ...` (run_assemble.c) */
int tdc_run_assemble_main(int argc, char **argv);

#endif
