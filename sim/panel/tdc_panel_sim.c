/* tdc_panel_sim.c - OLED low-persistence panel and LCD response (see header). */
#include "panel/tdc_panel_sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lcd/tdc_lcdsim.h"

typedef struct {
    tdc_lcdsim_panel_t panel;
    tdc_lcdsim_t sim;
    char model[160];
} lcdsim_ext_t;

double tdc_panel_sim_decode(int code, double g)
{
    return pow((double)code / 255.0, g);
}

int tdc_panel_sim_init(tdc_panel_sim_t *p, tdc_panel_sim_kind_t kind, int w, int h, const double gamma[3],
                       double persistence)
{
    if (!p || w < 1 || h < 1 || !gamma) {
        return -1;
    }
    memset(p, 0, sizeof(*p));
    p->kind = kind;
    p->width = w;
    p->height = h;
    for (int k = 0; k < 3; k++) {
        p->gamma[k] = gamma[k];
    }
    size_t n = 3 * (size_t)w * h;
    for (int k = 0; k < 3; k++) {
        for (int c = 0; c < 256; c++) {
            p->lut[256 * k + c] = tdc_panel_sim_decode(c, gamma[k]);
        }
    }
    int nbuf = kind == TDC_PANEL_SIM_LCD ? TDC_PANEL_SIM_MAX_SLICES : 0;
    for (int i = 0; i < nbuf; i++) {
        p->slice_buf[i] = calloc(n, sizeof(double));
        if (!p->slice_buf[i]) {
            tdc_panel_sim_free(p);
            return -1;
        }
    }
    if (kind == TDC_PANEL_SIM_LCD) {
        p->persistence = 1.0;
        p->tau_rise_s = 0.0025;
        p->tau_fall_s = 0.0060;
        p->state = calloc(n, sizeof(double));
        if (!p->state) {
            tdc_panel_sim_free(p);
            return -1;
        }
        p->model = "LCD (fallback: first-order relaxation, rise 2.5 ms / fall 6 ms, exact integration)";
    } else {
        p->persistence = persistence > 0.0 && persistence <= 1.0 ? persistence : 1.0;
        p->model = "OLED low persistence";
    }
    return 0;
}

int tdc_panel_sim_lcd_backlight(tdc_panel_sim_t *p, int strobe, double duty, double phase)
{
    lcdsim_ext_t *e = p ? (lcdsim_ext_t *)p->ext : NULL;
    if (!e || p->kind != TDC_PANEL_SIM_LCD ||
        (strobe && !(duty > 0.0 && duty <= 1.0 && phase >= 0.0 && phase + duty <= 1.0 + 1e-12))) {
        return -1;
    }
    e->panel.strobe = strobe != 0;
    e->panel.strobe_duty = strobe ? duty : 1.0;
    e->panel.strobe_phase = strobe ? phase : 0.0;
    snprintf(e->model, sizeof(e->model), "LCD: physical model sim/lcd (%s, %s backlight)", e->panel.name,
             e->panel.strobe ? "strobed" : "constant");
    return 0;
}

int tdc_panel_sim_use_lcdsim(tdc_panel_sim_t *p, const char *path, char *err, size_t errlen)
{
    if (!p || p->kind != TDC_PANEL_SIM_LCD || !path) {
        snprintf(err, errlen, "not an LCD panel");
        return -1;
    }
    lcdsim_ext_t *e = calloc(1, sizeof(*e));
    if (!e) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    if (tdc_lcdsim_load(path, &e->panel, err, errlen) != 0 ||
        tdc_lcdsim_init(&e->sim, &e->panel, 3 * (size_t)p->width * p->height) != 0) {
        free(e);
        return -1;
    }
    snprintf(e->model, sizeof(e->model), "LCD: physical model sim/lcd (%s, %s backlight)", e->panel.name,
             e->panel.strobe ? "strobed" : "constant");
    p->model = e->model;
    p->ext = e;
    return 0;
}

void tdc_panel_sim_free(tdc_panel_sim_t *p)
{
    if (!p) {
        return;
    }
    if (p->ext) {
        lcdsim_ext_t *e = p->ext;
        tdc_lcdsim_free(&e->sim);
        free(e);
        p->ext = NULL;
    }
    for (int i = 0; i < TDC_PANEL_SIM_MAX_SLICES; i++) {
        free(p->slice_buf[i]);
        p->slice_buf[i] = NULL;
    }
    free(p->state);
    p->state = NULL;
}

double tdc_panel_sim_duty(const tdc_panel_sim_t *p)
{
    return p->kind == TDC_PANEL_SIM_LCD ? 1.0 : p->persistence;
}

int tdc_panel_sim_show(tdc_panel_sim_t *p, const uint8_t *codes, double t, double frame_s, tdc_eye_slice_t *out)
{
    size_t n = 3 * (size_t)p->width * p->height;
    if (p->kind == TDC_PANEL_SIM_OLED) {
        memset(&out[0], 0, sizeof(out[0]));
        out[0].t0 = t;
        out[0].t1 = t + frame_s * p->persistence;
        out[0].codes = codes;
        out[0].lut = p->lut;
        return 1;
    }
    if (p->ext) {
        /* physical model: mean light of the refresh; a strobed backlight
         * emits it during its flash only */
        lcdsim_ext_t *e = p->ext;
        tdc_lcdsim_frame(&e->sim, codes, 1.0 / frame_s, p->slice_buf[0]);
        double a = 0.0, d = 1.0;
        if (e->panel.strobe && e->panel.strobe_duty > 0.0 && e->panel.strobe_duty <= 1.0) {
            a = e->panel.strobe_phase;
            d = e->panel.strobe_duty;
            for (size_t i = 0; i < n; i++) {
                p->slice_buf[0][i] /= d;
            }
        }
        out[0].t0 = t + a * frame_s;
        out[0].t1 = t + (a + d) * frame_s;
        out[0].lin = p->slice_buf[0];
        return 1;
    }
    /* LCD fallback: L(s) = T + (L0 - T) exp(-s / tau) within the frame; the
     * mean over [a, b] is T + (L0 - T) tau (e^{-a/tau} - e^{-b/tau}) / (b - a). */
    const int ns = TDC_PANEL_SIM_MAX_SLICES;
    double dt = frame_s / ns;
    for (size_t i = 0; i < n; i++) {
        double target = p->lut[256 * (i % 3) + codes[i]];
        double l0 = p->state[i];
        double tau = target >= l0 ? p->tau_rise_s : p->tau_fall_s;
        for (int s = 0; s < ns; s++) {
            double a = s * dt, b = a + dt;
            double ea = exp(-a / tau), eb = exp(-b / tau);
            p->slice_buf[s][i] = target + (l0 - target) * tau * (ea - eb) / dt;
        }
        p->state[i] = target + (l0 - target) * exp(-frame_s / tau);
    }
    for (int s = 0; s < ns; s++) {
        out[s].t0 = t + s * dt;
        out[s].t1 = t + (s + 1) * dt;
        out[s].lin = p->slice_buf[s];
    }
    return ns;
}
