/*
 * tdc_sim_mode.h - what a display-mode family implements for the simulator
 * (internal to sim/simulator).
 *
 * A family (plain, TRM, assembly, TAA/ASW, ...) is one file: its mode
 * descriptors and a table of four functions.  The driver (tdc_sim_run.c)
 * owns everything every mode shares - the clock, the link, the panel, the
 * eye's slice ring and the metrics - and calls per display refresh:
 *
 *     init  (once)        family state, firmware stages; may mark the mode
 *                         unavailable with a note (a part not in the build)
 *                         or refused (a firmware stage's status)
 *     frame (per refresh) render, send over m->link, run the firmware, leave
 *                         the codes the panel is to show in m->wanted
 *     reset (stream cut)  drop history (optional)
 *     free                release the family state
 *
 * The LCD drive stage is an output stage behind the same table: its frame
 * turns m->wanted into m->out (overdrive-aware drive codes).
 *
 * Adding a mode: a new tdc_sim_mode_<family>.c with its descriptors and its
 * tdc_sim_family_t, listed once in tdc_sim_modes.c and mk/sim.mk.
 *
 * Errors: every firmware / link / renderer return code goes through
 * tdc_sim_stage(); a failure is reported on stderr with the mode, the frame
 * and the stage, and the run ends with an error (tdc_sim_run returns -1).
 */
#ifndef TDC_SIM_MODE_H
#define TDC_SIM_MODE_H

#include <stddef.h>
#include <stdint.h>

#include "eye/tdc_eye_temporal.h"
#include "panel/tdc_panel_sim.h"
#include "simulator/tdc_sim.h"
#include "simulator/tdc_sim_gaze.h"
#include "simulator/tdc_sim_link.h"
#include "tdc_panels.h"

#define TDC_SIM_RING_MAX 96

typedef struct sim_mode sim_mode_t;

/* What init needs beyond the mode descriptor. */
typedef struct {
    const tdc_sim_config_t *cfg;
    int eyes;                     /* 1, or 2 (stereo: one sim_mode_t per eye) */
    const tdc_panel_t *fw_panel;  /* gamma / TRM profile */
    const tdc_panel_t *lcd_panel; /* LCD profile, NULL without an LCD panel */
    int src_full_frame;           /* the source traces whole frames (Embree) */
    int src_subframe;             /* the source traces subframes itself */
    int src_layers;               /* the source has layer outputs (tdc_source_t.layers) */
    int src_layered_subframe;     /* ... or traces layered subframes itself (tdc_source_t.layered_subframe) */
} tdc_sim_setup_t;

struct tdc_sim_family {
    const char *name;
    const tdc_mode_desc_t *modes; /* descriptors of the family's modes */
    int nmodes;
    /* 0, or -1 when out of memory (the mode may instead be made
     * unavailable with a note, or refused with a firmware status) */
    int (*init)(sim_mode_t *m, const tdc_sim_setup_t *s);
    /* one display refresh: link frame index lf, render time t, spp; 0 or the
     * failing stage's status (already reported by tdc_sim_stage) */
    int (*frame)(sim_mode_t *m, tdc_source_t *src, double t, int spp, uint32_t lf);
    void (*reset)(sim_mode_t *m); /* NULL: nothing to drop */
    void (*free)(sim_mode_t *m);
};

/* State every mode has, one per eye; the family's own state hangs off fam,
 * the LCD drive stage's off drive.  In stereo the two eyes of a mode share
 * the result (costs add up) and the link (one stream, packets per eye);
 * frame() is called for eye 0, then eye 1, of each refresh. */
struct sim_mode {
    const tdc_mode_desc_t *d;
    tdc_sim_result_t *res;
    int eye, eyes;        /* this eye, eyes of the run */
    tdc_sim_link_t *link; /* the mode's stream (eye 0 owns it: link_own) */
    tdc_sim_link_t link_own;
    int hz;
    double fs; /* frame period, s */
    int w, h;
    size_t npx;
    uint32_t frame; /* next display frame (absolute) */
    uint32_t lf;    /* frame index within the current link stream */
    double last_t;  /* render time of the previous displayed frame */
    int slot;       /* index of the mode (per-mode renderer state) */
    int failed;     /* a stage returned an error */
    tdc_panel_sim_t panel;
    /* buffers every family uses */
    uint8_t *render; /* the renderer's frame */
    uint8_t *wanted; /* codes the controller wants shown */
    uint8_t *out;    /* drive codes (= wanted without an LCD stage) */
    double *xy;      /* sample positions for src->samples (shared by all modes of a run) */
    double *scratch; /* W*H*3 doubles for src->frame (shared too) */
    void *fam;       /* family state */
    void *drive;     /* LCD drive-stage state */
    /* the residual the LCD stage adds (TRM), NULL if none */
    int32_t *(*residual)(sim_mode_t *m);
    /* slices covering the fused window: OLED slices as drive codes (decoded
     * by the panel's table in the eye: 1 byte per sample instead of 8),
     * LCD slices as linear light */
    int ring_n, ring_head, ring_count;
    void *ring_buf[TDC_SIM_RING_MAX];
    tdc_eye_slice_t ring[TDC_SIM_RING_MAX];
    double lut[3 * 256]; /* OLED: linear light of each code per channel */
    /* metrics of this eye (the buffers of one evaluation are the run's) */
    float *err_prev; /* the last instant's encoded error (crop), for flicker */
    int have_err_prev;
    double sum_psnr, sum_ssim, sum_flip, sum_flicker;
    int n_flicker;
    /* temporal visibility model (cfg->temporal): filter state, sum of terr */
    tdc_eye_temporal_t *temporal;
    double sum_terr;
    int n_terr;
    /* the run's gaze (where the fovea is) and the sums of the gaze metrics */
    const tdc_sim_gaze_t *gaze;
    double sum_flip_ecc, sum_flip_fovea, sum_flip_periph, sum_flip_wmed, sum_flicker_periph;
};

/* The families (tdc_sim_mode_*.c) and the LCD output stage. */
extern const tdc_sim_family_t tdc_sim_family_plain;
extern const tdc_sim_family_t tdc_sim_family_trm;
extern const tdc_sim_family_t tdc_sim_family_warp;
extern const tdc_sim_family_t tdc_sim_family_asm;
extern const tdc_sim_family_t tdc_sim_family_layers;
extern const tdc_sim_family_t tdc_sim_family_fov;
extern const tdc_sim_family_t tdc_sim_family_fovtrm;
extern const tdc_sim_family_t tdc_sim_stage_lcd;

/* ---- helpers shared by the families (tdc_sim_mode.c) ---- */

/* CPU seconds of this process (robust to a loaded host). */
double tdc_sim_now(void);
/* Appends a note to the mode's report line. */
void tdc_sim_note(sim_mode_t *m, const char *s);
/* Checks a stage's status: 0 passes; otherwise reports
 * "tdc-sim: mode M: frame F: stage S: NAME (text)" once (tdc_status_name,
 * tdc_status_text of the firmware's one status vocabulary), marks the mode
 * failed and returns the status. */
int tdc_sim_stage(sim_mode_t *m, const char *stage, int status);
/* A firmware stage refused the mode's configuration at init: noted, the
 * mode is unavailable, res->refused = status. */
void tdc_sim_refuse(sim_mode_t *m, const char *what, int status);

/* Renders a full frame into m->render (pixel centres + (jx, jy)); motion
 * vectors over dt into mv when mv != NULL.  Timed, rays counted. */
void tdc_sim_render_full(sim_mode_t *m, tdc_source_t *src, double t, int spp, double jx, double jy, int16_t *mv,
                         double dt, tdc_mv_kind_t kind);
/* Rows of parity p into m->render (others black), via tmp (npx*3). */
void tdc_sim_render_rows(sim_mode_t *m, tdc_source_t *src, double t, int spp, int parity, uint8_t *tmp);
/* Sends rgb as a FULL packet; what the decoder got becomes m->wanted.
 * 0 or the (reported) error. */
int tdc_sim_send_full(sim_mode_t *m, uint32_t lf, const uint8_t *rgb);
/* The decoded buffers of this eye. */
#define TDC_SIM_LINK_FULL(m) ((m)->link->full[(m)->eye])
#define TDC_SIM_LINK_REDUCED_BUF(m) ((m)->link->reduced[(m)->eye])

/* Renderer side of a tile-ordered subframe (assembly families): the sample
 * positions of subframe lf under the tile orderings `pattern` into m->xy,
 * each tile's pixel of the subframe, jittered (tdc_jitter_offset_q4) where
 * the (2 radius + 1)^2 neighbourhood of the renderer's motion buffer mvbuf
 * is static (radius 1: the controller's 3x3 rule; more where the controller
 * splats vectors further); returns the sample count.  keep_mv stores each sample's vector mv[2i..]
 * at its pixel of mvbuf (each pixel keeps its latest sample's vector). */
int tdc_sim_subframe_xy(sim_mode_t *m, const int16_t *mvbuf, const uint8_t *pattern, uint32_t lf, int radius);
void tdc_sim_subframe_keep_mv(sim_mode_t *m, int16_t *mvbuf, int n, const int16_t *mv);

/* The fov modes' footprint prefilter of nlp log-polar samples at display
 * positions xy with footprint sides side (display pixels) into samp
 * (tdc_sim_mode_fov.c, also used by fov-trm).  0, or -1 out of memory. */
int tdc_sim_fov_prefilter(sim_mode_t *m, tdc_source_t *src, double t, int spp, const double *xy, const double *side,
                          size_t nlp, uint8_t *samp);

/* The foveation parameters of a fov or fov-trm run as the link header
 * carries them (tdc_sim_mode_fov.c): alpha Q8, delta Q15 rounded up (so
 * that the buffer is floor(0.555 W) at every size here), disk Q15; with
 * the renderer's footprint prefilter and jitter choices. */
typedef struct {
    int lod;    /* TDC_FOV_LOD_* (cfg.fov_lod) */
    int jitter; /* TDC_FOV_JITTER_* (cfg.fov_jitter) */
    uint16_t alpha_q8, delta_q15, disk_q15;
} tdc_sim_fov_link_t;
tdc_sim_fov_link_t tdc_sim_fov_link_of(const tdc_sim_config_t *cfg);

/* Rounds and clamps to a code (bilinear samples of codes: tdc_bilinear_u8). */
uint8_t tdc_sim_to8(double v);

#endif
