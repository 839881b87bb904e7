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
#include <time.h>

#include "metrics/tdc_fov_metrics.h"
#include "metrics/tdc_metrics.h"
#include "report/tdc_report.h"
#include "simulator/tdc_sim.h"
#include "simulator/tdc_sim_link.h"
#include "simulator/tdc_sim_mode.h"
#include "simulator/tdc_sim_retina.h"
#include "tdc_bilinear.h"
#include "tdc_panels.h"
#include "tdc_par.h"

const tdc_panel_t *tdc_sim_panel_find(const char *name, int want_lcd)
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

/* Wall-clock seconds (stage breakdown: threads overlap, so not CPU time). */
static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* What one evaluation instant needs, shared by every mode (modes are
 * evaluated one after another, so one set of buffers serves all). */
typedef struct {
    double *gt;             /* ground truth of the eye being evaluated (cropped at once) */
    double *crop_g, *enc_g; /* that eye's ground truth: crop, encoded */
    /* the ground truth's half of SSIM and FLIP, computed once per eye and
     * instant and shared by every mode (eyes are evaluated one after another) */
    tdc_ssim_ref_t ssim_g;
    tdc_flip_ref_t flip_g;
    double *scratch, *perc, *crop_p, *enc_p, *err, *flipmap, *rows;
    float *err_spare; /* w x h x 3: changes places with a mode's err_prev at every evaluation */
    double *rows_out, *rows_n; /* flicker outside the foveal disk: per-row sums and counts */
    double *xy;   /* sample positions (render calls are sequential too) */
    char *series; /* one series line per mode and eye, written in mode order */
    void *mwork;  /* the metrics' scratch (SSIM and FLIP in turn), kept across calls */
} sim_eval_t;

#define SERIES_LINE 192

static void eval_free(sim_eval_t *e)
{
    free(e->enc_g); /* crop_g and crop_p are gt and perc themselves (crop_copy) */
    tdc_ssim_ref_free(&e->ssim_g);
    tdc_flip_ref_free(&e->flip_g);
    free(e->series);
    free(e->mwork);
    free(e->gt);
    free(e->scratch);
    free(e->perc);
    free(e->enc_p);
    free(e->err);
    free(e->err_spare);
    free(e->flipmap);
    free(e->rows);
    free(e->rows_out);
    free(e->rows_n);
    free(e->xy);
}

static int eval_alloc(sim_eval_t *e, int w, int h, int nseries)
{
    size_t n3 = (size_t)w * h * 3;
    memset(e, 0, sizeof(*e));
    int bad = 0;
    bad |= !(e->enc_g = malloc(sizeof(double) * n3));
    bad |= !(e->series = calloc((size_t)nseries, SERIES_LINE));
    size_t ws = tdc_ssim_work_bytes(w, h), wf = tdc_flip_work_bytes(w, h);
    bad |= !(e->mwork = malloc(ws > wf ? ws : wf));
    bad |= !(e->gt = malloc(sizeof(double) * n3));
    bad |= !(e->scratch = malloc(sizeof(double) * n3));
    bad |= !(e->perc = malloc(sizeof(double) * n3));
    bad |= !(e->enc_p = malloc(sizeof(double) * n3));
    bad |= !(e->err = malloc(sizeof(double) * n3));
    bad |= !(e->err_spare = malloc(sizeof(float) * n3));
    bad |= !(e->flipmap = malloc(sizeof(double) * (size_t)w * h));
    bad |= !(e->rows = malloc(sizeof(double) * (size_t)h));
    bad |= !(e->rows_out = malloc(sizeof(double) * (size_t)h));
    bad |= !(e->rows_n = malloc(sizeof(double) * (size_t)h));
    bad |= !(e->xy = malloc(sizeof(double) * 2 * (size_t)w * h));
    /* The crops are made in place: the full planes are not read after them
     * (110 MB less at 1440x1600) */
    e->crop_g = e->gt;
    e->crop_p = e->perc;
    return bad ? -1 : 0;
}

/* ---------------------------------------------------------------------
 * Mode set-up: what every mode shares, then its family and the LCD stage.
 * ------------------------------------------------------------------- */
static int mode_init(sim_mode_t *m, const tdc_mode_desc_t *d, tdc_sim_result_t *res, const tdc_sim_setup_t *s,
                     const double gamma[3], double window_s, int eye, sim_mode_t *eye0, double *xy, double *scratch)
{
    const tdc_sim_config_t *cfg = s->cfg;
    memset(m, 0, sizeof(*m));
    if (eye == 0) {
        memset(res, 0, sizeof(*res));
        res->desc = d;
        res->available = 1;
        res->psnr_min = 1e9;
        res->eyes = s->eyes;
    }
    m->d = d;
    m->res = res;
    m->eye = eye;
    m->eyes = s->eyes;
    m->hz = d->fixed_hz ? d->fixed_hz : cfg->refresh_hz;
    res->display_hz = m->hz;
    m->fs = 1.0 / m->hz;
    m->w = cfg->width;
    m->h = cfg->height;
    m->npx = (size_t)m->w * m->h;
    m->last_t = -1.0;
    m->xy = xy;
    m->scratch = scratch;
    double pers = cfg->persistence > 0 ? cfg->persistence : (cfg->refresh_hz >= 200 ? 1.0 : 0.2);
    if (tdc_panel_sim_init(&m->panel, cfg->panel, m->w, m->h, gamma, pers)) {
        return -1;
    }
    for (int k = 0; k < 3; k++) {
        for (int c = 0; c < 256; c++) {
            m->lut[256 * k + c] = tdc_panel_sim_decode(c, gamma[k]);
        }
    }
    int lcd = cfg->panel == TDC_PANEL_SIM_LCD;
    int spf = lcd ? TDC_PANEL_SIM_MAX_SLICES : 1;
    m->ring_n = ((int)ceil(window_s * m->hz) + 3) * spf;
    if (m->ring_n > TDC_SIM_RING_MAX) {
        m->ring_n = TDC_SIM_RING_MAX;
    }
    size_t n3 = m->npx * 3;
    for (int i = 0; i < m->ring_n; i++) {
        m->ring_buf[i] = calloc(n3, lcd ? sizeof(double) : 1);
        if (!m->ring_buf[i]) {
            return -1;
        }
    }
    m->render = calloc(n3, 1);
    m->wanted = calloc(n3, 1);
    m->out = calloc(n3, 1);
    m->err_prev = calloc(n3, sizeof(float));
    if (!m->render || !m->wanted || !m->out || !m->err_prev) {
        return -1;
    }

    if (eye == 0) {
        m->link = &m->link_own;
        if (tdc_sim_link_init(m->link, m->w, m->h, s->eyes, d->link_flags, d->r_num, d->r_den, (uint16_t)m->hz) != 0) {
            if (!m->link->full[0]) {
                return -1;
            }
            tdc_sim_note(m, "link stream header rejected");
        }
    } else {
        m->link = eye0->link;
    }
    int frc = d->family->init(m, s);
    if (frc) {
        return frc; /* -2: refused, reported by the family */
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
    free(m->err_prev);
    if (m->temporal) {
        tdc_eye_temporal_free(m->temporal);
        free(m->temporal);
    }
    if (m->link == &m->link_own) {
        tdc_sim_link_free(m->link);
    }
    tdc_panel_sim_free(&m->panel);
}

/* Stream reset (scene cut): new stream (once per mode), firmware history
 * dropped (every eye). */
static void mode_reset(sim_mode_t *m)
{
    m->lf = 0;
    if (m->eye == 0) {
        m->res->resets++;
        tdc_sim_stage(m, "link STREAM packet (reset)", tdc_sim_link_stream(m->link));
    }
    if (m->d->family->reset) {
        m->d->family->reset(m);
    }
    tdc_sim_stage_lcd.reset(m);
}

/* Produces drive codes for the next display frame of one eye and shows them. */
static void mode_display_frame(sim_mode_t *m, tdc_source_t *src, int spp, tdc_sim_times_t *tm)
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
    double dec0 = m->link->decode_s, enc0 = m->link->encode_s, fw0 = r->fw_s, ren0 = r->render_s;
    double w0 = wall_now();
    m->d->family->frame(m, src, t, spp, lf);
    memcpy(m->out, m->wanted, m->npx * 3);
    if (m->drive && !m->failed) {
        tdc_sim_stage_lcd.frame(m, src, t, spp, lf);
    }
    double w1 = wall_now();
    double dec = m->link->decode_s - dec0, enc = m->link->encode_s - enc0;
    r->fw_s += dec;
    r->render_s += enc;
    if (tm) {
        /* the families time source and firmware in CPU seconds; the wall
         * time of the frame is split between source, link and firmware in
         * the same proportions */
        double cpu = (r->fw_s - fw0) + (r->render_s - ren0);
        double k = cpu > 0.0 ? (w1 - w0) / cpu : 0.0;
        tm->link_s += k * (dec + enc);
        tm->firmware_s += k * (r->fw_s - fw0 - dec);
        tm->source_s += k * (r->render_s - ren0 - enc);
    }
    if (m->failed) {
        return; /* reported; a failed frame is not shown */
    }
    /* panel */
    tdc_eye_slice_t sl[TDC_PANEL_SIM_MAX_SLICES];
    int ns = tdc_panel_sim_show(&m->panel, m->out, t_show, m->fs, sl);
    for (int i = 0; i < ns; i++) {
        int slot = m->ring_head;
        tdc_eye_slice_t *rs = &m->ring[slot];
        memset(rs, 0, sizeof(*rs));
        if (m->panel.kind == TDC_PANEL_SIM_OLED) {
            /* the OLED slice is the panel's decode of the codes: keep the codes */
            memcpy(m->ring_buf[slot], m->out, m->npx * 3);
            rs->codes = m->ring_buf[slot];
            rs->lut = m->lut;
        } else {
            memcpy(m->ring_buf[slot], sl[i].lin, m->npx * 3 * sizeof(double));
            rs->lin = m->ring_buf[slot];
        }
        rs->t0 = sl[i].t0;
        rs->t1 = sl[i].t1;
        m->ring_head = (m->ring_head + 1) % m->ring_n;
        if (m->ring_count < m->ring_n) {
            m->ring_count++;
        }
    }
    if (tm) {
        tm->panel_s += wall_now() - w1;
    }
    if (m->eye == 0) {
        r->frames++;
    }
    m->last_t = t;
    m->frame++;
    m->lf++;
}

/* ---------------------------------------------------------------------
 * Metrics of one evaluation instant.
 * ------------------------------------------------------------------- */
static void crop_copy(const double *in, int w, int x0, int y0, int cw, int ch, double *out)
{
    if (in == out) {
        /* in place: row y moves down to y cw, never over a row not yet
         * moved (cw <= w, x0, y0 >= 0), so in row order, one thread */
        for (int y = 0; y < ch; y++) {
            memmove(out + (size_t)y * cw * 3, in + 3 * ((size_t)(y + y0) * w + x0), sizeof(double) * 3 * (size_t)cw);
        }
        return;
    }
    TDC_PAR_FOR((size_t)cw * ch)
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

/* Perceived error of one mode's eye at te against that eye's ground truth
 * (already cropped and encoded in ev); accumulates into m. */
static void eval_mode_eye(sim_mode_t *m, sim_eval_t *ev, const tdc_eye_cfg_t *ec, const tdc_sim_config_t *cfg, long j,
                          double te, double prev_te, const double v[2], const double gaze[2], int margin, int cw,
                          int ch, int strip_at, char *series, tdc_sim_times_t *tm)
{
    tdc_sim_result_t *r = m->res;
    int w = m->w, h = m->h;
    size_t n3 = m->npx * 3, cn = (size_t)cw * ch * 3;
    double w0 = wall_now();
    /* ev->scratch is free here: the ground truth's renders are done */
    if (tdc_eye_perceive_buf(ec, m->ring, m->ring_count, te, v, ev->perc, ev->scratch)) {
        tdc_sim_stage(m, "eye model (out of memory)", -1);
        return;
    }
    double w1 = wall_now();
    int nonfinite = 0;
    TDC_PAR_FOR((size_t)w * h)
    for (int y = 0; y < h; y++) {
        for (size_t k = 3 * (size_t)y * w; k < 3 * (size_t)(y + 1) * w; k++) {
            if (!isfinite(ev->perc[k])) {
                ev->perc[k] = 0.0;
                nonfinite = 1; /* benign race: every writer stores 1 */
            }
        }
    }
    (void)n3;
    r->nonfinite |= nonfinite;
    crop_copy(ev->perc, w, margin, margin, cw, ch, ev->crop_p);
    tdc_metrics_encode(ev->crop_p, ev->enc_p, cn);
    const double *enc_g = ev->enc_g, *crop_g = ev->crop_g;
    double psnr = tdc_psnr(ev->enc_p, enc_g, cn, 1.0);
    double ssim = tdc_ssim_vs(&ev->ssim_g, ev->enc_p, 1.0, ev->mwork);
    double flip = tdc_flip_vs(&ev->flip_g, ev->crop_p, ev->flipmap, ev->mwork);
    if (psnr < 0.0 || ssim < -1.0 || flip < 0.0) {
        tdc_sim_stage(m, "metrics (out of memory or size beyond the filters)", -1);
        return;
    }
    /* around the true gaze (crop coordinates): the foveal disk is the fov
     * modes' disk fraction of the distance to the farthest screen corner */
    double gz[2];
    tdc_sim_gaze_true(m->gaze, te, gz);
    const double gx = gz[0] - margin, gy = gz[1] - margin, rf = cfg->fov_disk * tdc_sim_gaze_rmax(m->gaze, gz);
    tdc_fov_stats_t fs;
    if (tdc_fov_stats(ev->flipmap, cw, ch, gx, gy, cfg->flip_ppd, rf, &fs)) {
        tdc_sim_stage(m, "gaze metrics (out of memory)", -1);
        return;
    }
    m->sum_flip_ecc += fs.ecc;
    m->sum_flip_fovea += fs.fovea;
    m->sum_flip_periph += fs.periph;
    m->sum_flip_wmed += fs.wmedian;
    /* The encoded error, its frame-to-frame change (flicker: the retinal
     * point at x now was at x - v dt in the last image, so the last error
     * is sampled there, bilinear with edges clamped as tdc_bilinear_f, its
     * column and row terms once per column and row) and the error kept as
     * float for the next instant, in one pass; the new error goes to the
     * spare plane, which then changes places with the mode's. */
    double flick = NAN;
    const int have_prev = m->have_err_prev, keep_err = cfg->temporal;
    const double sx = -v[0] * cfg->pursuit_gain * (te - prev_te), sy = -v[1] * cfg->pursuit_gain * (te - prev_te);
    const float *ep = m->err_prev;
    float *en = ev->err_spare;
    TDC_PAR_FOR((size_t)cw * ch)
    for (int y = 0; y < ch; y++) {
        double yc = y + sy;
        yc = yc < 0.0 ? 0.0 : (yc > ch - 1 ? ch - 1 : yc);
        const int y0 = (int)yc, y1 = y0 + 1 < ch ? y0 + 1 : y0;
        const double fy = yc - y0;
        const float *r0 = ep + 3 * (size_t)y0 * cw, *r1 = ep + 3 * (size_t)y1 * cw;
        const size_t i0 = 3 * (size_t)y * cw;
        double se = 0.0, so = 0.0, no = 0.0;
        for (int x = 0; x < cw; x++) {
            double sp = 0.0;
            double xc = x + sx;
            xc = xc < 0.0 ? 0.0 : (xc > cw - 1 ? cw - 1 : xc);
            const int x0 = (int)xc, x1 = x0 + 1 < cw ? x0 + 1 : x0;
            const double fx = xc - x0;
            for (int c = 0; c < 3; c++) {
                const size_t k = i0 + 3 * (size_t)x + c;
                const double d = ev->enc_p[k] - enc_g[k];
                if (keep_err) {
                    ev->err[k] = d;
                }
                en[k] = (float)d;
                if (have_prev) {
                    const double a = r0[3 * x0 + c], b = r0[3 * x1 + c], dd = r1[3 * x0 + c], e = r1[3 * x1 + c];
                    const double pe = (a + (b - a) * fx) * (1.0 - fy) + (dd + (e - dd) * fx) * fy;
                    const double df = d - pe;
                    sp += df * df;
                }
            }
            se += sp;
            const double dx = x + 0.5 - gx, dy = y + 0.5 - gy;
            if (dx * dx + dy * dy > rf * rf) {
                so += sp;
                no += 3.0;
            }
        }
        ev->rows[y] = se;
        ev->rows_out[y] = so;
        ev->rows_n[y] = no;
    }
    ev->err_spare = m->err_prev;
    m->err_prev = en;
    if (have_prev) {
        flick = 255.0 * sqrt(tdc_par_sum_rows(ev->rows, ch) / (double)cn);
        const double n_out = tdc_par_sum_rows(ev->rows_n, ch);
        m->sum_flicker_periph += n_out > 0 ? 255.0 * sqrt(tdc_par_sum_rows(ev->rows_out, ch) / n_out) : 0.0;
        m->sum_flicker += flick;
        m->n_flicker++;
    }
    m->have_err_prev = 1;
    if (cfg->temporal && !m->temporal) {
        /* on the evaluated interior, sampled at the evaluation rate */
        tdc_tcsf_t tp;
        tdc_tcsf_default(&tp);
        double rate = (double)cfg->refresh_hz / (cfg->metric_every > 1 ? cfg->metric_every : 1);
        m->temporal = calloc(1, sizeof(*m->temporal));
        if (!m->temporal || tdc_eye_temporal_init(m->temporal, &tp, rate, cw, ch)) {
            tdc_sim_stage(m, "temporal visibility model (out of memory)", -1);
            return;
        }
    }
    if (m->temporal) {
        /* the error in retinal coordinates through the temporal CSF */
        double te_rms = tdc_eye_temporal_push(m->temporal, ev->err, gaze[0], gaze[1]);
        if (te_rms >= 0.0) {
            m->sum_terr += te_rms;
            m->n_terr++;
        }
    }
    m->sum_psnr += psnr;
    m->sum_ssim += ssim;
    m->sum_flip += flip;
    r->psnr_min = psnr < r->psnr_min ? psnr : r->psnr_min;
    r->flip_max = flip > r->flip_max ? flip : r->flip_max;
    static const char *const eye_tag[2] = {".L", ".R"};
    const char *tag = m->eyes == 2 ? eye_tag[m->eye] : "";
    if (series) {
        snprintf(series, SERIES_LINE, "%s%s,%ld,%.6f,%.4f,%.6f,%.6f,%s%.4f,\n", r->desc->name, tag, j, te, psnr, ssim,
                 flip, isnan(flick) ? "" : "", isnan(flick) ? 0.0 : flick);
    }
    if (j == strip_at && cfg->outdir) {
        char name[96];
        snprintf(name, sizeof(name), "%s%s", r->desc->name, m->eyes == 2 ? (m->eye ? "_R" : "_L") : "");
        tdc_report_strip(cfg->outdir, name, m->out, ev->crop_p, crop_g, ev->flipmap, w, h, cw, ch, margin);
        if (m->eye == 0) {
            /* where the eye looked at the strip's instant (crop coordinates), for the fovea crops */
            char gp[1100];
            snprintf(gp, sizeof(gp), "%s/strip_gaze.json", cfg->outdir);
            FILE *gf = fopen(gp, "w");
            if (gf) {
                fprintf(gf, "{\"x\": %.3f, \"y\": %.3f, \"r\": %.3f, \"width\": %d, \"height\": %d}\n", gx, gy, rf, cw,
                        ch);
                fclose(gf);
            }
        }
    }
    if (tm) {
        tm->eye_s += w1 - w0;
        tm->metrics_s += wall_now() - w1;
    }
}

int tdc_sim_run(const tdc_sim_config_t *cfg, tdc_source_t *src, const tdc_mode_desc_t *const *modes, int nmodes,
                tdc_sim_result_t *results, FILE *series)
{
    const int eyes = cfg && cfg->eyes == 2 ? 2 : 1;
    if (!cfg || !src || nmodes < 1 || cfg->width < 2 || cfg->height < 2 || cfg->refresh_hz < 1 ||
        cfg->duration_s <= 0.0 || (eyes == 2 && !cfg->right)) {
        fprintf(stderr, "tdc-sim: invalid configuration\n");
        return -1;
    }
    tdc_source_t *srcs[2] = {src, eyes == 2 ? cfg->right : NULL};
    tdc_sim_times_t *tm = cfg->times;
    if (tm) {
        memset(tm, 0, sizeof(*tm));
    }
    double wall0 = wall_now();
    const int R = cfg->refresh_hz;
    const int wf = cfg->window_frames > 0 ? cfg->window_frames : (R >= 200 ? 4 : 2);
    const double W = (double)wf / R;
    const int spp = cfg->spp > 0 ? cfg->spp : (R >= 200 ? 1 : 4);
    const int w = cfg->width, h = cfg->height;
    const tdc_panel_t *fw_panel = tdc_sim_panel_find(cfg->panel == TDC_PANEL_SIM_LCD ? NULL : cfg->panel_profile, 0);
    const tdc_panel_t *lcd_panel = cfg->panel == TDC_PANEL_SIM_LCD ? tdc_sim_panel_find(cfg->panel_profile, 1) : NULL;
    if (!fw_panel) {
        fprintf(stderr, "tdc-sim: unknown panel profile '%s'\n", cfg->panel_profile ? cfg->panel_profile : "?");
        return -1;
    }
    const tdc_panel_t *gp = lcd_panel ? lcd_panel : fw_panel;
    double gamma[3];
    for (int k = 0; k < 3; k++) {
        gamma[k] = gp->gamma_micro[k] / 1e6;
        for (int e = 0; e < eyes; e++) {
            srcs[e]->gamma[k] = gamma[k];
        }
    }
    sim_mode_t *ms = calloc((size_t)nmodes * eyes, sizeof(sim_mode_t));
    sim_eval_t ev;
    if (!ms || eval_alloc(&ev, w, h, nmodes * eyes)) {
        fprintf(stderr, "tdc-sim: out of memory for %dx%d x %d eye(s)\n", w, h, eyes);
        free(ms);
        eval_free(&ev);
        return -1;
    }
    int rc = 0;
    tdc_sim_setup_t setup = {
        cfg, eyes, lcd_panel ? lcd_panel : fw_panel, lcd_panel, src->full_frame != NULL, src->subframe != NULL,
        src->layers != NULL, src->layered_subframe != NULL};
    for (int i = 0; i < nmodes; i++) {
        for (int e = 0; e < eyes; e++) {
            sim_mode_t *m = &ms[i * eyes + e];
            int irc = mode_init(m, modes[i], &results[i], &setup, gamma, W, e, &ms[i * eyes], ev.xy, ev.scratch);
            if (irc) {
                if (irc != -2) {
                    fprintf(stderr, "tdc-sim: out of memory setting up mode %s\n", modes[i]->name);
                }
                rc = -1;
            }
            m->slot = i;
        }
        if (src->note && src->full_frame) {
            tdc_sim_note(&ms[i * eyes], src->note);
        }
        if (rc == 0 && cfg->strict && results[i].refused) {
            fprintf(stderr, "tdc-sim: --mode %s at --refresh %d, --size %dx%d: %s\n", modes[i]->name, ms[i * eyes].hz,
                    w, h, results[i].note);
            rc = -1;
        }
    }
    /* the gaze (where the fovea is), for the fov modes and every mode's gaze metrics */
    tdc_sim_gaze_t fovea; /* the gaze point's table (main's `gaze` below: the pursuit shift) */
    memset(&fovea, 0, sizeof(fovea));
    fovea.schedule = cfg->gaze;
    fovea.at_x = cfg->gaze_at_x;
    fovea.at_y = cfg->gaze_at_y;
    fovea.latency_ms = cfg->gaze_latency_ms;
    fovea.noise_deg = cfg->gaze_noise_deg;
    fovea.ppd = cfg->flip_ppd;
    fovea.seed = cfg->seed;
    if (rc == 0 && tdc_sim_gaze_init(&fovea, src, w, h, R, cfg->duration_s)) {
        fprintf(stderr, "tdc-sim: out of memory for the gaze table\n");
        rc = -1;
    }
    for (int k = 0; k < nmodes * eyes; k++) {
        ms[k].gaze = &fovea;
    }
    /* the retinal signal, when a consumer or --dump wants it */
    int rrc = 0;
    sim_retina_t *retina = rc == 0 ? sim_retina_new(&setup, srcs, &fovea, gamma, gp, ms, nmodes, &rrc) : NULL;
    rc = rc ? rc : rrc;
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
        /* jod: empty here, filled by the judge after the run (tdc_sim_jod_series_merge) */
        fprintf(series, "mode,eval,t,psnr,ssim,flip,legacy_flicker,jod\n");
    }
    double prev_te = 0.0, gaze[2] = {0.0, 0.0};
    for (long j = 0; j < nevals && rc == 0; j++) {
        double te = (double)(j + wf) / R;
        for (int i = 0; i < nmodes; i++) {
            sim_mode_t *m0 = &ms[i * eyes];
            if (!m0->res->available) {
                continue;
            }
            /* both eyes of a refresh, eye 0 first (the stereo stream's order) */
            while (m0->frame * m0->fs < te - 1e-12 && rc == 0) {
                for (int e = 0; e < eyes; e++) {
                    sim_mode_t *m = &ms[i * eyes + e];
                    mode_display_frame(m, srcs[e], spp, tm);
                    if (m->failed) {
                        rc = -1; /* reported with the mode, frame and stage */
                        break;
                    }
                    rc = sim_retina_shown(retina, m);
                    if (rc) {
                        break;
                    }
                }
            }
        }
        rc = rc ? rc : sim_retina_advance(retina, te);
        if (rc) {
            break;
        }
        if (j % (cfg->metric_every > 0 ? cfg->metric_every : 1) != 0 && j != strip_at) {
            continue;
        }
        double v[2];
        src->pursuit(src, te, v);
        /* where the pursuing eye looks, cumulative over the evaluated
         * instants (the temporal model's retinal coordinates) */
        gaze[0] += v[0] * cfg->pursuit_gain * (te - prev_te);
        gaze[1] += v[1] * cfg->pursuit_gain * (te - prev_te);
        /* eye by eye: its ground truth and the ground truth's half of the
         * metrics once, then every mode against it */
        for (int e = 0; e < eyes && rc == 0; e++) {
            double w0 = wall_now();
            tdc_eye_ground_truth(&ec, srcs[e], te, v, gt_steps, ev.gt, ev.scratch);
            double w1 = wall_now();
            crop_copy(ev.gt, w, margin, margin, cw, ch, ev.crop_g);
            tdc_metrics_encode(ev.crop_g, ev.enc_g, (size_t)cw * ch * 3);
            if (tdc_ssim_prepare(&ev.ssim_g, ev.enc_g, cw, ch, ev.mwork) ||
                tdc_flip_prepare(&ev.flip_g, ev.crop_g, cw, ch, cfg->flip_ppd, ev.mwork)) {
                fprintf(stderr, "tdc-sim: metrics of the ground truth: out of memory or size beyond the filters\n");
                rc = -1;
                break;
            }
            if (tm) {
                tm->source_s += w1 - w0;
                tm->metrics_s += wall_now() - w1;
            }
            for (int i = 0; i < nmodes && rc == 0; i++) {
                if (!results[i].available) {
                    continue;
                }
                sim_mode_t *m = &ms[i * eyes + e];
                char *line = series ? ev.series + (size_t)(i * eyes + e) * SERIES_LINE : NULL;
                if (line) {
                    line[0] = 0;
                }
                eval_mode_eye(m, &ev, &ec, cfg, j, te, prev_te, v, gaze, margin, cw, ch, strip_at, line, tm);
                rc = m->failed ? -1 : 0;
            }
        }
        for (int i = 0; i < nmodes; i++) {
            if (!results[i].available) {
                continue;
            }
            for (int e = 0; e < eyes && series; e++) {
                fputs(ev.series + (size_t)(i * eyes + e) * SERIES_LINE, series);
            }
            results[i].evals++;
        }
        prev_te = te;
        if (cfg->progress && (j % ((nevals + 99) / 100) == 0 || j == nevals - 1)) {
            progress((double)(j + 1) / nevals, cfg->label);
        }
    }
    if (cfg->progress) {
        fputc('\n', stderr);
    }
    {
        int frc = sim_retina_free(retina, rc == 0);
        rc = rc ? rc : frc;
    }
    for (int i = 0; i < nmodes; i++) {
        tdc_sim_result_t *r = &results[i];
        double sp = 0.0, ss = 0.0, sf = 0.0, sk = 0.0;
        for (int e = 0; e < eyes; e++) {
            sim_mode_t *m = &ms[i * eyes + e];
            if (r->evals) {
                r->eye_psnr[e] = m->sum_psnr / r->evals;
                r->eye_ssim[e] = m->sum_ssim / r->evals;
                r->eye_flip[e] = m->sum_flip / r->evals;
                /* gaze metrics: the mean of the eyes */
                r->flip_ecc += m->sum_flip_ecc / r->evals / eyes;
                r->flip_fovea += m->sum_flip_fovea / r->evals / eyes;
                r->flip_periph += m->sum_flip_periph / r->evals / eyes;
                r->flip_wmedian += m->sum_flip_wmed / r->evals / eyes;
            }
            r->flicker_periph += m->n_flicker ? m->sum_flicker_periph / m->n_flicker / eyes : 0.0;
            r->eye_flicker[e] = m->n_flicker ? m->sum_flicker / m->n_flicker : 0.0;
            r->eye_terr[e] = m->n_terr ? m->sum_terr / m->n_terr : NAN;
            sp += r->eye_psnr[e];
            ss += r->eye_ssim[e];
            sf += r->eye_flip[e];
            sk += r->eye_flicker[e];
        }
        /* both eyes: the mean of the two eyes' figures */
        r->psnr = sp / eyes;
        r->ssim = ss / eyes;
        r->flip = sf / eyes;
        r->flicker = sk / eyes;
        r->terr = eyes == 2 ? 0.5 * (r->eye_terr[0] + r->eye_terr[1]) : r->eye_terr[0];
        sim_mode_t *m0 = &ms[i * eyes];
        r->link_bytes = m0->link ? m0->link->bytes : 0;
        r->link_errors += m0->link ? m0->link->errors : 0;
        r->sim_s = m0->frame * m0->fs;
        for (int e = 0; e < eyes; e++) {
            mode_free(&ms[i * eyes + e]);
        }
    }
    free(ms);
    eval_free(&ev);
    tdc_sim_gaze_free(&fovea);
    if (tm) {
        tm->total_s = wall_now() - wall0;
    }
    return rc;
}
