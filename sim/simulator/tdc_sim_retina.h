/*
 * tdc_sim_retina.h - the simulator's side of the retinal signal (internal to
 * sim/simulator): the reference's own panel per eye, the step clock, the
 * hand-over of each step to the consumer (cfg->retina_cb) and --dump.
 * The signal itself is eye/tdc_retina.h.
 */
#ifndef TDC_SIM_RETINA_H
#define TDC_SIM_RETINA_H

#include "simulator/tdc_sim_mode.h"

typedef struct sim_retina sim_retina_t;

/* NULL when neither a consumer nor --dump asks for the signal, or on error
 * (*rc = -1 setup / memory, -2 an output could not be created; reported). */
sim_retina_t *sim_retina_new(const tdc_sim_setup_t *s, tdc_source_t *const srcs[2], const tdc_sim_gaze_t *gaze,
                             const double gamma[3], const tdc_panel_t *profile, sim_mode_t *ms, int nmodes, int *rc);
/* After mode m showed a refresh (drive codes in m->out): --dump's codes. */
int sim_retina_shown(sim_retina_t *r, const sim_mode_t *m);
/* Every step that ends by te: the reference's refreshes, then per eye the
 * reference's and each available mode's retinal image, to the consumer and
 * the dump.  0, -1 (memory), -2 (output failed). */
int sim_retina_advance(sim_retina_t *r, double te);
/* Closes the dump (writes dump.json).  0 or -2.  Frees r. */
int sim_retina_free(sim_retina_t *r, int ok);

#endif
