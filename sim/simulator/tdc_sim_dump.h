/*
 * tdc_sim_dump.h - tdc-sim --dump DIR: the frames a run displays and the
 * retinal signal (eye/tdc_retina.h) as files, so that any external metric
 * can score the same signal.  Layout (docs/eye.md):
 *
 *   DIR/dump.json                display, gaze and time parameters, file patterns
 *   DIR/steps.csv                per eye and step: times, gaze, retinal shift
 *   DIR/S/codes_RRRRRR.png       drive codes of refresh R (8-bit RGB)
 *   DIR/S/emitted_KKKKKK.png     light on the screen, mean over step K
 *   DIR/S/retina_KKKKKK.png      the stabilised (retinal) image of step K
 *   DIR/S/retina.y4m             its luminance, one frame per step
 *
 * S is "ref" (the reference) or a mode's name, with "_L" / "_R" in stereo.
 * The 16-bit PNGs and the Y4M (mono16, little-endian) are linear:
 * cd/m^2 = value / 65535 * full_scale_cdm2 (in dump.json).
 *
 * Every write is checked: a failure prints one line and the run ends with
 * TDC_EXIT_FILE.
 */
#ifndef TDC_SIM_DUMP_H
#define TDC_SIM_DUMP_H

#include <stdint.h>

#include "eye/tdc_retina.h"
#include "simulator/tdc_sim.h"

typedef struct tdc_sim_dump tdc_sim_dump_t;

/* Creates DIR and one folder per stream (names[0..n-1]; stream i of eye e is
 * names[i] with the eye suffix in stereo).  NULL with a message on stderr. */
tdc_sim_dump_t *tdc_sim_dump_open(const char *dir, const char *const *names, int n, int eyes, int w, int h,
                                  double full_scale_cdm2);
/* Drive codes of refresh `refresh` of stream s, eye e. */
int tdc_sim_dump_codes(tdc_sim_dump_t *d, int s, int e, long refresh, const uint8_t *codes);
/* One step of stream s, eye e: emitted light (may be NULL) and the retinal
 * image (rgb and its luminance y), cd/m^2. */
int tdc_sim_dump_step(tdc_sim_dump_t *d, int s, int e, long step, const float *emitted, const float *rgb,
                      const float *y, double fps);
/* One row of steps.csv (once per eye and step). */
int tdc_sim_dump_step_row(tdc_sim_dump_t *d, const tdc_retina_frame_t *f);
/* Writes dump.json and closes every file; 0, or -1 (reported) if anything
 * failed now or before.  Frees d. */
int tdc_sim_dump_close(tdc_sim_dump_t *d, const tdc_sim_config_t *cfg, const tdc_retina_display_t *disp, int steps,
                       double fps, long nsteps, double persistence);

#endif
