/*
 * tdc_image_source.c - pan / zoom / rotate across a photograph with exact
 * area-sampled ground truth (the filter and the map: tdc_image_source.h).
 */
#include "image/tdc_image_source.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image/tdc_image_read.h"
#include "tdc_sim_codes.h"

typedef struct {
    int iw, ih;
    double *S;     /* per-row prefix sums, (iw + 1) * ih * 3: S[j][i][k] = sum of texels 0..i-1 of row j */
    double vx, vy; /* pan speed at the centre at t = 0, screen px/s */
    double ux, uy; /* c'(t) = -u, texels/s */
    tdc_image_motion_t m;
    int pursuit;
    double *eh0, *eh1, *ev; /* ground truth: contour integrals of two rows of horizontal edges, one of vertical */
} img_ctx_t;

static const img_ctx_t *ctx_of(const tdc_source_t *s)
{
    return (const img_ctx_t *)s->ctx;
}

void tdc_image_motion_default(tdc_image_motion_t *m)
{
    m->zoom = 1.0;
    m->zoom_rate = 0.0;
    m->rotate_dps = 0.0;
    m->cx = NAN;
    m->cy = NAN;
}

static void map_at(const img_ctx_t *c, int sw, int sh, double t, double A[4], double b[2])
{
    double z = c->m.zoom * exp(c->m.zoom_rate * t);
    double th = c->m.rotate_dps * (3.141592653589793 / 180.0) * t;
    double co = cos(th) / z, si = sin(th) / z;
    A[0] = co;
    A[1] = si;
    A[2] = -si;
    A[3] = co;
    double cx = c->m.cx - c->ux * t, cy = c->m.cy - c->uy * t;
    double px = 0.5 * sw, py = 0.5 * sh;
    b[0] = cx - (A[0] * px + A[1] * py);
    b[1] = cy - (A[2] * px + A[3] * py);
}

void tdc_image_source_map(const tdc_source_t *s, double t, double A[4], double b[2])
{
    map_at(ctx_of(s), s->width, s->height, t, A, b);
}

double tdc_image_source_max_speed(const tdc_source_t *s, double duration)
{
    const img_ctx_t *c = ctx_of(s);
    double zmax = c->m.zoom * fmax(1.0, exp(c->m.zoom_rate * duration));
    return hypot(c->ux, c->uy) * zmax;
}

/* Mirrored texel index: period 2n, [n, 2n) reflected onto [0, n). */
static int64_t mirror_index(int64_t i, int n)
{
    int64_t p = 2 * (int64_t)n;
    int64_t r = i % p;
    r += r < 0 ? p : 0;
    return r < n ? r : p - 1 - r;
}

/* Running integral F(x, row) of the mirrored field along a row, channel
 * 3-vector: F(x) = k T + F0(xr) on period k (T = 2 S(W)); on the reflected
 * half F0(x) = T - F0(2W - x). */
static void row_integral(const img_ctx_t *c, double x, int64_t row, double out[3])
{
    const int w = c->iw;
    const double *S = c->S + (size_t)(row >= 0 && row < c->ih ? row : mirror_index(row, c->ih)) * (size_t)(w + 1) * 3;
    if (x >= 0.0 && x < (double)w) {
        /* inside the image (the common case): no period, no reflection */
        int col = (int)x;
        double fr = x - col;
        const double *a = S + 3 * col;
        out[0] = a[0] + fr * (a[3] - a[0]);
        out[1] = a[1] + fr * (a[4] - a[1]);
        out[2] = a[2] + fr * (a[5] - a[2]);
        return;
    }
    double p = 2.0 * w;
    double k = floor(x / p);
    double xr = x - k * p;
    int refl = xr > w;
    double xi = refl ? p - xr : xr;
    int col = (int)xi;
    col = col < 0 ? 0 : (col > w - 1 ? w - 1 : col);
    double fr = xi - col;
    for (int ch = 0; ch < 3; ch++) {
        double T = 2.0 * S[3 * w + ch];
        double f0 = S[3 * col + ch] + fr * (S[3 * (col + 1) + ch] - S[3 * col + ch]);
        out[ch] = k * T + (refl ? T - f0 : f0);
    }
}

/* Contour integral of F dy along the segment (x0, y0) -> (x1, y1), cut at
 * every integer x and y so that F is linear on each piece. */
static void edge_integral(const img_ctx_t *c, double x0, double y0, double x1, double y1, double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    double dx = x1 - x0, dy = y1 - y0;
    if (dy == 0.0) {
        return;
    }
    /* next crossing parameters along x and y, and their steps */
    double lx = 2.0, sx = 0.0, ly, sy;
    double nx = 0.0, ny;
    if (dx != 0.0) {
        nx = dx > 0 ? floor(x0) + 1.0 : ceil(x0) - 1.0;
        sx = 1.0 / fabs(dx);
        lx = (nx - x0) / dx;
    }
    ny = dy > 0 ? floor(y0) + 1.0 : ceil(y0) - 1.0;
    sy = 1.0 / fabs(dy);
    ly = (ny - y0) / dy;
    double la = 0.0;
    for (;;) {
        double lb = lx < ly ? lx : ly;
        if (lb > 1.0) {
            lb = 1.0;
        }
        if (lb > la) {
            double lm = 0.5 * (la + lb);
            double xm = x0 + lm * dx, ym = y0 + lm * dy;
            double f[3];
            row_integral(c, xm, (int64_t)floor(ym), f);
            double w = (lb - la) * dy;
            out[0] += w * f[0];
            out[1] += w * f[1];
            out[2] += w * f[2];
        }
        if (lb >= 1.0) {
            break;
        }
        if (lx <= lb) {
            lx = (lx + sx > 2.0) ? 2.0 : lx + sx;
        }
        if (ly <= lb) {
            ly += sy;
        }
        la = lb;
    }
}

static void src_ground_truth(tdc_source_t *s, double t, double ox, double oy, double *lin)
{
    img_ctx_t *c = (img_ctx_t *)s->ctx;
    const int w = s->width, h = s->height;
    double A[4], b[2];
    map_at(c, w, h, t, A, b);
    double inv_det = 1.0 / (A[0] * A[3] - A[1] * A[2]); /* z^2 */
#define QX(px, py) (A[0] * (px) + A[1] * (py) + b[0])
#define QY(px, py) (A[2] * (px) + A[3] * (py) + b[1])
    /* horizontal edges of corner row j: from corner (i, j) to (i + 1, j) */
    for (int j = 0; j <= h; j++) {
        double py = j + oy;
        double *eh = c->eh1;
        for (int i = 0; i < w; i++) {
            double pa = i + ox, pb = i + 1 + ox;
            edge_integral(c, QX(pa, py), QY(pa, py), QX(pb, py), QY(pb, py), eh + 3 * i);
        }
        if (j > 0) {
            /* vertical edges of pixel row j - 1: corner (i, j - 1) -> (i, j) */
            for (int i = 0; i <= w; i++) {
                double px = i + ox;
                edge_integral(c, QX(px, py - 1), QY(px, py - 1), QX(px, py), QY(px, py), c->ev + 3 * i);
            }
            /* counter-clockwise in (x, y): top, right, bottom reversed, left reversed */
            double *o = lin + (size_t)(j - 1) * w * 3;
            for (int i = 0; i < w; i++) {
                for (int k = 0; k < 3; k++) {
                    double v = c->eh0[3 * i + k] + c->ev[3 * (i + 1) + k] - eh[3 * i + k] - c->ev[3 * i + k];
                    o[3 * i + k] = v * inv_det;
                }
            }
        }
        c->eh1 = c->eh0;
        c->eh0 = eh;
    }
#undef QX
#undef QY
}

static double texel(const img_ctx_t *c, double qx, double qy, int ch)
{
    int64_t i = mirror_index((int64_t)floor(qx), c->iw), j = mirror_index((int64_t)floor(qy), c->ih);
    const double *S = c->S + ((size_t)j * (size_t)(c->iw + 1) + (size_t)i) * 3;
    return S[3 + ch] - S[ch];
}

static void src_samples(tdc_source_t *s, double t, int n, const double *xy, int spp, uint8_t *rgb, int16_t *mv,
                        double dt, tdc_mv_kind_t kind)
{
    const img_ctx_t *c = ctx_of(s);
    (void)kind; /* a flat photograph casts no shadows: shadow MVs = surface MVs */
    double A[4], b[2], Ap[4], bp[2];
    map_at(c, s->width, s->height, t, A, b);
    if (mv) {
        map_at(c, s->width, s->height, t - dt, Ap, bp);
    }
    int g = tdc_sim_spp_grid(spp);
    for (int i = 0; i < n; i++) {
        double x = xy[2 * i], y = xy[2 * i + 1];
        double acc[3] = {0, 0, 0};
        if (spp <= 1) {
            double qx = A[0] * x + A[1] * y + b[0], qy = A[2] * x + A[3] * y + b[1];
            for (int k = 0; k < 3; k++) {
                acc[k] = texel(c, qx, qy, k);
            }
        } else {
            double px = floor(x), py = floor(y);
            for (int jj = 0; jj < g; jj++) {
                for (int kk = 0; kk < g; kk++) {
                    double sx = px + (kk + 0.5) / g, sy = py + (jj + 0.5) / g;
                    double qx = A[0] * sx + A[1] * sy + b[0], qy = A[2] * sx + A[3] * sy + b[1];
                    for (int k = 0; k < 3; k++) {
                        acc[k] += texel(c, qx, qy, k);
                    }
                }
            }
            for (int k = 0; k < 3; k++) {
                acc[k] /= (double)(g * g);
            }
        }
        for (int k = 0; k < 3; k++) {
            rgb[3 * i + k] = tdc_sim_encode_code(acc[k], s->gamma[k]);
        }
        if (mv) {
            /* p' with q(p', t - dt) = q(p, t): p' = Ap^-1 (q - bp) */
            double qx = A[0] * x + A[1] * y + b[0] - bp[0], qy = A[2] * x + A[3] * y + b[1] - bp[1];
            double id = 1.0 / (Ap[0] * Ap[3] - Ap[1] * Ap[2]);
            double ppx = (Ap[3] * qx - Ap[1] * qy) * id, ppy = (-Ap[2] * qx + Ap[0] * qy) * id;
            mv[2 * i] = tdc_sim_mv_q4(ppx - x);
            mv[2 * i + 1] = tdc_sim_mv_q4(ppy - y);
        }
    }
}

static void src_pursuit(tdc_source_t *s, double t, double v[2])
{
    /* dp/dt of the image point at the centre: z(t) R(theta(t)) u */
    const img_ctx_t *c = ctx_of(s);
    if (!c->pursuit) {
        v[0] = v[1] = 0.0;
        return;
    }
    double z = c->m.zoom * exp(c->m.zoom_rate * t) / c->m.zoom;
    double th = c->m.rotate_dps * (3.141592653589793 / 180.0) * t;
    v[0] = z * (cos(th) * c->vx - sin(th) * c->vy);
    v[1] = z * (sin(th) * c->vx + cos(th) * c->vy);
}

static void ctx_free(img_ctx_t *c)
{
    if (c) {
        free(c->S);
        free(c->eh0);
        free(c->eh1);
        free(c->ev);
        free(c);
    }
}

static void src_destroy(tdc_source_t *s)
{
    if (s) {
        ctx_free((img_ctx_t *)s->ctx);
        free(s);
    }
}

/* Builds the source around prefix sums filled by fill(row, S_row) */
static tdc_source_t *create(int iw, int ih, const tdc_scene_params_t *p, const tdc_image_motion_t *m,
                            void (*fill)(const void *src, int iw, int row, double *lin_row), const void *fsrc,
                            char *err, size_t errlen)
{
    if (iw < 1 || ih < 1) {
        snprintf(err, errlen, "image size %dx%d: must be at least 1x1", iw, ih);
        return NULL;
    }
    if (!p || p->width < 1 || p->height < 1) {
        snprintf(err, errlen, "screen size must be at least 1x1");
        return NULL;
    }
    tdc_image_motion_t mm;
    tdc_image_motion_default(&mm);
    if (m) {
        mm = *m;
    }
    if (!(mm.zoom > 1e-3 && mm.zoom < 1e3) || !isfinite(mm.zoom_rate) || fabs(mm.zoom_rate) > 20.0 ||
        !isfinite(mm.rotate_dps) || fabs(mm.rotate_dps) > 3600.0) {
        snprintf(err, errlen,
                 "image motion out of range: zoom %g (1e-3 .. 1e3), zoom rate %g (|r| <= 20 /s), "
                 "rotation %g (|w| <= 3600 deg/s)",
                 mm.zoom, mm.zoom_rate, mm.rotate_dps);
        return NULL;
    }
    if (isnan(mm.cx)) {
        mm.cx = 0.5 * iw;
    }
    if (isnan(mm.cy)) {
        mm.cy = 0.5 * ih;
    }
    tdc_source_t *s = calloc(1, sizeof(*s));
    img_ctx_t *c = calloc(1, sizeof(*c));
    size_t rows = (size_t)(iw + 1) * 3;
    if (c) {
        c->S = malloc(sizeof(double) * rows * (size_t)ih);
        c->eh0 = malloc(sizeof(double) * 3 * (size_t)(p->width + 1));
        c->eh1 = malloc(sizeof(double) * 3 * (size_t)(p->width + 1));
        c->ev = malloc(sizeof(double) * 3 * (size_t)(p->width + 1));
    }
    double *lrow = malloc(sizeof(double) * 3 * (size_t)iw);
    if (!s || !c || !c->S || !c->eh0 || !c->eh1 || !c->ev || !lrow) {
        snprintf(err, errlen, "out of memory for a %dx%d image (%.0f MB of prefix sums)", iw, ih,
                 sizeof(double) * (double)rows * ih / 1e6);
        free(lrow);
        ctx_free(c);
        free(s);
        return NULL;
    }
    for (int j = 0; j < ih; j++) {
        fill(fsrc, iw, j, lrow);
        double *S = c->S + (size_t)j * rows;
        S[0] = S[1] = S[2] = 0.0;
        for (int i = 0; i < iw; i++) {
            for (int k = 0; k < 3; k++) {
                S[3 * (i + 1) + k] = S[3 * i + k] + lrow[3 * i + k];
            }
        }
    }
    free(lrow);
    c->iw = iw;
    c->ih = ih;
    c->m = mm;
    c->pursuit = p->pursuit;
    double speed = p->speed > 0.0 ? p->speed : 0.0;
    double a = p->angle_deg * 3.141592653589793 / 180.0;
    c->vx = speed * cos(a);
    c->vy = speed * sin(a);
    c->vx = fabs(c->vx) < 1e-12 ? 0.0 : c->vx;
    c->vy = fabs(c->vy) < 1e-12 ? 0.0 : c->vy;
    c->ux = c->vx / mm.zoom;
    c->uy = c->vy / mm.zoom;
    s->name = "image";
    s->width = p->width;
    s->height = p->height;
    s->gamma[0] = s->gamma[1] = s->gamma[2] = 2.2;
    s->gt_ss = 1; /* exact: no supersampling */
    /* a pure pan tracked by the eye is rigid: one ground-truth instant */
    s->rigid = mm.zoom_rate == 0.0 && mm.rotate_dps == 0.0 && (p->pursuit || speed == 0.0);
    s->ctx = c;
    s->samples = src_samples;
    s->ground_truth = src_ground_truth;
    s->pursuit = src_pursuit;
    s->cut = NULL; /* never cut (the run treats NULL as no cut) */
    s->destroy = src_destroy;
    return s;
}

static void fill_linear(const void *src, int iw, int row, double *lin_row)
{
    memcpy(lin_row, (const double *)src + (size_t)row * iw * 3, sizeof(double) * 3 * (size_t)iw);
}

tdc_source_t *tdc_image_source_from_linear(const double *lin, int iw, int ih, const tdc_scene_params_t *p,
                                           const tdc_image_motion_t *m, char *err, size_t errlen)
{
    return create(iw, ih, p, m, fill_linear, lin, err, errlen);
}

/* sRGB EOTF (IEC 61966-2-1) of a code normalised to [0, 1]. */
static double srgb_to_linear(double v)
{
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

typedef struct {
    const tdc_image_t *img;
    const double *lut; /* 256 or 65536 entries */
} fill_img_t;

static void fill_image(const void *src, int iw, int row, double *lin_row)
{
    const fill_img_t *f = (const fill_img_t *)src;
    size_t n = (size_t)iw * 3, o = (size_t)row * n;
    if (f->img->bits == 16) {
        const uint16_t *d = (const uint16_t *)f->img->data + o;
        for (size_t i = 0; i < n; i++) {
            lin_row[i] = f->lut[d[i]];
        }
    } else {
        const uint8_t *d = (const uint8_t *)f->img->data + o;
        for (size_t i = 0; i < n; i++) {
            lin_row[i] = f->lut[d[i]];
        }
    }
}

tdc_source_t *tdc_image_source_open(const char *path, const tdc_scene_params_t *p, const tdc_image_motion_t *m,
                                    char *err, size_t errlen)
{
    tdc_image_t img;
    if (tdc_image_read(path, &img, err, errlen) != 0) {
        return NULL;
    }
    int levels = img.bits == 16 ? 65536 : 256;
    double *lut = malloc(sizeof(double) * (size_t)levels);
    if (!lut) {
        snprintf(err, errlen, "%s: out of memory", path);
        tdc_png_free(&img);
        return NULL;
    }
    for (int i = 0; i < levels; i++) {
        lut[i] = srgb_to_linear((double)i / (double)(levels - 1));
    }
    fill_img_t f = {&img, lut};
    char e2[256];
    tdc_source_t *s = create(img.width, img.height, p, m, fill_image, &f, e2, sizeof e2);
    if (!s) {
        snprintf(err, errlen, "%s: %s", path, e2);
    }
    free(lut);
    tdc_png_free(&img);
    return s;
}
