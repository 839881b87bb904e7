/*
 * tdc_render_trace.c - the per-sample passes of Whitted ray tracing on
 * Embree and the motion vectors:
 *   primary      camera rays through (x, y), 16 at a time (rtcIntersect16)
 *   shade        procedural texture, ambient + point/rect lights with shadow
 *                rays (a tile's, 16 at a time through rtcOccluded16; one by
 *                one with rtcIntersect1 when shadow MVs need the blocker)
 *   reflect      mirror bounces, up to 3
 *   mv           primary MV: P_{i-1} T^{-1} P_i^{-1} x (Zeng eq. 1), by
 *                carrying the object-space hit through both frames' matrices
 *   mv-reflect   TDRT §3.1.2: the mirror image of the reflected hit's
 *                previous position, reflected through the mirror chain's
 *                previous planes (Householder reflections), projected
 *   mv-shadow    Zeng eq. 3 + falloff eq. 4 (the previous FULL frame's G-buffer
 *                at x^V; without one, one previous-frame ray)
 *   mv-dual      Zeng eq. 6: x^O = y + (x - z), "where y = P_{i-1} T^{-1}(x_i)
 *                P_i^{-1} x_i and z = P_i T(y) P_{i-1}^{-1} y": a lookup in the
 *                previous FULL frame's depth / object-id G-buffer; without
 *                one (first frame, subframes, sample sets, probes, option
 *                dual_trace) one previous-frame ray, a tile's 16 at a time
 * MVs are in float px, backward (previous minus current position).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tdc_math.h"
#include "tdc_render_trace.h"
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

/* GCC 12 vectorises straight-line code at -O2 (SLP): vectors are loaded from
 * arrays just written element by element (the ray set-up after the
 * reflection or light direction, a colour after the texture call), and such
 * loads stall on store forwarding (the profile showed ~30 % of several passes
 * there).  Scalar code here; it does the same floating-point operations, so
 * the results are unchanged. */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("no-tree-slp-vectorize")
#endif

double tdc_r_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}


double tdc_r_rand(uint32_t seed, uint32_t frame, uint32_t dst, uint32_t k, uint32_t dim)
{
    uint32_t h = tdc_mix32(seed ^ tdc_mix32(frame ^ tdc_mix32(dst ^ tdc_mix32(k * 16u + dim + 0x9E3779B9u))));
    return (h >> 8) * (1.0 / 16777216.0);
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Element-wise copy of a 3-vector that was just written element by element:
 * memcpy's 16-byte load of it would stall on store forwarding. */
static inline void copy3(double dst[3], const double src[3])
{
    double x = src[0], y = src[1], z = src[2];
    dst[0] = x;
    dst[1] = y;
    dst[2] = z;
}

static void record(rthread_t *t, const struct RTCRay *ray, uint32_t kind, uint32_t flags)
{
    if (t->nrec == t->crec) {
        size_t c = t->crec ? t->crec * 2 : 65536;
        tdc_render_ray_t *p = realloc(t->rec, c * sizeof *p);
        if (!p) {
            t->record = 0; /* out of memory: stop recording, the render goes on */
            return;
        }
        t->rec = p;
        t->crec = c;
    }
    tdc_render_ray_t *o = &t->rec[t->nrec++];
    o->org[0] = ray->org_x;
    o->org[1] = ray->org_y;
    o->org[2] = ray->org_z;
    o->tnear = ray->tnear;
    o->dir[0] = ray->dir_x;
    o->dir[1] = ray->dir_y;
    o->dir[2] = ray->dir_z;
    o->tfar = ray->tfar;
    o->kind = kind;
    o->flags = flags;
}

static inline void set_ray(struct RTCRay *ray, const double o[3], const double d[3], double tnear, double tfar)
{
    ray->org_x = (float)o[0];
    ray->org_y = (float)o[1];
    ray->org_z = (float)o[2];
    ray->tnear = (float)tnear;
    ray->dir_x = (float)d[0];
    ray->dir_y = (float)d[1];
    ray->dir_z = (float)d[2];
    ray->time = 0;
    ray->tfar = (float)tfar;
    ray->mask = 0xFFFFFFFFu;
    ray->id = 0;
    ray->flags = 0;
}

/* Closest hit; returns the object index or -1. */
static inline int intersect(rthread_t *t, int prevf, const double o[3], const double d[3], double tnear, double tfar,
                            uint32_t kind, struct RTCRayHit *rh)
{
    set_ray(&rh->ray, o, d, tnear, tfar);
    rh->hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    t->rays[kind]++;
    if (t->record) record(t, &rh->ray, kind, prevf ? TDC_RAY_PREV_FRAME : 0);
    rtcIntersect1(prevf ? t->top_prev : t->top, &t->ctx, rh);
    return rh->hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1 : (int)rh->hit.instID[0];
}

static inline int occluded(rthread_t *t, const double o[3], const double d[3], double tfar)
{
    struct RTCRay ray;
    set_ray(&ray, o, d, 0, tfar);
    t->rays[TDC_RAY_SHADOW]++;
    if (t->record) record(t, &ray, TDC_RAY_SHADOW, TDC_RAY_OCCLUSION);
    rtcOccluded1(t->top, &t->ctx, &ray);
    return ray.tfar < 0;
}

/* Fills the surface fields from a hit at ray parameter tt of ray (o, d) with
 * Embree's raw object-space normal ng.  P in locals: storing it element by
 * element and reading it back as a vector stalled on store forwarding. */
/* The last world normal computed from a raw normal: neighbouring samples hit
 * the same triangle, and the same object with the same normal bits gives the
 * same (deterministic) result without the square root and division. */
typedef struct {
    int obj;        /* -1: empty */
    uint32_t ng[3]; /* bits of Embree's raw normal */
    double n[3];    /* tdc_r_xform_normal of it (before facing the ray) */
} wncache_t;

static inline __attribute__((always_inline)) void surface(const rframe_t *f, float tt_f, const float ng[3], int obj,
                                                          const double o[3], const double d[3], double P[3],
                                                          double Q[3], double N[3], double NQ[3], int need_n,
                                                          wncache_t *wc)
{
    double tt = tt_f;
    double p0 = o[0] + tt * d[0], p1 = o[1] + tt * d[1], p2 = o[2] + tt * d[2];
    const double *m = f->minv[obj];
    Q[0] = m[0] * p0 + m[1] * p1 + m[2] * p2 + m[3];
    Q[1] = m[4] * p0 + m[5] * p1 + m[6] * p2 + m[7];
    Q[2] = m[8] * p0 + m[9] * p1 + m[10] * p2 + m[11];
    P[0] = p0;
    P[1] = p1;
    P[2] = p2;
    NQ[0] = ng[0];
    NQ[1] = ng[1];
    NQ[2] = ng[2];
    if (!need_n) { /* nobody reads it (unlit, no mirror) */
        N[0] = N[1] = N[2] = 0;
        return;
    }
    uint32_t b[3];
    memcpy(b, ng, sizeof b);
    if (wc->obj != obj || wc->ng[0] != b[0] || wc->ng[1] != b[1] || wc->ng[2] != b[2]) {
        tdc_r_xform_normal(f->nm[obj], NQ, wc->n);
        wc->obj = obj;
        wc->ng[0] = b[0];
        wc->ng[1] = b[1];
        wc->ng[2] = b[2];
    }
    copy3(N, wc->n);
    if (dot3(N, d) > 0)
        for (int i = 0; i < 3; i++) N[i] = -N[i];
}

static inline void surface_rh(const rframe_t *f, const struct RTCRayHit *rh, int obj, const double o[3],
                              const double d[3], double P[3], double Q[3], double N[3], double NQ[3], wncache_t *wc)
{
    const float ng[3] = {rh->hit.Ng_x, rh->hit.Ng_y, rh->hit.Ng_z};
    surface(f, rh->ray.tfar, ng, obj, o, d, P, Q, N, NQ, 1, wc);
}

static double offset_eps(const double P[3])
{
    double m = fabs(P[0]);
    if (fabs(P[1]) > m) m = fabs(P[1]);
    if (fabs(P[2]) > m) m = fabs(P[2]);
    return 1e-4 * (1 + m);
}

/* A shadow ray of the packet path (tdc_r_pass_shade): the ray, what its
 * light sample adds to e when it is not blocked, and the answer. */
struct tdc_r_shadow {
    struct RTCRay ray;
    double q[3];
    int blocked;
};

void tdc_r_thread_free(rthread_t *t)
{
    free(t->rec);
    free(t->sq);
    free(t->sq_cnt);
    free(t->dq);
    t->rec = NULL;
    t->sq = NULL;
    t->sq_cnt = NULL;
    t->dq = NULL;
    t->nrec = t->crec = t->nsq = t->csq = t->csq_cnt = t->cdq = 0;
}

/* Queues a shadow ray; 0, or -1 out of memory (nothing queued). */
static int sq_push(rthread_t *t, const double O[3], const double L[3], double tfar, const double q[3])
{
    if (t->nsq == t->csq) {
        size_t c = t->csq ? 2 * t->csq : 1024;
        struct tdc_r_shadow *p = realloc(t->sq, c * sizeof *p);
        if (!p) return -1;
        t->sq = p;
        t->csq = c;
    }
    struct tdc_r_shadow *r = &t->sq[t->nsq++];
    set_ray(&r->ray, O, L, 0, tfar);
    copy3(r->q, q);
    r->blocked = 0;
    return 0;
}

/* The queued shadow rays [0, nsq), 16 at a time through rtcOccluded16 in
 * queue order - the order of the tile's samples and their light samples,
 * which the tile fixes whatever the thread count, so the packets (and
 * their answers) are the same in every run. */
static void sq_trace(rthread_t *t)
{
    /* the default (incoherent) traversal: with RTC_INTERSECT_CONTEXT_FLAG_COHERENT
     * Debian's Embree 3.13.5 never returned from rtcOccluded16 on
     * test_render_stream's static sphere (AVX-512 host) */
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (size_t i = 0; i < t->nsq; i += 16) {
        _Alignas(64) int valid[16];
        _Alignas(64) struct RTCRay16 p;
        const int m = t->nsq - i < 16 ? (int)(t->nsq - i) : 16;
        for (int k = 0; k < 16; k++) {
            const struct RTCRay *r = &t->sq[i + (size_t)(k < m ? k : 0)].ray;
            valid[k] = k < m ? -1 : 0;
            p.org_x[k] = r->org_x;
            p.org_y[k] = r->org_y;
            p.org_z[k] = r->org_z;
            p.tnear[k] = r->tnear;
            p.dir_x[k] = r->dir_x;
            p.dir_y[k] = r->dir_y;
            p.dir_z[k] = r->dir_z;
            p.time[k] = 0;
            p.tfar[k] = r->tfar;
            p.mask[k] = 0xFFFFFFFFu;
            p.id[k] = 0;
            p.flags[k] = 0;
        }
        rtcOccluded16(valid, t->top, &ctx, &p);
        for (int k = 0; k < m; k++) {
            struct tdc_r_shadow *r = &t->sq[i + (size_t)k];
            t->rays[TDC_RAY_SHADOW]++;
            if (t->record) record(t, &r->ray, TDC_RAY_SHADOW, TDC_RAY_OCCLUSION);
            r->blocked = p.tfar[k] < 0;
        }
    }
}

/* How the light samples' visibility is found: a ray at once (rtcOccluded1,
 * or rtcIntersect1 when shadow MVs track the blocker), or queued for the
 * packet path (nothing added to e: sq_finish adds the unblocked ones). */
enum { LIGHTS_TRACE, LIGHTS_QUEUE };

/* The direct light at P (normal N, facing the viewer) into e (started at
 * the ambient) and, if eu, every light sample's light, blocked or not;
 * optionally records the first blocked light sample's blocker into track.
 * LIGHTS_QUEUE returns -1 when the queue is out of memory. */
static int light_loop(rthread_t *t, const double P[3], const double N[3], uint32_t dst, uint32_t k, uint32_t salt,
                      rsample_t *track, double e[3], double eu[3], int how)
{
    const tdc_render_t *r = t->r;
    const tdc_scene_t *sc = r->scene;
    double eps = offset_eps(P);
    double O[3] = {P[0] + N[0] * eps, P[1] + N[1] * eps, P[2] + N[2] * eps};
    for (int li = 0; li < sc->nlights; li++) {
        const tdc_light_t *l = &sc->lights[li];
        const double *lp = t->cur->light_pos[li];
        if (l->kind == TDC_LIGHT_POINT) {
            double L0 = lp[0] - O[0], L1 = lp[1] - O[1], L2 = lp[2] - O[2];
            double d = sqrt(L0 * L0 + L1 * L1 + L2 * L2);
            if (!(d > 0)) continue;
            double L[3];
#if defined(__SSE2__)
            /* two of the three divisions in one instruction (same quotients) */
            _mm_storeu_pd(L, _mm_div_pd(_mm_set_pd(L1, L0), _mm_set1_pd(d)));
            L[2] = L2 / d;
#else
            L[0] = L0 / d;
            L[1] = L1 / d;
            L[2] = L2 / d;
#endif
            double c = dot3(N, L);
            if (c <= 0) continue;
            if (eu)
                for (int i = 0; i < 3; i++) eu[i] += l->intensity[i] * c / (d * d);
            double q[3];
#if defined(__SSE2__)
            _mm_storeu_pd(q, _mm_div_pd(_mm_mul_pd(_mm_loadu_pd(l->intensity), _mm_set1_pd(c)), _mm_set1_pd(d * d)));
            q[2] = l->intensity[2] * c / (d * d);
#else
            for (int i = 0; i < 3; i++) q[i] = l->intensity[i] * c / (d * d);
#endif
            if (how == LIGHTS_QUEUE) {
                if (sq_push(t, O, L, d * (1 - 1e-6), q)) return -1;
                continue;
            }
            int blocked;
            if (track && t->track_blockers && !track->in_shadow) {
                struct RTCRayHit rh;
                int b = intersect(t, 0, O, L, 0, d * (1 - 1e-6), TDC_RAY_SHADOW, &rh);
                blocked = b >= 0;
                if (blocked) {
                    double BP[3];
                    for (int i = 0; i < 3; i++) BP[i] = O[i] + rh.ray.tfar * L[i];
                    tdc_r_xform_point(t->cur->minv[b], BP, track->BQ);
                    track->in_shadow = 1;
                    track->blk_obj = b;
                    track->blk_light = li;
                    track->loff[0] = track->loff[1] = track->loff[2] = 0;
                }
            } else {
                blocked = occluded(t, O, L, d * (1 - 1e-6));
            }
            if (!blocked) {
                e[0] += q[0];
                e[1] += q[1];
                e[2] += q[2];
            }
        } else {
            /* Rect light: stratified samples over the rectangle; ground truth
             * takes one sample per pixel sample, stratified by k. */
            int ns = t->gt ? 1 : l->samples;
            int nx = (int)ceil(sqrt((double)ns));
            int ny = (ns + nx - 1) / nx;
            double ln[3] = {l->u[1] * l->v[2] - l->u[2] * l->v[1], l->u[2] * l->v[0] - l->u[0] * l->v[2],
                            l->u[0] * l->v[1] - l->u[1] * l->v[0]};
            double lnl = sqrt(dot3(ln, ln));
            if (!(lnl > 0)) continue;
            for (int i = 0; i < 3; i++) ln[i] /= lnl;
            for (int j = 0; j < ns; j++) {
                double a, b;
                if (t->gt) {
                    uint32_t g = (uint32_t)floor(sqrt((double)t->spp));
                    uint32_t kk = k % (g * g);
                    a = (kk % g + tdc_r_rand(r->cfg.seed, t->frame, dst, k, 8 + salt)) / g;
                    b = (kk / g + tdc_r_rand(r->cfg.seed, t->frame, dst, k, 9 + salt)) / g;
                } else {
                    a = (j % nx + tdc_r_rand(r->cfg.seed, t->frame, dst, k * 64u + (uint32_t)j, 8 + salt)) / nx;
                    b = (j / nx + tdc_r_rand(r->cfg.seed, t->frame, dst, k * 64u + (uint32_t)j, 9 + salt)) / ny;
                }
                double S[3], L[3];
                for (int i = 0; i < 3; i++) {
                    S[i] = lp[i] + (a - 0.5) * l->u[i] + (b - 0.5) * l->v[i];
                    L[i] = S[i] - O[i];
                }
                double d = sqrt(dot3(L, L));
                if (!(d > 0)) continue;
                for (int i = 0; i < 3; i++) L[i] /= d;
                double c = dot3(N, L), cl = fabs(dot3(ln, L));
                if (c <= 0) continue;
                if (eu)
                    for (int i = 0; i < 3; i++) eu[i] += l->intensity[i] * c * cl / (d * d) / ns;
                double q[3];
                for (int i = 0; i < 3; i++) q[i] = l->intensity[i] * c * cl / (d * d) / ns;
                if (how == LIGHTS_QUEUE) {
                    if (sq_push(t, O, L, d * (1 - 1e-6), q)) return -1;
                    continue;
                }
                if (track && t->track_blockers && !track->in_shadow) {
                    /* shadow MVs: the first blocked light sample keeps its
                     * blocker and its offset on the (translating) light */
                    struct RTCRayHit rh;
                    int bo = intersect(t, 0, O, L, 0, d * (1 - 1e-6), TDC_RAY_SHADOW, &rh);
                    if (bo >= 0) {
                        double BP[3];
                        for (int i = 0; i < 3; i++) {
                            BP[i] = O[i] + rh.ray.tfar * L[i];
                            track->loff[i] = S[i] - lp[i];
                        }
                        tdc_r_xform_point(t->cur->minv[bo], BP, track->BQ);
                        track->in_shadow = 1;
                        track->blk_obj = bo;
                        track->blk_light = li;
                        continue;
                    }
                } else if (occluded(t, O, L, d * (1 - 1e-6))) {
                    continue;
                }
                for (int i = 0; i < 3; i++) e[i] += q[i];
            }
        }
    }
    return 0;
}

/* Local (direct) radiance at a surface; optionally records the first
 * blocked point light's blocker into s.  queued >= 0: the light samples'
 * rays were queued and traced (tdc_r_pass_shade); their answers start at
 * t->sq[*next], queued of them, and unshadowed already holds the sum of
 * every light sample's light (eu). */
static void shade_direct(rthread_t *t, int obj, const double P[3], const double Q[3], const double N[3],
                         const double NQ[3], uint32_t dst, uint32_t k, uint32_t salt, rsample_t *track, double out[3],
                         double *unshadowed, int queued, size_t *next)
{
    const tdc_render_t *r = t->r;
    const tdc_scene_t *sc = r->scene;
    const tdc_object_t *o = &sc->objects[obj];
    const tdc_material_t *m = &sc->materials[o->material];
    if (m->unlit) { /* straight into out: a copy through base[] stalled on store forwarding */
        tdc_r_base_color(r, o, Q, NQ, t->tex_fw, out);
        if (unshadowed) copy3(unshadowed, out);
        return;
    }
    double base[3];
    tdc_r_base_color(r, o, Q, NQ, t->tex_fw, base);
    double e[3] = {sc->ambient[0], sc->ambient[1], sc->ambient[2]};
    /* layers: the same sums without the visibility term (eu: every light
     * sample counted, blocked or not); e itself is computed as before */
    double eu[3] = {e[0], e[1], e[2]};
    if (queued >= 0) {
        for (int i = 0; i < queued; i++) {
            const struct tdc_r_shadow *q = &t->sq[(*next)++];
            if (!q->blocked) {
                e[0] += q->q[0];
                e[1] += q->q[1];
                e[2] += q->q[2];
            }
        }
        if (unshadowed) copy3(eu, unshadowed);
    } else {
        light_loop(t, P, N, dst, k, salt, track, e, unshadowed ? eu : NULL, LIGHTS_TRACE);
    }
    for (int i = 0; i < 3; i++) out[i] = base[i] * e[i];
    if (unshadowed)
        for (int i = 0; i < 3; i++) unshadowed[i] = base[i] * eu[i];
}

/* Random numbers are keyed by the pixel (not the output slot), so a pixel
 * gets the same light samples in full frames, subframes and probes. */
#define rng_key tdc_r_rng_key

/* Layers of a shaded primary sample (Zeng §4: shading without shadows,
 * visibility, reflection): lshade = unshadowed local radiance scaled like
 * col by (1 - k), vis = luminance of the shadowed over the unshadowed local
 * radiance (1 where nothing is lit), so col = vis * lshade exactly for
 * grey lights and up to the lights' colour differences otherwise; refl
 * starts at 0 and collects what the reflect pass adds to col. */
static void layer_split(rsample_t *a)
{
    double lu = 0.2126 * a->lshade[0] + 0.7152 * a->lshade[1] + 0.0722 * a->lshade[2];
    double ls = 0.2126 * a->col[0] + 0.7152 * a->col[1] + 0.0722 * a->col[2];
    double v = lu > 0 ? ls / lu : 1;
    a->vis = v < 0 ? 0 : v > 1 ? 1 : v;
    a->refl[0] = a->refl[1] = a->refl[2] = 0;
}

/* Closest hits of m <= 16 rays from o along dir[k] (tnear 0, no tfar) in
 * one rtcIntersect16 call with the coherent traversal (camera-like rays:
 * one origin): object (-1 = miss), t and Embree's raw normal per ray;
 * counted and recorded as single rays of `kind` would be.  Embree's packet
 * kernel may return other bits than rtcIntersect1 for the same ray (the
 * sign of a zero normal component, the last bit of t on spheres;
 * bench_render counts them), so images differ from single-ray tracing in
 * such bits; the callers' packets are consecutive samples of a tile, fixed
 * by the tile whatever the thread count, so they are the same in every run. */
static void closest16(rthread_t *t, int prevf, const double o[3], const double *const dir[16], int m, uint32_t kind,
                      int obj[16], float tfar[16], float ng[16][3])
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    _Alignas(64) int valid[16];
    _Alignas(64) struct RTCRayHit16 p;
    for (int k = 0; k < 16; k++) {
        struct RTCRay ray;
        set_ray(&ray, o, dir[k < m ? k : 0], 0, INFINITY);
        valid[k] = k < m ? -1 : 0;
        p.ray.org_x[k] = ray.org_x;
        p.ray.org_y[k] = ray.org_y;
        p.ray.org_z[k] = ray.org_z;
        p.ray.tnear[k] = ray.tnear;
        p.ray.dir_x[k] = ray.dir_x;
        p.ray.dir_y[k] = ray.dir_y;
        p.ray.dir_z[k] = ray.dir_z;
        p.ray.time[k] = 0;
        p.ray.tfar[k] = ray.tfar;
        p.ray.mask[k] = ray.mask;
        p.ray.id[k] = 0;
        p.ray.flags[k] = 0;
        p.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        p.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        if (k < m) {
            t->rays[kind]++;
            if (t->record) record(t, &ray, kind, prevf ? TDC_RAY_PREV_FRAME : 0);
        }
    }
    rtcIntersect16(valid, prevf ? t->top_prev : t->top, &ctx, &p);
    for (int k = 0; k < m; k++) {
        obj[k] = p.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID ? -1 : (int)p.hit.instID[0][k];
        tfar[k] = p.ray.tfar[k];
        ng[k][0] = p.hit.Ng_x[k];
        ng[k][1] = p.hit.Ng_y[k];
        ng[k][2] = p.hit.Ng_z[k];
    }
}

/* Primary rays 16 at a time (closest16): the samples of a tile in their
 * order (place_samples). */
void tdc_r_pass_primary(rthread_t *t, rsample_t *s, int n)
{
    const rcam_t *cam = &t->cur->cam;
    for (int i0 = 0; i0 < n; i0 += 16) {
        const int m = n - i0 < 16 ? n - i0 : 16;
        const double *dir[16];
        int obj[16];
        float tf[16], ng[16][3];
        for (int k = 0; k < m; k++) {
            rsample_t *a = &s[i0 + k];
            tdc_r_cam_ray(cam, a->x, a->y, a->dir);
            a->in_shadow = 0;
            a->nmir = 0;
            a->mirror = 0;
            dir[k] = a->dir;
        }
        closest16(t, 0, cam->pos, dir, m, TDC_RAY_PRIMARY, obj, tf, ng);
        for (int k = 0; k < m; k++) {
            rsample_t *a = &s[i0 + k];
            a->obj = obj[k];
            a->hit_t = tf[k];
            a->hit_ng[0] = ng[k][0];
            a->hit_ng[1] = ng[k][1];
            a->hit_ng[2] = ng[k][2];
        }
    }
    wncache_t wc = {.obj = -1};
    /* Surfaces in a second loop: its iterations are independent, so the
     * square roots and divisions of successive samples overlap instead of
     * each waiting behind the next Embree call. Same arithmetic. */
    for (int i = 0; i < n; i++) {
        rsample_t *a = &s[i];
        if (a->obj >= 0) {
            surface(t->cur, a->hit_t, a->hit_ng, a->obj, cam->pos, a->dir, a->P, a->Q, a->N, a->NQ,
                    t->r->obj_needs_n[a->obj], &wc);
            a->depth = dot3(a->dir, cam->fwd) * (double)a->hit_t;
        } else {
            a->depth = INFINITY;
        }
    }
}

void tdc_r_pass_shade(rthread_t *t, rsample_t *s, int n)
{
    const tdc_scene_t *sc = t->r->scene;
    /* Texture coordinates that need atan2 (unlit textured spheres and
     * cylinders) first, in a loop of their own: its iterations are
     * independent and overlap, then the texture lookups below. Same
     * arithmetic as tdc_r_base_color. */
    const uint8_t *uv_first = t->r->obj_uv_first;
    if (t->r->any_uv_first)
        for (int i = 0; i < n; i++) {
            rsample_t *a = &s[i];
            if (a->obj >= 0 && uv_first[a->obj]) tdc_r_tex_uv(&sc->objects[a->obj], a->Q, a->NQ, &a->tu, &a->tv);
        }
    /* Shadow rays in packets (without blocker tracking, which needs each
     * blocked ray's hit at once): every lit sample's light samples are
     * queued first, in sample order, traced 16 at a time, and the shading
     * below adds the unblocked ones - the same sums in the same order. */
    int queued = !t->track_blockers && n > 0;
    if (queued) {
        if (t->csq_cnt < (size_t)n) {
            int *c = realloc(t->sq_cnt, (size_t)(unsigned)n * sizeof *c);
            if (c) {
                t->sq_cnt = c;
                t->csq_cnt = (size_t)n;
            }
        }
        queued = t->csq_cnt >= (size_t)n;
        t->nsq = 0;
        for (int i = 0; i < n && queued; i++) {
            rsample_t *a = &s[i];
            t->sq_cnt[i] = -1;
            if (a->obj < 0 || uv_first[a->obj] || sc->materials[sc->objects[a->obj].material].unlit) continue;
            size_t n0 = t->nsq;
            double *eu = t->layers ? a->lshade : NULL, e[3];
            if (eu) copy3(eu, sc->ambient);
            if (light_loop(t, a->P, a->N, rng_key(a), a->k, 0, NULL, e, eu, LIGHTS_QUEUE)) queued = 0;
            t->sq_cnt[i] = (int)(t->nsq - n0);
        }
        if (queued) sq_trace(t);
    }
    size_t next = 0;
    for (int i = 0; i < n; i++) {
        rsample_t *a = &s[i];
        if (a->obj < 0) {
            memcpy(a->col, sc->background, sizeof a->col);
            if (t->layers) {
                a->rough = 0;
                copy3(a->lshade, a->col);
                layer_split(a);
            }
            continue;
        }
        const tdc_object_t *o = &sc->objects[a->obj];
        const tdc_material_t *m = &sc->materials[o->material];
        t->tex_fw = tdc_r_sample_fw(t, a, a->hit_t * sqrt(dot3(a->dir, a->dir)), a->dir, a->NQ, t->cur->minv[a->obj]);
        if (uv_first[a->obj]) /* the texture colour at the coordinates computed above */
            tdc_r_tex_color(t->r, o, a->tu, a->tv, t->tex_fw, a->col);
        else if (m->unlit) /* the texture colour: no call into the lighting code */
            tdc_r_base_color(t->r, o, a->Q, a->NQ, t->tex_fw, a->col);
        else
            shade_direct(t, a->obj, a->P, a->Q, a->N, a->NQ, rng_key(a), a->k, 0, a, a->col,
                         t->layers ? a->lshade : NULL, queued ? t->sq_cnt[i] : -1, &next);
        a->mirror = t->r->cfg.max_bounces > 0 ? m->mirror : 0;
        a->rough = m->roughness;
        if (t->layers && (uv_first[a->obj] || m->unlit)) copy3(a->lshade, a->col);
        if (a->mirror > 0)
            for (int c = 0; c < 3; c++) a->col[c] *= 1 - a->mirror;
        if (t->layers) {
            if (a->mirror > 0)
                for (int c = 0; c < 3; c++) a->lshade[c] *= 1 - a->mirror;
            layer_split(a);
        }
    }
}

/* GGX (Trowbridge-Reitz) reflection, importance-sampled by the visible
 * normals (Heitz 2018, "Sampling the GGX distribution of visible normals"):
 * d = incoming direction (any length), N = unit normal facing the viewer,
 * alpha = roughness, (u1, u2) in [0, 1)^2.  Writes the unit reflected
 * direction to out (may alias d) and returns the estimator's weight
 * f cos / pdf = G1(l) (Smith, separable; no Fresnel: the material's k
 * scales it), or 0 when the sampled direction is below the surface. */
double tdc_r_ggx_sample(const double d[3], const double N[3], double alpha, double u1, double u2, double out[3])
{
    double dl = sqrt(dot3(d, d));
    double wo[3] = {-d[0] / dl, -d[1] / dl, -d[2] / dl};
    double T[3], B[3];
    tdc_r_onb(N, T, B);
    double vx = dot3(wo, T), vy = dot3(wo, B), vz = dot3(wo, N);
    if (!(vz > 0)) return 0;
    /* the view direction stretched to the unit-roughness configuration */
    double hx = alpha * vx, hy = alpha * vy, hz = vz, hl = sqrt(hx * hx + hy * hy + hz * hz);
    hx /= hl;
    hy /= hl;
    hz /= hl;
    double lensq = hx * hx + hy * hy;
    double t1x = 1, t1y = 0, t1z = 0;
    if (lensq > 0) {
        double il = 1 / sqrt(lensq);
        t1x = -hy * il;
        t1y = hx * il;
    }
    double t2x = hy * t1z - hz * t1y, t2y = hz * t1x - hx * t1z, t2z = hx * t1y - hy * t1x;
    double rr = sqrt(u1), phi = 2 * M_PI * u2;
    double p1 = rr * cos(phi), p2 = rr * sin(phi), sm = 0.5 * (1 + hz);
    p2 = (1 - sm) * sqrt(1 - p1 * p1) + sm * p2;
    double p3 = 1 - p1 * p1 - p2 * p2;
    p3 = p3 > 0 ? sqrt(p3) : 0;
    double nx = p1 * t1x + p2 * t2x + p3 * hx, ny = p1 * t1y + p2 * t2y + p3 * hy, nz = p1 * t1z + p2 * t2z + p3 * hz;
    /* back to the roughness-alpha configuration: the microfacet normal */
    double mx = alpha * nx, my = alpha * ny, mz = nz > 0 ? nz : 0, ml = sqrt(mx * mx + my * my + mz * mz);
    if (!(ml > 0)) return 0;
    mx /= ml;
    my /= ml;
    mz /= ml;
    double m[3] = {mx * T[0] + my * B[0] + mz * N[0], mx * T[1] + my * B[1] + mz * N[1],
                   mx * T[2] + my * B[2] + mz * N[2]};
    double om = dot3(wo, m);
    double l[3] = {2 * om * m[0] - wo[0], 2 * om * m[1] - wo[1], 2 * om * m[2] - wo[2]};
    double lz = dot3(l, N);
    if (!(lz > 0)) return 0;
    /* G1(l) = 1 / (1 + Lambda(l)), Lambda = (sqrt(1 + alpha^2 tan^2) - 1) / 2 */
    double t2 = (1 - lz * lz) / (lz * lz);
    double g1 = 2 / (1 + sqrt(1 + alpha * alpha * t2));
    copy3(out, l);
    return g1;
}

void tdc_r_trace_local(rthread_t *t, const double P[3], const double N[3], const double d[3], const rsample_t *a,
                       uint32_t salt, double L[3])
{
    double eps = offset_eps(P);
    double O[3] = {P[0] + N[0] * eps, P[1] + N[1] * eps, P[2] + N[2] * eps};
    struct RTCRayHit rh;
    int h = intersect(t, 0, O, d, 0, INFINITY, TDC_RAY_REFLECT, &rh);
    if (h < 0) {
        copy3(L, t->r->scene->background);
        return;
    }
    double P2[3], Q2[3], N2[3], NQ2[3];
    wncache_t wc = {.obj = -1};
    surface_rh(t->cur, &rh, h, O, d, P2, Q2, N2, NQ2, &wc);
    t->tex_fw = 0; /* a diffuse bounce: its Monte Carlo estimate averages the texture (point-sampled as before) */
    shade_direct(t, h, P2, Q2, N2, NQ2, rng_key(a), a->k, salt, NULL, L, NULL, -1, NULL);
}

void tdc_r_pass_reflect(rthread_t *t, rsample_t *s, int n)
{
    const tdc_scene_t *sc = t->r->scene;
    int maxb = t->r->cfg.max_bounces;
    wncache_t wc = {.obj = -1};
    for (int i = 0; i < n; i++) {
        rsample_t *a = &s[i];
        if (!(a->mirror > 0)) continue;
        double thr = a->mirror, P[3], N[3], Q[3], NQ[3], d[3];
        int obj = a->obj;
        memcpy(P, a->P, sizeof P);
        memcpy(N, a->N, sizeof N);
        memcpy(Q, a->Q, sizeof Q);
        memcpy(NQ, a->NQ, sizeof NQ);
        memcpy(d, a->dir, sizeof d);
        a->robj = -1;
        double dist = a->hit_t * sqrt(dot3(d, d)); /* ray-cone length so far (texture footprint) */
        for (int b = 0; b < maxb; b++) {
            a->mobj[b] = obj;
            copy3(a->mQ[b], Q);
            copy3(a->mNQ[b], NQ);
            a->nmir = b + 1;
            double rough = b ? sc->materials[sc->objects[obj].material].roughness : a->rough;
            if (rough > 0) {
                /* glossy: one importance-sampled GGX direction (1 secondary
                 * ray per pixel, Zeng §4.2), weight G1 of the sampled side */
                uint32_t dim = 2u + 4u * (uint32_t)b;
                double u1 = tdc_r_rand(t->r->cfg.seed, t->frame, rng_key(a), a->k, dim);
                double u2 = tdc_r_rand(t->r->cfg.seed, t->frame, rng_key(a), a->k, dim + 1);
                double g = tdc_r_ggx_sample(d, N, rough, u1, u2, d);
                if (!(g > 0)) { /* sampled below the surface: the lobe's lost energy, no reflected hit */
                    a->nmir = 0;
                    break;
                }
                thr *= g;
            } else {
                double dn = dot3(d, N);
                for (int c = 0; c < 3; c++) d[c] -= 2 * dn * N[c];
            }
            /* start exactly at the mirror point (so the reflected MV geometry is
             * exact) and skip self-hits with tnear instead of a normal offset */
            double O[3] = {P[0], P[1], P[2]};
            struct RTCRayHit rh;
            int h = intersect(t, 0, O, d, offset_eps(P), INFINITY, TDC_RAY_REFLECT, &rh);
            if (h < 0) {
                for (int c = 0; c < 3; c++) a->col[c] += thr * sc->background[c];
                if (t->layers)
                    for (int c = 0; c < 3; c++) a->refl[c] += thr * sc->background[c];
                copy3(a->rdir, d);
                break;
            }
            surface_rh(t->cur, &rh, h, O, d, P, Q, N, NQ, &wc);
            dist += rh.ray.tfar * sqrt(dot3(d, d));
            t->tex_fw = tdc_r_sample_fw(t, a, dist, d, NQ, t->cur->minv[h]);
            double loc[3];
            shade_direct(t, h, P, Q, N, NQ, rng_key(a), a->k, 4u * (uint32_t)(b + 1), NULL, loc, NULL, -1, NULL);
            double m2 = sc->materials[sc->objects[h].material].mirror;
            obj = h;
            if (m2 > 0 && b + 1 < maxb) {
                for (int c = 0; c < 3; c++) a->col[c] += thr * (1 - m2) * loc[c];
                if (t->layers)
                    for (int c = 0; c < 3; c++) a->refl[c] += thr * (1 - m2) * loc[c];
                thr *= m2;
                continue;
            }
            for (int c = 0; c < 3; c++) a->col[c] += thr * loc[c];
            if (t->layers)
                for (int c = 0; c < 3; c++) a->refl[c] += thr * loc[c];
            a->robj = h;
            copy3(a->rQ, Q);
            break;
        }
    }
}

/* tdc_r_project of the point (p0, p1, p2) held in registers: the same
 * operations, without arrays (a point stored element by element and copied
 * or read back as a vector stalled on store forwarding). */
static inline int project_s(const rcam_t *c, double p0, double p1, double p2, double *x, double *y)
{
    double d0 = p0 - c->pos[0], d1 = p1 - c->pos[1], d2 = p2 - c->pos[2];
    double z = d0 * c->fwd[0] + d1 * c->fwd[1] + d2 * c->fwd[2];
    if (!(z > 1e-12)) return -1;
    double iz = 1.0 / z;
    double u = (d0 * c->right[0] + d1 * c->right[1] + d2 * c->right[2]) * iz;
    double v = (d0 * c->up[0] + d1 * c->up[1] + d2 * c->up[2]) * iz;
    *x = u * c->kx + 0.5 * c->w;
    *y = 0.5 * c->h - v * c->ky;
    return 0;
}

/* Object point q of object obj in world space in the current (c) and the
 * previous (p) frame (the products as in tdc_r_xform_point), sharing the
 * product when the matrix or its rotation-scale part did not change. */
static inline __attribute__((always_inline)) void xform_both(const rthread_t *t, int obj, const double q[3],
                                                             double c[3], double p[3])
{
    const double *mc = t->cur->m[obj], *mp = t->prev->m[obj];
    if (t->r->obj_same_m[obj]) { /* same matrix: same product */
        c[0] = p[0] = mc[0] * q[0] + mc[1] * q[1] + mc[2] * q[2] + mc[3];
        c[1] = p[1] = mc[4] * q[0] + mc[5] * q[1] + mc[6] * q[2] + mc[7];
        c[2] = p[2] = mc[8] * q[0] + mc[9] * q[1] + mc[10] * q[2] + mc[11];
    } else if (t->r->obj_same_rs[obj]) {
        /* translation only: ((m0 q0 + m1 q1) + m2 q2) is the same in both
         * frames, then each adds its own translation */
        const double r0 = mc[0] * q[0] + mc[1] * q[1] + mc[2] * q[2];
        const double r1 = mc[4] * q[0] + mc[5] * q[1] + mc[6] * q[2];
        const double r2 = mc[8] * q[0] + mc[9] * q[1] + mc[10] * q[2];
        c[0] = r0 + mc[3];
        c[1] = r1 + mc[7];
        c[2] = r2 + mc[11];
        p[0] = r0 + mp[3];
        p[1] = r1 + mp[7];
        p[2] = r2 + mp[11];
    } else {
        c[0] = mc[0] * q[0] + mc[1] * q[1] + mc[2] * q[2] + mc[3];
        c[1] = mc[4] * q[0] + mc[5] * q[1] + mc[6] * q[2] + mc[7];
        c[2] = mc[8] * q[0] + mc[9] * q[1] + mc[10] * q[2] + mc[11];
        p[0] = mp[0] * q[0] + mp[1] * q[1] + mp[2] * q[2] + mp[3];
        p[1] = mp[4] * q[0] + mp[5] * q[1] + mp[6] * q[2] + mp[7];
        p[2] = mp[8] * q[0] + mp[9] * q[1] + mp[10] * q[2] + mp[11];
    }
}

/* Current and previous screen position of object point q of object obj
 * (the products as in tdc_r_xform_point). */
static inline __attribute__((always_inline)) int track_point(const rthread_t *t, int obj, const double q[3], double *xc,
                                                             double *yc, double *xp, double *yp)
{
    double c[3], p[3];
    xform_both(t, obj, q, c, p);
    if (project_s(&t->cur->cam, c[0], c[1], c[2], xc, yc) < 0) return -1;
    return project_s(&t->prev->cam, p[0], p[1], p[2], xp, yp);
}

/* The point or direction each MV sample projects, as camera-relative
 * directions (d = point - camera position, or the ray direction of a
 * miss) for both frames: the projections then run two samples at a time. */
static inline void track_dirs(const rthread_t *t, const rsample_t *a, double dc[3], double dp[3])
{
    if (a->obj < 0) {
        for (int c = 0; c < 3; c++) dc[c] = dp[c] = a->dir[c];
        return;
    }
    const double *pc = t->cur->cam.pos, *pp = t->prev->cam.pos;
    double c[3], p[3];
    xform_both(t, a->obj, a->Q, c, p);
    dc[0] = c[0] - pc[0]; /* the subtraction project_s starts with */
    dc[1] = c[1] - pc[1];
    dc[2] = c[2] - pc[2];
    dp[0] = p[0] - pp[0];
    dp[1] = p[1] - pp[1];
    dp[2] = p[2] - pp[2];
}

#if defined(__SSE2__)
/* tdc_r_project_dir for two directions (one per lane), without the depth
 * test (the caller tests z): every lane does the same IEEE operations in
 * the same order as the scalar function (SSE2 mul/add/sub/div are
 * correctly rounded per lane, no FMA), so the results are bit-identical. */
static inline void project_dir2(const rcam_t *c, __m128d d0, __m128d d1, __m128d d2, __m128d *x, __m128d *y, __m128d *z)
{
    __m128d zz = _mm_add_pd(_mm_add_pd(_mm_mul_pd(d0, _mm_set1_pd(c->fwd[0])), _mm_mul_pd(d1, _mm_set1_pd(c->fwd[1]))),
                            _mm_mul_pd(d2, _mm_set1_pd(c->fwd[2])));
    __m128d iz = _mm_div_pd(_mm_set1_pd(1.0), zz);
    __m128d u = _mm_mul_pd(
        _mm_add_pd(_mm_add_pd(_mm_mul_pd(d0, _mm_set1_pd(c->right[0])), _mm_mul_pd(d1, _mm_set1_pd(c->right[1]))),
                   _mm_mul_pd(d2, _mm_set1_pd(c->right[2]))),
        iz);
    __m128d v =
        _mm_mul_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(d0, _mm_set1_pd(c->up[0])), _mm_mul_pd(d1, _mm_set1_pd(c->up[1]))),
                              _mm_mul_pd(d2, _mm_set1_pd(c->up[2]))),
                   iz);
    *x = _mm_add_pd(_mm_mul_pd(u, _mm_set1_pd(c->kx)), _mm_set1_pd(0.5 * c->w));
    *y = _mm_sub_pd(_mm_set1_pd(0.5 * c->h), _mm_mul_pd(v, _mm_set1_pd(c->ky)));
    *z = zz;
}
#endif

/* MV of one sample from its projections (depths zc, zp as tested by
 * tdc_r_project_dir); results in locals, stored once: reading back fields
 * just written one by one stalled on store forwarding. */
static inline void mv_store(rsample_t *a, double zc, double zp, double xc, double yc, double xp, double yp)
{
    int ok = zc > 1e-12 && zp > 1e-12;
    if (!ok) { /* behind a camera: no correspondence */
        xc = a->x;
        yc = a->y;
        xp = a->x;
        yp = a->y;
    }
    a->xc = xc;
    a->yc = yc;
    a->mv_valid = ok;
    a->mv[0] = xp - xc;
    a->mv[1] = yp - yc;
    a->refl_used = 0;
}

#define MV_CHUNK 64
void tdc_r_pass_mv(rthread_t *t, rsample_t *s, int n)
{
    const rcam_t *cc = &t->cur->cam, *cp = &t->prev->cam;
    /* pending samples of a chunk and their camera-relative directions (SoA) */
    int idx[MV_CHUNK + 1];
    double dc[3][MV_CHUNK + 1], dp[3][MV_CHUNK + 1];
    for (int i0 = 0; i0 < n; i0 += MV_CHUNK) {
        int i1 = i0 + MV_CHUNK < n ? i0 + MV_CHUNK : n, m = 0;
        for (int i = i0; i < i1; i++) {
            rsample_t *a = &s[i];
            if (!t->r->cam_moved && (a->obj < 0 || !t->r->obj_moved[a->obj])) {
                /* nothing here moved: the point is where it was */
                a->xc = a->x;
                a->yc = a->y;
                a->mv_valid = 1;
                a->mv[0] = a->mv[1] = 0;
                a->refl_used = 0;
                continue;
            }
            idx[m++] = i;
        }
        for (int j = 0; j < m; j++) {
            double c3[3], p3[3];
            track_dirs(t, &s[idx[j]], c3, p3);
            for (int c = 0; c < 3; c++) {
                dc[c][j] = c3[c];
                dp[c][j] = p3[c];
            }
        }
        int j = 0;
#if defined(__SSE2__)
        for (; j + 2 <= m; j += 2) {
            __m128d xc, yc, zc, xp, yp, zp;
            project_dir2(cc, _mm_loadu_pd(&dc[0][j]), _mm_loadu_pd(&dc[1][j]), _mm_loadu_pd(&dc[2][j]), &xc, &yc, &zc);
            project_dir2(cp, _mm_loadu_pd(&dp[0][j]), _mm_loadu_pd(&dp[1][j]), _mm_loadu_pd(&dp[2][j]), &xp, &yp, &zp);
            double r[6][2];
            _mm_storeu_pd(r[0], zc);
            _mm_storeu_pd(r[1], zp);
            _mm_storeu_pd(r[2], xc);
            _mm_storeu_pd(r[3], yc);
            _mm_storeu_pd(r[4], xp);
            _mm_storeu_pd(r[5], yp);
            for (int l = 0; l < 2; l++) mv_store(&s[idx[j + l]], r[0][l], r[1][l], r[2][l], r[3][l], r[4][l], r[5][l]);
        }
#endif
        for (; j < m; j++) {
            const double d3c[3] = {dc[0][j], dc[1][j], dc[2][j]}, d3p[3] = {dp[0][j], dp[1][j], dp[2][j]};
            double xc = 0, yc = 0, xp = 0, yp = 0;
            double zc = tdc_r_project_dir(cc, d3c, &xc, &yc) == 0 ? 1 : 0;
            double zp = zc > 0 && tdc_r_project_dir(cp, d3p, &xp, &yp) == 0 ? 1 : 0;
            mv_store(&s[idx[j]], zc, zp, xc, yc, xp, yp);
        }
    }
}

/* Reflects V (a point, or a direction when dir_only) through the plane
 * (P, n): V -= 2 ((V - P) . n) n. */
static inline void mirror_reflect(double V[3], const double P[3], const double nrm[3], int dir_only)
{
    double dd = dir_only ? dot3(V, nrm) : (V[0] - P[0]) * nrm[0] + (V[1] - P[1]) * nrm[1] + (V[2] - P[2]) * nrm[2];
    for (int c = 0; c < 3; c++) V[c] -= 2 * dd * nrm[c];
}

/* Mirror images of Vc and Vp through the chain's planes in the current and
 * the previous frame.  A mirror whose matrix did not change has the same
 * plane in both frames: transformed and normalised once. */
/* The last mirror plane normals computed in a pass: neighbouring samples
 * see the same mirror triangle, so the same object and the same raw normal
 * bits give the same (deterministic) normalised normals without the square
 * root and division again. */
typedef struct {
    int o;               /* -1: empty */
    uint64_t nq[3];      /* bits of the raw object-space normal */
    double nc[3], np[3]; /* current / previous world normal */
} ncache_t;

static inline void plane_normals(const rthread_t *t, ncache_t *nc_, int o, const double nq[3], double nc[3],
                                 double np[3])
{
    uint64_t b[3];
    memcpy(b, nq, sizeof b);
    if (nc_->o != o || nc_->nq[0] != b[0] || nc_->nq[1] != b[1] || nc_->nq[2] != b[2]) {
        tdc_r_xform_normal(t->cur->nm[o], nq, nc_->nc);
        if (t->r->obj_same_m[o])
            copy3(nc_->np, nc_->nc); /* unused: the same plane is taken */
        else
            tdc_r_xform_normal(t->prev->nm[o], nq, nc_->np);
        nc_->o = o;
        nc_->nq[0] = b[0];
        nc_->nq[1] = b[1];
        nc_->nq[2] = b[2];
    }
    copy3(nc, nc_->nc);
    copy3(np, nc_->np);
}

static void mirror_chain2(const rthread_t *t, const rsample_t *a, double Vc[3], double Vp[3], int dir_only,
                          ncache_t *ncache)
{
    for (int j = a->nmir - 1; j >= 0; j--) {
        int o = a->mobj[j];
        double Pc[3], nc[3], np[3];
        tdc_r_xform_point(t->cur->m[o], a->mQ[j], Pc);
        plane_normals(t, ncache, o, a->mNQ[j], nc, np);
        mirror_reflect(Vc, Pc, nc, dir_only);
        if (t->r->obj_same_m[o]) { /* same matrix (so same normal matrix): same plane */
            mirror_reflect(Vp, Pc, nc, dir_only);
        } else {
            double Pp[3];
            tdc_r_xform_point(t->prev->m[o], a->mQ[j], Pp);
            mirror_reflect(Vp, Pp, np, dir_only);
        }
    }
}

/* Stochastic glossy MV (Zeng §4.2, eq. 5): the previous virtual image Vp
 * of the reflected hit is seen through the previous primary plane (Pp, np)
 * at s^C (projection mu = (xp, yp)); the pixels around it that reflect the
 * same hit form a Gaussian region, found by intersecting the lobe with the
 * plane: a cone of angular sigma sqrt(2) alpha (GGX's slope sigma alpha /
 * sqrt(2), doubled by the reflection) around the line Vp -> s^C, its apex
 * at d_h d_c / (d_h + d_c) before s^C (d_h: virtual image to s^C, d_c: s^C
 * to the camera; the paper's apex at the virtual image is the d_c >> d_h
 * limit: a pixel's reflected direction turns by the offset over d_h plus
 * the offset over d_c).  The four axis endpoints are projected; their
 * half-differences are the image half-axes (mvr_ax); the MV is mu +
 * g1 ax1 + g2 ax2 - x with g1, g2 standard normal (Box-Muller from the
 * sample's random numbers).  0 if the region cannot be formed. */
static int glossy_region(const rthread_t *t, const rsample_t *a, const double Vp[3], double ax[4])
{
    const rframe_t *p = t->prev;
    const rcam_t *cp = &p->cam;
    int o = a->mobj[0];
    double Pp[3], np[3];
    tdc_r_xform_point(p->m[o], a->mQ[0], Pp);
    tdc_r_xform_normal(p->nm[o], a->mNQ[0], np);
    /* s^C: the line camera -> Vp through the plane */
    double dv[3] = {Vp[0] - cp->pos[0], Vp[1] - cp->pos[1], Vp[2] - cp->pos[2]};
    double den = dot3(dv, np);
    if (!(fabs(den) > 1e-12 * sqrt(dot3(dv, dv)))) return 0;
    double tt = ((Pp[0] - cp->pos[0]) * np[0] + (Pp[1] - cp->pos[1]) * np[1] + (Pp[2] - cp->pos[2]) * np[2]) / den;
    if (!(tt > 0 && tt < 1)) return 0; /* the virtual image is not behind the reflector */
    double sC[3] = {cp->pos[0] + tt * dv[0], cp->pos[1] + tt * dv[1], cp->pos[2] + tt * dv[2]};
    double dc = tt * sqrt(dot3(dv, dv)), dh = (1 - tt) * sqrt(dot3(dv, dv));
    double ua[3] = {-dv[0], -dv[1], -dv[2]}; /* cone axis: from the virtual image toward s^C and the camera */
    double ul = sqrt(dot3(ua, ua));
    for (int c = 0; c < 3; c++) ua[c] /= ul;
    double deff = dh * dc / (dh + dc);
    double A[3] = {sC[0] - deff * ua[0], sC[1] - deff * ua[1], sC[2] - deff * ua[2]};
    /* e2 in the plane, across the axis; e1 across the axis in the plane of
     * the axis and the normal (the major axis of the footprint) */
    double e2[3] = {ua[1] * np[2] - ua[2] * np[1], ua[2] * np[0] - ua[0] * np[2], ua[0] * np[1] - ua[1] * np[0]};
    double l2 = sqrt(dot3(e2, e2));
    if (!(l2 > 1e-9)) { /* looking straight down the normal: any perpendicular pair */
        double h[3] = {fabs(ua[0]) < 0.9 ? 1 : 0, fabs(ua[0]) < 0.9 ? 0 : 1, 0};
        e2[0] = ua[1] * h[2] - ua[2] * h[1];
        e2[1] = ua[2] * h[0] - ua[0] * h[2];
        e2[2] = ua[0] * h[1] - ua[1] * h[0];
        l2 = sqrt(dot3(e2, e2));
    }
    for (int c = 0; c < 3; c++) e2[c] /= l2;
    double e1[3] = {e2[1] * ua[2] - e2[2] * ua[1], e2[2] * ua[0] - e2[0] * ua[2], e2[0] * ua[1] - e2[1] * ua[0]};
    double tn = tan(sqrt(2.0) * a->rough);
    double img[4][2];
    for (int k = 0; k < 4; k++) {
        const double *e = k < 2 ? e1 : e2;
        double sg = k & 1 ? -tn : tn;
        double dr[3] = {ua[0] + sg * e[0], ua[1] + sg * e[1], ua[2] + sg * e[2]};
        double dd = dot3(dr, np);
        if (!(fabs(dd) > 1e-12)) return 0;
        double u = ((Pp[0] - A[0]) * np[0] + (Pp[1] - A[1]) * np[1] + (Pp[2] - A[2]) * np[2]) / dd;
        if (!(u > 0)) return 0; /* the lobe edge runs along the plane (grazing) */
        double X[3] = {A[0] + u * dr[0], A[1] + u * dr[1], A[2] + u * dr[2]};
        if (tdc_r_project(cp, X, &img[k][0], &img[k][1]) < 0) return 0;
    }
    ax[0] = 0.5 * (img[0][0] - img[1][0]);
    ax[1] = 0.5 * (img[0][1] - img[1][1]);
    ax[2] = 0.5 * (img[2][0] - img[3][0]);
    ax[3] = 0.5 * (img[2][1] - img[3][1]);
    return 1;
}

void tdc_r_pass_mv_reflect(rthread_t *t, rsample_t *s, int n)
{
    ncache_t ncache = {.o = -1};
    int subst = t->r->cfg.reflect_mv; /* the single-layer MV takes the reflected one where k >= 0.5 */
    for (int i = 0; i < n; i++) {
        rsample_t *a = &s[i];
        a->mvr_ok = 0;
        if (a->nmir == 0 || (a->mirror < 0.5 && !t->layers)) continue;
        double Vc[3], Vp[3], xc, yc, xp, yp;
        int dir_only = a->robj < 0, ok;
        if (dir_only) {
            memcpy(Vc, a->rdir, sizeof Vc);
            memcpy(Vp, a->rdir, sizeof Vp);
        } else {
            tdc_r_xform_point(t->cur->m[a->robj], a->rQ, Vc);
            if (t->r->obj_same_m[a->robj])
                copy3(Vp, Vc);
            else
                tdc_r_xform_point(t->prev->m[a->robj], a->rQ, Vp);
        }
        mirror_chain2(t, a, Vc, Vp, dir_only, &ncache);
#if defined(__SSE2__)
        {
            /* both projections in one register (lane 0 current camera, lane
             * 1 previous): the operations of tdc_r_project(_dir) per lane */
            const rcam_t *cc = &t->cur->cam, *cp = &t->prev->cam;
            __m128d d[3];
            for (int c = 0; c < 3; c++) {
                d[c] = _mm_set_pd(Vp[c], Vc[c]);
                if (!dir_only) d[c] = _mm_sub_pd(d[c], _mm_set_pd(cp->pos[c], cc->pos[c]));
            }
            __m128d z = _mm_add_pd(_mm_add_pd(_mm_mul_pd(d[0], _mm_set_pd(cp->fwd[0], cc->fwd[0])),
                                              _mm_mul_pd(d[1], _mm_set_pd(cp->fwd[1], cc->fwd[1]))),
                                   _mm_mul_pd(d[2], _mm_set_pd(cp->fwd[2], cc->fwd[2])));
            __m128d iz = _mm_div_pd(_mm_set1_pd(1.0), z);
            __m128d u = _mm_mul_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(d[0], _mm_set_pd(cp->right[0], cc->right[0])),
                                                         _mm_mul_pd(d[1], _mm_set_pd(cp->right[1], cc->right[1]))),
                                              _mm_mul_pd(d[2], _mm_set_pd(cp->right[2], cc->right[2]))),
                                   iz);
            __m128d v = _mm_mul_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(d[0], _mm_set_pd(cp->up[0], cc->up[0])),
                                                         _mm_mul_pd(d[1], _mm_set_pd(cp->up[1], cc->up[1]))),
                                              _mm_mul_pd(d[2], _mm_set_pd(cp->up[2], cc->up[2]))),
                                   iz);
            __m128d x = _mm_add_pd(_mm_mul_pd(u, _mm_set_pd(cp->kx, cc->kx)), _mm_set_pd(0.5 * cp->w, 0.5 * cc->w));
            __m128d y = _mm_sub_pd(_mm_set_pd(0.5 * cp->h, 0.5 * cc->h), _mm_mul_pd(v, _mm_set_pd(cp->ky, cc->ky)));
            double zz[2], xx[2], yy[2];
            _mm_storeu_pd(zz, z);
            _mm_storeu_pd(xx, x);
            _mm_storeu_pd(yy, y);
            ok = zz[0] > 1e-12 && zz[1] > 1e-12;
            xc = xx[0];
            yc = yy[0];
            xp = xx[1];
            yp = yy[1];
        }
#else
        if (dir_only)
            ok = tdc_r_project_dir(&t->cur->cam, Vc, &xc, &yc) == 0 &&
                 tdc_r_project_dir(&t->prev->cam, Vp, &xp, &yp) == 0;
        else
            ok = tdc_r_project(&t->cur->cam, Vc, &xc, &yc) == 0 && tdc_r_project(&t->prev->cam, Vp, &xp, &yp) == 0;
#endif
        if (!ok) continue; /* virtual image behind a camera: keep the primary MV */
        if (a->rough > 0 && !dir_only) {
            if (!glossy_region(t, a, Vp, a->mvr_ax)) continue;
            double u1 = tdc_r_rand(t->r->cfg.seed, t->frame, rng_key(a), a->k, 14);
            double u2 = tdc_r_rand(t->r->cfg.seed, t->frame, rng_key(a), a->k, 15);
            double rr = sqrt(-2 * log(1 - u1)), g1 = rr * cos(2 * M_PI * u2), g2 = rr * sin(2 * M_PI * u2);
            a->mvr_mu[0] = xp - a->xc;
            a->mvr_mu[1] = yp - a->yc;
            a->mvr[0] = a->mvr_mu[0] + g1 * a->mvr_ax[0] + g2 * a->mvr_ax[2];
            a->mvr[1] = a->mvr_mu[1] + g1 * a->mvr_ax[1] + g2 * a->mvr_ax[3];
        } else {
            /* mirror (or a glossy reflection of the sky: directions only, no region) */
            a->mvr[0] = a->mvr_mu[0] = xp - xc;
            a->mvr[1] = a->mvr_mu[1] = yp - yc;
            a->mvr_ax[0] = a->mvr_ax[1] = a->mvr_ax[2] = a->mvr_ax[3] = 0;
        }
        a->mvr_ok = 1;
        if (!subst || a->mirror < 0.5) continue;
        a->mvsurf[0] = a->mv[0];
        a->mvsurf[1] = a->mv[1];
        a->mv[0] = a->mvr[0];
        a->mv[1] = a->mvr[1];
        a->refl_used = 1;
    }
}

/* Where image position (x, y) falls in the previous G-buffer: (fx, fy) in
 * sample units (its jitter removed) and (in, jn) the nearest sample.
 * Returns 0, or -1 when it lies outside the image.  Rounding by truncation
 * of a positive value instead of floor (a libm call, or a 6-instruction
 * sequence without SSE4.1). */
static int gbuf_at(const rthread_t *t, double x, double y, double *fx, double *fy, int *in, int *jn)
{
    *fx = x - 0.5 - t->gb_jx;
    *fy = y - 0.5 - t->gb_jy;
    if (!(*fx > -0.5 && *fy > -0.5 && *fx < t->r->W - 0.5 && *fy < t->r->H - 0.5)) return -1;
    *in = (int)(*fx + 0.5);
    *jn = (int)(*fy + 0.5);
    return 0;
}

/* The previous G-buffer's depth at (fx, fy) (sample units; (in, jn) its
 * nearest sample, inside the image), linear from the neighbour of the same
 * object toward it (extrapolated from the other side at its edge): a
 * grazing face changes depth by more than 1 % within half a pixel (the
 * analytic occlusion scene's boxes: 0.17 a pixel at 3.3), and the shadow
 * falloff's angle (eq. 4, sigma 0.1 rad) is as sensitive: with the
 * nearest sample's depth alone, 34 of 190 shadowed pixels' weights were
 * more than 0.1 from the traced ones (test_shadow_falloff_lookup), with
 * this none. */
static double gbuf_depth_at(const rthread_t *t, double fx, double fy, int in, int jn)
{
    const int W = t->r->W, H = t->r->H;
    const tdc_r_gpix_t *gn = &t->gb_prev[(size_t)jn * W + in];
    double dy = gn->depth; /* sky: INFINITY */
    const double off[2] = {fx - in, fy - jn};
    for (int ax = 0; ax < 2 && gn->obj >= 0; ax++) {
        const int sg = off[ax] >= 0 ? 1 : -1;
        for (int side = 0; side < 2; side++) {
            const int s2 = side ? -sg : sg, i = in + (ax ? 0 : s2), j = jn + (ax ? s2 : 0);
            if (i < 0 || j < 0 || i >= W || j >= H) continue;
            const tdc_r_gpix_t *g = &t->gb_prev[(size_t)j * W + i];
            if (g->obj != gn->obj) continue;
            dy += ((double)g->depth - gn->depth) * s2 * off[ax];
            break;
        }
    }
    return dy;
}

/* What the previous frame saw at (x, y): object (or -1) and world point.
 * With the previous FULL frame's G-buffer, the sample nearest (x, y) (its
 * object, and gbuf_depth_at along the ray through (x, y)), as a GPU renderer
 * reads its previous G-buffer; else a previous-frame primary ray.  The
 * shadow falloff's 1080x1200 fence traced 112 k such rays a frame, half of
 * the pass (zeng-cost). */
static int prev_visible(rthread_t *t, double x, double y, double W[3], double d[3])
{
    const rcam_t *cam = &t->prev->cam;
    tdc_r_cam_ray(cam, x, y, d);
    double fx, fy;
    int in, jn;
    if (t->gb_prev && gbuf_at(t, x, y, &fx, &fy, &in, &jn) == 0) {
        const int o = t->gb_prev[(size_t)jn * t->r->W + in].obj;
        if (o >= 0) {
            const double dy = gbuf_depth_at(t, fx, fy, in, jn);
            for (int c = 0; c < 3; c++) W[c] = cam->pos[c] + dy * d[c];
        }
        return o;
    }
    struct RTCRayHit rh;
    int o = intersect(t, 1, cam->pos, d, 0, INFINITY, TDC_RAY_MV, &rh);
    if (o >= 0)
        for (int c = 0; c < 3; c++) W[c] = cam->pos[c] + rh.ray.tfar * d[c];
    return o;
}

void tdc_r_pass_mv_shadow(rthread_t *t, rsample_t *s, int n)
{
    for (int i = 0; i < n; i++) {
        rsample_t *a = &s[i];
        a->mvs[0] = a->mv[0];
        a->mvs[1] = a->mv[1];
        a->sw = 0;
        if (!a->in_shadow) continue;
        const rframe_t *p = t->prev;
        /* the light sample in the previous frame: rect lights translate, so
         * the sample keeps its offset from the light's position */
        const double *lp0 = p->light_pos[a->blk_light];
        double lp[3] = {lp0[0] + a->loff[0], lp0[1] + a->loff[1], lp0[2] + a->loff[2]};
        double bp[3], sp[3], np[3];
        tdc_r_xform_point(p->m[a->blk_obj], a->BQ, bp);
        tdc_r_xform_point(p->m[a->obj], a->Q, sp);
        tdc_r_xform_normal(p->nm[a->obj], a->NQ, np);
        double d[3] = {bp[0] - lp[0], bp[1] - lp[1], bp[2] - lp[2]};
        double den = dot3(d, np);
        if (fabs(den) < 1e-12 * sqrt(dot3(d, d))) continue; /* blocker ray parallel to the receiver plane */
        double tt = ((sp[0] - lp[0]) * np[0] + (sp[1] - lp[1]) * np[1] + (sp[2] - lp[2]) * np[2]) / den;
        double sv[3] = {lp[0] + tt * d[0], lp[1] + tt * d[1], lp[2] + tt * d[2]};
        double xv, yv;
        if (tdc_r_project(&p->cam, sv, &xv, &yv) < 0) continue;
        a->mvs[0] = xv - a->xc;
        a->mvs[1] = yv - a->yc;
        /* Falloff (Zeng eq. 4): theta between the receiver normal and the
         * direction to the point actually seen at x^V in the previous frame. */
        double W[3], dd[3];
        int o = prev_visible(t, xv, yv, W, dd);
        if (o < 0) continue;
        double v[3] = {W[0] - sp[0], W[1] - sp[1], W[2] - sp[2]};
        double vl = sqrt(dot3(v, v));
        if (vl < 1e-9 * (1 + sqrt(dot3(sp, sp)))) {
            a->sw = 1;
            continue;
        }
        double ct = dot3(v, np) / vl;
        ct = ct < -1 ? -1 : ct > 1 ? 1 : ct;
        double th = acos(ct) - M_PI / 2;
        a->sw = exp(-th * th / (2 * 0.1 * 0.1));
    }
}

/* The dual pass's previous-frame visibility ray of a sample: where it
 * looks (y), the ray's direction, what it hit and where (prev_visible's
 * values, traced 16 at a time by closest16). */
typedef struct tdc_r_dual {
    int i;       /* the sample */
    double y[2]; /* previous-frame position */
    double d[3], W[3];
    int o;
} tdc_r_dual_t;

/* Eq. 6's P_{i-1}^{-1} y and T(y) read from the previous frame's G-buffer
 * (Zeng §4.3: "y = P_{i-1} T^{-1}(x_i) P_i^{-1} x_i and z = P_i T(y)
 * P_{i-1}^{-1} y"; the object at y and its depth are what the previous frame
 * saw there), at the sample nearest y.  Sample a was occluded at y if that
 * sample saw something in front of a's previous point (depth dp): nearer
 * than dp by more than the traced test's 1e-3 (1 + dp) plus 1 % of dp, at
 * the sample and at y (its depth there from the neighbour toward y).  A
 * farther or equal depth is not an occluder: y is then a's own surface or lies within half a pixel of its
 * silhouette, where the nearest sample fell on the background (a test of the
 * object id alone would call those disoccluded: 16 of 48 at a moving box's
 * edges in test_render_mv; a test of 2x2 samples missed a turning box's own
 * faces, 20 of 62).  Sky (dp infinite) was occluded unless the sample saw
 * sky.  When occluded, q gets the sample's object q->o and point q->W =
 * camera + depth * d(y) (d's forward component is 1, tdc_r_cam_ray), as the
 * traced ray would return them.  Returns 1 not occluded, 0 occluded (q
 * filled), -1 y is outside the image: no correspondence exists there (Zeng
 * §7: "we do not explicitly handle the cases where the motion vectors point
 * to regions outside the image plane"), the pixel keeps its vector. */
static int gbuf_lookup(const rthread_t *t, const rsample_t *a, tdc_r_dual_t *q)
{
    double fx, fy;
    int in, jn;
    if (gbuf_at(t, q->y[0], q->y[1], &fx, &fy, &in, &jn) != 0) return -1;
    const tdc_r_gpix_t *gn = &t->gb_prev[(size_t)jn * t->r->W + in];
    const rcam_t *cam = &t->prev->cam;
    if (a->obj < 0) {
        if (gn->obj < 0) return 1; /* sky then and now */
    } else {
        double sp[3];
        tdc_r_xform_point(t->prev->m[a->obj], a->Q, sp);
        const double dp = (sp[0] - cam->pos[0]) * cam->fwd[0] + (sp[1] - cam->pos[1]) * cam->fwd[1] +
                          (sp[2] - cam->pos[2]) * cam->fwd[2];
        const double lim = dp - (1e-3 * (1 + dp) + 0.01 * dp);
        if (gn->depth >= lim) return 1; /* sky: INFINITY */
        if (gbuf_depth_at(t, fx, fy, in, jn) >= lim) return 1;
    }
    tdc_r_cam_ray(cam, q->y[0], q->y[1], q->d);
    q->o = gn->obj;
    if (q->o >= 0)
        for (int c = 0; c < 3; c++) q->W[c] = cam->pos[c] + (double)gn->depth * q->d[c];
    return 0;
}

void tdc_r_pass_mv_dual(rthread_t *t, rsample_t *s, int n)
{
    /* the samples that need a ray, with their previous-frame positions */
    if (t->cdq < (size_t)(unsigned)n) {
        tdc_r_dual_t *q = realloc(t->dq, (size_t)(unsigned)n * sizeof *q);
        if (!q) {
            for (int i = 0; i < n; i++) { /* out of memory: no dual MVs for this tile */
                s[i].mvd[0] = s[i].mv[0];
                s[i].mvd[1] = s[i].mv[1];
                s[i].disocc = 0;
            }
            return;
        }
        t->dq = q;
        t->cdq = (size_t)(unsigned)n;
    }
    int nq = 0;
    for (int i = 0; i < n; i++) {
        rsample_t *a = &s[i];
        a->mvd[0] = a->mv[0];
        a->mvd[1] = a->mv[1];
        a->disocc = 0;
        if (!a->mv_valid) continue;
        if (t->ndual_rect >= 0 && (a->obj < 0 || !t->r->obj_moved[a->obj])) {
            /* still camera, still surface (or sky): the previous ray at y = x
             * is this sample's primary ray in a scene whose still objects are
             * unchanged, so it sees the same point unless a moving object
             * covered the pixel; outside their previous screen rectangles it
             * did not, and the ray would only confirm "same" */
            float px = a->x, py = a->y;
            int inside = 0;
            for (int k = 0; k < t->ndual_rect && !inside; k++) {
                const float *b = t->dual_rect[k];
                inside = px >= b[0] && px <= b[2] && py >= b[1] && py <= b[3];
            }
            if (!inside) {
                t->dual_culled++;
                continue;
            }
        }
        tdc_r_dual_t *q = &t->dq[nq];
        q->y[0] = a->xc + a->mv[0];
        q->y[1] = a->yc + a->mv[1];
        if (a->refl_used) { /* dual MVs are for primary visibility: use the primary correspondence */
            if (a->obj < 0 || track_point(t, a->obj, a->Q, &a->xc, &a->yc, &q->y[0], &q->y[1]) < 0) continue;
        }
        if (t->gb_prev && gbuf_lookup(t, a, q) != 0) continue; /* same surface at y, or y off the image */
        q->i = i;
        nq++;
    }
    const rcam_t *cam = &t->prev->cam;
    for (int i0 = 0; i0 < nq && !t->gb_prev; i0 += 16) {
        const int m = nq - i0 < 16 ? nq - i0 : 16;
        const double *dir[16];
        int obj[16];
        float tf[16], ng[16][3];
        for (int k = 0; k < m; k++) {
            tdc_r_dual_t *q = &t->dq[i0 + k];
            tdc_r_cam_ray(cam, q->y[0], q->y[1], q->d);
            dir[k] = q->d;
        }
        closest16(t, 1, cam->pos, dir, m, TDC_RAY_MV, obj, tf, ng);
        for (int k = 0; k < m; k++) {
            tdc_r_dual_t *q = &t->dq[i0 + k];
            q->o = obj[k];
            if (q->o >= 0)
                for (int c = 0; c < 3; c++) q->W[c] = cam->pos[c] + tf[k] * q->d[c];
        }
    }
    for (int j = 0; j < nq; j++) {
        const tdc_r_dual_t *q = &t->dq[j];
        rsample_t *a = &s[q->i];
        const int o = q->o;
        int same;
        if (t->gb_prev)
            same = 0; /* the lookup decided */
        else if (a->obj < 0)
            same = o < 0;
        else if (o != a->obj)
            same = 0;
        else {
            double sp[3];
            tdc_r_xform_point(t->prev->m[a->obj], a->Q, sp);
            double e[3] = {q->W[0] - sp[0], q->W[1] - sp[1], q->W[2] - sp[2]};
            same = sqrt(dot3(e, e)) <= 1e-3 * (1 + a->depth);
        }
        if (same) continue;
        /* Disoccluded: z = where the previous occluder point is now. */
        double z[2];
        if (o >= 0) {
            double qq[3], wc[3];
            tdc_r_xform_point(t->prev->minv[o], q->W, qq);
            tdc_r_xform_point(t->cur->m[o], qq, wc);
            if (tdc_r_project(&t->cur->cam, wc, &z[0], &z[1]) < 0) continue;
        } else if (tdc_r_project_dir(&t->cur->cam, q->d, &z[0], &z[1]) < 0) {
            continue;
        }
        a->disocc = 1;
        a->mvd[0] = q->y[0] - z[0];
        a->mvd[1] = q->y[1] - z[1];
    }
}
