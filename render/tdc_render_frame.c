/*
 * tdc_render_frame.c - one refresh: sample placement per mode (full,
 * reduced, subframe, ground truth), tiles distributed over pthreads, the
 * passes of tdc_render_trace.c, output packing (Q4 MVs, MV history), the
 * Gaussian resolve of reduced frames, per-stage timings and ray counts.
 * Stages a scene or frame does not need are not entered (0 ms, ran = 0).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_ordering.h"
#include "tdc_png.h"
#include "tdc_render_trace.h"

typedef struct {
    tdc_render_t *r;
    tdc_render_mode_t mode;
    uint32_t frame;
    int sw, sh;       /* slot grid */
    int spp;          /* samples per slot */
    int tile, tile_h; /* tile width and height in slots */
    int ntx, nty;
    /* atomic work counter on a cache line of its own: each add would
     * otherwise take the line holding the fields the other thread reads */
    _Alignas(64) int next;
    char next_pad[60];
    int32_t jx, jy; /* subframe static jitter, Q4 */
    int do_reflect, do_mv, do_mv_reflect, do_mv_shadow, do_mv_dual, frame_static, do_layers, do_indirect;
    float *cone_cur;
    const float *cone_prev;
    tdc_r_gpix_t *gb_cur;       /* FULL frames with dual or shadow MVs: this frame's G-buffer, written per sample */
    const tdc_r_gpix_t *gb_prev; /* the previous frame's, read by the dual and shadow passes (NULL: they trace) */
    int ndual_rect; /* dual-MV culling rectangles (rthread_t), -1 = none */
    float dual_rect[TDC_SCENE_MAX_OBJECTS][4];
    const tdc_render_out_t *out;
    float *ss; /* reduced: supersample buffer sw*sh*3; GT: accumulation target */
    int record;
} job_t;

typedef struct {
    _Alignas(64) job_t *job; /* whole cache lines per worker: th (ray counts, */
    rthread_t th;            /* stage ticks) is written per ray and per stage */
    rsample_t *s;
    pthread_t tid;
} worker_t;

/* round(v * 16) half up, clamped; floor without a libm call (x86-64
 * baseline has no SSE4.1 round instruction).  f is clamped to
 * [-32767, 32767] first, so its floor is in range too. */
static inline int16_t q4(double v)
{
    double f = v * 16 + 0.5;
    if (f > 32767) f = 32767;
    if (!(f >= -32767)) f = -32767; /* also NaN */
    long i = (long)f;
    return (int16_t)(i - (i > f));
}

/* 1 if any MV in the 3x3 pixel neighbourhood of (x, y) in the history (as
 * it was before this frame) is non-zero. */
static int hist_dynamic(const tdc_render_t *r, int x, int y)
{
    for (int j = y - 1; j <= y + 1; j++) {
        if (j < 0 || j >= r->H) continue;
        for (int i = x - 1; i <= x + 1; i++) {
            if (i < 0 || i >= r->W) continue;
            const int16_t *m = &r->mv_hist_prev[((size_t)j * r->W + i) * 2];
            if (m[0] || m[1]) return 1;
        }
    }
    return 0;
}

static int place_samples(job_t *jb, int tx, int ty, rsample_t *s)
{
    tdc_render_t *r = jb->r;
    int n = 0;
    int x0 = tx * jb->tile, y0 = ty * jb->tile_h;
    int x1 = x0 + jb->tile < jb->sw ? x0 + jb->tile : jb->sw;
    int y1 = y0 + jb->tile_h < jb->sh ? y0 + jb->tile_h : jb->sh;
    if (jb->mode == TDC_RENDER_FULL) { /* the common case without the per-slot switch */
        for (int sy = y0; sy < y1; sy++)
            for (int sx = x0; sx < x1; sx++) {
                s[n].x = sx + 0.5f + r->full_jx;
                s[n].y = sy + 0.5f + r->full_jy;
                s[n].px = sx;
                s[n].py = sy;
                s[n].dst = (uint32_t)sy * (uint32_t)jb->sw + (uint32_t)sx;
                s[n].k = 0;
                n++;
            }
        return n;
    }
    if (jb->mode == TDC_RENDER_FOVEATED) { /* one row of sample positions */
        for (int sx = x0; sx < x1; sx++) {
            const float x = r->fov_xy[2 * sx], y = r->fov_xy[2 * sx + 1];
            int px = (int)floorf(x), py = (int)floorf(y); /* random-number key: the pixel it falls in */
            s[n].x = x;
            s[n].y = y;
            s[n].px = px < 0 ? 0 : px >= r->W ? r->W - 1 : px;
            s[n].py = py < 0 ? 0 : py >= r->H ? r->H - 1 : py;
            s[n].dst = (uint32_t)sx;
            s[n].k = 0;
            n++;
        }
        return n;
    }
    for (int sy = y0; sy < y1; sy++)
        for (int sx = x0; sx < x1; sx++) {
            uint32_t slot = (uint32_t)sy * (uint32_t)jb->sw + (uint32_t)sx;
            switch (jb->mode) {
            case TDC_RENDER_FULL:
                s[n].x = sx + 0.5f;
                s[n].y = sy + 0.5f;
                s[n].px = sx;
                s[n].py = sy;
                s[n].dst = slot;
                s[n].k = 0;
                n++;
                break;
            case TDC_RENDER_SUBFRAME: {
                tdc_ordering_t o = tdc_ordering_get(r->pattern, slot);
                unsigned p = tdc_ordering_pixel(o, jb->frame & 3u);
                int px = 2 * sx + (int)(p & 1u), py = 2 * sy + (int)(p >> 1);
                if (px >= r->W) px = r->W - 1; /* partial tile at an odd size */
                if (py >= r->H) py = r->H - 1;
                int dyn = hist_dynamic(r, px, py);
                s[n].x = px + 0.5f + (dyn ? 0.0f : jb->jx / 16.0f);
                s[n].y = py + 0.5f + (dyn ? 0.0f : jb->jy / 16.0f);
                s[n].px = px;
                s[n].py = py;
                s[n].dst = slot;
                s[n].k = 0;
                n++;
                break;
            }
            case TDC_RENDER_REDUCED:
                /* a regular supersample grid (MSAA-like, TRM §4.3); jitter
                 * would turn resolved detail into noise the resolve cannot
                 * remove as well as it removes a regular pattern */
                s[n].x = (float)((sx + 0.5) * r->W / jb->sw);
                s[n].y = (float)((sy + 0.5) * r->H / jb->sh);
                s[n].px = sx; /* random-number key only: no MV history in this mode */
                s[n].py = sy;
                s[n].dst = slot;
                s[n].k = 0;
                n++;
                break;
            case TDC_RENDER_FOVEATED: /* placed above */ break;
            case TDC_RENDER_GROUND_TRUTH: {
                int N = jb->spp, g = (int)floor(sqrt((double)N));
                for (int k = 0; k < N; k++) {
                    double ox, oy;
                    double u1 = tdc_r_rand(r->cfg.seed, jb->frame, slot, (uint32_t)k, 0);
                    double u2 = tdc_r_rand(r->cfg.seed, jb->frame, slot, (uint32_t)k, 1);
                    if (g * g == N) { /* jittered grid */
                        ox = (k % g + u1) / g;
                        oy = (k / g + u2) / g;
                    } else { /* Latin hypercube: 7919 is prime > N, so k -> 7919 k mod N permutes */
                        ox = (k + u1) / N;
                        oy = ((int)(((long)k * 7919 + slot) % N) + u2) / N;
                    }
                    s[n].x = (float)(sx + ox);
                    s[n].y = (float)(sy + oy);
                    s[n].px = sx;
                    s[n].py = sy;
                    s[n].dst = slot;
                    s[n].k = (uint32_t)k;
                    n++;
                }
                break;
            }
            }
        }
    return n;
}

/* Stage timing with one clock read per stage: the time from the previous
 * stamp (t_) to the end of the call goes to the stage, so consecutive
 * stages share their boundary stamp.  The stamps are time-stamp-counter
 * ticks on x86 (a few ns; clock_gettime cost ~1 % of a cheap scene's frame
 * at a handful of reads per tile), turned into ms after the workers finish
 * with the ticks per ms of the whole worker span (wall clock). */
#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
static inline uint64_t stamp(void)
{
    return __rdtsc();
}
#else
static inline uint64_t stamp(void)
{
    return (uint64_t)(tdc_r_now_ms() * 1e6);
} /* ns */
#endif
#define TIMED(th, stage, call)          \
    do {                                \
        call;                           \
        uint64_t t1_ = stamp();         \
        (th)->ticks[stage] += t1_ - t_; \
        t_ = t1_;                       \
    } while (0)

static void write_rare(job_t *jb, const rsample_t *s, int n, int depth);

/* The layer outputs of FULL, SUBFRAME and FOVEATED samples (Zeng §4). */
static void write_layers(job_t *jb, const rsample_t *s, int n)
{
    const tdc_render_out_t *o = jb->out;
    for (int i = 0; i < n; i++) {
        const rsample_t *a = &s[i];
        size_t d = a->dst;
        if (o->shade)
            for (int c = 0; c < 3; c++) o->shade[d * 3 + c] = (float)a->lshade[c];
        if (o->vis) o->vis[d] = (float)a->vis;
        if (o->refl)
            for (int c = 0; c < 3; c++) o->refl[d * 3 + c] = (float)a->refl[c];
        /* the primary MV (mv holds the reflected one where refl_used) */
        double ms0 = 0, ms1 = 0, mr0 = 0, mr1 = 0;
        if (jb->do_mv) {
            ms0 = a->refl_used ? a->mvsurf[0] : a->mv[0];
            ms1 = a->refl_used ? a->mvsurf[1] : a->mv[1];
            int rok = jb->do_mv_reflect && a->mvr_ok;
            mr0 = rok ? a->mvr[0] : ms0;
            mr1 = rok ? a->mvr[1] : ms1;
        }
        if (o->mv_surf) {
            o->mv_surf[d * 2] = q4(ms0);
            o->mv_surf[d * 2 + 1] = q4(ms1);
        }
        if (o->mv_refl) {
            o->mv_refl[d * 2] = q4(mr0);
            o->mv_refl[d * 2 + 1] = q4(mr1);
        }
        if (o->shadow_src) o->shadow_src[d] = (uint8_t)(jb->do_mv_shadow && a->in_shadow);
        if (o->indirect)
            for (int c = 0; c < 3; c++) o->indirect[d * 3 + c] = jb->do_indirect ? (float)a->ind[c] : 0.0f;
    }
}

static void write_outputs(job_t *jb, const rsample_t *s, int n)
{
    tdc_render_t *r = jb->r;
    const tdc_render_out_t *o = jb->out;
    if (jb->mode == TDC_RENDER_REDUCED) {
        for (int i = 0; i < n; i++)
            for (int c = 0; c < 3; c++) jb->ss[(size_t)s[i].dst * 3 + c] = (float)s[i].col[c];
        return;
    }
    if (jb->mode == TDC_RENDER_GROUND_TRUTH) {
        /* all samples of a slot are in this tile, in k order: deterministic */
        for (int i = 0; i < n; i++) {
            float *d = &jb->ss[(size_t)s[i].dst * 3];
            if (s[i].k == 0) d[0] = d[1] = d[2] = 0;
            for (int c = 0; c < 3; c++) d[c] += (float)(s[i].col[c] / jb->spp);
        }
        return;
    }
    if (jb->mode == TDC_RENDER_FOVEATED) { /* samples, not pixels: no MV history */
        for (int i = 0; i < n; i++) {
            const rsample_t *a = &s[i];
            if (o->rgb)
                for (int c = 0; c < 3; c++) o->rgb[(size_t)a->dst * 3 + c] = (float)a->col[c];
            if (o->mv) {
                o->mv[(size_t)a->dst * 2] = jb->do_mv ? q4(a->mv[0]) : 0;
                o->mv[(size_t)a->dst * 2 + 1] = jb->do_mv ? q4(a->mv[1]) : 0;
            }
            if (o->depth) o->depth[a->dst] = (float)a->depth;
        }
        /* layers, shadow and dual MVs of the samples (tdc_render_set_samples) */
        if (jb->do_layers) write_layers(jb, s, n);
        if (o->mv_shadow || o->shadow_weight || o->mv_dual || o->mv_f) write_rare(jb, s, n, 0);
        return;
    }
    /* the common outputs in a loop of their own, without per-sample tests */
    float *rgb = o->rgb;
    int16_t *mv = o->mv, *hist = r->mv_hist;
    size_t W = (size_t)r->W;
    if (rgb)
        for (int i = 0; i < n; i++) {
            float *p = &rgb[(size_t)s[i].dst * 3];
            p[0] = (float)s[i].col[0];
            p[1] = (float)s[i].col[1];
            p[2] = (float)s[i].col[2];
        }
    if (jb->do_mv) {
        for (int i = 0; i < n; i++) {
            const rsample_t *a = &s[i];
            int16_t m0 = 0, m1 = 0; /* q4(+-0) = 0: no conversions for the many pixels that did not move */
            if (a->mv[0] != 0 || a->mv[1] != 0) {
                m0 = q4(a->mv[0]);
                m1 = q4(a->mv[1]);
            }
            int16_t *h = &hist[((size_t)a->py * W + (size_t)a->px) * 2];
            h[0] = m0;
            h[1] = m1;
            if (mv) {
                mv[(size_t)a->dst * 2] = m0;
                mv[(size_t)a->dst * 2 + 1] = m1;
            }
        }
    } else {
        for (int i = 0; i < n; i++) {
            const rsample_t *a = &s[i];
            int16_t *h = &hist[((size_t)a->py * W + (size_t)a->px) * 2];
            h[0] = h[1] = 0;
            if (mv) mv[(size_t)a->dst * 2] = mv[(size_t)a->dst * 2 + 1] = 0;
        }
    }
    if (jb->gb_cur) /* the next frame's eq. 6 lookup */
        for (int i = 0; i < n; i++) {
            tdc_r_gpix_t *g = &jb->gb_cur[(size_t)s[i].py * W + (size_t)s[i].px];
            g->depth = (float)s[i].depth;
            g->obj = s[i].obj;
        }
    if (jb->do_layers) write_layers(jb, s, n);
    if (!o->depth && !o->mv_f && !o->mv_shadow && !o->shadow_weight && !o->mv_dual) return;
    write_rare(jb, s, n, 1);
}

/* Depth, float MVs, shadow MVs and weights, dual MVs. */
static void write_rare(job_t *jb, const rsample_t *s, int n, int depth)
{
    const tdc_render_out_t *o = jb->out;
    for (int i = 0; i < n; i++) {
        const rsample_t *a = &s[i];
        size_t d = a->dst;
        if (o->depth && depth) o->depth[d] = (float)a->depth;
        int16_t m0 = 0, m1 = 0;
        if (jb->do_mv) {
            m0 = q4(a->mv[0]);
            m1 = q4(a->mv[1]);
        }
        if (o->mv_f) {
            o->mv_f[d * 2] = jb->do_mv ? (float)a->mv[0] : 0;
            o->mv_f[d * 2 + 1] = jb->do_mv ? (float)a->mv[1] : 0;
        }
        if (o->mv_shadow) {
            o->mv_shadow[d * 2] = jb->do_mv_shadow ? q4(a->mvs[0]) : m0;
            o->mv_shadow[d * 2 + 1] = jb->do_mv_shadow ? q4(a->mvs[1]) : m1;
        }
        if (o->shadow_weight) o->shadow_weight[d] = jb->do_mv_shadow ? (float)a->sw : 0;
        if (o->mv_dual) {
            o->mv_dual[d * 2] = jb->do_mv_dual ? q4(a->mvd[0]) : m0;
            o->mv_dual[d * 2 + 1] = jb->do_mv_dual ? q4(a->mvd[1]) : m1;
        }
    }
}

static void *worker_main(void *arg)
{
    worker_t *w = arg;
    job_t *jb = w->job;
    rthread_t *th = &w->th;
    int ntiles = jb->ntx * jb->nty;
    /* tiles are taken a row of tiles at a time: threads then never write
     * the same output cache lines (8x8 tiles of different threads side by
     * side shared lines of the rgb, MV and history rows: 2 threads cost
     * ~20 % more CPU than 1), and the locked add, which waits for the
     * previous tile's output stores to drain, is rare */
    int ti = 0, left = 0, grab = jb->ntx;
    for (;; ti++, left--) {
        if (!left) {
            ti = __atomic_fetch_add(&jb->next, grab, __ATOMIC_RELAXED);
            left = grab;
        }
        if (ti >= ntiles) break;
        rsample_t *s = w->s;
        int n = place_samples(jb, ti % jb->ntx, ti / jb->ntx, s);
        for (int i = 0; i < n; i++) /* the sample's ray cone (FOVEATED: its log-polar LOD) */
            s[i].cone_k = jb->mode == TDC_RENDER_FOVEATED && jb->r->fov_cone ? jb->r->fov_cone[s[i].dst] : 1.0f;
        uint64_t t_ = stamp();
        TIMED(th, TDC_STAGE_PRIMARY, tdc_r_pass_primary(th, s, n));
        TIMED(th, TDC_STAGE_SHADE, tdc_r_pass_shade(th, s, n));
        if (jb->do_reflect) TIMED(th, TDC_STAGE_REFLECT, tdc_r_pass_reflect(th, s, n));
        if (jb->do_mv) TIMED(th, TDC_STAGE_MV, tdc_r_pass_mv(th, s, n));
        if (jb->do_mv_reflect) TIMED(th, TDC_STAGE_MV_REFLECT, tdc_r_pass_mv_reflect(th, s, n));
        if (jb->do_mv_shadow) TIMED(th, TDC_STAGE_MV_SHADOW, tdc_r_pass_mv_shadow(th, s, n));
        if (jb->do_mv_dual) TIMED(th, TDC_STAGE_MV_DUAL, tdc_r_pass_mv_dual(th, s, n));
        if (jb->do_indirect) TIMED(th, TDC_STAGE_INDIRECT, tdc_r_pass_indirect(th, s, n));
        write_outputs(jb, s, n);
    }
    return NULL;
}

/* Linear radiance <-> gamma-coded value in place (reduced_gamma): to code clamps
 * to [0, 1] as the link's coding does, so the resolve filters what is shown. */
static void code_domain(float *v, size_t n, const double gamma[3], int to_linear)
{
    for (size_t i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++) {
            double x = v[3 * i + k];
            x = x < 0 ? 0 : x > 1 ? 1 : x;
            v[3 * i + k] = (float)pow(x, to_linear ? gamma[k] : 1.0 / gamma[k]);
        }
    }
}

/* Separable Gaussian resolve of the supersample grid (sw x sh) to ow x oh. */
static void resolve_gaussian(const float *ss, int sw, int sh, int ow, int oh, double sigma_s, int ssx, int ssy,
                             float *out)
{
    float *tmp = malloc((size_t)ow * sh * 3 * sizeof(float));
    double *wt = malloc(sizeof(double) * (size_t)(2 * (int)ceil(3 * sigma_s) + 3));
    if (!tmp || !wt) {
        free(tmp);
        free(wt);
        memset(out, 0, (size_t)ow * oh * 3 * sizeof(float));
        return;
    }
    int rad = (int)ceil(3 * sigma_s);
    for (int pass = 0; pass < 2; pass++) {
        int no = pass ? oh : ow, ss_n = pass ? sh : sw, ssf = pass ? ssy : ssx;
        for (int o = 0; o < no; o++) {
            double c = (o + 0.5) * ssf - 0.5;
            int i0 = (int)ceil(c - rad), i1 = (int)floor(c + rad);
            double sum = 0;
            for (int i = i0; i <= i1; i++) sum += wt[i - i0] = exp(-(i - c) * (i - c) / (2 * sigma_s * sigma_s));
            for (int i = i0; i <= i1; i++) wt[i - i0] /= sum;
            if (!pass) {
                for (int y = 0; y < sh; y++) {
                    double acc[3] = {0, 0, 0};
                    for (int i = i0; i <= i1; i++) {
                        int ii = i < 0 ? 0 : i >= ss_n ? ss_n - 1 : i;
                        const float *p = &ss[((size_t)y * sw + ii) * 3];
                        for (int k = 0; k < 3; k++) acc[k] += wt[i - i0] * p[k];
                    }
                    for (int k = 0; k < 3; k++) tmp[((size_t)y * ow + o) * 3 + k] = (float)acc[k];
                }
            } else {
                for (int x = 0; x < ow; x++) {
                    double acc[3] = {0, 0, 0};
                    for (int i = i0; i <= i1; i++) {
                        int ii = i < 0 ? 0 : i >= ss_n ? ss_n - 1 : i;
                        const float *p = &tmp[((size_t)ii * ow + x) * 3];
                        for (int k = 0; k < 3; k++) acc[k] += wt[i - i0] * p[k];
                    }
                    for (int k = 0; k < 3; k++) out[((size_t)o * ow + x) * 3 + k] = (float)acc[k];
                }
            }
        }
    }
    free(tmp);
    free(wt);
}

static void init_thread(rthread_t *th, tdc_render_t *r, uint32_t frame, int gt, int spp, int record, int track)
{
    memset(th, 0, sizeof *th);
    th->r = r;
    th->frame = frame;
    th->cur = tdc_r_frame(r, (long)frame);
    th->prev = tdc_r_frame(r, (long)frame - 1);
    th->top = r->top[frame & 1u].top;
    th->top_prev = r->top[(frame - 1) & 1u].top;
    rtcInitIntersectContext(&th->ctx);
    th->gt = gt;
    th->spp = (uint32_t)spp;
    th->record = record;
    th->track_blockers = track;
    th->ndual_rect = -1;
}

/* Dual-MV culling (tdc_r_pass_mv_dual): under a still camera, the screen
 * rectangle of every moving object's previous-frame bounds (its Embree
 * bounds' 8 corners through the previous matrix, projected), grown by 2 px
 * for the float instance transform and rounding.  A moving object partly
 * behind the camera disables the culling (ndual_rect stays -1). */
static void dual_rects(tdc_render_t *r, long frame, job_t *jb)
{
    if (r->cam_moved) return;
    const rframe_t *p = tdc_r_frame(r, frame - 1);
    int nr = 0;
    for (int i = 0; i < r->scene->nobjects; i++) {
        if (!r->obj_moved[i]) continue;
        struct RTCBounds b;
        rtcGetSceneBounds(r->obj[i].scene, &b);
        double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
        for (int k = 0; k < 8; k++) {
            double q[3] = {k & 1 ? b.upper_x : b.lower_x, k & 2 ? b.upper_y : b.lower_y, k & 4 ? b.upper_z : b.lower_z};
            double w[3], x, y;
            tdc_r_xform_point(p->m[i], q, w);
            if (tdc_r_project(&p->cam, w, &x, &y) < 0 || !isfinite(x) || !isfinite(y)) return;
            if (x < x0) x0 = x;
            if (x > x1) x1 = x;
            if (y < y0) y0 = y;
            if (y > y1) y1 = y;
        }
        if (!(x1 - x0 < 1e7 && y1 - y0 < 1e7)) return; /* near the camera plane: keep the float casts in range */
        jb->dual_rect[nr][0] = (float)(x0 - 2);
        jb->dual_rect[nr][1] = (float)(y0 - 2);
        jb->dual_rect[nr][2] = (float)(x1 + 2);
        jb->dual_rect[nr][3] = (float)(y1 + 2);
        nr++;
    }
    jb->ndual_rect = nr;
}

int tdc_render_frame(tdc_render_t *r, uint32_t frame, tdc_render_mode_t mode, const tdc_render_out_t *out,
                     tdc_render_stats_t *stats)
{
    static const tdc_render_out_t none;
    if (!r || (unsigned)mode > TDC_RENDER_FOVEATED || (mode == TDC_RENDER_FOVEATED && !r->fov_n)) return -1;
    if (!out) out = &none;
    double wall0 = tdc_r_now_ms();
    tdc_render_stats_t st;
    memset(&st, 0, sizeof st);
    job_t jb;
    memset(&jb, 0, sizeof jb);
    jb.r = r;
    jb.mode = mode;
    jb.frame = frame;
    jb.out = out;
    jb.record = r->cfg.record_rays;
    tdc_render_output_size(r, mode, &st.out_w, &st.out_h);

    /* Stage selection: leave out what the scene or this frame does not need. */
    st.frame_static = tdc_render_frame_static(r, frame);
    int mv_mode = mode == TDC_RENDER_FULL || mode == TDC_RENDER_SUBFRAME || mode == TDC_RENDER_FOVEATED;
    jb.frame_static = st.frame_static;
    jb.do_reflect = r->feat.mirrors && r->cfg.max_bounces > 0;
    jb.do_mv = mv_mode && !st.frame_static;
    jb.do_layers = (mode == TDC_RENDER_FULL || mode == TDC_RENDER_SUBFRAME || mode == TDC_RENDER_FOVEATED) &&
                   (out->shade || out->vis || out->refl || out->mv_surf || out->mv_refl || out->shadow_src ||
                    out->indirect);
    jb.do_indirect = r->cfg.indirect && r->feat.lights;
    jb.do_mv_reflect = jb.do_mv && jb.do_reflect && (r->cfg.reflect_mv || jb.do_layers);
    jb.do_mv_shadow = jb.do_mv && r->cfg.shadow_mv && r->feat.moving_blocker;
    jb.do_mv_dual = jb.do_mv && r->cfg.dual_mv;

    double t0 = tdc_r_now_ms();
    tdc_r_top(r, (long)frame);
    if (jb.do_mv_shadow || jb.do_mv_dual) tdc_r_top(r, (long)frame - 1);
    tdc_r_frame(r, (long)frame);
    tdc_r_frame(r, (long)frame - 1);
    jb.ndual_rect = -1;
    if (jb.do_mv_dual) dual_rects(r, (long)frame, &jb);
    int reuse = jb.do_indirect && r->cfg.indirect_reuse && mode == TDC_RENDER_FULL;
    if (reuse) { /* the cone history of two frames, allocated on first use */
        size_t nf = (size_t)r->W * r->H * TDC_R_CONE_FLOATS;
        for (int k = 0; k < 2; k++)
            if (!r->cone_hist[k] && !(r->cone_hist[k] = calloc(nf, sizeof(float)))) return -1;
        jb.cone_cur = r->cone_hist[frame & 1u];
        jb.cone_prev = r->cone_frame == (long)frame - 1 ? r->cone_hist[(frame - 1) & 1u] : NULL;
    }
    /* Zeng eq. 6 (and eq. 4's falloff) reads the previous frame's depth and object ids: FULL
     * frames keep their G-buffer; the next FULL frame looks it up.  Other
     * modes trace one pixel in four (subframes) or arbitrary positions, so
     * no previous G-buffer exists there and the dual pass traces. */
    if ((r->cfg.dual_mv || r->cfg.shadow_mv) && mode == TDC_RENDER_FULL) {
        const unsigned k = frame & 1u;
        if (!r->gbuf[k] && !(r->gbuf[k] = malloc((size_t)r->W * r->H * sizeof(tdc_r_gpix_t)))) return -1;
        r->gbuf_frame[k] = -2; /* until this frame is written */
        jb.gb_cur = r->gbuf[k];
        if ((jb.do_mv_dual || jb.do_mv_shadow) && !r->cfg.dual_trace && r->gbuf_frame[k ^ 1u] == (long)frame - 1)
            jb.gb_prev = r->gbuf[k ^ 1u];
    }
    st.ms[TDC_STAGE_SCENE] = tdc_r_now_ms() - t0;
    st.ran[TDC_STAGE_SCENE] = 1;

    jb.spp = 1;
    jb.tile = 8; /* 64 samples: their hot fields (16 KiB) stay in L1 across the passes */
    jb.tile_h = 8;
    float *ss = NULL;
    int ssx = 1, ssy = 1;
    switch (mode) {
    case TDC_RENDER_FULL:
        jb.sw = r->W;
        jb.sh = r->H;
        break;
    case TDC_RENDER_FOVEATED:
        jb.sw = r->fov_n;
        jb.sh = 1;
        jb.tile = 64;
        jb.tile_h = 1;
        break;
    case TDC_RENDER_SUBFRAME:
        jb.sw = st.out_w;
        jb.sh = st.out_h;
        if ((frame & 3u) == 0) {
            t0 = tdc_r_now_ms();
            tdc_ordering_update(r->mv_hist, r->W, r->H, r->pattern, frame);
            st.ms[TDC_STAGE_ORDERING] = tdc_r_now_ms() - t0;
            st.ran[TDC_STAGE_ORDERING] = 1;
        }
        tdc_jitter_offset_q4(frame, &jb.jx, &jb.jy);
        /* pixel classes from the history before this frame: tiles update
         * the live history while others still classify */
        memcpy(r->mv_hist_prev, r->mv_hist, (size_t)r->W * r->H * 2 * sizeof(int16_t));
        break;
    case TDC_RENDER_REDUCED:
        ssx = ssy = r->cfg.reduced_ss;
        jb.sw = st.out_w * ssx;
        jb.sh = st.out_h * ssy;
        ss = malloc((size_t)jb.sw * jb.sh * 3 * sizeof(float));
        if (!ss) return -1;
        jb.ss = ss;
        break;
    case TDC_RENDER_GROUND_TRUTH:
        jb.sw = r->W;
        jb.sh = r->H;
        jb.spp = r->cfg.gt_samples;
        jb.tile = jb.tile_h = jb.spp <= 4 ? 16 : jb.spp <= 64 ? 4 : 2;
        if (!out->rgb) {
            ss = malloc((size_t)r->W * r->H * 3 * sizeof(float));
            if (!ss) return -1;
        }
        jb.ss = out->rgb ? out->rgb : ss;
        break;
    }
    jb.ntx = (jb.sw + jb.tile - 1) / jb.tile;
    jb.nty = (jb.sh + jb.tile_h - 1) / jb.tile_h;

    int nth = r->cfg.threads;
    worker_t *w = aligned_alloc(64, (size_t)nth * sizeof *w); /* sizeof is a multiple of 64 */
    if (w) memset(w, 0, (size_t)nth * sizeof *w);
    if (!w) {
        free(ss);
        return -1;
    }
    size_t cap = (size_t)jb.tile * jb.tile_h * jb.spp;
    int ok = 1;
    for (int i = 0; i < nth; i++) {
        w[i].job = &jb;
        init_thread(&w[i].th, r, frame, mode == TDC_RENDER_GROUND_TRUTH, jb.spp, jb.record, jb.do_mv_shadow);
        w[i].th.cone = tdc_r_sample_cone(r, mode, jb.sw, jb.spp, w[i].th.cur->cam.tan_half);
        w[i].th.layers = jb.do_layers;
        w[i].th.have_mv = jb.do_mv;
        w[i].th.have_dual = jb.do_mv_dual;
        w[i].th.cone_cur = jb.cone_cur;
        w[i].th.cone_prev = jb.cone_prev;
        w[i].th.ndual_rect = jb.ndual_rect;
        w[i].th.gb_prev = jb.gb_prev;
        w[i].th.gb_jx = r->gbuf_j[(frame - 1) & 1u][0];
        w[i].th.gb_jy = r->gbuf_j[(frame - 1) & 1u][1];
        if (jb.ndual_rect > 0) memcpy(w[i].th.dual_rect, jb.dual_rect, (size_t)jb.ndual_rect * sizeof jb.dual_rect[0]);
        if (r->sbuf_cap[i] < cap) { /* kept between frames: no page faults per frame */
            free(r->sbuf[i]);
            /* cache-line aligned: the hot fields of a sample are 4 whole lines */
            r->sbuf[i] = aligned_alloc(64, cap * sizeof(rsample_t));
            r->sbuf_cap[i] = r->sbuf[i] ? cap : 0;
        }
        w[i].s = r->sbuf[i];
        if (!w[i].s) ok = 0;
    }
    double ms_per_tick = 0;
    if (ok) {
        double span0 = tdc_r_now_ms();
        uint64_t tick0 = stamp();
        for (int i = 1; i < nth; i++)
            if (pthread_create(&w[i].tid, NULL, worker_main, &w[i]) != 0) w[i].tid = 0;
        worker_main(&w[0]);
        for (int i = 1; i < nth; i++)
            if (w[i].tid) pthread_join(w[i].tid, NULL);
        uint64_t ticks = stamp() - tick0;
        ms_per_tick = ticks ? (tdc_r_now_ms() - span0) / (double)ticks : 0;
    }
    if (jb.record) {
        r->nrec = 0;
        size_t total = 0;
        for (int i = 0; i < nth; i++) total += w[i].th.nrec;
        tdc_render_ray_t *rec = realloc(r->rec, (total ? total : 1) * sizeof *rec);
        if (rec) {
            r->rec = rec;
            for (int i = 0; i < nth; i++) {
                memcpy(r->rec + r->nrec, w[i].th.rec, w[i].th.nrec * sizeof *rec);
                r->nrec += w[i].th.nrec;
            }
        }
    }
    for (int i = 0; i < nth; i++) {
        for (int s = 0; s < TDC_STAGE_COUNT; s++) st.ms[s] += (double)w[i].th.ticks[s] * ms_per_tick;
        for (int k = 0; k < TDC_RAY_KIND_COUNT; k++) st.rays[k] += w[i].th.rays[k];
        st.dual_culled += w[i].th.dual_culled;
        tdc_r_thread_free(&w[i].th);
    }
    free(w);
    if (!ok) {
        free(ss);
        return -1;
    }
    st.ran[TDC_STAGE_PRIMARY] = st.ran[TDC_STAGE_SHADE] = 1;
    st.ran[TDC_STAGE_REFLECT] = jb.do_reflect;
    st.ran[TDC_STAGE_MV] = jb.do_mv;
    st.ran[TDC_STAGE_MV_REFLECT] = jb.do_mv_reflect;
    st.ran[TDC_STAGE_MV_SHADOW] = jb.do_mv_shadow;
    st.ran[TDC_STAGE_MV_DUAL] = jb.do_mv_dual;
    st.ran[TDC_STAGE_INDIRECT] = jb.do_indirect;
    if (reuse) r->cone_frame = (long)frame;
    if (jb.gb_cur) {
        r->gbuf_frame[frame & 1u] = (long)frame;
        r->gbuf_j[frame & 1u][0] = r->full_jx;
        r->gbuf_j[frame & 1u][1] = r->full_jy;
    }
    st.dual_lookup = jb.gb_prev != NULL;

    if (mode == TDC_RENDER_REDUCED) {
        t0 = tdc_r_now_ms();
        double sigma_s = r->cfg.reduced_sigma * jb.sw / (double)r->W;
        if (out->rgb) {
            const double *g = r->cfg.reduced_gamma;
            int coded = g[0] > 0 && g[1] > 0 && g[2] > 0;
            if (coded) code_domain(ss, (size_t)jb.sw * jb.sh, g, 0);
            resolve_gaussian(ss, jb.sw, jb.sh, st.out_w, st.out_h, sigma_s, ssx, ssy, out->rgb);
            if (coded) code_domain(out->rgb, (size_t)st.out_w * st.out_h, g, 1);
        }
        st.ms[TDC_STAGE_RESOLVE] = tdc_r_now_ms() - t0;
        st.ran[TDC_STAGE_RESOLVE] = 1;
    }
    free(ss);
    st.wall_ms = tdc_r_now_ms() - wall0;
    if (stats) *stats = st;
    return 0;
}

/* ---- single-ray queries for tests and tools ---- */

int tdc_render_probe(tdc_render_t *r, uint32_t frame, double x, double y, tdc_render_probe_t *p)
{
    memset(p, 0, sizeof *p);
    tdc_render_frame_static(r, frame); /* camera / object motion flags of this frame */
    tdc_r_top(r, (long)frame);
    tdc_r_top(r, (long)frame - 1);
    rthread_t th;
    init_thread(&th, r, frame, 0, 1, 0, 1);
    th.cone = tdc_r_sample_cone(r, TDC_RENDER_FULL, r->W, 1, th.cur->cam.tan_half); /* what a frame's sample sees */
    th.layers = 1;
    rsample_t s;
    memset(&s, 0, sizeof s);
    s.x = (float)x;
    s.y = (float)y;
    s.px = (int)floor(x); /* same random-number key as a frame's sample in this pixel */
    s.py = (int)floor(y);
    s.cone_k = 1.0f; /* one display pixel's cone */
    tdc_r_pass_primary(&th, &s, 1);
    tdc_r_pass_shade(&th, &s, 1);
    if (r->feat.mirrors && r->cfg.max_bounces > 0) tdc_r_pass_reflect(&th, &s, 1);
    tdc_r_pass_mv(&th, &s, 1);
    tdc_r_pass_mv_reflect(&th, &s, 1); /* reflect_mv = 0 only keeps it out of mv */
    tdc_r_pass_mv_shadow(&th, &s, 1);
    tdc_r_pass_mv_dual(&th, &s, 1);
    th.have_mv = th.have_dual = 1;
    if (r->cfg.indirect && r->feat.lights) tdc_r_pass_indirect(&th, &s, 1);
    memcpy(p->indirect, s.ind, sizeof p->indirect);
    p->hit = s.obj >= 0;
    p->obj = s.obj;
    memcpy(p->q, s.Q, sizeof p->q);
    memcpy(p->world, s.P, sizeof p->world);
    memcpy(p->mv, s.mv, sizeof p->mv);
    p->mirror_hit = s.nmir > 0 && s.robj >= 0;
    p->refl_obj = s.robj;
    memcpy(p->refl_q, s.rQ, sizeof p->refl_q);
    p->in_shadow = s.in_shadow;
    p->blocker_obj = s.blk_obj;
    memcpy(p->blocker_q, s.BQ, sizeof p->blocker_q);
    memcpy(p->shadow_mv, s.mvs, sizeof p->shadow_mv);
    p->shadow_weight = s.sw;
    memcpy(p->dual_mv, s.mvd, sizeof p->dual_mv);
    p->disoccluded = s.disocc;
    memcpy(p->rgb, s.col, sizeof p->rgb);
    p->refl_mv_ok = s.mvr_ok;
    if (s.mvr_ok) {
        memcpy(p->refl_mv, s.mvr, sizeof p->refl_mv);
        memcpy(p->refl_mu, s.mvr_mu, sizeof p->refl_mu);
        memcpy(p->refl_axes, s.mvr_ax, sizeof p->refl_axes);
    } else {
        memcpy(p->refl_mv, s.refl_used ? s.mvsurf : s.mv, sizeof p->refl_mv);
    }
    memcpy(p->shade, s.lshade, sizeof p->shade);
    tdc_r_thread_free(&th);
    p->vis = s.vis;
    memcpy(p->refl, s.refl, sizeof p->refl);
    return 0;
}

int tdc_render_project(tdc_render_t *r, uint32_t frame, int obj, const double q[3], double *x, double *y)
{
    const rframe_t *f = tdc_r_frame(r, (long)frame);
    double w[3];
    if (obj >= 0)
        tdc_r_xform_point(f->m[obj], q, w);
    else
        memcpy(w, q, sizeof w);
    return tdc_r_project(&f->cam, w, x, y);
}

int tdc_render_project_reflected(tdc_render_t *r, uint32_t frame, int mobj, const double mq[3], int obj,
                                 const double q[3], double *x, double *y)
{
    const rframe_t *f = tdc_r_frame(r, (long)frame);
    double w[3], pm[3], n[3];
    tdc_r_xform_point(f->m[obj], q, w);
    tdc_r_xform_point(f->m[mobj], mq, pm);
    /* the mirror's local normal: rects and discs are local XY planes (+Z);
     * other shapes are not planar mirrors for this helper */
    double nq[3] = {0, 0, 1};
    tdc_r_xform_normal(f->nm[mobj], nq, n);
    double d = (w[0] - pm[0]) * n[0] + (w[1] - pm[1]) * n[1] + (w[2] - pm[2]) * n[2];
    for (int c = 0; c < 3; c++) w[c] -= 2 * d * n[c];
    return tdc_r_project(&f->cam, w, x, y);
}

/* ---- output encoding ---- */

void tdc_render_linear_to_rgb888(const float *lin, size_t n, uint8_t *rgb)
{
    static uint8_t lut[4097];
    static int init;
    if (!__atomic_load_n(&init, __ATOMIC_ACQUIRE)) {
        for (int i = 0; i <= 4096; i++) lut[i] = (uint8_t)floor(255 * pow(i / 4096.0, 1 / 2.2) + 0.5);
        __atomic_store_n(&init, 1, __ATOMIC_RELEASE);
    }
    for (size_t i = 0; i < n * 3; i++) {
        float v = lin[i];
        if (!(v > 0)) v = 0;
        if (v > 1) v = 1;
        /* 4096-entry table with rounding of the index: the error against the
         * exact transfer is at most one code, only near black */
        rgb[i] = v < 1.0f / 4096 ? (uint8_t)floor(255 * pow(v, 1 / 2.2) + 0.5) : lut[(int)(v * 4096 + 0.5f)];
    }
}

int tdc_render_write_png(const char *path, const float *lin, int w, int h, char *err, size_t errlen)
{
    uint8_t *b = malloc((size_t)w * h * 3);
    if (!b) {
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    }
    tdc_render_linear_to_rgb888(lin, (size_t)w * h, b);
    int rc = tdc_png_write(path, b, w, h, 8, (size_t)w * 3, err, errlen);
    free(b);
    return rc;
}
