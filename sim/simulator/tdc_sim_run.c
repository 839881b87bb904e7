/*
 * tdc_sim_run.c - runs display modes through the whole data path in
 * lockstep and measures perceived error and cost (see tdc_sim.h).  What a
 * mode does per refresh is its family's (tdc_sim_mode.h); this file owns
 * the clock, the link, the panel, the eye and the metrics.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "metrics/tdc_metrics.h"
#include "report/tdc_report.h"
#include "simulator/tdc_sim.h"
#include "simulator/tdc_sim_link.h"
#include "simulator/tdc_sim_mode.h"
#include "tdc_panels.h"

static const tdc_panel_t *find_panel(const char *name, int want_lcd)
{
#define X(p) &p,
    static const tdc_panel_t *const all[] = {TDC_PANEL_LIST(X) NULL};
#undef X
    for (int i = 0; all[i]; i++) {
        if (name && strcmp(all[i]->name, name) == 0) {
            return all[i];
        }
    }
    if (name) {
        return NULL;
    }
    for (int i = 0; all[i]; i++) {
        if ((all[i]->type == TDC_PANEL_LCD) == want_lcd) {
            return all[i];
        }
    }
    return want_lcd ? NULL : all[0];
}

/* ---------------------------------------------------------------------
 * Mode set-up: what every mode shares, then its family and the LCD stage.
 * ------------------------------------------------------------------- */
static int mode_init(sim_mode_t *m, const tdc_mode_desc_t *d, tdc_sim_result_t *res, const tdc_sim_setup_t *s,
                     const double gamma[3], double window_s)
{
    const tdc_sim_config_t *cfg = s->cfg;
    memset(m, 0, sizeof(*m));
    memset(res, 0, sizeof(*res));
    m->d = d;
    m->res = res;
    res->desc = d;
    res->available = 1;
    m->hz = d->fixed_hz ? d->fixed_hz : cfg->refresh_hz;
    res->display_hz = m->hz;
    m->fs = 1.0 / m->hz;
    m->w = cfg->width;
    m->h = cfg->height;
    m->npx = (size_t)m->w * m->h;
    m->last_t = -1.0;
    res->psnr_min = 1e9;
    double pers = cfg->persistence > 0 ? cfg->persistence : (cfg->refresh_hz >= 200 ? 1.0 : 0.2);
    if (tdc_panel_sim_init(&m->panel, cfg->panel, m->w, m->h, gamma, pers)) {
        return -1;
    }
    int spf = cfg->panel == TDC_PANEL_SIM_LCD ? TDC_PANEL_SIM_MAX_SLICES : 1;
    m->ring_n = ((int)ceil(window_s * m->hz) + 3) * spf;
    if (m->ring_n > TDC_SIM_RING_MAX) {
        m->ring_n = TDC_SIM_RING_MAX;
    }
    size_t n3 = m->npx * 3;
    for (int i = 0; i < m->ring_n; i++) {
        m->ring_buf[i] = calloc(n3, sizeof(double));
        if (!m->ring_buf[i]) {
            return -1;
        }
    }
    m->render = calloc(n3, 1);
    m->wanted = calloc(n3, 1);
    m->out = calloc(n3, 1);
    m->xy = calloc(m->npx * 2, sizeof(double));
    m->perc = calloc(n3, sizeof(double));
    m->crop_p = calloc(n3, sizeof(double));
    m->crop_g = calloc(n3, sizeof(double));
    m->enc_p = calloc(n3, sizeof(double));
    m->enc_g = calloc(n3, sizeof(double));
    m->err = calloc(n3, sizeof(double));
    m->err_prev = calloc(n3, sizeof(double));
    m->flipmap = calloc(m->npx, sizeof(double));
    if (!m->render || !m->wanted || !m->out || !m->xy || !m->perc || !m->crop_p || !m->crop_g || !m->enc_p ||
        !m->enc_g || !m->err || !m->err_prev || !m->flipmap) {
        return -1;
    }
    if (tdc_sim_link_init(&m->link, m->w, m->h, d->link_flags, d->r_num, d->r_den, (uint16_t)m->hz) != 0) {
        if (!m->link.full) {
            return -1;
        }
        tdc_sim_note(m, "link stream header rejected");
    }
    if (!m->link.real) {
        tdc_sim_note(m, "link: payload copied, bytes = payload + 32-byte header (encoder/decoder not in this build)");
    }
    if (d->family->init(m, s)) {
        return -1;
    }
    if (cfg->panel == TDC_PANEL_SIM_LCD && tdc_sim_stage_lcd.init(m, s)) {
        return -1;
    }
    return 0;
}

static void mode_free(sim_mode_t *m)
{
    if (m->d) {
        m->d->family->free(m);
        tdc_sim_stage_lcd.free(m);
    }
    for (int i = 0; i < TDC_SIM_RING_MAX; i++) {
        free(m->ring_buf[i]);
    }
    free(m->render);
    free(m->wanted);
    free(m->out);
    free(m->xy);
    free(m->perc);
    free(m->crop_p);
    free(m->crop_g);
    free(m->enc_p);
    free(m->enc_g);
    free(m->err);
    free(m->err_prev);
    free(m->flipmap);
    tdc_sim_link_free(&m->link);
    tdc_panel_sim_free(&m->panel);
}

/* Stream reset (scene cut): new stream, firmware history dropped. */
static void mode_reset(sim_mode_t *m)
{
    m->lf = 0;
    m->res->resets++;
    tdc_sim_stage(m, "link STREAM packet (reset)", tdc_sim_link_stream(&m->link));
    if (m->d->family->reset) {
        m->d->family->reset(m);
    }
    tdc_sim_stage_lcd.reset(m);
}

/* Produces drive codes for the next display frame and shows them. */
static void mode_display_frame(sim_mode_t *m, tdc_source_t *src, int spp)
{
    /* Frames are rendered for the middle of their emission (as a renderer
     * predicts the display time), then shown from the frame start. */
    double t_show = m->frame * m->fs;
    double t = t_show + 0.5 * tdc_panel_sim_duty(&m->panel) * m->fs;
    tdc_sim_result_t *r = m->res;
    if (m->last_t >= 0.0 && src->cut && src->cut(src, m->last_t, t)) {
        mode_reset(m);
    }
    uint32_t lf = m->lf;
    double dec0 = m->link.decode_s, enc0 = m->link.encode_s;
    m->d->family->frame(m, src, t, spp, lf);
    memcpy(m->out, m->wanted, m->npx * 3);
    if (m->drive && !m->failed) {
        tdc_sim_stage_lcd.frame(m, src, t, spp, lf);
    }
    if (m->failed) {
        return; /* reported; a failed frame is not shown */
    }
    r->fw_s += m->link.decode_s - dec0;
    r->render_s += m->link.encode_s - enc0;
    /* panel */
    tdc_eye_slice_t sl[TDC_PANEL_SIM_MAX_SLICES];
    int ns = tdc_panel_sim_show(&m->panel, m->out, t_show, m->fs, sl);
    for (int i = 0; i < ns; i++) {
        int slot = m->ring_head;
        memcpy(m->ring_buf[slot], sl[i].lin, m->npx * 3 * sizeof(double));
        m->ring[slot].t0 = sl[i].t0;
        m->ring[slot].t1 = sl[i].t1;
        m->ring[slot].lin = m->ring_buf[slot];
        m->ring_head = (m->ring_head + 1) % m->ring_n;
        if (m->ring_count < m->ring_n) {
            m->ring_count++;
        }
    }
    r->frames++;
    m->last_t = t;
    m->frame++;
    m->lf++;
}

/* ---------------------------------------------------------------------
 * Metrics of one evaluation instant.
 * ------------------------------------------------------------------- */
static void crop_copy(const double *in, int w, int x0, int y0, int cw, int ch, double *out)
{
    for (int y = 0; y < ch; y++) {
        memcpy(out + (size_t)y * cw * 3, in + 3 * ((size_t)(y + y0) * w + x0), sizeof(double) * 3 * (size_t)cw);
    }
}

static void progress(double frac, const char *label)
{
    int n = (int)(frac * 40.0 + 0.5);
    fprintf(stderr, "\r%-18.18s [", label ? label : "tdc-sim");
    for (int i = 0; i < 40; i++) {
        fputc(i < n ? '#' : '.', stderr);
    }
    fprintf(stderr, "] %3d%%", (int)(frac * 100.0 + 0.5));
    fflush(stderr);
}

int tdc_sim_run(const tdc_sim_config_t *cfg, tdc_source_t *src, const tdc_mode_desc_t *const *modes, int nmodes,
                tdc_sim_result_t *results, FILE *series)
{
    if (!cfg || !src || nmodes < 1 || cfg->width < 2 || cfg->height < 2 || cfg->refresh_hz < 1 ||
        cfg->duration_s <= 0.0) {
        fprintf(stderr, "tdc-sim: invalid configuration\n");
        return -1;
    }
    const int R = cfg->refresh_hz;
    const int wf = cfg->window_frames > 0 ? cfg->window_frames : (R >= 200 ? 4 : 2);
    const double W = (double)wf / R;
    const int spp = cfg->spp > 0 ? cfg->spp : (R >= 200 ? 1 : 4);
    const int w = cfg->width, h = cfg->height;
    const size_t n3 = (size_t)w * h * 3;
    const tdc_panel_t *fw_panel = find_panel(cfg->panel == TDC_PANEL_SIM_LCD ? NULL : cfg->panel_profile, 0);
    const tdc_panel_t *lcd_panel = cfg->panel == TDC_PANEL_SIM_LCD ? find_panel(cfg->panel_profile, 1) : NULL;
    if (!fw_panel) {
        fprintf(stderr, "tdc-sim: unknown panel profile '%s'\n", cfg->panel_profile ? cfg->panel_profile : "?");
        return -1;
    }
    const tdc_panel_t *gp = lcd_panel ? lcd_panel : fw_panel;
    double gamma[3];
    for (int k = 0; k < 3; k++) {
        gamma[k] = gp->gamma_micro[k] / 1e6;
        src->gamma[k] = gamma[k];
    }
    sim_mode_t *ms = calloc((size_t)nmodes, sizeof(sim_mode_t));
    double *gt = malloc(sizeof(double) * n3), *scratch = malloc(sizeof(double) * n3);
    if (!ms || !gt || !scratch) {
        free(ms);
        free(gt);
        free(scratch);
        return -1;
    }
    int rc = 0;
    tdc_sim_setup_t setup = {cfg, lcd_panel ? lcd_panel : fw_panel, lcd_panel, src->full_frame != NULL,
                             src->subframe != NULL};
    for (int i = 0; i < nmodes; i++) {
        if (mode_init(&ms[i], modes[i], &results[i], &setup, gamma, W)) {
            fprintf(stderr, "tdc-sim: out of memory setting up mode %s\n", modes[i]->name);
            rc = -1;
        }
        ms[i].slot = i;
        if (src->note && src->full_frame) {
            tdc_sim_note(&ms[i], src->note);
        }
        if (rc == 0 && cfg->strict && results[i].refused) {
            fprintf(stderr, "tdc-sim: --mode %s at --refresh %d, --size %dx%d: %s\n", modes[i]->name, ms[i].hz, w, h,
                    results[i].note);
            rc = -1;
        }
    }
    long total = (long)floor(cfg->duration_s * R + 1e-9);
    long nevals = total - (wf - 1);
    if (nevals < 1) {
        nevals = 1;
    }
    int strip_at = cfg->strip_at >= 0 ? cfg->strip_at : (int)(nevals / 2);
    tdc_eye_cfg_t ec = {w, h, W, 1.0 / tdc_panel_sim_duty(&ms[0].panel), 0.5, cfg->pursuit_gain};
    double speed = 0.0;
    {
        double v[2];
        src->pursuit(src, 0.0, v);
        speed = sqrt(v[0] * v[0] + v[1] * v[1]);
        double sp = cfg->scene.speed >= 0 ? cfg->scene.speed : tdc_scene_default_speed(cfg->scene.kind);
        speed = speed > sp ? speed : sp;
    }
    /* evaluated interior: content shifted in from beyond the edges during the
     * window (pursuit shift up to v T) is excluded */
    int margin = (int)ceil(speed * W * fmax(1.0, fabs(cfg->pursuit_gain))) + 2;
    int maxm = ((w < h ? w : h) - 8) / 2;
    margin = margin > maxm ? (maxm > 0 ? maxm : 0) : margin;
    int cw = w - 2 * margin, ch = h - 2 * margin;
    int gt_steps = src->rigid ? 1 : (int)fmin(16.0, fmax(2.0, ceil(speed * W / 0.5)));
    if (series) {
        fprintf(series, "mode,eval,t,psnr,ssim,flip,flicker\n");
    }
    double prev_te = 0.0;
    for (long j = 0; j < nevals && rc == 0; j++) {
        double te = (double)(j + wf) / R;
        for (int i = 0; i < nmodes; i++) {
            sim_mode_t *m = &ms[i];
            if (!m->res->available) {
                continue;
            }
            while (m->frame * m->fs < te - 1e-12 && !m->failed) {
                mode_display_frame(m, src, spp);
            }
            if (m->failed) {
                rc = -1; /* reported with the mode, frame and stage */
            }
        }
        if (rc) {
            break;
        }
        if (j % (cfg->metric_every > 0 ? cfg->metric_every : 1) != 0 && j != strip_at) {
            continue;
        }
        double v[2];
        src->pursuit(src, te, v);
        tdc_eye_ground_truth(&ec, src, te, v, gt_steps, gt, scratch);
        for (int i = 0; i < nmodes; i++) {
            sim_mode_t *m = &ms[i];
            tdc_sim_result_t *r = m->res;
            if (!r->available) {
                continue;
            }
            /* slices in ring order */
            tdc_eye_perceive(&ec, m->ring, m->ring_count, te, v, m->perc);
            for (size_t k = 0; k < n3; k++) {
                if (!isfinite(m->perc[k])) {
                    r->nonfinite = 1;
                    m->perc[k] = 0.0;
                }
            }
            crop_copy(m->perc, w, margin, margin, cw, ch, m->crop_p);
            crop_copy(gt, w, margin, margin, cw, ch, m->crop_g);
            size_t cn = (size_t)cw * ch * 3;
            tdc_metrics_encode(m->crop_p, m->enc_p, cn);
            tdc_metrics_encode(m->crop_g, m->enc_g, cn);
            double psnr = tdc_psnr(m->enc_p, m->enc_g, cn, 1.0);
            double ssim = tdc_ssim(m->enc_p, m->enc_g, cw, ch, 1.0);
            double flip = tdc_flip(m->crop_g, m->crop_p, cw, ch, cfg->flip_ppd, m->flipmap);
            for (size_t k = 0; k < cn; k++) {
                m->err[k] = m->enc_p[k] - m->enc_g[k];
            }
            double flick = NAN;
            if (m->have_err_prev) {
                /* frame-to-frame change of the motion-compensated error: the
                 * retinal point at x now was at x - v dt in the last image */
                double sx = -v[0] * cfg->pursuit_gain * (te - prev_te), sy = -v[1] * cfg->pursuit_gain * (te - prev_te);
                double se = 0.0;
                for (int y = 0; y < ch; y++) {
                    for (int x = 0; x < cw; x++) {
                        for (int c = 0; c < 3; c++) {
                            double pe = tdc_eye_bilinear(m->err_prev, cw, ch, x + sx, y + sy, c);
                            double d = m->err[3 * ((size_t)y * cw + x) + c] - pe;
                            se += d * d;
                        }
                    }
                }
                flick = 255.0 * sqrt(se / (double)cn);
                m->sum_flicker += flick;
                m->n_flicker++;
            }
            memcpy(m->err_prev, m->err, cn * sizeof(double));
            m->have_err_prev = 1;
            m->sum_psnr += psnr;
            m->sum_ssim += ssim;
            m->sum_flip += flip;
            r->evals++;
            r->psnr_min = psnr < r->psnr_min ? psnr : r->psnr_min;
            r->flip_max = flip > r->flip_max ? flip : r->flip_max;
            if (series) {
                fprintf(series, "%s,%ld,%.6f,%.4f,%.6f,%.6f,%s%.4f\n", r->desc->name, j, te, psnr, ssim, flip,
                        isnan(flick) ? "" : "", isnan(flick) ? 0.0 : flick);
            }
            if (j == strip_at && cfg->outdir) {
                tdc_report_strip(cfg->outdir, r->desc->name, m->out, m->crop_p, m->crop_g, m->flipmap, w, h, cw, ch,
                                 margin);
            }
        }
        prev_te = te;
        if (cfg->progress && (j % 16 == 0 || j == nevals - 1)) {
            progress((double)(j + 1) / nevals, cfg->label);
        }
    }
    if (cfg->progress) {
        fputc('\n', stderr);
    }
    for (int i = 0; i < nmodes; i++) {
        sim_mode_t *m = &ms[i];
        tdc_sim_result_t *r = m->res;
        if (r->evals) {
            r->psnr = m->sum_psnr / r->evals;
            r->ssim = m->sum_ssim / r->evals;
            r->flip = m->sum_flip / r->evals;
        }
        r->flicker = m->n_flicker ? m->sum_flicker / m->n_flicker : 0.0;
        r->link_bytes = m->link.bytes;
        r->link_errors += m->link.errors;
        r->sim_s = (double)nevals / R + W - 1.0 / R;
        r->sim_s = m->frame * m->fs;
        mode_free(m);
    }
    free(ms);
    free(gt);
    free(scratch);
    return rc;
}
