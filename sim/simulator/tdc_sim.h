/*
 * tdc_sim.h - the host simulator: drives every display mode through the
 * data path  source (renderer) -> link encoder -> link decoder + firmware
 * stages (exactly the board code) -> panel simulation -> eye model ->
 * metrics against the ground truth, and collects cost figures.
 *
 * All modes of one run share the source, the evaluation clock and the fused
 * window; they advance in lockstep so the ground truth of each evaluation
 * instant is computed once.  Evaluation instants are the ends of the frames
 * of the run's refresh clock; the perceived image at instant t is the eye's
 * integral over [t - T, t] (T = window frames / refresh).
 */
#ifndef TDC_SIM_H
#define TDC_SIM_H

#include <stdint.h>
#include <stdio.h>

#include "eye/tdc_eye.h"
#include "eye/tdc_retina.h"
#include "panel/tdc_panel_sim.h"
#include "simulator/tdc_sim_scene.h"
#include "tdc_panel.h"

/* A mode family (tdc_sim_mode.h): the file that implements its modes. */
typedef struct tdc_sim_family tdc_sim_family_t;

typedef struct {
    const char *name;
    const tdc_sim_family_t *family;
    int variant;           /* which mode of the family (family's own enum) */
    uint32_t link_flags;   /* TDC_SIM_LINK_* of the mode's stream */
    uint16_t r_num, r_den; /* TRM ratio */
    uint16_t fixed_hz;     /* 0: the run's refresh */
    int8_t ordering;       /* ASM: 0 hourglass, 1 bowtie, -1 adaptive */
    uint8_t shadow_mv;     /* ASM: shadow + dual motion vectors */
    const char *what;      /* one-line description */
} tdc_mode_desc_t;

/* Every mode, in the families' order; n receives the count. */
const tdc_mode_desc_t *const *tdc_sim_modes(int *n);
const tdc_mode_desc_t *tdc_sim_mode_find(const char *name);

/* Wall-clock seconds per stage of a run (tdc_sim_config_t.times). */
typedef struct {
    double source_s;   /* renderer: frames, subframes, ground truth */
    double link_s;     /* encoder + decoder */
    double firmware_s; /* firmware stages (TRM, assembly, LCD) */
    double panel_s;    /* panel simulation */
    double eye_s;      /* eye integration */
    double metrics_s;  /* PSNR, SSIM, FLIP, flicker, encoding, crops */
    double total_s;
} tdc_sim_times_t;

typedef struct {
    tdc_scene_params_t scene;
    int width, height;
    int eyes;               /* 1, or 2: stereo (TRM §7.2), eye 1's view from `right` */
    tdc_source_t *right;    /* eye 1's source (its own camera) when eyes == 2 */
    tdc_sim_times_t *times; /* optional: receives the stage breakdown */
    int refresh_hz;         /* run clock: display rate of the modes without a fixed rate */
    int window_frames;      /* legacy eye: fused window in frames of the run clock (0: 2 below 200 Hz,
                               else 4); the retinal signal has none */
    double duration_s;
    int spp; /* rays per pixel of full frames (0: 4 below 200 Hz, else 1) */
    tdc_panel_sim_kind_t panel;
    const char *panel_profile;        /* firmware panel profile name (gamma, LCD model), NULL = htc-vive / first LCD */
    int lcd_mode;                     /* LCD firmware inverse (tdc_lcd_mode_t; default exact), docs/lcd.md */
    int lcd_bits;                     /* LCD history / state bits (4..8, default 8) */
    int backlight;                    /* LCD backlight: -1 as the panel's sim file, 0 hold (constant), 1 strobed */
    double strobe_duty, strobe_phase; /* backlight 1: flash duty and phase (fractions of the refresh) */
    double persistence;               /* OLED duty */
    double pursuit_gain;
    int metric_every; /* evaluate every k-th instant (1 = all) */
    int temporal;     /* 1: temporal visibility model (eye/tdc_eye_temporal.h): terr */
    double flip_ppd;
    const char *ppd_from; /* where flip_ppd came from: "profile", "--ppd" or "default" (NULL: profile) */
    int trm_s;    /* TRM motion sensitivity s (0: firmware default) */
    double trm_sigma; /* sigma of TRM's D in full-res px (0: firmware default 2.5; < 0: 1.25 / r,
                         i.e. 2.5 px at r = 1/2 scaled with r) */
    int progress; /* progress bar on stderr */
    int strip_at; /* evaluation index for the picture strip (-1: middle) */
    uint32_t seed;
    int strict;         /* 1: a mode a firmware stage refuses is an error, not a note */
    /* foveation (issue 14, tdc_sim_gaze.h): gaze schedule, eye tracker, stream parameters */
    int gaze;                 /* tdc_gaze_schedule_t: pursuit (default), fixed, saccade */
    double gaze_at_x, gaze_at_y; /* fixed: the point (< 0: the centre) */
    double gaze_latency_ms;   /* tracker latency */
    double gaze_noise_deg;    /* tracker noise, sigma per axis */
    double fov_alpha;         /* K(x) = x^alpha of the fov modes (default 4) */
    double fov_delta;         /* buffer downscale (default 0.555) */
    double fov_disk;          /* disk fraction (default 0.12443) */
    int fov_lod;              /* TDC_FOV_LOD_* (ref_fov.h): footprint prefilter of the log-polar samples
                                 (default FOOTPRINT; the renderer's texture LOD, the other sources' box average) */
    int fov_jitter;           /* TDC_FOV_JITTER_* (ref_fov.h): what fov-taa's Halton jitter moves a log-polar
                                 sample by (default PIXEL: <= half a texel and <= half a display pixel) */
    /* the retinal signal (eye/tdc_retina.h), computed when a consumer or
     * --dump wants it: steps per refresh (0: automatic), the eye's pursuit
     * lag, the consumer, the dump folder */
    int retina_steps;
    double pursuit_lag_ms;
    tdc_retina_cb_t retina_cb;
    void *retina_ctx;
    const char *dump_dir;
    int judge;          /* the report's judge: TDC_JUDGE_* (set by tdc-sim's main) */
    const char *outdir; /* NULL: no files */
    const char *label;  /* run label for the report */
} tdc_sim_config_t;

/* cfg.judge: FovVideoVDP's JOD (the default), the legacy columns alone
 * (--judge legacy), or no JOD because the run is no longer than the judge's
 * warm-up (simulator/tdc_sim_jod.h: nothing would be pooled). */
enum { TDC_JUDGE_JOD = 0, TDC_JUDGE_LEGACY = 1, TDC_JUDGE_SHORT = 2 };

void tdc_sim_default_config(tdc_sim_config_t *c);

/* A firmware panel profile by name; name NULL: the first OLED (want_lcd 0)
 * or LCD profile.  NULL if unknown. */
const tdc_panel_t *tdc_sim_panel_find(const char *name, int want_lcd);

/* Per-mode results. */
typedef struct {
    const tdc_mode_desc_t *desc;
    int display_hz;
    int available; /* 0: a part it needs is missing or a stage refused (see note) */
    int refused;   /* a firmware stage refused the configuration: its status (< 0), else 0 */
    char note[256];
    /* perceived error, means over evaluated instants */
    double psnr, ssim, flip, flicker;
    double psnr_min, flip_max;
    double terr;        /* temporally filtered error, RMS code values (cfg.temporal; else NAN) */
    double eye_terr[2];
    int evals;
    int eyes; /* 1 or 2; the figures above are the mean of the eyes */
    double eye_psnr[2], eye_ssim[2], eye_flip[2], eye_flicker[2];
    /* cost */
    uint64_t rays;         /* primary rays traced (samples x spp) */
    uint64_t link_bytes;   /* bytes on the link (packets incl. headers; stereo: both eyes' stream) */
    uint64_t frames;       /* display refreshes */
    uint64_t rendered;     /* frames/subframes the renderer produced */
    double fw_s, render_s; /* seconds in firmware (decode + stages), in the renderer (+ encoder) */
    uint32_t link_errors;
    uint32_t resets; /* stream resets (scene cuts) */
    double sim_s;    /* duration simulated */
    int nonfinite;   /* any NaN/Inf seen in a perceived image */
    /* around the true gaze (every mode; tdc_fov_metrics.h): FLIP weighted by
     * eccentricity, FLIP inside the foveal disk (the fov modes' disk
     * fraction of the distance to the farthest corner) and outside it,
     * FLIP's weighted median (thesis Tables 5.1-5.3), flicker outside the disk */
    double flip_ecc, flip_fovea, flip_periph, flip_wmedian, flicker_periph;
    int foveated; /* the mode foveates (fov family) */
    /* FovVideoVDP on the retinal signal (the judge, simulator/tdc_sim_jod.h):
     * JOD of the view, within 5 deg of the gaze and beyond, mean of the
     * eyes; refreshes pooled after the warm-up.  judged 0: not run. */
    int judged, jod_frames;
    double jod, jod_fovea, jod_periphery, eye_jod[2];
} tdc_sim_result_t;

/* Runs the given modes; results[i] for modes[i].  Writes per-instant rows
 * to series (CSV, may be NULL) and picture strips into cfg->outdir; hands
 * the retinal signal to cfg->retina_cb and writes cfg->dump_dir.
 * Returns 0, -1 on a setup or stage error, -2 when an output (--dump, the
 * consumer) failed (message on stderr). */
int tdc_sim_run(const tdc_sim_config_t *cfg, tdc_source_t *src, const tdc_mode_desc_t *const *modes, int nmodes,
                tdc_sim_result_t *results, FILE *series);

#endif
