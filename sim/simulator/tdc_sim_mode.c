/* tdc_sim_mode.c - helpers the mode families share (see tdc_sim_mode.h). */
#include "simulator/tdc_sim_mode.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

#include "tdc_status.h"
#include "tdc_ordering.h"

double tdc_sim_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts); /* CPU time: robust to a loaded host */
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void tdc_sim_note(sim_mode_t *m, const char *s)
{
    size_t l = strlen(m->res->note);
    if (l + strlen(s) + 3 < sizeof(m->res->note)) {
        snprintf(m->res->note + l, sizeof(m->res->note) - l, "%s%s", l ? "; " : "", s);
    }
}

int tdc_sim_stage(sim_mode_t *m, const char *stage, int status)
{
    if (status == 0) {
        return 0;
    }
    if (!m->failed) {
        /* firmware stages (tdc_*) return a tdc_status_t; the renderer and the
         * link wrappers return -1 */
        char eye[16] = "";
        if (m->eyes == 2) {
            snprintf(eye, sizeof(eye), " eye %d", m->eye);
        }
        int fw = strncmp(stage, "tdc_", 4) == 0;
        fprintf(stderr, "tdc-sim: mode %s: frame %u%s: stage %s: %s (%s)\n", m->d->name, (unsigned)m->frame, eye, stage,
                fw ? tdc_status_name((tdc_status_t)status) : "failed",
                fw ? tdc_status_text((tdc_status_t)status) : "returned an error");
    }
    m->failed = 1;
    return status;
}

void tdc_sim_refuse(sim_mode_t *m, const char *what, int status)
{
    char b[160];
    snprintf(b, sizeof(b), "%s refused the configuration (%s)", what, tdc_status_name((tdc_status_t)status));
    tdc_sim_note(m, b);
    m->res->available = 0;
    m->res->refused = status ? status : -1;
}

void tdc_sim_render_full(sim_mode_t *m, tdc_source_t *src, double t, int spp, double jx, double jy, int16_t *mv,
                         double dt, tdc_mv_kind_t kind)
{
    if (src->full_frame) {
        /* a renderer tracing whole frames (Embree): its own timing and rays */
        uint64_t rays = 0;
        double ms = 0.0;
        double t1 = tdc_sim_now();
        if (src->jitter) {
            src->jitter(src, jx, jy);
        }
        src->full_frame(src, t, mv ? dt : 0.0, m->render, mv, &rays, &ms);
        m->res->render_s += tdc_sim_now() - t1;
        m->res->rays += rays;
        m->res->rendered++;
        return;
    }
    double t0 = tdc_sim_now();
    if (!mv && src->frame && src->frame(src, t, jx, jy, spp, m->render, m->scratch) == 0) {
        /* the source's whole-frame path (tabulated, threaded) */
        m->res->render_s += tdc_sim_now() - t0;
        m->res->rays += (uint64_t)m->npx * (uint64_t)(spp < 1 ? 1 : spp);
        m->res->rendered++;
        return;
    }
    for (int y = 0; y < m->h; y++) {
        for (int x = 0; x < m->w; x++) {
            size_t i = (size_t)y * m->w + x;
            m->xy[2 * i] = x + 0.5 + jx;
            m->xy[2 * i + 1] = y + 0.5 + jy;
        }
    }
    src->samples(src, t, (int)m->npx, m->xy, spp, m->render, mv, dt, kind);
    m->res->render_s += tdc_sim_now() - t0;
    m->res->rays += (uint64_t)m->npx * (uint64_t)(spp < 1 ? 1 : spp);
    m->res->rendered++;
}

void tdc_sim_render_rows(sim_mode_t *m, tdc_source_t *src, double t, int spp, int parity, uint8_t *tmp)
{
    if (src->full_frame) {
        /* whole-frame renderer: trace the frame, keep the field's rows;
         * rays are counted for the field only (a renderer restricted to
         * those rows would trace that many) */
        tdc_sim_render_full(m, src, t, spp, 0, 0, NULL, 0, TDC_MV_SURFACE);
        m->res->rays -= m->res->rays ? (uint64_t)m->w * (m->h / 2) : 0;
        for (int y = 1 - parity; y < m->h; y += 2) {
            memset(m->render + (size_t)y * m->w * 3, 0, (size_t)m->w * 3);
        }
        return;
    }
    double t0 = tdc_sim_now();
    int n = 0;
    for (int y = parity; y < m->h; y += 2) {
        for (int x = 0; x < m->w; x++) {
            m->xy[2 * n] = x + 0.5;
            m->xy[2 * n + 1] = y + 0.5;
            n++;
        }
    }
    src->samples(src, t, n, m->xy, spp, tmp, NULL, 0.0, TDC_MV_SURFACE);
    memset(m->render, 0, m->npx * 3);
    int k = 0;
    for (int y = parity; y < m->h; y += 2) {
        memcpy(m->render + (size_t)y * m->w * 3, tmp + (size_t)k * m->w * 3, (size_t)m->w * 3);
        k++;
    }
    m->res->render_s += tdc_sim_now() - t0;
    m->res->rays += (uint64_t)n * (uint64_t)(spp < 1 ? 1 : spp);
    m->res->rendered++;
}

int tdc_sim_send_full(sim_mode_t *m, uint32_t lf, const uint8_t *rgb)
{
    int st = tdc_sim_stage(m, "link FULL packet", tdc_sim_link_full(m->link, m->eye, lf, rgb));
    if (st == 0) {
        memcpy(m->wanted, TDC_SIM_LINK_FULL(m), m->npx * 3);
    }
    return st;
}

uint8_t tdc_sim_to8(double v)
{
    v += 0.5;
    return (uint8_t)(v <= 0 ? 0 : (v >= 255 ? 255 : (int)v));
}

int tdc_sim_subframe_xy(sim_mode_t *m, const int16_t *mvbuf, const uint8_t *pattern, uint32_t lf, int radius)
{
    const int tx = (m->w + 1) / 2, ty = (m->h + 1) / 2;
    int32_t jx, jy;
    tdc_jitter_offset_q4(lf, &jx, &jy);
    int n = 0;
    static const int pos_x[4] = {0, 1, 0, 1}, pos_y[4] = {0, 0, 1, 1};
    for (int y = 0; y < ty; y++) {
        for (int x = 0; x < tx; x++, n++) {
            tdc_ordering_t o = tdc_ordering_get(pattern, (uint32_t)n);
            unsigned pos = tdc_ordering_pixel(o, lf & 3u);
            int px = 2 * x + pos_x[pos], py = 2 * y + pos_y[pos];
            px = px >= m->w ? m->w - 1 : px;
            py = py >= m->h ? m->h - 1 : py;
            int dyn = 0;
            for (int dy = -radius; dy <= radius && !dyn; dy++) {
                for (int dx = -radius; dx <= radius; dx++) {
                    int xx = px + dx, yy = py + dy;
                    if (xx >= 0 && yy >= 0 && xx < m->w && yy < m->h) {
                        const int16_t *v = mvbuf + 2 * ((size_t)yy * m->w + xx);
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
    return n;
}

void tdc_sim_subframe_keep_mv(sim_mode_t *m, int16_t *mvbuf, int n, const int16_t *mv)
{
    for (int i = 0; i < n; i++) {
        int px = (int)m->xy[2 * i], py = (int)m->xy[2 * i + 1];
        px = px < 0 ? 0 : (px >= m->w ? m->w - 1 : px);
        py = py < 0 ? 0 : (py >= m->h ? m->h - 1 : py);
        int16_t *v = mvbuf + 2 * ((size_t)py * m->w + px);
        v[0] = mv[2 * i];
        v[1] = mv[2 * i + 1];
    }
}
