/*
 * tdc_sim_scene.c - built-in procedural scenes: analytic radiance in linear
 * light, exact motion, exact (densely supersampled) ground truth.  They
 * stand in for the papers' stimuli (moving discs, scrolling text, panned
 * panorama, thin vertical features under a pan, a fence whose shadow moves)
 * and stay useful for tiny smoke tests.
 */
#include "tdc_sim_scene.h"

#include <math.h>
#include <stdlib.h>
#include <stdint.h>
#include <string.h>

#include "tdc_layer_link.h"
#include "tdc_math.h"
#include "tdc_par.h"
#include "tdc_sim_codes.h"

/* ---------------------------------------------------------------------
 * Tabulated functions for the inner loops (no libm call per sample).
 *
 * turns_sin(x) = sin(2 pi x) from a table of TURN_N + 1 samples over one
 * turn, linearly interpolated: error <= (2 pi / TURN_N)^2 / 8 = 2.9e-7
 * (TURN_N = 4096), 1/1700 of an 8-bit code step.  ffloor() is floor()
 * without the libm call (x86-64 baseline has no SSE4.1 round): exact for
 * |x| < 2^62, which every texture coordinate is.
 * ------------------------------------------------------------------- */
#define TURN_N 4096
static double k_turn[TURN_N + 2];

static void turn_table_init(void)
{
    static int done;
    if (!done) {
        for (int i = 0; i <= TURN_N + 1; i++) {
            k_turn[i] = sin(6.283185307179586 * (double)i / TURN_N);
        }
        done = 1;
    }
}

static inline double ffloor(double x)
{
    double t = (double)(int64_t)x;
    return t > x ? t - 1.0 : t;
}

static inline double turns_sin(double x)
{
    double f = (x - ffloor(x)) * TURN_N;
    int i = (int)f;
    double a = k_turn[i];
    return a + (k_turn[i + 1] - a) * (f - i);
}

static inline double turns_cos(double x)
{
    return turns_sin(x + 0.25);
}

static const char *const k_scene_names[TDC_SCENE_COUNT] = {"static", "pan",   "text",  "discs", "thin",
                                                           "fence",  "black", "white", "cut"};

const char *tdc_scene_name(tdc_scene_kind_t k)
{
    return (unsigned)k < TDC_SCENE_COUNT ? k_scene_names[k] : "?";
}

int tdc_scene_from_name(const char *name)
{
    for (int i = 0; i < TDC_SCENE_COUNT; i++) {
        if (strcmp(name, k_scene_names[i]) == 0) {
            return i;
        }
    }
    return -1;
}

double tdc_scene_default_speed(tdc_scene_kind_t k)
{
    switch (k) {
    case TDC_SCENE_STATIC:
    case TDC_SCENE_BLACK:
    case TDC_SCENE_WHITE: return 0.0;
    case TDC_SCENE_THIN: return 330.0; /* 1.375 px/frame at 240 Hz: fractional motion */
    case TDC_SCENE_FENCE: return 270.0;
    case TDC_SCENE_DISCS: return 600.0;
    default: return 450.0;
    }
}

typedef struct {
    tdc_scene_params_t p;
    double vx, vy;         /* main motion, px/s */
    tdc_sim_code_table_t codes[3]; /* drive-code decision levels per channel (MIDPOINT) */
} scene_ctx_t;

static uint32_t hash2(int32_t a, int32_t b, uint32_t seed)
{
    return tdc_mix32((uint32_t)a * 0x9E3779B1u ^ ((uint32_t)b * 0x85EBCA77u) ^ (seed * 0xC2B2AE3Du));
}

static double clamp01(double v)
{
    return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
}

/* Panorama-like texture: smooth colour fields, an 8-px checker, a fine
 * grating band, 1-px lines and small dots. */
static void tex_pan(double u, double v, uint32_t seed, double c[3])
{
    const double tau = 6.283185307179586;
    c[0] = 0.30 + 0.22 * turns_sin(u / 53.0 + 1.3 / tau) * turns_cos(v / 41.0);
    c[1] = 0.30 + 0.20 * turns_sin((u + v) / 67.0);
    c[2] = 0.30 + 0.22 * turns_cos((u - v) / 47.0 + 0.4 / tau);
    double fu = ffloor(u), fv = ffloor(v);
    int chk = ((int64_t)ffloor(u / 8.0) + (int64_t)ffloor(v / 8.0)) & 1;
    double d = chk ? 0.12 : -0.08;
    double vm = fv - 64.0 * ffloor(fv / 64.0);
    if (vm < 14.0) {
        d += 0.18 * turns_sin(u / 3.0); /* fine grating: near Nyquist */
    }
    double um = fu - 23.0 * ffloor(fu / 23.0);
    uint32_t h = hash2((int32_t)ffloor(u / 5.0), (int32_t)ffloor(v / 5.0), seed);
    for (int k = 0; k < 3; k++) {
        c[k] = clamp01(c[k] + d);
    }
    if (um == 0.0) {
        c[0] = c[1] = c[2] = 0.85;
    }
    if ((h & 31u) == 0u) {
        double cx = ffloor(u / 5.0) * 5.0 + 2.5, cy = ffloor(v / 5.0) * 5.0 + 2.5;
        if ((u - cx) * (u - cx) + (v - cy) * (v - cy) < 1.2) {
            c[0] = 1.0;
            c[1] = 0.9;
            c[2] = 0.3;
        }
    }
}

/* Pseudo text: 6x9 cells, glyph strokes one pixel wide, dark ink on paper. */
static void tex_text(double u, double v, uint32_t seed, double c[3])
{
    int32_t iu = (int32_t)ffloor(u), iv = (int32_t)ffloor(v);
    int32_t cx = (int32_t)ffloor(u / 6.0), cy = (int32_t)ffloor(v / 9.0);
    int32_t gx = iu - cx * 6, gy = iv - cy * 9;
    uint32_t g = hash2(cx, cy, seed + 77u);
    int ink = 0;
    if (gx < 5 && gy < 7 && (g & 7u) != 0u && ((uint32_t)cy % 5u) != 4u) {
        ink = ((g >> 3) & (1u << gx)) && gy >= (int32_t)((g >> 9) & 3u);
        ink |= ((g >> 12) & (1u << gy)) && gx < 4;
    }
    if (ink) {
        c[0] = 0.01;
        c[1] = 0.01;
        c[2] = 0.02;
    } else {
        c[0] = 0.80;
        c[1] = 0.77;
        c[2] = 0.66;
    }
}

/* Room with thin vertical features: a dim wall with posts of sub-pixel to
 * 1.5 px width and a few shelves. */
static void tex_thin(double u, double v, uint32_t seed, double c[3])
{
    const double inv_tau = 1.0 / 6.283185307179586;
    c[0] = 0.12 + 0.06 * turns_sin(u / 90.0 * inv_tau);
    c[1] = 0.10;
    c[2] = 0.08 + 0.05 * turns_cos(v / 40.0 * inv_tau);
    int32_t cell = (int32_t)ffloor(u / 7.0);
    uint32_t h = hash2(cell, 0, seed + 5u);
    if ((h & 3u) != 0u) {
        static const double widths[4] = {0.5, 0.75, 1.0, 1.5};
        double w = widths[(h >> 2) & 3u];
        double x0 = cell * 7.0 + 1.0 + (double)((h >> 4) % 4u);
        if (u >= x0 && u < x0 + w) {
            double b = 0.75 + 0.25 * (double)((h >> 8) & 1u);
            c[0] = b;
            c[1] = b * 0.95;
            c[2] = b * 0.85;
        }
    }
    double vm = v - 37.0 * ffloor(v / 37.0);
    if (vm < 1.0) {
        c[0] = 0.5;
        c[1] = 0.45;
        c[2] = 0.35;
    }
}

/* Foreground speed of the thin-feature scene relative to the pan. */
#define THIN_FG (8.0 / 11.0)

/* Fence scene: static floor, shadow bars moving at (vx, vy). */
static double fence_shadow(const scene_ctx_t *sc, double x, double t)
{
    const double period = 14.0, bar = 5.0, pen = 1.0;
    double u = x - sc->vx * t;
    double m = u - period * ffloor(u / period); /* 0 .. period */
    /* fully shadowed in [pen, bar], ramps of width pen on both sides */
    if (m < pen) {
        return m / pen;
    }
    if (m <= bar) {
        return 1.0;
    }
    if (m < bar + pen) {
        return 1.0 - (m - bar) / pen;
    }
    return 0.0;
}

static void tex_floor(double x, double y, uint32_t seed, double c[3])
{
    int chk = ((int64_t)ffloor(x / 16.0) + (int64_t)ffloor(y / 16.0)) & 1;
    uint32_t h = hash2((int32_t)ffloor(x / 3.0), (int32_t)ffloor(y / 3.0), seed + 9u);
    double n = ((double)(h & 255u) / 255.0 - 0.5) * 0.12;
    double b = (chk ? 0.55 : 0.38) + n;
    c[0] = clamp01(b * 1.05);
    c[1] = clamp01(b);
    c[2] = clamp01(b * 0.85);
}

/* Discs: 6 discs on a static background with a grid. */
#define N_DISCS 6
/* The disc centres depend on t only, and every caller samples a whole frame
 * (or a block of samples) at one t: they are computed once per thread and
 * (size, velocity, t: all they depend on), with exactly the arithmetic they had per sample,
 * so every output is bit-identical.  Per sample they were 89 % of a discs job
 * (trm-refresh at headset scale, session 6: 12 divides and floors a sample of
 * the supersampled ground truth). */
typedef struct {
    int valid;
    double w, h, vx, vy, t; /* all the centres depend on */
    double x0[N_DISCS], y0[N_DISCS];
} disc_centres_t;

static const disc_centres_t *disc_centres(const scene_ctx_t *sc, double t)
{
    static _Thread_local disc_centres_t cache;
    const double w = sc->p.width, h = sc->p.height;
    if (cache.valid && cache.w == w && cache.h == h && cache.vx == sc->vx && cache.vy == sc->vy && cache.t == t) {
        return &cache;
    }
    const double pw = w + 40.0, ph = h + 40.0;
    for (int i = 0; i < N_DISCS; i++) {
        double x0 = (double)i * pw / N_DISCS + sc->vx * t;
        double y0 = (0.15 + 0.7 * (double)i / (N_DISCS - 1)) * h + sc->vy * t;
        cache.x0[i] = x0 - pw * ffloor(x0 / pw) - 20.0;
        cache.y0[i] = y0 - ph * ffloor(y0 / ph) - 20.0;
    }
    cache.valid = 1, cache.w = w, cache.h = h, cache.vx = sc->vx, cache.vy = sc->vy, cache.t = t;
    return &cache;
}

static int disc_at(const scene_ctx_t *sc, double x, double y, double t, double c[3])
{
    static const double cols[N_DISCS][3] = {{0.9, 0.2, 0.1},  {0.1, 0.8, 0.2}, {0.15, 0.3, 0.95},
                                            {0.95, 0.9, 0.2}, {0.9, 0.9, 0.9}, {0.8, 0.2, 0.8}};
    const disc_centres_t *dc = disc_centres(sc, t);
    for (int i = 0; i < N_DISCS; i++) {
        double r = 4.0 + (double)(i % 3) * 2.5;
        double dx = x - dc->x0[i], dy = y - dc->y0[i];
        if (dx * dx + dy * dy < r * r) {
            if (c) {
                c[0] = cols[i][0];
                c[1] = cols[i][1];
                c[2] = cols[i][2];
            }
            return 1;
        }
    }
    return 0;
}

void tdc_scene_radiance(const tdc_source_t *s, double x, double y, double t, double rgb[3])
{
    const scene_ctx_t *sc = (const scene_ctx_t *)s->ctx;
    x += sc->p.shift_x; /* stereo: this eye's view */
    double u = x - sc->vx * t, v = y - sc->vy * t;
    switch (sc->p.kind) {
    case TDC_SCENE_STATIC: tex_pan(x, y, sc->p.seed, rgb); break;
    case TDC_SCENE_PAN: tex_pan(u, v, sc->p.seed, rgb); break;
    case TDC_SCENE_TEXT: tex_text(u, v, sc->p.seed, rgb); break;
    case TDC_SCENE_THIN:
        /* parallax: the lower half (foreground) moves at 8/11 of the pan
         * (330 -> 240 px/s), so its fractional motion per frame differs */
        if (y >= 0.5 * sc->p.height) {
            tex_thin(x - THIN_FG * sc->vx * t, y - THIN_FG * sc->vy * t + 1000.0, sc->p.seed, rgb);
        } else {
            tex_thin(u, v, sc->p.seed, rgb);
        }
        break;
    case TDC_SCENE_DISCS:
        if (!disc_at(sc, x, y, t, rgb)) {
            double gx = x - 16.0 * ffloor(x / 16.0), gy = y - 16.0 * ffloor(y / 16.0);
            double b = (gx < 1.0 || gy < 1.0) ? 0.35 : 0.06;
            rgb[0] = rgb[1] = rgb[2] = b;
        }
        break;
    case TDC_SCENE_FENCE: {
        tex_floor(x, y, sc->p.seed, rgb);
        double f = 1.0 - 0.8 * fence_shadow(sc, x, t);
        for (int k = 0; k < 3; k++) {
            rgb[k] *= f;
        }
        break;
    }
    case TDC_SCENE_BLACK: rgb[0] = rgb[1] = rgb[2] = 0.0; break;
    case TDC_SCENE_WHITE: rgb[0] = rgb[1] = rgb[2] = 1.0; break;
    case TDC_SCENE_CUT:
        if (t < sc->p.cut_time) {
            tex_pan(u, v, sc->p.seed, rgb);
        } else {
            tex_text(u, v, sc->p.seed + 1u, rgb);
        }
        break;
    default: rgb[0] = rgb[1] = rgb[2] = 0.0; break;
    }
}

/* Screen velocity (px/s) of what is seen at (x, y, t). */
static void scene_velocity(const scene_ctx_t *sc, double x, double y, double t, double dt, tdc_mv_kind_t kind,
                           double v[2])
{
    x += sc->p.shift_x; /* stereo: this eye's view */
    v[0] = v[1] = 0.0;
    switch (sc->p.kind) {
    case TDC_SCENE_PAN:
    case TDC_SCENE_TEXT:
    case TDC_SCENE_CUT:
        v[0] = sc->vx;
        v[1] = sc->vy;
        break;
    case TDC_SCENE_THIN: {
        double k = y >= 0.5 * sc->p.height ? THIN_FG : 1.0;
        v[0] = k * sc->vx;
        v[1] = k * sc->vy;
        break;
    }
    case TDC_SCENE_DISCS:
        if (disc_at(sc, x, y, t, NULL)) {
            v[0] = sc->vx;
            v[1] = sc->vy;
        }
        break;
    case TDC_SCENE_FENCE:
        /* The floor never moves: surface MVs are zero.  Shadow MVs follow
         * the shadow where there is shadow now; dual MVs also where the
         * shadow was one frame ago (the disoccluded, newly lit floor). */
        if (kind == TDC_MV_SHADOW && (fence_shadow(sc, x, t) > 0.0 || fence_shadow(sc, x, t - dt) > 0.0)) {
            v[0] = sc->vx;
            v[1] = sc->vy;
        }
        break;
    default: break;
    }
}

static void src_samples(tdc_source_t *s, double t, int n, const double *xy, int spp, uint8_t *rgb, int16_t *mv,
                        double dt, tdc_mv_kind_t kind)
{
    scene_ctx_t *sc = (scene_ctx_t *)s->ctx;
    int g = tdc_sim_spp_grid(spp);
    for (int k = 0; k < 3; k++) {
        tdc_sim_code_table_init(&sc->codes[k], s->gamma[k], TDC_SIM_CODES_MIDPOINT);
    }
    const tdc_sim_code_table_t *ct = sc->codes;
    const int blk = 256; /* samples per work item */
    TDC_PAR_FOR((size_t)n)
    for (int b = 0; b < (n + blk - 1) / blk; b++) {
        for (int i = b * blk; i < n && i < (b + 1) * blk; i++) {
            double x = xy[2 * i], y = xy[2 * i + 1];
            double acc[3] = {0, 0, 0};
            if (spp <= 1) {
                tdc_scene_radiance(s, x, y, t, acc);
            } else {
                double px = floor(x), py = floor(y);
                for (int j = 0; j < g; j++) {
                    for (int k = 0; k < g; k++) {
                        double c[3];
                        tdc_scene_radiance(s, px + (k + 0.5) / g, py + (j + 0.5) / g, t, c);
                        acc[0] += c[0];
                        acc[1] += c[1];
                        acc[2] += c[2];
                    }
                }
                for (int k = 0; k < 3; k++) {
                    acc[k] /= (double)(g * g);
                }
            }
            for (int k = 0; k < 3; k++) {
                rgb[3 * i + k] = tdc_sim_code_lookup(&ct[k], acc[k]);
            }
            if (mv) {
                double v[2];
                scene_velocity(sc, x, y, t, dt, kind, v);
                mv[2 * i] = tdc_sim_mv_q4(-v[0] * dt);
                mv[2 * i + 1] = tdc_sim_mv_q4(-v[1] * dt);
            }
        }
    }
}

/* Layered samples (tdc_source_t.layers).  The fence is exact in layers:
 * shading = the floor, visibility = 1 - 0.8 shadow, the shadow vector = the
 * bars' motion where a sample is in shadow now (Zeng eq. 3 on a plane: the
 * renderer does not splat, the controller does, §4.1), falloff G = 1 (a
 * planar receiver).  Every other scene is one SHADING layer (its colour and
 * surface vectors). */
static int src_layers(tdc_source_t *s, double t, int n, const double *xy, double dt, int zeng,
                      struct tdc_layer_frame *out)
{
    scene_ctx_t *sc = (scene_ctx_t *)s->ctx;
    const int fence = sc->p.kind == TDC_SCENE_FENCE;
    for (int k = 0; k < 3; k++) {
        tdc_sim_code_table_init(&sc->codes[k], s->gamma[k], TDC_SIM_CODES_MIDPOINT);
    }
    const tdc_sim_code_table_t *ct = sc->codes;
    for (int i = 0; i < n; i++) {
        double x = xy[2 * i], y = xy[2 * i + 1], c[3], v[2];
        if (fence) {
            tex_floor(x + sc->p.shift_x, y, sc->p.seed, c);
        } else {
            tdc_scene_radiance(s, x, y, t, c);
        }
        for (int k = 0; k < 3; k++) {
            out->value[0][3 * i + k] = tdc_sim_code_lookup(&ct[k], c[k]);
        }
        scene_velocity(sc, x, y, t, dt, TDC_MV_SURFACE, v);
        out->mv[0][2 * i] = tdc_sim_mv_q4(-v[0] * dt);
        out->mv[0][2 * i + 1] = tdc_sim_mv_q4(-v[1] * dt);
        if (fence) {
            const double sh = fence_shadow(sc, x + sc->p.shift_x, t);
            out->value[1][i] = (uint8_t)floor(255.0 * (1.0 - 0.8 * sh) + 0.5);
            const int moving = zeng && sh > 0.0;
            out->mv[1][2 * i] = moving ? tdc_sim_mv_q4(-sc->vx * dt) : 0;
            out->mv[1][2 * i + 1] = moving ? tdc_sim_mv_q4(-sc->vy * dt) : 0;
            out->falloff[i] = TDC_LAYER_W_ONE;
        }
    }
    out->present = (uint16_t)(TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING) |
                              (fence ? TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY) | TDC_LAYER_PKT_FALLOFF : 0u));
    out->hdr.version = TDC_LAYER_LAYOUT_VERSION;
    out->hdr.count = (uint8_t)(fence ? 2 : 1);
    memset(out->hdr.type, 0, sizeof out->hdr.type);
    memset(out->hdr.mv_kind, 0, sizeof out->hdr.mv_kind);
    out->hdr.type[0] = TDC_LAYER_SHADING;
    out->hdr.mv_kind[0] = TDC_LAYER_MV_SURFACE;
    if (fence) {
        out->hdr.type[1] = TDC_LAYER_VISIBILITY;
        out->hdr.mv_kind[1] = zeng ? TDC_LAYER_MV_SHADOW : TDC_LAYER_MV_SURFACE;
    }
    out->hdr.flags = fence ? 1u : 0u;
    out->hdr.reserved = 0;
    out->hdr.tiles_x = (uint16_t)((sc->p.width + 1) / 2);
    out->hdr.tiles_y = (uint16_t)((sc->p.height + 1) / 2);
    return 0;
}

/* ---------------------------------------------------------------------
 * Regular grids (full frames, ground truth): every pixel of a W x H frame,
 * g x g box samples at (x + ox + (k + 0.5) / g, y + oy + (j + 0.5) / g).
 *
 * The panorama texture is separable into functions of u (column) and v
 * (row) - the two products of sines by angle addition - so a grid call
 * tabulates the column terms once (W g entries, exact libm values) and each
 * sample row its row terms; a sample is then a handful of multiply-adds
 * and two table reads, no transcendental call and no division.  Other
 * scenes sample tdc_scene_radiance() per point.  Rows run in parallel.
 * ------------------------------------------------------------------- */
/* Sample rows per pixel the specialised grid paths hold on the stack
 * (ground truth: --gt-ss, default 4). */
#define TDC_SIM_MAX_GRID 64

/* The column terms of a grid call, one array per term (structure of
 * arrays: the sample loop below is element-wise and vectorises), n = W g. */
typedef struct {
    double *s53, *s67, *c67, *sa, *ca; /* the sines of the colour fields */
    double *g3;                        /* 0.18 sin(tau u / 3): the grating's term */
    double *d[2];                      /* checker offset where the row's floor(v / 8) is even, odd */
    double *line;                      /* 1 on the 1-px lines, else 0 */
    double *u;
    int32_t *cell;                     /* dot cells along the row: first column of each, ncell + 1 */
    int32_t *cu;                       /* floor(u / 5) of each cell */
    int ncell;
    void *mem;
} pan_cols_t;

/* The scene kinds whose texture at t is tex_pan(x - vx t, y - vy t). */
static int pan_like(const scene_ctx_t *sc, double t, double *du, double *dv)
{
    switch (sc->p.kind) {
    case TDC_SCENE_STATIC: *du = *dv = 0.0; return 1;
    case TDC_SCENE_PAN:
        *du = sc->vx * t;
        *dv = sc->vy * t;
        return 1;
    case TDC_SCENE_CUT:
        *du = sc->vx * t;
        *dv = sc->vy * t;
        return t < sc->p.cut_time;
    default: return 0;
    }
}

static int32_t floor_div(double x, double d)
{
    /* floor(x / d) for the exact quotient, without a division */
    double q = ffloor(x * (1.0 / d));
    if (q * d > x) {
        q -= 1.0;
    } else if ((q + 1.0) * d <= x) {
        q += 1.0;
    }
    return (int32_t)q;
}

/* Column q's terms at u (exact libm values). */
static void pan_col(double u, pan_cols_t *c, int q)
{
    const double tau = 6.283185307179586;
    c->u[q] = u;
    c->s53[q] = sin(tau * u / 53.0 + 1.3);
    c->s67[q] = sin(tau * u / 67.0);
    c->c67[q] = cos(tau * u / 67.0);
    c->sa[q] = sin(tau * u / 47.0 + 0.4);
    c->ca[q] = cos(tau * u / 47.0 + 0.4);
    c->g3[q] = 0.18 * sin(tau * u / 3.0);
    const int p8 = floor_div(u, 8.0) & 1;
    c->d[0][q] = p8 ? 0.12 : -0.08; /* (p8 of the column) xor (p8 of the row) */
    c->d[1][q] = p8 ? -0.08 : 0.12;
    c->line[q] = floor_div(ffloor(u), 23.0) * 23 == (int32_t)ffloor(u);
}

static void pan_cols_free(pan_cols_t *c)
{
    free(c->mem);
    free(c->cell);
}

/* Columns q of a grid call: u = (q / g) + ox + ((q % g) + 0.5) / g + shift - du. */
static int pan_cols_init(pan_cols_t *c, int n, int g, double ox, double shift, double du)
{
    memset(c, 0, sizeof(*c));
    double *m = malloc(sizeof(double) * 11 * (size_t)n);
    c->mem = m;
    c->cell = malloc(sizeof(int32_t) * 2 * ((size_t)n + 1));
    if (!m || !c->cell) {
        pan_cols_free(c);
        return -1;
    }
    double **arr[] = {&c->s53, &c->s67, &c->c67, &c->sa, &c->ca, &c->g3, &c->d[0], &c->d[1], &c->line, &c->u};
    for (size_t k = 0; k < sizeof(arr) / sizeof(arr[0]); k++) {
        *arr[k] = m + k * (size_t)n;
    }
    c->cu = c->cell + n + 1;
    int32_t last = INT32_MIN;
    for (int q = 0; q < n; q++) {
        pan_col((q / g) + ox + ((q % g) + 0.5) / g + shift - du, c, q);
        const int32_t cu = floor_div(c->u[q], 5.0);
        if (cu != last) {
            c->cu[c->ncell] = cu;
            c->cell[c->ncell++] = q;
            last = cu;
        }
    }
    c->cell[c->ncell] = n;
    return 0;
}

/* One row of samples at v over the tabulated columns: light into acc
 * (3 per pixel, its g samples added in sample order); rgb: 3 n scratch.
 * The samples first (element-wise, vectorised), then the dots of the
 * row's dot cells (one hash per 5-px cell) over them, then the sums - the
 * same values and the same sums as sample by sample. */
TDC_SIMD_CLONES static void pan_row(const pan_cols_t *c, int n, double v, uint32_t seed, double *acc, int g,
                                    double *rgb)
{
    const double tau = 6.283185307179586;
    const double c41 = cos(tau * v / 41.0), s67 = sin(tau * v / 67.0), c67 = cos(tau * v / 67.0);
    const double sb = sin(tau * v / 47.0), cb = cos(tau * v / 47.0);
    const int p8 = floor_div(v, 8.0) & 1;
    const double fv = ffloor(v);
    const int band = fv - 64.0 * ffloor(fv / 64.0) < 14.0;
    const int32_t cv = floor_div(v, 5.0);
    const double cy = cv * 5.0 + 2.5;
    double *restrict R = rgb, *restrict G = rgb + n, *restrict B = rgb + 2 * (size_t)n;
    const double *restrict dd = c->d[p8], *restrict g3 = c->g3, *restrict line = c->line;
    const double *restrict s53 = c->s53, *restrict cs67 = c->s67, *restrict cc67 = c->c67;
    const double *restrict sa = c->sa, *restrict ca = c->ca;
    const double gb = band ? 1.0 : 0.0;
    TDC_SIMD
    for (int q = 0; q < n; q++) {
        double r = 0.30 + 0.22 * s53[q] * c41;
        double gg = 0.30 + 0.20 * (cs67[q] * c67 + cc67[q] * s67); /* sin(a + b) */
        double b = 0.30 + 0.22 * (ca[q] * cb + sa[q] * sb);        /* cos(a - b) */
        /* d + 0 where there is no grating: d is 0.12 or -0.08, exact */
        const double d = dd[q] + (gb != 0.0 ? g3[q] : 0.0);
        r = r + d;
        gg = gg + d;
        b = b + d;
        r = r < 0.0 ? 0.0 : (r > 1.0 ? 1.0 : r);
        gg = gg < 0.0 ? 0.0 : (gg > 1.0 ? 1.0 : gg);
        b = b < 0.0 ? 0.0 : (b > 1.0 ? 1.0 : b);
        const int on = line[q] != 0.0;
        R[q] = on ? 0.85 : r;
        G[q] = on ? 0.85 : gg;
        B[q] = on ? 0.85 : b;
    }
    for (int k = 0; k < c->ncell; k++) {
        if ((hash2(c->cu[k], cv, seed) & 31u) != 0u) {
            continue;
        }
        const double cx = c->cu[k] * 5.0 + 2.5;
        for (int q = c->cell[k]; q < c->cell[k + 1]; q++) {
            if ((c->u[q] - cx) * (c->u[q] - cx) + (v - cy) * (v - cy) < 1.2) {
                R[q] = 1.0;
                G[q] = 0.9;
                B[q] = 0.3;
            }
        }
    }
    for (int px = 0; px < n / g; px++) {
        double *o = acc + 3 * px;
        double s0 = o[0], s1 = o[1], s2 = o[2];
        for (int q = px * g; q < (px + 1) * g; q++) {
            s0 += R[q];
            s1 += G[q];
            s2 += B[q];
        }
        o[0] = s0;
        o[1] = s1;
        o[2] = s2;
    }
}

/* The fence scene on a grid: tex_floor's cells and the shadow depend on x
 * or on y alone, so the column terms (checker index, 3-px cell, shadow
 * factor) are tabulated once per call and the row terms once per sample
 * row; a sample is then the cell hash and a few multiply-adds - the same
 * operations on the same values as tdc_scene_radiance per point, summed in
 * the same order (1920x1080 240 Hz: the source was ~86 % of the run). */
static int grid_fence(const tdc_source_t *s, const scene_ctx_t *sc, double t, double ox, double oy, int g,
                      double *lin)
{
    const int W = s->width, H = s->height, n = W * g;
    const double inv = 1.0 / (double)(g * g);
    int64_t *chx = malloc(sizeof(int64_t) * (size_t)n);
    int32_t *c3x = malloc(sizeof(int32_t) * (size_t)n);
    double *fx = malloc(sizeof(double) * (size_t)n);
    if (!chx || !c3x || !fx) {
        free(chx);
        free(c3x);
        free(fx);
        return -1;
    }
    for (int x = 0; x < W; x++) {
        for (int k = 0; k < g; k++) {
            const double xs = x + ox + (k + 0.5) / g + sc->p.shift_x; /* as tdc_scene_radiance sees it */
            const int q = x * g + k;
            chx[q] = (int64_t)ffloor(xs / 16.0);
            c3x[q] = (int32_t)ffloor(xs / 3.0);
            fx[q] = 1.0 - 0.8 * fence_shadow(sc, xs, t);
        }
    }
    const uint32_t seed = sc->p.seed + 9u;
    TDC_PAR_FOR((size_t)W * H)
    for (int y = 0; y < H; y++) {
        int64_t chy[TDC_SIM_MAX_GRID];
        int32_t c3y[TDC_SIM_MAX_GRID];
        for (int j = 0; j < g; j++) {
            const double ys = y + oy + (j + 0.5) / g;
            chy[j] = (int64_t)ffloor(ys / 16.0);
            c3y[j] = (int32_t)ffloor(ys / 3.0);
        }
        for (int x = 0; x < W; x++) {
            double acc[3] = {0, 0, 0};
            for (int j = 0; j < g; j++) {
                for (int q = x * g; q < (x + 1) * g; q++) {
                    const int chk = (chx[q] + chy[j]) & 1;
                    const uint32_t h = hash2(c3x[q], c3y[j], seed);
                    const double nz = ((double)(h & 255u) / 255.0 - 0.5) * 0.12;
                    const double b = (chk ? 0.55 : 0.38) + nz, f = fx[q];
                    acc[0] += clamp01(b * 1.05) * f;
                    acc[1] += clamp01(b) * f;
                    acc[2] += clamp01(b * 0.85) * f;
                }
            }
            double *o = lin + 3 * ((size_t)y * W + x);
            o[0] = acc[0] * inv;
            o[1] = acc[1] * inv;
            o[2] = acc[2] * inv;
        }
    }
    free(chx);
    free(c3x);
    free(fx);
    return 0;
}

/* Mean linear light of every pixel of rows [0, H) into lin (W*H*3). */
static int grid_lin(const tdc_source_t *s, double t, double ox, double oy, int g, double *lin)
{
    const scene_ctx_t *sc = (const scene_ctx_t *)s->ctx;
    const int W = s->width, H = s->height;
    const double inv = 1.0 / (double)(g * g);
    double du, dv;
    if (pan_like(sc, t, &du, &dv)) {
        int n = W * g, bad = 0;
        pan_cols_t cols;
        if (pan_cols_init(&cols, n, g, ox, sc->p.shift_x, du)) {
            return -1;
        }
        TDC_PAR_REGION((size_t)W * H)
        {
            double *rgb = malloc(sizeof(double) * 3 * (size_t)n);
            if (!rgb) {
                bad = 1; /* benign race: every writer stores 1 */
            }
            TDC_PAR_BANDS
            for (int y = 0; y < H; y++) {
                double *o = lin + 3 * (size_t)y * W;
                memset(o, 0, sizeof(double) * 3 * (size_t)W);
                for (int j = 0; j < g && rgb; j++) {
                    pan_row(&cols, n, y + oy + (j + 0.5) / g - dv, sc->p.seed, o, g, rgb);
                }
                for (int i = 0; i < 3 * W; i++) {
                    o[i] *= inv;
                }
            }
            free(rgb);
        }
        pan_cols_free(&cols);
        return bad ? -1 : 0;
    }
    if (sc->p.kind == TDC_SCENE_FENCE && g <= TDC_SIM_MAX_GRID) {
        return grid_fence(s, sc, t, ox, oy, g, lin);
    }
    TDC_PAR_FOR((size_t)W * H)
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            double acc[3] = {0, 0, 0};
            for (int j = 0; j < g; j++) {
                for (int k = 0; k < g; k++) {
                    double c[3];
                    tdc_scene_radiance(s, x + ox + (k + 0.5) / g, y + oy + (j + 0.5) / g, t, c);
                    acc[0] += c[0];
                    acc[1] += c[1];
                    acc[2] += c[2];
                }
            }
            double *o = lin + 3 * ((size_t)y * W + x);
            o[0] = acc[0] * inv;
            o[1] = acc[1] * inv;
            o[2] = acc[2] * inv;
        }
    }
    return 0;
}

static void src_ground_truth(tdc_source_t *s, double t, double ox, double oy, double *lin)
{
    if (grid_lin(s, t, ox, oy, s->gt_ss, lin) != 0) {
        memset(lin, 0, sizeof(double) * 3 * (size_t)s->width * s->height); /* out of memory */
    }
}

/* A full frame of drive codes: spp box samples per pixel (g x g, g the
 * largest with g^2 <= spp) or, at spp 1, one at the centre + (jx, jy).
 * The same samples src_samples takes for a frame's pixel grid. */
static int src_frame(tdc_source_t *s, double t, double jx, double jy, int spp, uint8_t *rgb, double *lin)
{
    scene_ctx_t *sc = (scene_ctx_t *)s->ctx;
    int g = tdc_sim_spp_grid(spp);
    double ox = g == 1 ? jx : 0.0, oy = g == 1 ? jy : 0.0;
    if (grid_lin(s, t, ox, oy, g, lin) != 0) {
        return -1;
    }
    for (int k = 0; k < 3; k++) {
        tdc_sim_code_table_init(&sc->codes[k], s->gamma[k], TDC_SIM_CODES_MIDPOINT);
    }
    const tdc_sim_code_table_t *ct = sc->codes;
    size_t n = (size_t)s->width * s->height;
    TDC_PAR_FOR((size_t)s->width * s->height)
    for (int y = 0; y < s->height; y++) {
        for (size_t i = (size_t)y * s->width; i < (size_t)(y + 1) * s->width; i++) {
            for (int k = 0; k < 3; k++) {
                rgb[3 * i + k] = tdc_sim_code_lookup(&ct[k], lin[3 * i + k]);
            }
        }
    }
    (void)n;
    return 0;
}

static void src_pursuit(tdc_source_t *s, double t, double v[2])
{
    const scene_ctx_t *sc = (const scene_ctx_t *)s->ctx;
    (void)t;
    v[0] = sc->p.pursuit ? sc->vx : 0.0;
    v[1] = sc->p.pursuit ? sc->vy : 0.0;
}

static int src_cut(tdc_source_t *s, double t0, double t1)
{
    const scene_ctx_t *sc = (const scene_ctx_t *)s->ctx;
    return sc->p.kind == TDC_SCENE_CUT && t0 < sc->p.cut_time && t1 >= sc->p.cut_time;
}

static void src_destroy(tdc_source_t *s)
{
    if (s) {
        free(s->ctx);
        free(s);
    }
}

tdc_source_t *tdc_scene_create(const tdc_scene_params_t *p, const double gamma[3])
{
    if (!p || (unsigned)p->kind >= TDC_SCENE_COUNT || p->width < 1 || p->height < 1) {
        return NULL;
    }
    tdc_source_t *s = calloc(1, sizeof(*s));
    scene_ctx_t *sc = calloc(1, sizeof(*sc));
    if (!s || !sc) {
        free(s);
        free(sc);
        return NULL;
    }
    sc->p = *p;
    turn_table_init();
    double speed = p->speed < 0.0 ? tdc_scene_default_speed(p->kind) : p->speed;
    if (p->kind == TDC_SCENE_STATIC || p->kind == TDC_SCENE_BLACK || p->kind == TDC_SCENE_WHITE) {
        speed = 0.0;
    }
    double a = p->angle_deg * 3.141592653589793 / 180.0;
    sc->vx = speed * cos(a);
    sc->vy = speed * sin(a);
    if (fabs(sc->vx) < 1e-12) {
        sc->vx = 0.0;
    }
    if (fabs(sc->vy) < 1e-12) {
        sc->vy = 0.0;
    }
    s->name = tdc_scene_name(p->kind);
    s->width = p->width;
    s->height = p->height;
    for (int k = 0; k < 3; k++) {
        s->gamma[k] = gamma ? gamma[k] : 2.2;
    }
    s->gt_ss = p->gt_ss > 0 ? p->gt_ss : 4;
    s->rigid = !(p->kind == TDC_SCENE_DISCS || p->kind == TDC_SCENE_FENCE || p->kind == TDC_SCENE_CUT ||
                 p->kind == TDC_SCENE_THIN) ||
               (speed == 0.0 && p->kind != TDC_SCENE_CUT);
    if (!p->pursuit && speed != 0.0) {
        s->rigid = 0;
    }
    s->ctx = sc;
    s->samples = src_samples;
    s->ground_truth = src_ground_truth;
    s->frame = src_frame;
    s->pursuit = src_pursuit;
    s->cut = src_cut;
    s->destroy = src_destroy;
    s->layers = src_layers;
    return s;
}
