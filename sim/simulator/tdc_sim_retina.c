/* tdc_sim_retina.c - reference panel, step clock, consumer and dump of the
 * retinal signal (see tdc_sim_retina.h and eye/tdc_retina.h). */
#include "simulator/tdc_sim_retina.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_sim_codes.h"
#include "simulator/tdc_sim_dump.h"
#include "tdc_free.h"
#include "tdc_par.h"

/* The reference's slices: those of the refresh being sampled (steps tile
 * the refreshes, every slice lies inside its refresh, and the reference
 * shows a refresh only when its first step is sampled). */
#define REF_RING TDC_PANEL_SIM_MAX_SLICES

struct sim_retina {
    const tdc_sim_config_t *cfg;
    int eyes, w, h, R, steps, lcd;
    double dt, norm, pers;
    long next; /* next step to sample */
    tdc_retina_display_t disp;
    tdc_retina_eye_t eye;
    tdc_source_t *src[2];
    sim_mode_t *ms;
    int nmodes;
    tdc_panel_sim_t panel[2];
    long ref_frame[2];
    int head[2], count[2];
    void *buf[2][REF_RING];
    tdc_eye_slice_t ring[2][REF_RING];
    double lut[3 * 256], gamma[3];
    tdc_sim_code_table_t code_tab[3]; /* the reference's drive codes: tdc_sim_encode_code's, by table */
    double *gt, *acc;
    uint8_t *codes;
    float *ref_rgb, *ref_y, *test_rgb, *test_y, *emit;
    tdc_sim_dump_t *dump;
};

static void retina_release(sim_retina_t *r)
{
    for (int e = 0; e < 2; e++) {
        tdc_panel_sim_free(&r->panel[e]);
        for (int i = 0; i < REF_RING; i++) {
            free(r->buf[e][i]);
        }
    }
    tdc_retina_eye_free(&r->eye);
    TDC_FREE_ALL(r->acc, r->codes, r->ref_rgb, r->ref_y, r->test_rgb, r->test_y, r->emit, r);
}

sim_retina_t *sim_retina_new(const tdc_sim_setup_t *s, tdc_source_t *const srcs[2], const tdc_sim_gaze_t *gaze,
                             const double gamma[3], const tdc_panel_t *profile, sim_mode_t *ms, int nmodes, int *rc)
{
    const tdc_sim_config_t *cfg = s->cfg;
    *rc = 0;
    if (!cfg->retina_cb && !cfg->dump_dir) {
        return NULL;
    }
    *rc = -1;
    sim_retina_t *r = calloc(1, sizeof(*r));
    if (!r) {
        fprintf(stderr, "tdc-sim: retinal signal: out of memory\n");
        return NULL;
    }
    char why[256];
    if (tdc_retina_display_from_panel(profile, cfg->flip_ppd, cfg->ppd_from ? cfg->ppd_from : "profile", cfg->width,
                                      &r->disp, why, sizeof(why))) {
        fprintf(stderr, "tdc-sim: retinal signal: %s\n", why);
        free(r);
        return NULL;
    }
    if (strcmp(r->disp.ppd_from, "default") == 0) {
        fprintf(stderr, "tdc-sim: note: panel profile %s has no ppd: the retinal signal uses %.2f px/deg (the "
                        "documented default; --ppd sets it)\n", profile->name, r->disp.ppd);
    }
    r->cfg = cfg;
    r->eyes = s->eyes;
    r->w = cfg->width;
    r->h = cfg->height;
    r->R = cfg->refresh_hz;
    r->lcd = cfg->panel == TDC_PANEL_SIM_LCD;
    r->ms = ms;
    r->nmodes = nmodes;
    r->pers = tdc_panel_sim_duty(&ms[0].panel);
    r->norm = 1.0 / r->pers;
    r->steps = tdc_retina_steps(cfg->retina_steps, r->lcd, r->pers);
    r->dt = 1.0 / ((double)r->R * r->steps);
    const size_t n3 = 3 * (size_t)r->w * r->h, np = (size_t)r->w * r->h;
    int bad = 0;
    for (int k = 0; k < 3; k++) {
        r->gamma[k] = gamma[k];
        for (int c = 0; c < 256; c++) {
            r->lut[256 * k + c] = tdc_panel_sim_decode(c, gamma[k]);
        }
        tdc_sim_code_table_init(&r->code_tab[k], gamma[k], TDC_SIM_CODES_EXACT);
    }
    for (int e = 0; e < r->eyes; e++) {
        r->src[e] = srcs[e];
        /* the reference's panel: the same simulation as the modes' */
        bad |= tdc_panel_sim_init(&r->panel[e], cfg->panel, r->w, r->h, gamma, r->pers) != 0;
        if (!bad && r->lcd) {
            char path[512], err[256];
            snprintf(path, sizeof(path), "sim/lcd/panels/%s.lcdsim", s->lcd_panel ? s->lcd_panel->name : "pg279q");
            if (tdc_panel_sim_use_lcdsim(&r->panel[e], path, err, sizeof(err)) == 0 && cfg->backlight >= 0) {
                tdc_panel_sim_lcd_backlight(&r->panel[e], cfg->backlight, cfg->strobe_duty, cfg->strobe_phase);
            }
        }
        for (int i = 0; i < REF_RING && !bad; i++) {
            bad |= !(r->buf[e][i] = calloc(n3, r->lcd ? sizeof(double) : 1));
        }
    }
    /* The consumer (the judge) reads the luminance alone; only --dump needs
     * the channels (55 MB a plane at 1440x1600) */
    bad |= !(r->acc = malloc(sizeof(double) * n3));
    r->gt = r->acc; /* the reference's ground truth is encoded before any step is sampled: one plane */
    bad |= !(r->codes = malloc(n3));
    bad |= cfg->dump_dir && !(r->ref_rgb = malloc(sizeof(float) * n3));
    bad |= cfg->dump_dir && !(r->test_rgb = malloc(sizeof(float) * n3));
    bad |= !(r->ref_y = malloc(sizeof(float) * np));
    bad |= !(r->test_y = malloc(sizeof(float) * np));
    bad |= cfg->dump_dir && !(r->emit = malloc(sizeof(float) * n3));
    bad |= !bad && tdc_retina_eye_init(&r->eye, gaze, srcs[0], cfg->pursuit_gain, cfg->pursuit_lag_ms * 1e-3, r->w,
                                       r->h, cfg->duration_s) != 0;
    if (bad) {
        fprintf(stderr, "tdc-sim: retinal signal: out of memory for %dx%d\n", r->w, r->h);
        retina_release(r);
        return NULL;
    }
    if (cfg->dump_dir) {
        const char *names[65];
        names[0] = "ref";
        for (int i = 0; i < nmodes && i < 64; i++) {
            names[i + 1] = ms[i * r->eyes].d->name;
        }
        /* the brightest a step can be: a pulse of 1 / duty covering it */
        double scale = r->disp.peak_cdm2 * (r->lcd && cfg->backlight == 1 ? 1.0 / cfg->strobe_duty : r->norm);
        r->dump = tdc_sim_dump_open(cfg->dump_dir, names, (nmodes < 64 ? nmodes : 64) + 1, r->eyes, r->w, r->h,
                                    scale);
        if (!r->dump) {
            *rc = -2;
            retina_release(r);
            return NULL;
        }
    }
    *rc = 0;
    return r;
}

int sim_retina_shown(sim_retina_t *r, const sim_mode_t *m)
{
    if (!r || !r->dump) {
        return 0;
    }
    return tdc_sim_dump_codes(r->dump, m->slot + 1, m->eye, (long)m->frame - 1, m->out) ? -2 : 0;
}

/* The reference's next refresh of eye e: the ground truth at the middle of
 * its emission (as the modes render), as drive codes, on its own panel. */
static int ref_refresh(sim_retina_t *r, int e)
{
    const long f = r->ref_frame[e]++;
    const double fs = 1.0 / r->R, t_show = f * fs, t = t_show + 0.5 * r->pers * fs;
    const size_t n3 = 3 * (size_t)r->w * r->h;
    r->src[e]->ground_truth(r->src[e], t, 0.0, 0.0, r->gt);
    const double *gt = r->gt;
    const tdc_sim_code_table_t *tab = r->code_tab;
    uint8_t *codes = r->codes;
    /* by table, not a pow per sample (7 M a refresh of 1440x1600: ~5 % of
     * a judged run's CPU at 720x800); the same codes */
    TDC_PAR_FOR(n3)
    for (int y = 0; y < r->h; y++) {
        for (size_t i = 3 * (size_t)y * r->w; i < 3 * (size_t)(y + 1) * r->w; i += 3) {
            for (int c = 0; c < 3; c++) {
                codes[i + c] = tdc_sim_code_lookup(&tab[c], gt[i + c]);
            }
        }
    }
    if (r->dump && tdc_sim_dump_codes(r->dump, 0, e, f, r->codes)) {
        return -2;
    }
    tdc_eye_slice_t sl[TDC_PANEL_SIM_MAX_SLICES];
    int ns = tdc_panel_sim_show(&r->panel[e], r->codes, t_show, fs, sl);
    for (int i = 0; i < ns; i++) {
        int slot = r->head[e];
        tdc_eye_slice_t *rs = &r->ring[e][slot];
        memset(rs, 0, sizeof(*rs));
        if (r->lcd) {
            memcpy(r->buf[e][slot], sl[i].lin, n3 * sizeof(double));
            rs->lin = r->buf[e][slot];
        } else {
            memcpy(r->buf[e][slot], r->codes, n3); /* decoded by the lut in the sampler */
            rs->codes = r->buf[e][slot];
            rs->lut = r->lut;
        }
        rs->t0 = sl[i].t0;
        rs->t1 = sl[i].t1;
        r->head[e] = (slot + 1) % REF_RING;
        r->count[e] += r->count[e] < REF_RING;
    }
    return 0;
}

int sim_retina_advance(sim_retina_t *r, double te)
{
    if (!r) {
        return 0;
    }
    const tdc_sim_config_t *cfg = r->cfg;
    for (; (r->next + 1) * r->dt <= te + 1e-9; r->next++) {
        const long k = r->next;
        /* the reference shows the refresh this step lies in (one at a time:
         * its ring holds one refresh's slices) */
        for (int e = 0; e < r->eyes; e++) {
            while (r->ref_frame[e] <= k / r->steps) {
                int rc = ref_refresh(r, e);
                if (rc) {
                    return rc;
                }
            }
        }
        tdc_retina_frame_t fr;
        memset(&fr, 0, sizeof(fr));
        fr.step = k;
        fr.refresh = k / r->steps;
        fr.t0 = k * r->dt;
        fr.t1 = (k + 1) * r->dt;
        fr.fps = (double)r->R * r->steps;
        fr.width = r->w;
        fr.height = r->h;
        fr.display = &r->disp;
        double pos[2], anc[2];
        tdc_retina_eye_at(&r->eye, 0.5 * (fr.t0 + fr.t1), pos, anc);
        for (int c = 0; c < 2; c++) {
            fr.gaze[c] = anc[c];
            fr.gaze_screen[c] = pos[c];
            fr.shift[c] = pos[c] - anc[c];
        }
        for (int e = 0; e < r->eyes; e++) {
            fr.eye = e;
            fr.ref_dark = tdc_retina_sample(&r->eye, r->ring[e], r->count[e], fr.t0, fr.t1, r->norm, &r->disp, r->w,
                                            r->h, r->acc, r->ref_rgb, r->ref_y);
            if (fr.ref_dark < 0) {
                return -1;
            }
            if (r->dump) {
                if (tdc_retina_sample(NULL, r->ring[e], r->count[e], fr.t0, fr.t1, r->norm, &r->disp, r->w, r->h,
                                      r->acc, r->emit, NULL) < 0 ||
                    tdc_sim_dump_step(r->dump, 0, e, k, r->emit, r->ref_rgb, r->ref_y, fr.fps) ||
                    tdc_sim_dump_step_row(r->dump, &fr)) {
                    return -2;
                }
            }
            fr.ref = r->ref_rgb;
            fr.ref_y = r->ref_y;
            for (int i = 0; i < r->nmodes; i++) {
                sim_mode_t *m = &r->ms[i * r->eyes + e];
                if (!m->res->available || m->failed) {
                    continue;
                }
                const double norm = 1.0 / tdc_panel_sim_duty(&m->panel);
                fr.test_dark = tdc_retina_sample(&r->eye, m->ring, m->ring_count, fr.t0, fr.t1, norm, &r->disp, r->w,
                                                 r->h, r->acc, r->test_rgb, r->test_y);
                if (fr.test_dark < 0) {
                    return -1;
                }
                fr.mode = m->d->name;
                fr.test = r->test_rgb;
                fr.test_y = r->test_y;
                if (cfg->retina_cb && cfg->retina_cb(cfg->retina_ctx, &fr)) {
                    fprintf(stderr, "tdc-sim: retinal signal: the consumer failed at mode %s, step %ld\n", fr.mode, k);
                    return -2;
                }
                if (r->dump && i < 64) {
                    if (tdc_retina_sample(NULL, m->ring, m->ring_count, fr.t0, fr.t1, norm, &r->disp, r->w, r->h,
                                          r->acc, r->emit, NULL) < 0 ||
                        tdc_sim_dump_step(r->dump, i + 1, e, k, r->emit, r->test_rgb, r->test_y, fr.fps)) {
                        return -2;
                    }
                }
            }
        }
    }
    return 0;
}

int sim_retina_free(sim_retina_t *r, int ok)
{
    if (!r) {
        return 0;
    }
    int rc = 0;
    if (r->dump) {
        rc = tdc_sim_dump_close(r->dump, ok ? r->cfg : NULL, &r->disp, r->steps, (double)r->R * r->steps, r->next,
                                r->pers) ? -2 : 0;
    }
    retina_release(r);
    return rc;
}
