/*
 * tdc_render_texture.c - procedural textures in object space: checker,
 * stripes, 5x7 glyph text and a city skyline for panoramas.  Texture
 * coordinates (u, v) are object-space lengths, chosen per shape:
 * rect/disc (x, y) from the lower-left corner / centre, box and fence faces
 * the two axes across the face's dominant normal, sphere and cylinder
 * arc length around Y and height, heightfield and mesh (x, z).
 * Textures are box-filtered over each sample's ray-cone footprint fw
 * (TDRT §3.1.1; tdc_r_tex_footprint): checker and stripes exactly (the box
 * average of a square wave is a difference of its triangle-wave integral;
 * the checker is the product of two), text and skyline by averaging up to
 * 4x4 point samples spread over the footprint once it exceeds a fifth of
 * their smallest feature.  fw = 0 is the plain point sample of before.
 * A footprint of one pixel keeps subsampled and reduced frames from
 * judging aliased textures; the ground truth's samples use 1/sqrt(N) of a
 * pixel, so its box filter is unchanged.
 */
#include <math.h>
#include <string.h>

#include "tdc_render_internal.h"

/* 5x7 glyphs, rows top to bottom, bit 4 = leftmost column. */
static const unsigned char font_digits[10][7] = {
    {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}, {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E},
    {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}, {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E},
    {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}, {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E},
    {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}, {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08},
    {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}, {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}};
static const unsigned char font_upper[26][7] = {
    {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}, {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E},
    {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}, {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C},
    {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}, {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10},
    {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}, {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11},
    {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}, {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C},
    {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}, {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F},
    {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}, {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11},
    {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}, {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10},
    {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}, {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11},
    {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}, {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04},
    {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}, {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04},
    {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}, {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11},
    {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04}, {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}};

static const unsigned char *glyph(char ch)
{
    static const unsigned char space[7] = {0};
    static const unsigned char dot[7] = {0, 0, 0, 0, 0, 0x0C, 0x0C};
    static const unsigned char comma[7] = {0, 0, 0, 0, 0x0C, 0x04, 0x08};
    static const unsigned char dash[7] = {0, 0, 0, 0x1F, 0, 0, 0};
    static const unsigned char bang[7] = {0x04, 0x04, 0x04, 0x04, 0x04, 0, 0x04};
    static const unsigned char colon[7] = {0, 0x0C, 0x0C, 0, 0x0C, 0x0C, 0};
    static const unsigned char slash[7] = {0, 0x01, 0x02, 0x04, 0x08, 0x10, 0};
    static const unsigned char quest[7] = {0x0E, 0x11, 0x01, 0x02, 0x04, 0, 0x04};
    if (ch >= '0' && ch <= '9') return font_digits[ch - '0'];
    if (ch >= 'a' && ch <= 'z') ch = (char)(ch - 'a' + 'A');
    if (ch >= 'A' && ch <= 'Z') return font_upper[ch - 'A'];
    switch (ch) {
    case ' ': return space;
    case '.': return dot;
    case ',': return comma;
    case '-': return dash;
    case '!': return bang;
    case ':': return colon;
    case '/': return slash;
    default: return quest;
    }
}

/* floor() without a libm call (the x86-64 baseline has no SSE4.1 round);
 * texture coordinates are far inside the long range */
static inline double ffloor(double x)
{
    if (!(x > -1e15 && x < 1e15)) return 0;
    long i = (long)x;
    return (double)(i - (i > x));
}

/* (long)ffloor(x) without the round trip through double */
static inline long lfloor(double x)
{
    if (!(x > -1e15 && x < 1e15)) return 0;
    long i = (long)x;
    return i - (i > x);
}

static double hash01(long a, long b)
{
    uint32_t h = (uint32_t)a * 0x9E3779B1u ^ ((uint32_t)b + 0x7F4A7C15u) * 0x85EBCA77u;
    h ^= h >> 15;
    h *= 0x2C1B3C6Du;
    h ^= h >> 12;
    h *= 0x297A2D39u;
    h ^= h >> 15;
    return (h >> 8) * (1.0 / 16777216.0);
}

static void uv_of(const tdc_object_t *o, const double q[3], const double n[3], double *u, double *v)
{
    switch (o->shape) {
    case TDC_SHAPE_RECT:
        *u = q[0] + o->p[0] / 2;
        *v = q[1] + o->p[1] / 2;
        return;
    case TDC_SHAPE_DISC:
        *u = q[0];
        *v = q[1];
        return;
    case TDC_SHAPE_BOX:
    case TDC_SHAPE_FENCE: {
        double ax = fabs(n[0]), ay = fabs(n[1]), az = fabs(n[2]);
        if (ax >= ay && ax >= az) {
            *u = q[2];
            *v = q[1];
        } else if (ay >= az) {
            *u = q[0];
            *v = q[2];
        } else {
            *u = q[0];
            *v = q[1];
        }
        return;
    }
    case TDC_SHAPE_SPHERE: {
        double rr = o->p[0];
        *u = atan2(q[0], q[2]) * rr;
        double s = q[1] / rr;
        *v = asin(s < -1 ? -1 : s > 1 ? 1 : s) * rr;
        return;
    }
    case TDC_SHAPE_CYLINDER:
        *u = atan2(q[0], q[2]) * o->p[0];
        *v = q[1];
        return;
    default: *u = q[0]; *v = q[2];
    }
}

void tdc_r_tex_prepare(tdc_render_t *r)
{
    for (int i = 0; i < r->scene->nmaterials; i++) {
        const tdc_material_t *m = &r->scene->materials[i];
        rtex_t *t = &r->tex[i];
        t->text_len1 = m->tex == TDC_TEX_TEXT ? (long)strlen(m->text) + 1 : 1;
        t->text_cell6 = 6 * (m->tex_scale / 8); /* the same operations as the per-sample code had */
        t->text_mod_m = UINT64_MAX / (uint64_t)t->text_len1 + 1;
        t->text_mod_k = ((1L << 30) + t->text_len1 - 1) / t->text_len1 * t->text_len1;
        for (long k = 0; k < t->text_len1; k++) {
            memcpy(t->rows[k], glyph(k < t->text_len1 - 1 ? m->text[k] : ' '), 7);
            t->rows[k][7] = 0;
        }
    }
    for (int i = 0; i < r->scene->nobjects; i++) {
        const tdc_material_t *m = &r->scene->materials[r->scene->objects[i].material];
        r->obj_needs_n[i] = !m->unlit || m->mirror > 0;
        int shape = r->scene->objects[i].shape;
        r->obj_uv_first[i] =
            m->unlit && m->tex != TDC_TEX_NONE && (shape == TDC_SHAPE_SPHERE || shape == TDC_SHAPE_CYLINDER);
        r->any_uv_first |= r->obj_uv_first[i];
    }
}

static inline __attribute__((always_inline)) void tex_color(const tdc_render_t *r, const tdc_object_t *o, double u,
                                                            double v, double out[3]);
static void tex_color_filtered(const tdc_render_t *r, const tdc_object_t *o, double u, double v, double fw,
                               double out[3]);

void tdc_r_tex_uv(const tdc_object_t *o, const double q[3], const double nq[3], double *u, double *v)
{
    uv_of(o, q, nq, u, v);
}

void tdc_r_base_color(const tdc_render_t *r, const tdc_object_t *o, const double q[3], const double nq[3], double fw,
                      double out[3])
{
    const tdc_material_t *m = &r->scene->materials[o->material];
    if (m->tex == TDC_TEX_NONE) {
        out[0] = m->diffuse[0];
        out[1] = m->diffuse[1];
        out[2] = m->diffuse[2];
        return;
    }
    double u, v;
    uv_of(o, q, nq, &u, &v);
    tex_color_filtered(r, o, u, v, fw, out);
}

void tdc_r_tex_color(const tdc_render_t *r, const tdc_object_t *o, double u, double v, double fw, double out[3])
{
    tex_color_filtered(r, o, u, v, fw, out);
}

/* x mod len in [0, len) (`x % len`, plus len when negative) without a
 * 64-bit division (it was ~40 % of the text texture's time): for |x| < 2^30,
 * a = x + K (K a multiple of len, 2^30 <= K < 2^30 + len) is a 32-bit
 * number with the same remainder, and Lemire's multiply-shift
 * ((M a mod 2^64) len) >> 64 with M = floor((2^64 - 1) / len) + 1 is the
 * exact remainder for every 32-bit a and divisor (Lemire, Kaser, Kurz,
 * "Faster remainder by direct computation", 2019).  Same results. */
static inline long text_mod(const rtex_t *tx, long x)
{
    long len = tx->text_len1;
    if (x >= -(1L << 30) && x < (1L << 30)) {
        uint32_t a = (uint32_t)(x + tx->text_mod_k);
        uint64_t low = tx->text_mod_m * a;
        __extension__ typedef unsigned __int128 u128;
        return (long)(((u128)low * (uint64_t)len) >> 64);
    }
    long i = x % len;
    return i + (i < 0 ? len : 0);
}

/* inlined into both callers above: one call per sample, not two */
static inline __attribute__((always_inline)) void tex_color(const tdc_render_t *r, const tdc_object_t *o, double u,
                                                            double v, double out[3])
{
    const tdc_material_t *m = &r->scene->materials[o->material];
    const double *c = m->diffuse;
    {
        double sc = m->tex_scale;
        switch (m->tex) {
        case TDC_TEX_CHECKER:
            if ((lfloor(u / sc) + lfloor(v / sc)) & 1) c = m->color2;
            break;
        case TDC_TEX_STRIPES:
            if (u / sc - ffloor(u / sc) >= 0.5) c = m->color2;
            break;
        case TDC_TEX_TEXT: {
            /* Lines of height sc: 7 glyph rows + 1 gap row; cells 6 columns
             * wide.  No branches on the ink: the glyph bit selects the
             * colour (ink flips every few pixels; branches mispredicted). */
            const rtex_t *tx = &r->tex[o->material];
            double vs = v / sc, fl = ffloor(vs);
            double fy = vs - fl;
            int row = (int)((1 - fy) * 8);
            if (row > 7) row = 7;
            double cx = u / tx->text_cell6;
            long ci = lfloor(cx);
            int col = (int)((cx - ci) * 6);
            if (col > 5) col = 5;
            long idx = text_mod(tx, ci + (long)fl * 7); /* successive lines start at different letters */
            /* bit (4 - col) of the row; col = 5 (gap column) reads the 0 shifted in */
            unsigned ink = ((unsigned)tx->rows[idx][row] << 1 >> (5 - col)) & 1u;
            c = ink ? m->color2 : m->diffuse;
            break;
        }
        case TDC_TEX_SKYLINE: {
            long b = lfloor(u / sc);
            double top = 4 + 4 * hash01(b, 1);
            if (v < top) {
                double shade = 0.6 + 0.4 * hash01(b, 2);
                double wu = u / (sc * 0.25), wv = v / (sc * 0.4);
                long wi = lfloor(wu), wj = lfloor(wv);
                double fu = wu - wi, fv = wv - wj;
                /* & instead of &&, and the hash always: windows flip every
                 * few pixels and the branches were mispredicted */
                int in_window = (fu > 0.35) & (fu < 0.8) & (fv > 0.3) & (fv < 0.75) & (v < top - 0.2) &
                                (hash01(b * 131 + wi, wj) > 0.55);
                double d0 = m->diffuse[0] * shade, d1 = m->diffuse[1] * shade, d2 = m->diffuse[2] * shade;
                out[0] = in_window ? 1.0 : d0;
                out[1] = in_window ? 0.85 : d1;
                out[2] = in_window ? 0.45 : d2;
            } else {
                double g = (v - 4) / 10;
                g = g < 0 ? 0 : g > 1 ? 1 : g;
                for (int k = 0; k < 3; k++) out[k] = m->color2[k] * (1.15 - 0.5 * g);
            }
            return;
        }
        default: break;
        }
    }
    out[0] = c[0];
    out[1] = c[1];
    out[2] = c[2];
}

/* Integral from 0 to x of the square wave that is +1 on [0, h) and -1 on
 * [h, 2h), period 2h: the triangle wave y or 2h - y of y = x mod 2h. */
static inline double square_integral(double x, double h)
{
    double y = x - 2 * h * ffloor(x / (2 * h));
    return y < h ? y : 2 * h - y;
}

/* Box average of that square wave over [x - w/2, x + w/2], in [-1, 1]. */
static inline double square_box(double x, double h, double w)
{
    double m = (square_integral(x + 0.5 * w, h) - square_integral(x - 0.5 * w, h)) / w;
    return m < -1 ? -1 : (m > 1 ? 1 : m);
}

/* Footprints below a fifth of the smallest feature are point-sampled: the
 * box would move the colour by < 10 % of an edge's step at one sample in
 * the footprint's width of an edge, and most samples see none. */
#define TEX_MIN_FRACTION 0.2

static void tex_color_filtered(const tdc_render_t *r, const tdc_object_t *o, double u, double v, double fw,
                               double out[3])
{
    const tdc_material_t *m = &r->scene->materials[o->material];
    double sc = m->tex_scale, feature;
    switch (m->tex) {
    case TDC_TEX_CHECKER:
    case TDC_TEX_STRIPES: {
        if (!(fw > TEX_MIN_FRACTION * 0.5 * sc)) break;
        /* fraction of color2: checker (1 - su sv) / 2 with su, sv the box
         * averages of the +-1 parity waves (period 2 sc); stripes (1 - s) / 2
         * of the wave of period sc (color2 on the upper half) */
        double a = m->tex == TDC_TEX_CHECKER ? 0.5 * (1 - square_box(u, sc, fw) * square_box(v, sc, fw))
                                             : 0.5 * (1 - square_box(u, 0.5 * sc, fw));
        for (int k = 0; k < 3; k++) out[k] = m->diffuse[k] + a * (m->color2[k] - m->diffuse[k]);
        return;
    }
    case TDC_TEX_TEXT: feature = sc / 8; goto supersample;     /* a glyph row */
    case TDC_TEX_SKYLINE: feature = sc * 0.1; goto supersample; /* a window's margin */
    supersample: {
        if (!(fw > TEX_MIN_FRACTION * feature)) break;
        int g = (int)(fw / (TEX_MIN_FRACTION * feature) + 0.999);
        g = g > 4 ? 4 : g;
        double acc[3] = {0, 0, 0}, c[3];
        for (int j = 0; j < g; j++) {
            for (int i = 0; i < g; i++) {
                tex_color(r, o, u + fw * ((i + 0.5) / g - 0.5), v + fw * ((j + 0.5) / g - 0.5), c);
                acc[0] += c[0];
                acc[1] += c[1];
                acc[2] += c[2];
            }
        }
        for (int k = 0; k < 3; k++) out[k] = acc[k] / (g * g);
        return;
    }
    default: break;
    }
    tex_color(r, o, u, v, out);
}

double tdc_r_sample_cone(const tdc_render_t *r, int mode, int sw, int spp, double tan_half)
{
    if (!r->cfg.tex_filter) return 0.0;
    double px = 2.0 * tan_half / r->H; /* one pixel's angle at the image centre */
    switch (mode) {
    case TDC_RENDER_REDUCED: return px * r->W / (sw > 0 ? sw : r->W);
    case TDC_RENDER_GROUND_TRUTH: return px / sqrt(spp > 1 ? spp : 1);
    default: return px;
    }
}

double tdc_r_tex_footprint(double cone, double dist, const double dw[3], const double n[3], const double *minv)
{
    double dq[3], scale = 1.0;
    const double *d = dw;
    if (minv) {
        for (int i = 0; i < 3; i++) dq[i] = minv[4 * i] * dw[0] + minv[4 * i + 1] * dw[1] + minv[4 * i + 2] * dw[2];
        d = dq;
        /* object lengths per world length: the geometric mean of the inverse scales (objects are T R S) */
        double det = minv[0] * (minv[5] * minv[10] - minv[6] * minv[9]) -
                     minv[1] * (minv[4] * minv[10] - minv[6] * minv[8]) +
                     minv[2] * (minv[4] * minv[9] - minv[5] * minv[8]);
        scale = cbrt(fabs(det));
    }
    double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    double c = fabs(d[0] * n[0] + d[1] * n[1] + d[2] * n[2]) / sqrt(dd * nn + 1e-300);
    return scale * cone * dist / (c > 1.0 / 16 ? c : 1.0 / 16);
}
