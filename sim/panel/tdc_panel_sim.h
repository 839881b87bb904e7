/*
 * tdc_panel_sim.h - what light the panel emits for the drive codes the
 * controller outputs, as time slices for the eye model.
 *
 *  - OLED, low persistence: L = (code/255)^gamma per channel (the panel
 *    profile's gammas, TRM paper §4.4), emitted during the first
 *    `persistence` fraction of each frame and dark for the rest.
 *  - LCD: hold-type (persistence 1) with a temporal pixel response.  The
 *    physical liquid-crystal model comes from sim/lcd/ when it has landed;
 *    until then the built-in fallback is a first-order relaxation of light
 *    towards the target with rise/fall time constants, integrated exactly
 *    (the closed-form exponential: A-stable for any time constant, so stiff
 *    transitions far shorter or longer than a frame are fine).  The slices
 *    carry the exact mean light of each quarter frame.
 */
#ifndef TDC_PANEL_SIM_H
#define TDC_PANEL_SIM_H

#include <stddef.h>
#include <stdint.h>

#include "eye/tdc_eye.h"

#define TDC_PANEL_SIM_MAX_SLICES 4

typedef enum { TDC_PANEL_SIM_OLED = 0, TDC_PANEL_SIM_LCD = 1 } tdc_panel_sim_kind_t;

typedef struct {
    tdc_panel_sim_kind_t kind;
    int width, height;
    double gamma[3];
    double persistence; /* OLED: fraction of the frame emitting (0, 1] */
    double tau_rise_s;  /* LCD fallback: time constants */
    double tau_fall_s;
    const char *model; /* description for reports */
    double *state;     /* LCD: current light per sample (W*H*3) */
    double *slice_buf[TDC_PANEL_SIM_MAX_SLICES]; /* LCD only */
    double lut[3 * 256]; /* OLED: light of each code, per channel (the slice's decode) */
    void *ext; /* physical LCD model from sim/lcd, when linked */
} tdc_panel_sim_t;

/* Returns 0, or -1 (bad arguments / allocation). */
int tdc_panel_sim_init(tdc_panel_sim_t *p, tdc_panel_sim_kind_t kind, int w, int h, const double gamma[3],
                       double persistence);
void tdc_panel_sim_free(tdc_panel_sim_t *p);

/* Switches an LCD panel to the physical liquid-crystal model of sim/lcd
 * (tdc_lcdsim: transition-dependent time constants, exact integration,
 * constant or strobed backlight) loaded from a .lcdsim file.  Returns 0, or
 * -1 (not an LCD panel, or the file does not load: message in err);
 * the built-in fallback stays in use then. */
int tdc_panel_sim_use_lcdsim(tdc_panel_sim_t *p, const char *path, char *err, size_t errlen);

/* Overrides the physical LCD's backlight (after tdc_panel_sim_use_lcdsim):
 * strobe 0 = hold-type (constant), 1 = strobed for duty of the refresh from
 * phase.  0, or -1 if there is no physical LCD or the timing is invalid. */
int tdc_panel_sim_lcd_backlight(tdc_panel_sim_t *p, int strobe, double duty, double phase);

/* Duty cycle for the eye's normalisation. */
double tdc_panel_sim_duty(const tdc_panel_sim_t *p);

/*
 * Shows `codes` (RGB888, W*H, tightly packed) for the frame [t, t + frame_s).
 * Writes up to TDC_PANEL_SIM_MAX_SLICES slices; an LCD's images live in the
 * panel's buffers and stay valid until the next call, so copy them; an
 * OLED's slice is `codes` itself with the panel's lut (codes and lut, no
 * light plane: a 1440x1600 plane of doubles is 55 MB per panel, and every
 * consumer keeps the codes), valid while `codes` is.
 * Returns the number of slices.
 */
int tdc_panel_sim_show(tdc_panel_sim_t *p, const uint8_t *codes, double t, double frame_s, tdc_eye_slice_t *out);

/* Linear light of a code under gamma g. */
double tdc_panel_sim_decode(int code, double g);

#endif
