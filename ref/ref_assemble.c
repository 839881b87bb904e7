/*
 * ref_assemble.c - double-precision reference of tile-ordered frame assembly
 * and a synthetic subframe stream; see ref_assemble.h.
 */
#include "ref_assemble.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_math.h"

/* ------------------------------------------------------------------------
 * Ordering decision, straight from docs/design.md §4.3 / paper eq. 2-5.
 * ---------------------------------------------------------------------- */
tdc_ordering_t tdc_ref_ordering_decide(double mx, double my, tdc_ordering_t current, uint32_t tile_x, uint32_t tile_y,
                                       uint32_t frame)
{
    if (mx == 0.0 && my == 0.0) return current;
    const double gamma = M_PI / 40.0;
    double a = atan2(fabs(my), fabs(mx)); /* folded into [0, pi/2] */
    if (fabs(a - M_PI / 4.0) < gamma)
        return (tdc_hash3(tile_x, tile_y, frame) >> 31) ? TDC_ORDER_BOWTIE : TDC_ORDER_HOURGLASS;
    double l = hypot(mx, my);
    double lf = l - floor(l);
    double s = 0.5 * a / (M_PI / 2.0);
    int hourglass;
    if (a < M_PI / 4.0) {
        double x = fmod(lf - s + 1.0, 1.0);
        hourglass = x > 0.25 && x < 0.75;
    } else {
        double x = fmod(lf + s, 1.0);
        hourglass = x >= 0.25 && x <= 0.75;
    }
    return hourglass ? TDC_ORDER_HOURGLASS : TDC_ORDER_BOWTIE;
}

/* ------------------------------------------------------------------------
 * Reference assembly.
 * ---------------------------------------------------------------------- */
struct tdc_ref_asm {
    int w, h, tx, ty;
    uint8_t *out;     /* last output, 8-bit */
    double *exact;    /* last output before rounding */
    uint8_t *samples; /* per pixel 4 slots RGB */
    uint8_t *window;  /* slot mask */
    uint8_t *isnew;   /* traced this frame */
    int16_t *mv;
    uint8_t *pattern;
    int have_sub;
    uint32_t next_frame;
    tdc_ref_nbhd_t nbhd; /* the clamp's neighbourhood (NEWEST: the paper's) */
};

void tdc_ref_asm_set_nbhd(tdc_ref_asm_t *r, tdc_ref_nbhd_t nbhd)
{
    r->nbhd = nbhd;
}

tdc_ref_asm_t *tdc_ref_asm_new(int w, int h)
{
    tdc_ref_asm_t *r = calloc(1, sizeof(*r));
    if (!r) return NULL;
    size_t px = (size_t)w * h;
    r->w = w, r->h = h, r->tx = (w + 1) / 2, r->ty = (h + 1) / 2;
    r->out = calloc(px * 3, 1);
    r->exact = calloc(px * 3, sizeof(double));
    r->samples = calloc(px * 12, 1);
    r->window = calloc(px, 1);
    r->isnew = calloc(px, 1);
    r->mv = calloc(px * 2, sizeof(int16_t));
    r->pattern = calloc((size_t)TDC_PATTERN_BYTES(w, h), 1);
    if (!r->out || !r->exact || !r->samples || !r->window || !r->isnew || !r->mv || !r->pattern) {
        tdc_ref_asm_free(r);
        return NULL;
    }
    return r;
}

void tdc_ref_asm_free(tdc_ref_asm_t *r)
{
    if (!r) return;
    free(r->out), free(r->exact), free(r->samples), free(r->window), free(r->isnew), free(r->mv);
    free(r->pattern), free(r);
}

const uint8_t *tdc_ref_asm_output(const tdc_ref_asm_t *r)
{
    return r->out;
}
const double *tdc_ref_asm_output_exact(const tdc_ref_asm_t *r)
{
    return r->exact;
}

int tdc_ref_asm_ingest(tdc_ref_asm_t *r, uint32_t frame, const uint8_t *samples, const int16_t *mvs,
                       const uint8_t *pattern_bits)
{
    if (!samples || frame != r->next_frame || r->have_sub) return -1;
    unsigned k = frame & 3u, slot = (frame >> 2) & 3u;
    if (pattern_bits && k == 0) memcpy(r->pattern, pattern_bits, (size_t)TDC_PATTERN_BYTES(r->w, r->h));
    memset(r->isnew, 0, (size_t)r->w * r->h);
    for (int ty = 0; ty < r->ty; ty++)
        for (int tx = 0; tx < r->tx; tx++) {
            int ti = ty * r->tx + tx;
            unsigned pos = tdc_ordering_pixel(tdc_ordering_get(r->pattern, (uint32_t)ti), k);
            int x = 2 * tx + (int)(pos & 1u), y = 2 * ty + (int)(pos >> 1);
            if (x >= r->w || y >= r->h) continue;
            size_t p = (size_t)y * r->w + x;
            memcpy(r->samples + p * 12 + slot * 3, samples + ti * 3, 3);
            r->mv[p * 2] = mvs ? mvs[ti * 2] : 0;
            r->mv[p * 2 + 1] = mvs ? mvs[ti * 2 + 1] : 0;
            r->isnew[p] = 1;
        }
    r->have_sub = 1;
    return 0;
}

static double ref_prev(const tdc_ref_asm_t *r, int x, int y, int c)
{
    return r->out[((size_t)y * r->w + x) * 3 + c];
}

/* The previous output bilinearly at (sx, sy), clamped to the frame. */
static void ref_bilinear_prev(const tdc_ref_asm_t *r, double sx, double sy, double v[3])
{
    sx = sx < 0 ? 0 : (sx > r->w - 1 ? r->w - 1 : sx);
    sy = sy < 0 ? 0 : (sy > r->h - 1 ? r->h - 1 : sy);
    int x0 = (int)floor(sx), y0 = (int)floor(sy);
    int x1 = x0 + 1 < r->w ? x0 + 1 : x0, y1 = y0 + 1 < r->h ? y0 + 1 : y0;
    double fx = sx - x0, fy = sy - y0;
    for (int c = 0; c < 3; c++)
        v[c] = (1 - fx) * (1 - fy) * ref_prev(r, x0, y0, c) + fx * (1 - fy) * ref_prev(r, x1, y0, c) +
               (1 - fx) * fy * ref_prev(r, x0, y1, c) + fx * fy * ref_prev(r, x1, y1, c);
}

/* Adds tile (tx, ty)'s sample of the newest subframe (if it has one) to the box sums. */
static void ref_box_add_tile(const tdc_ref_asm_t *r, int tx, int ty, unsigned slot, int *n, double s1[3],
                             double s2[3])
{
    if (tx < 0 || ty < 0 || tx >= r->tx || ty >= r->ty) return;
    for (int k = 0; k < 4; k++) {
        int x = 2 * tx + (k & 1), y = 2 * ty + (k >> 1);
        if (x >= r->w || y >= r->h) continue;
        size_t q = (size_t)y * r->w + x;
        if (!r->isnew[q]) continue;
        (*n)++;
        for (int c = 0; c < 3; c++) {
            double v = r->samples[q * 12 + slot * 3 + c];
            s1[c] += v, s2[c] += v * v;
        }
    }
}

int tdc_ref_asm_assemble(tdc_ref_asm_t *r, uint32_t frame)
{
    if (frame != r->next_frame) return -1;
    int w = r->w, h = r->h;
    unsigned slot = (frame >> 2) & 3u;
    if (!r->have_sub) memset(r->isnew, 0, (size_t)w * h);
    double *val = malloc((size_t)w * h * 3 * sizeof(double));
    if (!val) return -1;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t p = (size_t)y * w + x;
            /* m = longest MV of the 3x3 neighbourhood (first in raster order). */
            double best = 0.0;
            int mx = 0, my = 0;
            for (int oy = -1; oy <= 1; oy++)
                for (int ox = -1; ox <= 1; ox++) {
                    int nx = x + ox, ny = y + oy;
                    if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                    const int16_t *v = r->mv + ((size_t)ny * w + nx) * 2;
                    double l2 = (double)v[0] * v[0] + (double)v[1] * v[1];
                    if (l2 > best) best = l2, mx = v[0], my = v[1];
                }
            double *o = val + p * 3;
            if (best == 0.0) { /* static: moving-window mean of up to 4 samples */
                if (r->isnew[p]) {
                    r->window[p] |= (uint8_t)(1u << slot);
                    int n = 0;
                    double s[3] = {0, 0, 0};
                    for (int i = 0; i < 4; i++)
                        if (r->window[p] & (1u << i)) {
                            n++;
                            for (int c = 0; c < 3; c++) s[c] += r->samples[p * 12 + i * 3 + c];
                        }
                    for (int c = 0; c < 3; c++) o[c] = s[c] / n;
                } else {
                    for (int c = 0; c < 3; c++) o[c] = ref_prev(r, x, y, c);
                }
                continue;
            }
            r->window[p] = 0; /* dynamic: averaging reset */
            if (r->isnew[p]) {
                for (int c = 0; c < 3; c++) o[c] = r->samples[p * 12 + slot * 3 + c];
                continue;
            }
            /* Old dynamic: bilinear from the previous output at p + m. */
            double vb[3];
            ref_bilinear_prev(r, x + mx / 16.0, y + my / 16.0, vb);
            /* The clamp's box (Fig. 7): by default the immediate neighbours
             * in the newest subframe. */
            int n = 0;
            double s1[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
            if (r->nbhd == TDC_REF_NBHD_SUB3X3) {
                for (int oy = -1; oy <= 1; oy++)
                    for (int ox = -1; ox <= 1; ox++)
                        ref_box_add_tile(r, x / 2 + ox, y / 2 + oy, slot, &n, s1, s2);
            } else {
                for (int oy = -1; oy <= 1; oy++)
                    for (int ox = -1; ox <= 1; ox++) {
                        int nx = x + ox, ny = y + oy;
                        if ((ox == 0 && oy == 0) || nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                        size_t q = (size_t)ny * w + nx;
                        double v3[3];
                        if (r->isnew[q]) {
                            for (int c = 0; c < 3; c++) v3[c] = r->samples[q * 12 + slot * 3 + c];
                        } else if (r->nbhd == TDC_REF_NBHD_ALL) {
                            ref_bilinear_prev(r, nx + mx / 16.0, ny + my / 16.0, v3);
                        } else {
                            continue;
                        }
                        n++;
                        for (int c = 0; c < 3; c++) s1[c] += v3[c], s2[c] += v3[c] * v3[c];
                    }
            }
            for (int c = 0; c < 3; c++) {
                double v = vb[c];
                if (n > 0) {
                    double mean = s1[c] / n, var = s2[c] / n - mean * mean;
                    double sd = sqrt(var > 0 ? var : 0);
                    if (v < mean - sd) v = mean - sd;
                    if (v > mean + sd) v = mean + sd;
                }
                o[c] = v;
            }
        }
    for (size_t i = 0; i < (size_t)w * h * 3; i++) {
        r->exact[i] = val[i];
        double v = floor(val[i] + 0.5);
        r->out[i] = (uint8_t)(v < 0 ? 0 : (v > 255 ? 255 : v));
    }
    free(val);
    if ((frame & 3u) == 3u) {
        /* Own decision for the next cycle: longest MV over 3x3 tiles. */
        for (int ty = 0; ty < r->ty; ty++)
            for (int tx = 0; tx < r->tx; tx++) {
                double best = 0;
                int mx = 0, my = 0;
                for (int y = 2 * ty - 2; y <= 2 * ty + 3; y++)
                    for (int x = 2 * tx - 2; x <= 2 * tx + 3; x++) {
                        if (x < 0 || y < 0 || x >= w || y >= h) continue;
                        const int16_t *v = r->mv + ((size_t)y * w + x) * 2;
                        double l2 = (double)v[0] * v[0] + (double)v[1] * v[1];
                        if (l2 > best) best = l2, mx = v[0], my = v[1];
                    }
                uint32_t ti = (uint32_t)(ty * r->tx + tx);
                tdc_ordering_set(r->pattern, ti,
                                 tdc_ref_ordering_decide(mx / 16.0, my / 16.0, tdc_ordering_get(r->pattern, ti),
                                                         (uint32_t)tx, (uint32_t)ty, frame + 1));
            }
    }
    r->have_sub = 0;
    r->next_frame = frame + 1;
    return 0;
}

/* ------------------------------------------------------------------------
 * Synthetic stream.
 * ---------------------------------------------------------------------- */
int tdc_scene_init(tdc_scene_t *s, tdc_scene_kind_t kind, int w, int h, int32_t vx_q4, int32_t vy_q4, uint32_t seed)
{
    memset(s, 0, sizeof(*s));
    s->kind = kind, s->w = w, s->h = h, s->vx_q4 = vx_q4, s->vy_q4 = vy_q4, s->seed = seed;
    s->mvbuf = calloc((size_t)w * h * 2, sizeof(int16_t));
    s->pattern = calloc((size_t)TDC_PATTERN_BYTES(w, h), 1);
    return s->mvbuf && s->pattern ? 0 : -1;
}

void tdc_scene_free(tdc_scene_t *s)
{
    free(s->mvbuf), free(s->pattern);
    s->mvbuf = NULL, s->pattern = NULL;
}

/* Textured panorama: smooth colour waves plus a hard-edged checker. */
static void scene_texture(double u, double v, uint32_t seed, double rgb[3])
{
    double ph = (seed % 97) * 0.1;
    int chk = ((int)floor(u / 7.0) + (int)floor(v / 5.0)) & 1;
    rgb[0] = 128 + 100 * sin(0.31 * u + ph) * cos(0.17 * v);
    rgb[1] = chk ? 220 : 35;
    rgb[2] = 128 + 110 * sin(0.9 * u + 0.6 * v + ph);
}

static double line_pos(const tdc_scene_t *s, uint32_t t, int horizontal)
{
    return 5.0 + (horizontal ? s->vy_q4 : s->vx_q4) / 16.0 * (double)t;
}

/* Distance from coordinate c to the nearest line of the family (period 16). */
static double line_dist(double c, double l0)
{
    double d = fmod(c - l0, 16.0);
    if (d < 0) d += 16.0;
    return d > 8.0 ? 16.0 - d : d;
}

void tdc_scene_color(const tdc_scene_t *s, double x, double y, uint32_t t, double rgb[3])
{
    switch (s->kind) {
    case TDC_SCENE_STATIC: scene_texture(x, y, s->seed, rgb); break;
    case TDC_SCENE_PAN: scene_texture(x - s->vx_q4 / 16.0 * t, y - s->vy_q4 / 16.0 * t, s->seed, rgb); break;
    case TDC_SCENE_LINE:
    case TDC_SCENE_HLINE: {
        int hor = s->kind == TDC_SCENE_HLINE;
        rgb[0] = 40 + 0.3 * x, rgb[1] = 60 + 0.2 * y, rgb[2] = 90;
        if (line_dist(hor ? y : x, line_pos(s, t, hor)) < 0.5) rgb[0] = rgb[1] = rgb[2] = 250;
        break;
    }
    }
    for (int c = 0; c < 3; c++) rgb[c] = rgb[c] < 0 ? 0 : (rgb[c] > 255 ? 255 : rgb[c]);
}

void tdc_scene_mv(const tdc_scene_t *s, int x, int y, uint32_t t, int16_t mv[2])
{
    mv[0] = mv[1] = 0;
    switch (s->kind) {
    case TDC_SCENE_STATIC: break;
    case TDC_SCENE_PAN: mv[0] = (int16_t)-s->vx_q4, mv[1] = (int16_t)-s->vy_q4; break;
    case TDC_SCENE_LINE:
    case TDC_SCENE_HLINE: {
        /* Moving within 1.5 px of a line's centre: wide enough that a
         * jittered static sample (offset <= 3/8 px) never hits a line, and
         * that the pixels beside a line carry its motion. */
        int hor = s->kind == TDC_SCENE_HLINE;
        if (line_dist(hor ? y : x, line_pos(s, t, hor)) < 1.5) {
            mv[0] = (int16_t)-s->vx_q4 * (hor ? 0 : 1);
            mv[1] = (int16_t)-s->vy_q4 * (hor ? 1 : 0);
        }
        break;
    }
    }
}

void tdc_scene_subframe(tdc_scene_t *s, uint32_t frame, uint8_t *samples, int16_t *mvs, uint8_t *bits_out)
{
    int w = s->w, h = s->h, tx_n = (w + 1) / 2, ty_n = (h + 1) / 2;
    unsigned k = frame & 3u;
    if (k == 0) {
        tdc_ordering_update(s->mvbuf, w, h, s->pattern, frame);
        if (bits_out) memcpy(bits_out, s->pattern, (size_t)TDC_PATTERN_BYTES(w, h));
    }
    int32_t jx, jy;
    tdc_jitter_offset_q4(frame, &jx, &jy);
    for (int ty = 0; ty < ty_n; ty++)
        for (int tx = 0; tx < tx_n; tx++) {
            int ti = ty * tx_n + tx;
            unsigned pos = tdc_ordering_pixel(tdc_ordering_get(s->pattern, (uint32_t)ti), k);
            int x = 2 * tx + (int)(pos & 1u), y = 2 * ty + (int)(pos >> 1);
            int16_t mv[2];
            tdc_scene_mv(s, x, y, frame, mv);
            double sx = x, sy = y, rgb[3];
            if (mv[0] == 0 && mv[1] == 0) sx += jx / 16.0, sy += jy / 16.0;
            tdc_scene_color(s, sx, sy, frame, rgb);
            for (int c = 0; c < 3; c++) samples[ti * 3 + c] = (uint8_t)floor(rgb[c] + 0.5);
            mvs[ti * 2] = mv[0], mvs[ti * 2 + 1] = mv[1];
            if (x < w && y < h) {
                s->mvbuf[((size_t)y * w + x) * 2] = mv[0];
                s->mvbuf[((size_t)y * w + x) * 2 + 1] = mv[1];
            }
        }
}

void tdc_asm_err_add(tdc_asm_err_t *e, const uint8_t *fixed, const uint8_t *ref8, const double *exact, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        int d = abs((int)fixed[i] - (int)ref8[i]);
        e->hist[d > 3 ? 3 : d]++;
        if (d > e->max_abs) e->max_abs = d;
        if (exact) {
            double de = fabs(fixed[i] - exact[i]);
            if (de > e->max_exact) e->max_exact = de;
        }
    }
    e->n += n;
}
