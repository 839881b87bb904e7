/*
 * tdc_sim_mode_warp.c - the GPU-side reprojection baselines: ASW-style
 * extrapolation (half rate, the in-between frame warped by the renderer's
 * exact motion vectors, `asw`, or by motion block-matched between the last
 * two decoded frames, `asw-est`, as a compositor without the renderer's
 * vectors must: tdc_sim_blockmatch.h) and TAA (jittered 1 spp, history reprojected by the MVs, clamped
 * to the current 3x3 neighbourhood, blended 0.9 / 0.1).  Both run on the
 * renderer side (their time counts as render time); the link carries full
 * frames.
 */
#include <stdlib.h>
#include <string.h>

#include "simulator/tdc_sim_blockmatch.h"
#include "simulator/tdc_sim_mode.h"
#include "tdc_bilinear.h"
#include "tdc_free.h"

enum { WARP_ASW, WARP_TAA, WARP_ASW_EST, WARP_JITTER };

#define F &tdc_sim_family_warp
static const tdc_mode_desc_t k_modes[] = {
    {"asw", F, WARP_ASW, 0, 1, 1, 0, 0, 0, "half rate, in-between frame warped by motion vectors (ASW style)"},
    {"asw-est", F, WARP_ASW_EST, 0, 1, 1, 0, 0, 0,
     "half rate, in-between frame warped by motion block-matched on the last two decoded frames"},
    {"taa60", F, WARP_TAA, 0, 1, 1, 60, 0, 0, "60 Hz, jittered 1 spp with TAA (reprojection, clamp, blend 0.1)"},
    {"taa", F, WARP_TAA, 0, 1, 1, 0, 0, 0, "the run's refresh, jittered 1 spp with TAA (as taa60)"},
    {"taa120", F, WARP_TAA, 0, 1, 1, 120, 0, 0, "120 Hz, jittered 1 spp with TAA (as taa60)"},
    {"taa80", F, WARP_TAA, 0, 1, 1, 80, 0, 0, "80 Hz, jittered 1 spp with TAA (as taa60)"},
    {"jitter1", F, WARP_JITTER, 0, 1, 1, 0, 0, 0,
     "the run's refresh, 1 spp at the 4x MSAA pattern's positions in turn, shown as rendered (TDRT Fig. 1)"},
};
#undef F

typedef struct {
    uint8_t *hist, *tmp; /* last frame / TAA history; the warped or resolved frame */
    int16_t *mv;         /* backward MVs of the last rendered frame, Q4 */
    int have_hist;
    /* asw-est: the decoded frame before the last one, and the estimator */
    uint8_t *prev;
    int have_prev;
    tdc_bm_t bm;
} warp_state_t;

static int warp_init(sim_mode_t *m, const tdc_sim_setup_t *s)
{
    (void)s;
    warp_state_t *st = calloc(1, sizeof(*st));
    if (!st) {
        return -1;
    }
    m->fam = st;
    st->hist = calloc(m->npx * 3, 1);
    st->tmp = calloc(m->npx * 3, 1);
    st->mv = calloc(m->npx * 2, sizeof(int16_t));
    if (m->d->variant == WARP_ASW_EST) {
        st->prev = calloc(m->npx * 3, 1);
        if (!st->prev || tdc_bm_init(&st->bm, m->w, m->h) != 0) {
            return -1;
        }
    }
    return st->hist && st->tmp && st->mv ? 0 : -1;
}

/* ASW-style extrapolation: the content at p next frame came from p + mv. */
static void warp_by_mv(const sim_mode_t *m, const uint8_t *src, const int16_t *mv, uint8_t *dst)
{
    for (int y = 0; y < m->h; y++) {
        for (int x = 0; x < m->w; x++) {
            size_t i = (size_t)y * m->w + x;
            double sx = x + mv[2 * i] / 16.0, sy = y + mv[2 * i + 1] / 16.0;
            for (int c = 0; c < 3; c++) {
                dst[3 * i + c] = tdc_sim_to8(tdc_bilinear_u8(src, m->w, m->h, 3, sx, sy, c));
            }
        }
    }
}

/* TAA resolve: history reprojected by the MV, clamped to the current 3x3
 * min/max, blended 0.9 history + 0.1 current (code space). */
static void taa_resolve(sim_mode_t *m, warp_state_t *st)
{
    for (int y = 0; y < m->h; y++) {
        for (int x = 0; x < m->w; x++) {
            size_t i = (size_t)y * m->w + x;
            for (int c = 0; c < 3; c++) {
                double cur = m->render[3 * i + c];
                if (!st->have_hist) {
                    st->tmp[3 * i + c] = (uint8_t)cur;
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
                double hv =
                    tdc_bilinear_u8(st->hist, m->w, m->h, 3, x + st->mv[2 * i] / 16.0, y + st->mv[2 * i + 1] / 16.0, c);
                hv = hv < lo ? lo : (hv > hi ? hi : hv);
                st->tmp[3 * i + c] = tdc_sim_to8(0.9 * hv + 0.1 * cur);
            }
        }
    }
    memcpy(st->hist, st->tmp, m->npx * 3);
    st->have_hist = 1;
}

static int warp_frame(sim_mode_t *m, tdc_source_t *src, double t, int spp, uint32_t lf)
{
    warp_state_t *st = m->fam;
    double t0;
    if (m->d->variant == WARP_TAA) {
        static const double halton[8][2] = {{0.0, -0.1667},  {-0.25, 0.1667},   {0.25, -0.3889}, {-0.375, -0.0556},
                                            {0.125, 0.2778}, {-0.125, -0.2778}, {0.375, 0.0556}, {-0.4375, 0.3889}};
        tdc_sim_render_full(m, src, t, 1, halton[lf & 7u][0], halton[lf & 7u][1], st->mv, m->fs, TDC_MV_SURFACE);
        t0 = tdc_sim_now();
        taa_resolve(m, st);
        m->res->render_s += tdc_sim_now() - t0;
        return tdc_sim_send_full(m, lf, st->hist);
    }
    if (m->d->variant == WARP_JITTER) {
        /* the standard 4x MSAA sample positions (D3D: (-2,-6), (6,-2), (-6,2), (2,6) / 16 px), one
         * per refresh, no history: the eye integrates them (TDRT §2, Fig. 1) */
        static const double msaa4[4][2] = {{-0.125, -0.375}, {0.375, -0.125}, {-0.375, 0.125}, {0.125, 0.375}};
        tdc_sim_render_full(m, src, t, 1, msaa4[lf & 3u][0], msaa4[lf & 3u][1], NULL, 0, TDC_MV_SURFACE);
        return tdc_sim_send_full(m, lf, m->render);
    }
    if (m->d->variant == WARP_JITTER) {
        /* the standard 4x MSAA sample positions (D3D: (-2,-6), (6,-2), (-6,2), (2,6) / 16 px), one
         * per refresh, no history: the eye integrates them (TDRT §2, Fig. 1) */
        static const double msaa4[4][2] = {{-0.125, -0.375}, {0.375, -0.125}, {-0.375, 0.125}, {0.125, 0.375}};
        tdc_sim_render_full(m, src, t, 1, msaa4[lf & 3u][0], msaa4[lf & 3u][1], NULL, 0, TDC_MV_SURFACE);
        return tdc_sim_send_full(m, lf, m->render);
    }
    if (m->d->variant == WARP_ASW_EST) {
        if ((lf & 1u) == 0u || !st->have_hist) {
            /* no motion vectors asked of the renderer: the compositor has none */
            tdc_sim_render_full(m, src, t, spp, 0, 0, NULL, 0, TDC_MV_SURFACE);
            int rc = tdc_sim_send_full(m, lf, m->render);
            if (st->have_hist) {
                memcpy(st->prev, st->hist, m->npx * 3);
                st->have_prev = 1;
            }
            memcpy(st->hist, TDC_SIM_LINK_FULL(m), m->npx * 3); /* the decoded frame */
            st->have_hist = 1;
            return rc;
        }
        if (!st->have_prev) { /* one frame so far: nothing to match, repeat it */
            return tdc_sim_send_full(m, lf, st->hist);
        }
        t0 = tdc_sim_now();
        /* two frames apart: half the vector extrapolates one frame */
        tdc_bm_estimate(&st->bm, st->prev, st->hist, 0.5, st->mv);
        warp_by_mv(m, st->hist, st->mv, st->tmp);
        m->res->render_s += tdc_sim_now() - t0; /* the compositor's GPU time */
        return tdc_sim_send_full(m, lf, st->tmp);
    }
    if ((lf & 1u) == 0u || !st->have_hist) {
        tdc_sim_render_full(m, src, t, spp, 0, 0, st->mv, m->fs, TDC_MV_SURFACE);
        memcpy(st->hist, m->render, m->npx * 3);
        st->have_hist = 1;
        return tdc_sim_send_full(m, lf, m->render);
    }
    t0 = tdc_sim_now();
    warp_by_mv(m, st->hist, st->mv, st->tmp);
    m->res->render_s += tdc_sim_now() - t0; /* the warp runs on the GPU side */
    return tdc_sim_send_full(m, lf, st->tmp);
}

static void warp_reset(sim_mode_t *m)
{
    ((warp_state_t *)m->fam)->have_hist = 0;
    ((warp_state_t *)m->fam)->have_prev = 0;
}

static void warp_free(sim_mode_t *m)
{
    warp_state_t *st = m->fam;
    if (st) {
        TDC_FREE_ALL(st->hist, st->tmp, st->mv, st->prev);
        tdc_bm_free(&st->bm);
        free(st);
    }
    m->fam = NULL;
}

const tdc_sim_family_t tdc_sim_family_warp = {
    "warp", k_modes, (int)(sizeof(k_modes) / sizeof(k_modes[0])), warp_init, warp_frame, warp_reset, warp_free,
};
