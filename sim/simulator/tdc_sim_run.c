/*
 * tdc_sim_run.c - runs display modes through the whole data path in
 * lockstep and measures perceived error and cost (see tdc_sim.h).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "metrics/tdc_metrics.h"
#include "report/tdc_report.h"
#include "simulator/tdc_sim.h"
#include "simulator/tdc_sim_link.h"
#include "tdc_panels.h"
#include "tdc_sim_features.h"

#if TDC_SIM_HAVE_TRM
#include "tdc_trm.h"
#endif
#if TDC_SIM_HAVE_ASM
#include "tdc_assemble.h"
#include "tdc_ordering.h"
#endif
#if TDC_SIM_HAVE_LCD_FW
#include "tdc_lcd.h"
#endif

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts); /* CPU time: robust to a loaded host */
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#define RING_MAX 96

typedef struct {
    const tdc_mode_desc_t *d;
    tdc_sim_result_t *res;
    int hz;
    double fs;
    int w, h;
    size_t npx;
    uint32_t frame;   /* next display frame (absolute) */
    uint32_t lf;      /* frame index within the current link stream */
    double last_t;    /* start of the previous displayed frame */
    tdc_panel_sim_t panel;
    /* slices covering the fused window */
    int ring_n, ring_head, ring_count, spf;
    double *ring_buf[RING_MAX];
    tdc_eye_slice_t ring[RING_MAX];
    /* buffers */
    uint8_t *render, *reduced, *wanted, *out, *hist, *tmp;
    int16_t *mv, *mvbuf, *submv;
    double *xy;
    uint8_t *sub, *pattern;
    int have_hist;
    tdc_sim_link_t link;
    int link_ok;
    /* firmware stages */
    void *trm_mem, *trmr_mem, *asm_mem, *lcd_mem;
#if TDC_SIM_HAVE_TRM
    tdc_trm_t trm, trm_r;
#endif
#if TDC_SIM_HAVE_ASM
    tdc_asm_t as;
    size_t asm_bytes;
#endif
#if TDC_SIM_HAVE_LCD_FW
    tdc_lcd_t lcd;
#endif
    int use_trm, use_lcd;
    int slot; /* index of the mode (per-mode renderer state) */
    /* metrics */
    double *perc, *crop_p, *crop_g, *enc_p, *enc_g, *err, *err_prev, *flipmap;
    int have_err_prev;
    double sum_psnr, sum_ssim, sum_flip, sum_flicker;
    int n_flicker;
} sim_mode_t;

static void note(sim_mode_t *m, const char *s)
{
    size_t l = strlen(m->res->note);
    if (l + strlen(s) + 3 < sizeof(m->res->note)) {
        snprintf(m->res->note + l, sizeof(m->res->note) - l, "%s%s", l ? "; " : "", s);
    }
}

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
 * Renderer calls (timed, rays counted).
 * ------------------------------------------------------------------- */
static void render_full(sim_mode_t *m, tdc_source_t *src, double t, int spp, double jx, double jy, int with_mv,
                        double dt, tdc_mv_kind_t kind)
{
    if (src->full_frame) {
        /* a renderer tracing whole frames (Embree): its own timing and rays */
        uint64_t rays = 0;
        double ms = 0.0;
        double t1 = now_s();
        src->full_frame(src, t, with_mv ? dt : 0.0, m->render, with_mv ? m->mv : NULL, &rays, &ms);
        (void)ms;
        m->res->render_s += now_s() - t1;
        m->res->rays += rays;
        m->res->rendered++;
        return;
    }
    double t0 = now_s();
    for (int y = 0; y < m->h; y++) {
        for (int x = 0; x < m->w; x++) {
            size_t i = (size_t)y * m->w + x;
            m->xy[2 * i] = x + 0.5 + jx;
            m->xy[2 * i + 1] = y + 0.5 + jy;
        }
    }
    src->samples(src, t, (int)m->npx, m->xy, spp, m->render, with_mv ? m->mv : NULL, dt, kind);
    m->res->render_s += now_s() - t0;
    m->res->rays += (uint64_t)m->npx * (uint64_t)(spp < 1 ? 1 : spp);
    m->res->rendered++;
}

/* Interlaced rows of parity p: rendered directly into m->render. */
static void render_rows(sim_mode_t *m, tdc_source_t *src, double t, int spp, int parity)
{
    if (src->full_frame) {
        /* whole-frame renderer: trace the frame, keep the field's rows;
         * rays are counted for the field only (a renderer restricted to
         * those rows would trace that many) */
        render_full(m, src, t, spp, 0, 0, 0, 0, TDC_MV_SURFACE);
        m->res->rays -= m->res->rays ? (uint64_t)m->w * (m->h / 2) : 0;
        for (int y = 1 - parity; y < m->h; y += 2) {
            memset(m->render + (size_t)y * m->w * 3, 0, (size_t)m->w * 3);
        }
        return;
    }
    double t0 = now_s();
    int n = 0;
    for (int y = parity; y < m->h; y += 2) {
        for (int x = 0; x < m->w; x++) {
            m->xy[2 * n] = x + 0.5;
            m->xy[2 * n + 1] = y + 0.5;
            n++;
        }
    }
    src->samples(src, t, n, m->xy, spp, m->tmp, NULL, 0.0, TDC_MV_SURFACE);
    memset(m->render, 0, m->npx * 3);
    int k = 0;
    for (int y = parity; y < m->h; y += 2) {
        memcpy(m->render + (size_t)y * m->w * 3, m->tmp + (size_t)k * m->w * 3, (size_t)m->w * 3);
        k++;
    }
    m->res->render_s += now_s() - t0;
    m->res->rays += (uint64_t)n * (uint64_t)(spp < 1 ? 1 : spp);
    m->res->rendered++;
}

/* Bilinear sample of an RGB888 image at pixel-centre coordinates. */
static double sample8(const uint8_t *img, int w, int h, double x, double y, int c)
{
    x = x < 0 ? 0 : (x > w - 1 ? w - 1 : x);
    y = y < 0 ? 0 : (y > h - 1 ? h - 1 : y);
    int x0 = (int)x, y0 = (int)y;
    int x1 = x0 + 1 < w ? x0 + 1 : x0, y1 = y0 + 1 < h ? y0 + 1 : y0;
    double fx = x - x0, fy = y - y0;
    double a = img[3 * ((size_t)y0 * w + x0) + c], b = img[3 * ((size_t)y0 * w + x1) + c];
    double d = img[3 * ((size_t)y1 * w + x0) + c], e = img[3 * ((size_t)y1 * w + x1) + c];
    return (a + (b - a) * fx) * (1 - fy) + (d + (e - d) * fx) * fy;
}

static uint8_t to8(double v)
{
    v += 0.5;
    return (uint8_t)(v <= 0 ? 0 : (v >= 255 ? 255 : (int)v));
}

/* ASW-style extrapolation: the content at p next frame came from p + mv. */
static void warp_by_mv(sim_mode_t *m, const uint8_t *src, const int16_t *mv, uint8_t *dst)
{
    for (int y = 0; y < m->h; y++) {
        for (int x = 0; x < m->w; x++) {
            size_t i = (size_t)y * m->w + x;
            double sx = x + mv[2 * i] / 16.0, sy = y + mv[2 * i + 1] / 16.0;
            for (int c = 0; c < 3; c++) {
                dst[3 * i + c] = to8(sample8(src, m->w, m->h, sx, sy, c));
            }
        }
    }
}

/* TAA resolve: history reprojected by the MV, clamped to the current 3x3
 * min/max, blended 0.9 history + 0.1 current (code space). */
static void taa_resolve(sim_mode_t *m)
{
    for (int y = 0; y < m->h; y++) {
        for (int x = 0; x < m->w; x++) {
            size_t i = (size_t)y * m->w + x;
            for (int c = 0; c < 3; c++) {
                double cur = m->render[3 * i + c];
                if (!m->have_hist) {
                    m->tmp[3 * i + c] = (uint8_t)cur;
                    continue;
                }
                double lo = 255, hi = 0;
                for (int dy = -1; dy <= 1; dy++) {
                    for (int dx = -1; dx <= 1; dx++) {
                        int xx = x + dx < 0 ? 0 : (x + dx >= m->w ? m->w - 1 : x + dx);
                        int yy = y + dy < 0 ? 0 : (y + dy >= m->h ? m->h - 1 : y + dy);
                        double v = m->render[3 * ((size_t)yy * m->w + xx) + c];
                        lo = v < lo ? v : lo;
                        hi = v > hi ? v : hi;
                    }
                }
                double hv = sample8(m->hist, m->w, m->h, x + m->mv[2 * i] / 16.0, y + m->mv[2 * i + 1] / 16.0, c);
                hv = hv < lo ? lo : (hv > hi ? hi : hv);
                m->tmp[3 * i + c] = to8(0.9 * hv + 0.1 * cur);
            }
        }
    }
    memcpy(m->hist, m->tmp, m->npx * 3);
    m->have_hist = 1;
}

/* ---------------------------------------------------------------------
 * Mode set-up.
 * ------------------------------------------------------------------- */
static int mode_init(sim_mode_t *m, const tdc_mode_desc_t *d, tdc_sim_result_t *res, const tdc_sim_config_t *cfg,
                     const double gamma[3], double window_s, const tdc_panel_t *fw_panel,
                     const tdc_panel_t *lcd_panel, int src_full_frame, int src_subframe)
{
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
    m->spf = cfg->panel == TDC_PANEL_SIM_LCD ? TDC_PANEL_SIM_MAX_SLICES : 1;
    m->ring_n = ((int)ceil(window_s * m->hz) + 3) * m->spf;
    if (m->ring_n > RING_MAX) {
        m->ring_n = RING_MAX;
    }
    size_t n3 = m->npx * 3, tiles = (size_t)((m->w + 1) / 2) * ((m->h + 1) / 2);
    for (int i = 0; i < m->ring_n; i++) {
        m->ring_buf[i] = calloc(n3, sizeof(double));
        if (!m->ring_buf[i]) {
            return -1;
        }
    }
    m->render = calloc(n3, 1);
    m->reduced = calloc(n3, 1);
    m->wanted = calloc(n3, 1);
    m->out = calloc(n3, 1);
    m->hist = calloc(n3, 1);
    m->tmp = calloc(n3, 1);
    m->mv = calloc(m->npx * 2, sizeof(int16_t));
    m->mvbuf = calloc(m->npx * 2, sizeof(int16_t));
    m->submv = calloc(tiles * 2, sizeof(int16_t));
    m->xy = calloc(m->npx * 2, sizeof(double));
    m->sub = calloc(tiles * 3, 1);
    m->pattern = calloc((tiles + 7) / 8 + 1, 1);
    m->perc = calloc(n3, sizeof(double));
    m->crop_p = calloc(n3, sizeof(double));
    m->crop_g = calloc(n3, sizeof(double));
    m->enc_p = calloc(n3, sizeof(double));
    m->enc_g = calloc(n3, sizeof(double));
    m->err = calloc(n3, sizeof(double));
    m->err_prev = calloc(n3, sizeof(double));
    m->flipmap = calloc(m->npx, sizeof(double));
    if (!m->render || !m->reduced || !m->wanted || !m->out || !m->hist || !m->tmp || !m->mv || !m->mvbuf ||
        !m->submv || !m->xy || !m->sub || !m->pattern || !m->perc || !m->crop_p || !m->crop_g || !m->enc_p ||
        !m->enc_g || !m->err || !m->err_prev || !m->flipmap) {
        return -1;
    }
    uint32_t flags = 0;
    if (d->kind == TDC_MODE_TRM) {
        flags = TDC_SIM_LINK_REDUCED;
    } else if (d->kind == TDC_MODE_ASM) {
        flags = TDC_SIM_LINK_SUBFRAMES | TDC_SIM_LINK_SAMPLE_MV;
    }
    if (tdc_sim_link_init(&m->link, m->w, m->h, flags, d->r_num, d->r_den, (uint16_t)m->hz) != 0) {
        if (!m->link.full) {
            return -1;
        }
        note(m, "link stream header rejected");
    }
    if (!m->link.real) {
        note(m, "link: payload copied, bytes = payload + 32-byte header (encoder/decoder not in this build)");
    }
    /* firmware stages */
    if (d->kind == TDC_MODE_TRM || d->kind == TDC_MODE_NCSFI) {
#if TDC_SIM_HAVE_TRM
        tdc_trm_config_t tc;
        tdc_trm_default_config(&tc, (uint16_t)m->w, (uint16_t)m->h, (uint16_t)m->hz);
        tc.r_num = d->r_num;
        tc.r_den = d->r_den;
        if (cfg->trm_s > 0) {
            tc.s_q8 = (uint32_t)cfg->trm_s * 256u;
        }
        if (d->kind == TDC_MODE_NCSFI) {
            tc.s_q8 = 0; /* w = exp(0) = 1: residual added regardless of motion */
        }
        size_t n = tdc_trm_get_size(&tc);
        m->trm_mem = n ? malloc(n) : NULL;
        m->trmr_mem = n ? malloc(n) : NULL;
        tdc_status_t s1 = m->trm_mem ? tdc_trm_init(&m->trm, &tc, fw_panel, m->trm_mem, n) : TDC_ERR_SIZE;
        tdc_status_t s2 = m->trmr_mem ? tdc_trm_init(&m->trm_r, &tc, fw_panel, m->trmr_mem, n) : TDC_ERR_SIZE;
        if (s1 != TDC_OK || s2 != TDC_OK) {
            char b[96];
            snprintf(b, sizeof(b), "TRM firmware refused the configuration (%s)", tdc_status_name(s1 ? s1 : s2));
            note(m, b);
            res->available = 0;
        } else {
            m->use_trm = 1;
        }
#else
        note(m, "TRM firmware stage not in this build");
        res->available = 0;
#endif
    }
    if (d->kind == TDC_MODE_ASM && src_full_frame && (!src_subframe || d->ordering >= 0)) {
        note(m, src_subframe ? "the renderer chooses its own (adaptive) orderings: fixed orderings not available"
                             : "this source does not trace subframes");
        res->available = 0;
    } else if (d->kind == TDC_MODE_ASM) {
#if TDC_SIM_HAVE_ASM
        tdc_asm_config_t ac = {(uint16_t)m->w, (uint16_t)m->h};
        m->asm_bytes = tdc_asm_get_size(&ac);
        m->asm_mem = m->asm_bytes ? malloc(m->asm_bytes) : NULL;
        if (!m->asm_mem || tdc_asm_init(&m->as, &ac, m->asm_mem, m->asm_bytes) != TDC_OK) {
            note(m, "assembly firmware refused the configuration");
            res->available = 0;
        }
#else
        note(m, "tile-assembly firmware stage not in this build");
        res->available = 0;
#endif
    }
    if (cfg->panel == TDC_PANEL_SIM_LCD) {
#if TDC_SIM_HAVE_LCD_FW
        if (lcd_panel) {
            tdc_lcd_config_t lc = {(uint16_t)m->w, (uint16_t)m->h, (uint16_t)m->hz, (uint8_t)cfg->lcd_mode,
                                   (uint8_t)cfg->lcd_bits};
            size_t n = tdc_lcd_get_size(&lc);
            m->lcd_mem = n ? malloc(n) : NULL;
            if (m->lcd_mem && tdc_lcd_init(&m->lcd, &lc, lcd_panel, m->lcd_mem, n) == TDC_OK) {
                static const char *const names[] = {"gamma", "exact", "od17", "od33", "state", "state-pair"};
                char b[96];
                snprintf(b, sizeof(b), "LCD inverse %s, %d-bit history", names[cfg->lcd_mode % 6], cfg->lcd_bits);
                note(m, b);
                m->use_lcd = 1;
            } else {
                char b[160];
                snprintf(b, sizeof(b), "LCD firmware stage refused mode %d at %d Hz on %s: drive = wanted code",
                         cfg->lcd_mode, m->hz, lcd_panel->name);
                note(m, b);
            }
        } else {
            note(m, "no LCD panel profile: LCD firmware stage skipped, drive = wanted code");
        }
#else
        (void)lcd_panel;
        note(m, "LCD firmware stage not in this build: drive = wanted code");
#endif
        char path[512], err[256];
        snprintf(path, sizeof(path), "sim/lcd/panels/%s.lcdsim", lcd_panel ? lcd_panel->name : "pg279q");
        if (tdc_panel_sim_use_lcdsim(&m->panel, path, err, sizeof(err)) != 0) {
            note(m, err);
        } else if (cfg->backlight >= 0 &&
                   tdc_panel_sim_lcd_backlight(&m->panel, cfg->backlight, cfg->strobe_duty, cfg->strobe_phase) != 0) {
            note(m, "LCD backlight timing refused: the panel's own is used");
        }
        note(m, m->panel.model);
    }
    return 0;
}

static void mode_free(sim_mode_t *m)
{
    for (int i = 0; i < RING_MAX; i++) {
        free(m->ring_buf[i]);
    }
    free(m->render);
    free(m->reduced);
    free(m->wanted);
    free(m->out);
    free(m->hist);
    free(m->tmp);
    free(m->mv);
    free(m->mvbuf);
    free(m->submv);
    free(m->xy);
    free(m->sub);
    free(m->pattern);
    free(m->perc);
    free(m->crop_p);
    free(m->crop_g);
    free(m->enc_p);
    free(m->enc_g);
    free(m->err);
    free(m->err_prev);
    free(m->flipmap);
    free(m->trm_mem);
    free(m->trmr_mem);
    free(m->asm_mem);
    free(m->lcd_mem);
    tdc_sim_link_free(&m->link);
    tdc_panel_sim_free(&m->panel);
}

/* Stream reset (scene cut): new stream, firmware history dropped. */
#if TDC_SIM_HAVE_TRM || TDC_SIM_HAVE_ASM || TDC_SIM_HAVE_LCD_FW
/* A firmware stage refused a call the simulator made: a simulator bug (the
 * link layer already filters bad input), so report mode, frame and stage
 * and stop with a non-zero exit rather than measure a stale image. */
static void stage_ok(const sim_mode_t *m, const char *stage, tdc_status_t st)
{
    if (st != TDC_OK) {
        fprintf(stderr, "tdc-sim: mode %s: frame %u: %s failed: %s (%s)\n", m->d->name, m->lf, stage,
                tdc_status_name(st), tdc_status_text(st));
        exit(1);
    }
}
#endif

static void mode_reset(sim_mode_t *m)
{
    m->lf = 0;
    m->have_hist = 0;
    m->res->resets++;
    memset(m->mvbuf, 0, m->npx * 2 * sizeof(int16_t));
    if (tdc_sim_link_stream(&m->link) != 0) {
        m->res->link_errors++;
    }
#if TDC_SIM_HAVE_TRM
    if (m->use_trm) {
        tdc_trm_reset(&m->trm);
        tdc_trm_reset(&m->trm_r);
    }
#endif
#if TDC_SIM_HAVE_ASM
    if (m->d->kind == TDC_MODE_ASM && m->asm_mem) {
        tdc_asm_config_t ac = {(uint16_t)m->w, (uint16_t)m->h};
        stage_ok(m, "tdc_asm_init", tdc_asm_init(&m->as, &ac, m->asm_mem, m->asm_bytes));
    }
#endif
#if TDC_SIM_HAVE_LCD_FW
    if (m->use_lcd) {
        tdc_lcd_reset(&m->lcd);
    }
#endif
}

#if TDC_SIM_HAVE_ASM
/* Renderer side of one subframe: orderings, sample positions, MVs. */
static void asm_subframe(sim_mode_t *m, tdc_source_t *src, double t, uint32_t lf)
{
    int tx = (m->w + 1) / 2, ty = (m->h + 1) / 2;
    double t0 = now_s();
    if ((lf & 3u) == 0u) {
        size_t nb = ((size_t)tx * ty + 7) / 8;
        if (m->d->ordering < 0) {
            /* the firmware's own decision function, linked by the renderer */
            tdc_ordering_update(m->mvbuf, m->w, m->h, m->pattern, lf);
        } else {
            memset(m->pattern, m->d->ordering ? 0xFF : 0x00, nb);
        }
    }
    int32_t jx, jy;
    tdc_jitter_offset_q4(lf, &jx, &jy);
    int n = 0;
    int pos_x[4] = {0, 1, 0, 1}, pos_y[4] = {0, 0, 1, 1};
    for (int y = 0; y < ty; y++) {
        for (int x = 0; x < tx; x++, n++) {
            tdc_ordering_t o = tdc_ordering_get(m->pattern, (uint32_t)n);
            unsigned pos = tdc_ordering_pixel(o, lf & 3u);
            int px = 2 * x + pos_x[pos], py = 2 * y + pos_y[pos];
            px = px >= m->w ? m->w - 1 : px;
            py = py >= m->h ? m->h - 1 : py;
            int dyn = 0;
            for (int dy = -1; dy <= 1 && !dyn; dy++) {
                for (int dx = -1; dx <= 1; dx++) {
                    int xx = px + dx, yy = py + dy;
                    if (xx >= 0 && yy >= 0 && xx < m->w && yy < m->h) {
                        const int16_t *v = m->mvbuf + 2 * ((size_t)yy * m->w + xx);
                        if (v[0] || v[1]) {
                            dyn = 1;
                            break;
                        }
                    }
                }
            }
            m->xy[2 * n] = px + 0.5 + (dyn ? 0.0 : jx / 16.0);
            m->xy[2 * n + 1] = py + 0.5 + (dyn ? 0.0 : jy / 16.0);
        }
    }
    src->samples(src, t, n, m->xy, 1, m->sub, m->submv, m->fs, m->d->shadow_mv ? TDC_MV_SHADOW : TDC_MV_SURFACE);
    /* the renderer's motion buffer: each pixel keeps its latest sample's MV */
    for (int i = 0; i < n; i++) {
        int px = (int)m->xy[2 * i], py = (int)m->xy[2 * i + 1];
        px = px < 0 ? 0 : (px >= m->w ? m->w - 1 : px);
        py = py < 0 ? 0 : (py >= m->h ? m->h - 1 : py);
        int16_t *v = m->mvbuf + 2 * ((size_t)py * m->w + px);
        v[0] = m->submv[2 * i];
        v[1] = m->submv[2 * i + 1];
    }
    m->res->render_s += now_s() - t0;
    m->res->rays += (uint64_t)n;
    m->res->rendered++;
}
#endif

/* Produces drive codes for the next display frame and shows them. */
#if TDC_SIM_HAVE_TRM
/* The full-resolution frame of a TRM pair (TRM and NCSFI): render, send over
 * the link, run the firmware's full-frame step on what the decoder got. */
static void trm_full_frame(sim_mode_t *m, tdc_source_t *src, double t, int spp, uint32_t lf)
{
    render_full(m, src, t, spp, 0, 0, 0, 0, TDC_MV_SURFACE);
    if (tdc_sim_link_full(&m->link, lf, m->render) == 0) {
        double t0 = now_s();
        stage_ok(m, "tdc_trm_full", tdc_trm_full(&m->trm, m->link.full, (uint32_t)m->w * 3u, m->wanted, (uint32_t)m->w * 3u));
        m->res->fw_s += now_s() - t0;
    }
}
#endif

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
    double fw0 = r->fw_s;
    double dec0 = m->link.decode_s, enc0 = m->link.encode_s;
    double t0;
    int even = (lf & 1u) == 0u;
    switch (m->d->kind) {
    case TDC_MODE_FULL:
        render_full(m, src, t, spp, 0, 0, 0, 0, TDC_MV_SURFACE);
        if (tdc_sim_link_full(&m->link, lf, m->render) == 0) {
            memcpy(m->wanted, m->link.full, m->npx * 3);
        }
        break;
    case TDC_MODE_HALF:
    case TDC_MODE_BFI:
        if (even) {
            render_full(m, src, t, spp, 0, 0, 0, 0, TDC_MV_SURFACE);
            if (tdc_sim_link_full(&m->link, lf, m->render) == 0) {
                memcpy(m->wanted, m->link.full, m->npx * 3);
            }
        } else if (m->d->kind == TDC_MODE_BFI) {
            memset(m->wanted, 0, m->npx * 3); /* the controller inserts black */
        } /* HALF: the controller repeats the last frame */
        break;
    case TDC_MODE_INTERLACE:
        render_rows(m, src, t, spp, (int)(lf & 1u));
        tdc_sim_link_count_raw(&m->link, (size_t)m->w * ((m->h + 1 - (int)(lf & 1u)) / 2) * 3);
        memcpy(m->wanted, m->render, m->npx * 3);
        break;
    case TDC_MODE_NCSFI:
#if TDC_SIM_HAVE_TRM
        if (!m->use_trm) {
            break;
        }
        if (even) {
            trm_full_frame(m, src, t, spp, lf);
        } else {
            /* the blurred frame comes from the same rendered frame */
            t0 = now_s();
            stage_ok(m, "tdc_trm_downsample",
                     tdc_trm_downsample(&m->trm, m->link.full, (uint32_t)m->w * 3u, m->reduced, (uint32_t)m->trm.rw * 3u));
            stage_ok(m, "tdc_trm_reduced",
                     tdc_trm_reduced(&m->trm, m->reduced, (uint32_t)m->trm.rw * 3u, m->wanted, (uint32_t)m->w * 3u));
            r->fw_s += now_s() - t0;
        }
#endif
        break;
    case TDC_MODE_TRM:
#if TDC_SIM_HAVE_TRM
        if (!m->use_trm) {
            break;
        }
        if (even) {
            trm_full_frame(m, src, t, spp, lf);
        } else {
            /* Renderer: full-res render prefiltered by D (TRM §4.3); its cost
             * is counted as the reduced frame's rays (a renderer traces the
             * reduced target with MSAA). */
            uint64_t rays0 = r->rays;
            render_full(m, src, t, spp, 0, 0, 0, 0, TDC_MV_SURFACE);
            uint64_t traced = r->rays - rays0;
            r->rays = rays0 + traced * ((uint64_t)m->trm.rw * m->trm.rh) / m->npx;
            t0 = now_s();
            stage_ok(m, "tdc_trm_downsample",
                     tdc_trm_downsample(&m->trm_r, m->render, (uint32_t)m->w * 3u, m->reduced, (uint32_t)m->trm_r.rw * 3u));
            r->render_s += now_s() - t0;
            if (tdc_sim_link_reduced(&m->link, lf, m->reduced) == 0) {
                t0 = now_s();
                tdc_status_t st = tdc_trm_reduced(&m->trm, m->link.reduced, (uint32_t)m->trm.rw * 3u, m->wanted,
                                                  (uint32_t)m->w * 3u);
                r->fw_s += now_s() - t0;
                if (st != TDC_OK) {
                    r->link_errors++;
                }
            }
        }
#endif
        break;
    case TDC_MODE_ASW:
        if (even || !m->have_hist) {
            render_full(m, src, t, spp, 0, 0, 1, m->fs, TDC_MV_SURFACE);
            memcpy(m->hist, m->render, m->npx * 3);
            m->have_hist = 1;
            if (tdc_sim_link_full(&m->link, lf, m->render) == 0) {
                memcpy(m->wanted, m->link.full, m->npx * 3);
            }
        } else {
            t0 = now_s();
            warp_by_mv(m, m->hist, m->mv, m->tmp);
            r->render_s += now_s() - t0; /* the warp runs on the GPU side */
            if (tdc_sim_link_full(&m->link, lf, m->tmp) == 0) {
                memcpy(m->wanted, m->link.full, m->npx * 3);
            }
        }
        break;
    case TDC_MODE_TAA: {
        static const double halton[8][2] = {{0.0, -0.1667}, {-0.25, 0.1667}, {0.25, -0.3889}, {-0.375, -0.0556},
                                            {0.125, 0.2778}, {-0.125, -0.2778}, {0.375, 0.0556}, {-0.4375, 0.3889}};
        render_full(m, src, t, 1, halton[lf & 7u][0], halton[lf & 7u][1], 1, m->fs, TDC_MV_SURFACE);
        t0 = now_s();
        taa_resolve(m);
        r->render_s += now_s() - t0;
        if (tdc_sim_link_full(&m->link, lf, m->hist) == 0) {
            memcpy(m->wanted, m->link.full, m->npx * 3);
        }
        break;
    }
    case TDC_MODE_ASM:
#if TDC_SIM_HAVE_ASM
        if (m->asm_mem) {
            if (src->subframe) {
                uint64_t rays = 0;
                double t1 = now_s();
                if (src->subframe(src, m->slot, m->d->shadow_mv, lf, t, m->fs, m->sub, m->submv, m->pattern, &rays)) {
                    r->link_errors++;
                }
                r->render_s += now_s() - t1;
                r->rays += rays;
                r->rendered++;
            } else {
                asm_subframe(m, src, t, lf);
            }
            if (tdc_sim_link_subframe(&m->link, lf, m->sub, m->submv, (lf & 3u) == 0u ? m->pattern : NULL) == 0) {
                t0 = now_s();
                stage_ok(m, "tdc_asm_ingest",
                         tdc_asm_ingest(&m->as, lf, m->link.subframe, m->link.sample_motion,
                                        (lf & 3u) == 0u ? m->link.pattern : NULL));
                stage_ok(m, "tdc_asm_assemble", tdc_asm_assemble(&m->as, lf));
                int stride;
                const uint8_t *o = tdc_asm_output(&m->as, &stride);
                for (int y = 0; y < m->h; y++) {
                    memcpy(m->wanted + (size_t)y * m->w * 3, o + (size_t)y * stride, (size_t)m->w * 3);
                }
                r->fw_s += now_s() - t0;
            }
        }
#endif
        break;
    }
    /* LCD: TRM's wanted codes -> drive codes (overdrive-aware inverse). */
    memcpy(m->out, m->wanted, m->npx * 3);
#if TDC_SIM_HAVE_LCD_FW
    if (m->use_lcd) {
        tdc_res_t *rho = NULL;
#if TDC_SIM_HAVE_TRM
        if (m->use_trm) {
            rho = tdc_trm_residual(&m->trm);
        }
#endif
        t0 = now_s();
        stage_ok(m, "tdc_lcd_frame", tdc_lcd_frame(&m->lcd, m->wanted, (uint32_t)m->w * 3u, m->out, (uint32_t)m->w * 3u, rho));
        r->fw_s += now_s() - t0;
    }
#endif
    r->fw_s += m->link.decode_s - dec0;
    r->render_s += m->link.encode_s - enc0;
    (void)fw0;
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
    for (int i = 0; i < nmodes; i++) {
        if (mode_init(&ms[i], modes[i], &results[i], cfg, gamma, W, lcd_panel ? lcd_panel : fw_panel, lcd_panel,
                      src->full_frame != NULL, src->subframe != NULL)) {
            fprintf(stderr, "tdc-sim: out of memory setting up mode %s\n", modes[i]->name);
            rc = -1;
        }
        ms[i].slot = i;
        if (src->note && src->full_frame) {
            note(&ms[i], src->note);
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
            while (m->frame * m->fs < te - 1e-12) {
                mode_display_frame(m, src, spp);
            }
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
        if (cfg->progress && (j % ((nevals + 99) / 100) == 0 || j == nevals - 1)) {
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
