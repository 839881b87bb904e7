/*
 * ref_fov.c - double-precision reference of the foveated remap; see ref_fov.h.
 * Written from the thesis's equations, not from the fixed-point code: the
 * only shared decisions are the definitions tdc_fov.h states (pixel
 * centres, the sigma clamp, the kernel cut at 2 sigma, the 4-pixel blend
 * band, the saccade rule, Q4 motion vectors).
 */
#include "ref_fov.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BLEND_PX 4.0
#define REACH 4

void ref_fov_geom(ref_fov_geom_t *g, int width, int height, const ref_fov_params_t *p)
{
    g->width = width;
    g->height = height;
    g->lp_w = p->lp_w;
    g->lp_h = p->lp_h;
    g->cx = p->cx;
    g->cy = p->cy;
    g->alpha = p->alpha;
    const double ex = fmax(p->cx, width - p->cx), ey = fmax(p->cy, height - p->cy);
    g->R = sqrt(ex * ex + ey * ey);
    g->L = log(g->R);
    g->r_disk = p->disk * g->R;
    double e;
    g->l = ref_fov_disk_columns(g, g->r_disk, &e);
    g->u0 = 0;
    if (g->r_disk > BLEND_PX) {
        double u, v;
        ref_fov_to_lp(g, g->cx + g->r_disk - BLEND_PX, g->cy, &u, &v);
        const int fu = (int)floor(u);
        g->u0 = fu > REACH ? fu - REACH : 0;
    }
    if (g->u0 > g->l) {
        g->u0 = g->l;
    }
    g->transform = p->transform;
    if (p->transform) { /* log-rectilinear: the whole buffer */
        g->l = 0;
        g->u0 = 0;
        ref_fov_lr_axis(&g->ax, p->cx, p->kx, width, p->lp_w);
        ref_fov_lr_axis(&g->ay, p->cy, p->ky, height, p->lp_h);
    }
}

static double kinv(const ref_fov_geom_t *g, double x) /* K^-1(x) = x^(1/alpha), x >= 0 */
{
    return x <= 0 ? 0 : pow(x, 1.0 / g->alpha);
}

void ref_fov_to_lp(const ref_fov_geom_t *g, double x, double y, double *u, double *v)
{
    const double dx = x - g->cx, dy = y - g->cy;
    const double r = sqrt(dx * dx + dy * dy);
    *u = r <= 1 ? 0 : fmin(kinv(g, log(r) / g->L), 1.0) * g->lp_w;
    double a = (dx == 0 && dy == 0) ? 0 : atan2(dy, dx);
    if (a < 0) {
        a += 2 * M_PI; /* eq. 2.2: + 1[y' < 0] 2 pi */
    }
    *v = a * g->lp_h / (2 * M_PI);
    if (*v >= g->lp_h) {
        *v -= g->lp_h;
    }
}

void ref_fov_from_lp(const ref_fov_geom_t *g, double u, double v, double *x, double *y)
{
    const double r = exp(g->L * pow(u / g->lp_w, g->alpha));
    const double th = 2 * M_PI * v / g->lp_h;
    *x = r * cos(th) + g->cx;
    *y = r * sin(th) + g->cy;
}

int ref_fov_disk_columns(const ref_fov_geom_t *g, double r, double *exact)
{
    *exact = r <= 1 ? 0 : fmin(kinv(g, log(r) / g->L), 1.0) * g->lp_w;
    return (int)ceil(*exact);
}

double ref_fov_sigma_u(const ref_fov_geom_t *g, double r, double u)
{
    if (r <= 1 || u <= 0) {
        return 2.0;
    }
    const double eta = fmax(3 + 0.8 * (r / g->R - 0.1) / 0.05, 0); /* eq. 4.4, display pixels */
    const double dudr = u / (g->alpha * log(r) * r);               /* d/dr of eq. 2.2 */
    return eta / 4 * dudr;
}

static double gauss_cut(double t) /* the kernel, cut continuously at t = 2 */
{
    return t >= 2 ? 0 : (exp(-0.5 * t * t) - exp(-2.0)) / (1 - exp(-2.0));
}

/* One display pixel: composed colour, blend weight b; nearest sample. */
static double compose(const ref_fov_geom_t *g, const uint8_t *lp, size_t lp_stride, const uint8_t *dpix, int i, int j,
                      double c[3], int *iu, int *jv)
{
    const double x = i + 0.5, y = j + 0.5;
    const double r = hypot(x - g->cx, y - g->cy);
    const double b = fmin(fmax((r - (g->r_disk - BLEND_PX)) / BLEND_PX, 0), 1);
    double lpc[3] = {0, 0, 0};
    if (b > 0 && g->transform) {
        ref_fov_lr_sample(&g->ax, &g->ay, lp, lp_stride, x, y, lpc, iu, jv);
    } else if (b > 0) {
        double u, v;
        ref_fov_to_lp(g, x, y, &u, &v);
        const double sig = fmin(fmax(ref_fov_sigma_u(g, r, u), 0.5), 2.0);
        const int j0 = (int)floor(v), j1 = j0 + 1 == g->lp_h ? 0 : j0 + 1;
        const double fv = v - j0;
        double sum = 0;
        for (int t = (int)ceil(u - 2 * sig); t <= (int)floor(u + 2 * sig); t++) {
            const double w = gauss_cut(fabs(t - u) / sig);
            int col = t < g->u0 ? g->u0 : (t > g->lp_w - 1 ? g->lp_w - 1 : t);
            const uint8_t *p0 = lp + (size_t)j0 * lp_stride + (size_t)col * 3;
            const uint8_t *p1 = lp + (size_t)j1 * lp_stride + (size_t)col * 3;
            for (int ch = 0; ch < 3; ch++) {
                lpc[ch] += w * (p0[ch] * (1 - fv) + p1[ch] * fv);
            }
            sum += w;
        }
        for (int ch = 0; ch < 3; ch++) {
            lpc[ch] /= sum;
        }
        int ui = (int)floor(u + 0.5), vi = (int)floor(v + 0.5);
        *iu = ui < g->u0 ? g->u0 : (ui > g->lp_w - 1 ? g->lp_w - 1 : ui);
        *jv = vi >= g->lp_h ? 0 : vi;
    }
    for (int ch = 0; ch < 3; ch++) {
        c[ch] = (1 - b) * dpix[ch] + b * lpc[ch];
    }
    return b;
}

int ref_fov_init(ref_fov_t *st, int width, int height, int taa)
{
    memset(st, 0, sizeof *st);
    st->width = width;
    st->height = height;
    st->taa = taa;
    if (taa) {
        st->hist = calloc((size_t)width * height * 3, sizeof(double));
        if (!st->hist) {
            return -1;
        }
    }
    return 0;
}

void ref_fov_free(ref_fov_t *st)
{
    free(st->hist);
    st->hist = NULL;
}

void ref_fov_frame(ref_fov_t *st, const ref_fov_params_t *p, const uint8_t *lp, size_t lp_stride, const int16_t *mv,
                   size_t mv_stride, const uint8_t *disk, size_t disk_stride, uint32_t dt_us, double *out)
{
    const int W = st->width, H = st->height;
    ref_fov_geom_t g;
    ref_fov_geom(&g, W, H, p);
    const size_t n = (size_t)W * H;
    double *s = malloc(n * 3 * sizeof(double)), *h = malloc(n * 3 * sizeof(double));
    double *d = malloc(n * sizeof(double)), *hh = malloc(n * sizeof(double)), *bb = malloc(n * sizeof(double));
    char *valid = calloc(n, 1);
    int reject_all = 1;
    double r60 = 0, diag = hypot(W, H);
    if (st->taa) {
        const uint32_t dt = dt_us ? (dt_us < 100 ? 100 : dt_us) : (st->dt_prev_us ? st->dt_prev_us : 11111);
        const uint32_t dtp = st->dt_prev_us ? st->dt_prev_us : dt;
        const double rate = 0.1 * 1e6 / dt + 0.9 * 1e6 / dtp; /* eq. 4.7 */
        r60 = 60 / rate;
        st->dt_prev_us = dt;
        const double jump = hypot(p->cx - st->gaze_prev_x, p->cy - st->gaze_prev_y);
        reject_all = !st->have_hist || jump > diag / 8;
        st->gaze_prev_x = p->cx;
        st->gaze_prev_y = p->cy;
    }
    for (int j = 0; j < H; j++) {
        for (int i = 0; i < W; i++) {
            const size_t k = (size_t)j * W + i;
            int iu = 0, jv = 0;
            bb[k] =
                compose(&g, lp, lp_stride, disk + (size_t)j * disk_stride + (size_t)i * 3, i, j, s + 3 * k, &iu, &jv);
            d[k] = 255;
            if (!st->taa || reject_all || bb[k] <= 0) {
                continue;
            }
            double mx = 0, my = 0;
            if (mv) {
                mx = mv[(size_t)jv * mv_stride + (size_t)iu * 2] / 16.0;
                my = mv[(size_t)jv * mv_stride + (size_t)iu * 2 + 1] / 16.0;
            }
            double px = i + mx, py = j + my; /* backward MVs: the point was at p + mv */
            if (px < -0.5 || px > W - 0.5 || py < -0.5 || py > H - 0.5) {
                continue;
            }
            px = fmin(fmax(px, 0), W - 1);
            py = fmin(fmax(py, 0), H - 1);
            const int x0 = (int)floor(px), y0 = (int)floor(py);
            const int x1 = x0 + 1 < W ? x0 + 1 : x0, y1 = y0 + 1 < H ? y0 + 1 : y0;
            const double fx = px - x0, fy = py - y0;
            double dsum = 0;
            for (int ch = 0; ch < 3; ch++) {
                const double *hp = st->hist;
                const double top =
                    hp[((size_t)y0 * W + x0) * 3 + ch] * (1 - fx) + hp[((size_t)y0 * W + x1) * 3 + ch] * fx;
                const double bot =
                    hp[((size_t)y1 * W + x0) * 3 + ch] * (1 - fx) + hp[((size_t)y1 * W + x1) * 3 + ch] * fx;
                h[3 * k + ch] = top * (1 - fy) + bot * fy;
                dsum += fabs(s[3 * k + ch] - h[3 * k + ch]);
            }
            d[k] = dsum / 3;
            const double m = hypot(mx, my);
            hh[k] = m > 0 ? pow(m / diag, 0.25) * r60 : 0; /* eq. 4.8 */
            valid[k] = 1;
        }
    }
    for (int j = 0; j < H; j++) {
        for (int i = 0; i < W; i++) {
            const size_t k = (size_t)j * W + i;
            double f[3] = {s[3 * k], s[3 * k + 1], s[3 * k + 2]};
            if (valid[k]) {
                double sum = 0;
                int cnt = 0;
                for (int jj = j - 1; jj <= j + 1; jj++) {
                    for (int ii = i - 1; ii <= i + 1; ii++) {
                        if (jj >= 0 && jj < H && ii >= 0 && ii < W) {
                            sum += d[(size_t)jj * W + ii];
                            cnt++;
                        }
                    }
                }
                const double amin = fmin(fmax(sum / cnt / 255, 0.1), 1);             /* eq. 4.9 */
                const double a = amin + fmax(fmin((1 - amin) * hh[k], 1 - amin), 0); /* eq. 4.10 */
                const double aeff = 1 - bb[k] * (1 - a); /* phased out inside the disk border */
                for (int ch = 0; ch < 3; ch++) {
                    f[ch] = aeff * s[3 * k + ch] + (1 - aeff) * h[3 * k + ch]; /* eq. 2.5 */
                }
            }
            for (int ch = 0; ch < 3; ch++) {
                out[3 * k + ch] = f[ch];
            }
        }
    }
    if (st->taa) {
        memcpy(st->hist, out, n * 3 * sizeof(double));
        st->have_hist = 1;
    }
    free(s);
    free(h);
    free(d);
    free(hh);
    free(bb);
    free(valid);
}

double ref_fov_ray_share(const ref_fov_geom_t *g, long disk_pixels)
{
    return ((double)(g->lp_w - g->u0) * g->lp_h + (double)disk_pixels) / ((double)g->width * g->height);
}

double ref_fov_lod_cone(int mode, double r, double L, double alpha, double un, int w, int h)
{
    if (mode == TDC_FOV_LOD_FOOTPRINT) {
        const double radial = r * L * alpha * pow(un, alpha - 1) / w, tang = 2 * M_PI * r / h;
        const double side = radial > tang ? radial : tang;
        return side > 1 ? side : 1;
    }
    if (mode == TDC_FOV_LOD_THESIS) {
        const double x = fmin(fmax(pow(un, alpha), 0), 1), s1 = x * x * (3 - 2 * x); /* S1 */
        return exp2(3 * s1 * s1 * s1);
    }
    return 1;
}

void ref_fov_halton(uint32_t f, double *jx, double *jy)
{
    double hx = 0, hy = 0;
    for (uint32_t k = f + 1, b = 2; k; k /= 2, b *= 2) hx += (double)(k % 2) / b;
    for (uint32_t k = f + 1, b = 3; k; k /= 3, b *= 3) hy += (double)(k % 3) / b;
    *jx = hx - 0.5;
    *jy = hy - 0.5;
}

void ref_fov_lp_jitter(int mode, double L, double alpha, int w, int h, int i, int j, double jx, double jy, double *u,
                       double *v)
{
    double su = 1, sv = 1;
    if (mode == TDC_FOV_JITTER_PIXEL) {
        const double un = (double)i / w, r = exp(L * pow(un, alpha));
        const double radial = r * L * alpha * pow(un, alpha - 1) / w, tang = 2 * M_PI * r / h;
        su = radial > 1 ? 1 / radial : 1;
        sv = tang > 1 ? 1 / tang : 1;
    }
    *u = fmax(i + jx * su, 0.0);
    *v = j + jy * sv;
}

size_t ref_fov_lp_samples(const ref_fov_geom_t *g, int u0, double jx, double jy, int jitter, int lod, double *xy,
                          double *side)
{
    size_t k = 0;
    for (int j = 0; j < g->lp_h; j++) {
        for (int i = u0; i < g->lp_w; i++, k++) {
            double u, v;
            ref_fov_lp_jitter(jitter, g->L, g->alpha, g->lp_w, g->lp_h, i, j, jx, jy, &u, &v);
            ref_fov_from_lp(g, u, v, &xy[2 * k], &xy[2 * k + 1]);
            if (side) {
                const double un = u / g->lp_w, r = exp(g->L * pow(un, g->alpha));
                side[k] = ref_fov_lod_cone(lod, r, g->L, g->alpha, un, g->lp_w, g->lp_h);
            }
        }
    }
    return k;
}
