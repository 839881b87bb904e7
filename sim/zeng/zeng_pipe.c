/*
 * zeng_pipe.c - Zeng et al.'s temporal pipeline and its baselines
 * (zeng_pipe.h).
 */
#include "zeng/zeng_pipe.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "zeng/zeng_filter.h"

#define CH 3
#define EPS_WC 0.001 /* eq. 8's epsilon */
#define LLK_R 15      /* the [LLK*19] kernel's radius: 31 taps a pass */

static const char *const k_mnames[ZM_N] = {"trad", "trad-clamp", "spec", "ours", "svgf", "asvgf"};

const char *zp_method_name(int m) { return m >= 0 && m < ZM_N ? k_mnames[m] : "?"; }

int zp_init(zp_state_t *st, int method, int w, int h)
{
    memset(st, 0, sizeof *st);
    st->method = method;
    st->w = w;
    st->h = h;
    st->alpha = 0.1;
    st->clamp_r = 2;
    st->clamp_k = 3.0;
    const size_t n = (size_t)w * h;
    st->hist = calloc(n * CH, sizeof(double));
    st->out = calloc(n * CH, sizeof(double));
    st->filt = calloc(n * CH, sizeof(double));
    st->tmp = calloc(n * CH, sizeof(double));
    st->tmp2 = calloc(n * CH, sizeof(double));
    st->sig = calloc(n, sizeof(double));
    st->mvx = calloc(n * CH, sizeof(double));
    st->mom = calloc(n * 2, sizeof(double));
    st->len = calloc(n, sizeof(double));
    st->var = calloc(n, sizeof(double));
    st->var2 = calloc(n, sizeof(double));
    st->lam = calloc(n, sizeof(double));
    if (!st->lam || !st->hist || !st->out || !st->filt || !st->tmp || !st->tmp2 || !st->sig || !st->mvx || !st->mom || !st->len ||
        !st->var || !st->var2) {
        zp_free(st);
        return -1;
    }
    return 0;
}

void zp_free(zp_state_t *st)
{
    free(st->hist);
    free(st->out);
    free(st->filt);
    free(st->tmp);
    free(st->tmp2);
    free(st->sig);
    free(st->mvx);
    free(st->mom);
    free(st->len);
    free(st->var);
    free(st->var2);
    free(st->lam);
    memset(st, 0, sizeof *st);
}

static zf_guide_t guide_of(const zs_frame_t *f)
{
    zf_guide_t g = {f->w, f->h, f->id, f->depth, f->nrm};
    return g;
}

/* [LLK*19] (Liu, Llamas, Kelly et al., "Cinematic Rendering in UE4 with
 * Real-Time Ray Tracing and Denoising", Ray Tracing Gems ch. 19, 2019; the
 * same authors' patent US 10,776,985 describes the kernel): the
 * reflection filter's kernel is the BRDF lobe reflected below the surface
 * along the view ray and projected on the screen.  Here the lobe is a
 * Gaussian of angular sigma around the mirror direction, so the reflected
 * lobe is a cone of that sigma around the view ray continued past the
 * surface point (d_v from the eye); at the hit distance d_h its
 * cross-section, d_h tan(sigma) wide, lies d_v + d_h from the eye:
 * sigma_px = fpx d_h tan(sigma) / (d_v + d_h).  Isotropic here: a GGX lobe
 * stretches it along the plane of incidence, this scene's lobe does not.
 * The 1-sample hit distance is noisy, so the ratio d_h / (d_v + d_h) is
 * averaged over the pixel's 5x5 same-object neighbourhood (the sky's ratio
 * is 1: the lobe's angle alone).  Capped at LLK_R / 2.5 px. */
void zp_glossy_footprint(const zs_scene_t *s, const zs_frame_t *f, double *sg)
{
    const int w = f->w, h = f->h;
    const size_t n = (size_t)w * h;
    const double fpx = 0.5 * h / tan(0.5 * s->vfov);
    for (size_t p = 0; p < n; p++) {
        /* eye distance from the view depth: the pixel ray's length per unit
         * depth */
        const double px = (double)(p % w) + 0.5 - 0.5 * w, py = (double)(p / w) + 0.5 - 0.5 * h;
        const double dv = f->depth[p] * sqrt(fpx * fpx + px * px + py * py) / fpx, dh = f->hitd[p];
        sg[p] = isfinite(dh) ? dh / (dv + dh) : 1.0;
    }
    double *ratio = malloc(n * sizeof(double)); /* without it: each pixel's own ratio */
    if (ratio) {
        memcpy(ratio, sg, n * sizeof(double));
    }
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const size_t p = (size_t)y * w + x;
            const int id = f->id[p];
            double r = 0;
            int cnt = 0;
            for (int j = -2; j <= 2 && ratio; j++) {
                for (int i = -2; i <= 2; i++) {
                    const int xx = x + i, yy = y + j;
                    if (xx >= 0 && yy >= 0 && xx < w && yy < h && f->id[(size_t)yy * w + xx] == id) {
                        r += ratio[(size_t)yy * w + xx];
                        cnt++;
                    }
                }
            }
            r = cnt ? r / cnt : sg[p];
            const double rough = id >= 0 ? s->obj[id].rough : 0.0;
            sg[p] = rough > 0 ? fmin(fmax(fpx * tan(rough) * r, 0.5), LLK_R / 2.5) : 0.0;
        }
    }
    free(ratio);
}

void zp_spatial(const zs_scene_t *s, const zs_frame_t *f, const double *in, double *out, double *tmp)
{
    zf_guide_t g = guide_of(f);
    if (s->noisy == ZL_VIS) {
        /* 31x31 joint bilateral, its Gaussian sized by the penumbra
         * (sigma = half the PCSS width, 0.5..8 px) averaged over the
         * in-shadow pixels in reach */
        const size_t n = (size_t)f->w * f->h;
        double *pm = calloc(n * CH, sizeof(double)), *sg = calloc(n, sizeof(double));
        const zf_edges_t e = {0.05, 32, 0};
        if (!pm || !sg) {
            free(pm);
            free(sg);
            memcpy(out, in, n * CH * sizeof(double));
            return;
        }
        for (size_t p = 0; p < n; p++) {
            const double m = f->in_shadow[p] ? 1.0 : 0.0;
            pm[3 * p] = m * f->pen[p];
            pm[3 * p + 1] = pm[3 * p + 2] = m;
        }
        zf_bilateral(pm, CH, &g, &e, 15, 8.0, NULL, out, tmp);
        for (size_t p = 0; p < n; p++) {
            const double pw = out[3 * p + 1] > 1e-6 ? out[3 * p] / out[3 * p + 1] : 1.0;
            sg[p] = fmin(fmax(0.5 * pw, 0.5), 8.0);
        }
        zf_bilateral(in, CH, &g, &e, 15, 0.0, sg, out, tmp);
        free(pm);
        free(sg);
    } else if (s->noisy == ZL_GLOSSY && s->glossy_fixed) {
        const zf_edges_t e = {0.05, 32, 1};
        zf_bilateral(in, CH, &g, &e, 7, 3.0, NULL, out, tmp);
    } else if (s->noisy == ZL_GLOSSY) {
        double *sg = malloc((size_t)f->w * f->h * sizeof(double));
        if (!sg) {
            memcpy(out, in, (size_t)f->w * f->h * CH * sizeof(double));
            return;
        }
        zp_glossy_footprint(s, f, sg);
        /* the kernel lies on the reflector (world space in [LLK*19]): same
         * object and normal, no screen-depth test (along a floor seen at a
         * grazing angle the depth changes 2-3 % a row, which cut the
         * kernel's vertical reach to ~2 rows) */
        const zf_edges_t e = {0.0, 32, 1};
        zf_bilateral(in, CH, &g, &e, LLK_R, 0.0, sg, out, tmp);
        free(sg);
    } else {
        const zf_edges_t e = {0.05, 32, 0};
        zf_atrous(in, CH, &g, &e, 4, 0.0, out, tmp);
    }
}

double zp_depth_at(const zs_frame_t *f, int qx, int qy, double fx, double fy)
{
    const int w = f->w, h = f->h;
    const size_t q = (size_t)qy * w + qx;
    double d = f->depth[q];
    const double off[2] = {fx - qx, fy - qy};
    for (int a = 0; a < 2; a++) {
        const int sg = off[a] >= 0 ? 1 : -1;
        for (int side = 0; side < 2; side++) { /* toward y, else away from it (extrapolated) */
            const int s2 = side ? -sg : sg, nx = qx + (a ? 0 : s2), ny = qy + (a ? s2 : 0);
            if (nx < 0 || ny < 0 || nx >= w || ny >= h || f->id[(size_t)ny * w + nx] != f->id[q]) {
                continue;
            }
            d += (f->depth[(size_t)ny * w + nx] - f->depth[q]) * s2 * off[a];
            break;
        }
    }
    return d;
}

int zp_dual_vector(const zs_scene_t *s, int frame, const zs_frame_t *f, const zs_frame_t *pf, const zs_cam_t *cam,
                   const zs_cam_t *pc, int x, int y, double out[2])
{
    const size_t p = (size_t)y * f->w + x;
    const double yx = f->mv_trad[2 * p], yy = f->mv_trad[2 * p + 1];
    out[0] = yx;
    out[1] = yy;
    const int qx = (int)floor(yx), qy = (int)floor(yy);
    if (qx < 0 || qy < 0 || qx >= f->w || qy >= f->h) {
        return 0;
    }
    const size_t q = (size_t)qy * f->w + qx;
    const int occ = pf->id[q], me = f->id[p];
    if (occ < 0) {
        return 0; /* the previous frame saw sky there: nothing was in front */
    }
    double off[3], off0[3], pz[3], z[2];
    if (me >= 0) {
        /* occluded only if the previous frame saw something in front of this
         * point at y: a depth test, as the renderer's G-buffer lookup
         * (render/tdc_render_trace.c); an object-id test alone takes this
         * object's own silhouette pixels, whose nearest previous sample
         * fell on the wall behind, for disocclusions */
        const double *v = s->obj[me].vel; /* zs_obj_offset(frame) - zs_obj_offset(frame - 1) */
        const double *sp = f->pos + 3 * p;
        const double dp = (sp[0] - v[0] - pc->pos[0]) * pc->f[0] + (sp[1] - v[1] - pc->pos[1]) * pc->f[1] +
                          (sp[2] - v[2] - pc->pos[2]) * pc->f[2];
        const double lim = dp - (1e-3 * (1 + dp) + 0.01 * dp);
        if (pf->depth[q] >= lim || zp_depth_at(pf, qx, qy, yx - 0.5, yy - 0.5) >= lim) {
            return 0;
        }
    }
    zs_obj_offset(s, occ, frame, off);
    zs_obj_offset(s, occ, frame - 1, off0);
    for (int k = 0; k < 3; k++) {
        pz[k] = pf->pos[3 * q + k] + off[k] - off0[k];
    }
    if (!zs_project(cam, pz, 1, z)) {
        return 0;
    }
    out[0] = qx + 0.5 + (x + 0.5 - z[0]);
    out[1] = qy + 0.5 + (y + 0.5 - z[1]);
    return 1;
}

static double mean3(const double *v) { return (v[0] + v[1] + v[2]) / 3.0; }

/* Shadow vectors for every pixel: the in-shadow pixels' eq. 3
 * displacements averaged with the shadow filter's weights (Zeng §4.1:
 * "propagated (weight averaged) into the center of each filter"); pixels
 * with no in-shadow pixel in reach keep the traditional vector.  Writes
 * prev positions to mv (W*H*2) and alpha^V (eq. 4) to av. */
static void shadow_vectors(zp_state_t *st, const zs_scene_t *s, const zs_frame_t *f, const zs_frame_t *pf, double *mv, double *av)
{
    const int w = f->w, h = f->h;
    const size_t n = (size_t)w * h;
    for (size_t p = 0; p < n; p++) {
        const double m = f->in_shadow[p] ? 1.0 : 0.0;
        const int x = (int)(p % w), y = (int)(p / w);
        st->mvx[3 * p] = m * (f->mv_eff[2 * p] - (x + 0.5));
        st->mvx[3 * p + 1] = m * (f->mv_eff[2 * p + 1] - (y + 0.5));
        st->mvx[3 * p + 2] = m;
    }
    zf_guide_t g = guide_of(f);
    const zf_edges_t e = {0.05, 32, 0};
    zf_bilateral(st->mvx, CH, &g, &e, 15, 8.0, NULL, st->tmp2, st->tmp);
    for (size_t p = 0; p < n; p++) {
        const int x = (int)(p % w), y = (int)(p / w);
        const double m = st->tmp2[3 * p + 2];
        av[p] = st->alpha;
        if (m < 1e-6 || f->id[p] < 0) {
            mv[2 * p] = f->mv_trad[2 * p];
            mv[2 * p + 1] = f->mv_trad[2 * p + 1];
            continue;
        }
        mv[2 * p] = x + 0.5 + st->tmp2[3 * p] / m;
        mv[2 * p + 1] = y + 0.5 + st->tmp2[3 * p + 1] / m;
        /* eq. 4: the angle between the receiver's normal and the direction
         * from its (previous) point to the previous frame's point at x^V */
        const int qx = (int)floor(mv[2 * p]), qy = (int)floor(mv[2 * p + 1]);
        double theta = 0.0;
        if (qx >= 0 && qy >= 0 && qx < w && qy < h && pf->id[(size_t)qy * w + qx] >= 0) {
            const double *sv = pf->pos + 3 * ((size_t)qy * w + qx), *sp = f->pos + 3 * p, *nn = f->nrm + 3 * p;
            double d[3] = {sv[0] - sp[0], sv[1] - sp[1], sv[2] - sp[2]};
            double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            theta = l < 1e-9 ? 0.5 * M_PI : acos(fmax(-1.0, fmin(1.0, (d[0] * nn[0] + d[1] * nn[1] + d[2] * nn[2]) / l)));
        }
        av[p] = s->no_falloff ? st->alpha : zs_alpha_v(theta, st->alpha);
    }
}

/* Eq. 5's vectors weight-averaged with the glossy filter's kernel (the
 * reading of §4.2's "similar to the shadow motion vectors", whose
 * displacements §4.1 propagates "(weight averaged) into the center of each
 * filter"): the displacement of every glossy pixel with a vector, averaged
 * with [LLK*19]'s weights; mv holds the previous positions (W*H*2). */
static void glossy_vectors_splat(zp_state_t *st, const zs_scene_t *s, const zs_frame_t *f, double *mv)
{
    const int w = f->w, h = f->h;
    const size_t n = (size_t)w * h;
    double *sg = malloc(n * sizeof(double));
    if (!sg) {
        return; /* keep the per-pixel vectors */
    }
    zp_glossy_footprint(s, f, sg);
    for (size_t p = 0; p < n; p++) {
        const int x = (int)(p % w), y = (int)(p / w);
        const double m = f->id[p] >= 0 && s->obj[f->id[p]].ks > 0 && f->mv_eff[2 * p] > -1e8 ? 1.0 : 0.0;
        st->mvx[3 * p] = m * (f->mv_eff[2 * p] - (x + 0.5));
        st->mvx[3 * p + 1] = m * (f->mv_eff[2 * p + 1] - (y + 0.5));
        st->mvx[3 * p + 2] = m;
    }
    zf_guide_t g = guide_of(f);
    const zf_edges_t e = {0.0, 32, 1};
    zf_bilateral(st->mvx, CH, &g, &e, LLK_R, 0.0, sg, st->tmp2, st->tmp);
    for (size_t p = 0; p < n; p++) {
        const double m = st->tmp2[3 * p + 2];
        if (m > 1e-6 && f->id[p] >= 0 && s->obj[f->id[p]].ks > 0) {
            mv[2 * p] = (double)(p % w) + 0.5 + st->tmp2[3 * p] / m;
            mv[2 * p + 1] = (double)(p / w) + 0.5 + st->tmp2[3 * p + 1] / m;
        }
    }
    free(sg);
}

/* A-SVGF's temporal gradient (Schied et al. 2018, simplified to one
 * re-shaded sample per 3x3 stratum, no gradient a-trous): lambda per pixel
 * in st->lam. */
static void asvgf_gradient(zp_state_t *st, const zs_scene_t *s, int frame, const zs_frame_t *f, const zs_frame_t *pf)
{
    const int w = f->w, h = f->h, gw = (w + 2) / 3, gh = (h + 2) / 3;
    zs_cam_t cam;
    zs_camera(s, frame, w, h, &cam);
    double *g = st->mvx; /* gw x gh strata (mvx holds W*H*3 doubles) */
    for (int sy = 0; sy < gh; sy++) {
        for (int sx = 0; sx < gw; sx++) {
            const uint32_t hs = (uint32_t)(sx * 73856093u ^ sy * 19349663u ^ (uint32_t)frame * 83492791u);
            int qx = sx * 3 + (int)(hs % 3u), qy = sy * 3 + (int)((hs / 3u) % 3u);
            qx = qx < w ? qx : w - 1;
            qy = qy < h ? qy : h - 1;
            const size_t q = (size_t)qy * w + qx;
            double lam = 0;
            if (pf->id[q] >= 0) {
                double off[3], off0[3], pz[3], xy[2];
                zs_obj_offset(s, pf->id[q], frame, off);
                zs_obj_offset(s, pf->id[q], frame - 1, off0);
                for (int k = 0; k < 3; k++) {
                    pz[k] = pf->pos[3 * q + k] + off[k] - off0[k];
                }
                if (zs_project(&cam, pz, 1, xy) && xy[0] >= 0 && xy[1] >= 0 && xy[0] < w && xy[1] < h) {
                    const int px = (int)xy[0], py = (int)xy[1];
                    if (f->id[(size_t)py * w + px] == pf->id[q]) {
                        double v[3];
                        zs_sample(s, frame, w, h, px, py, st->seed, frame - 1, q, v);
                        const double a = mean3(v), b = mean3(pf->layer + 3 * q);
                        const double m = fmax(fabs(a), fabs(b));
                        lam = m > 1e-6 ? fmin(1.0, fabs(a - b) / m) : 0.0;
                    }
                }
            }
            g[(size_t)sy * gw + sx] = lam;
        }
    }
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const int sx = x / 3, sy = y / 3;
            double acc = 0;
            int cnt = 0;
            for (int j = -1; j <= 1; j++) {
                for (int i = -1; i <= 1; i++) {
                    if (sx + i >= 0 && sy + j >= 0 && sx + i < gw && sy + j < gh) {
                        acc += g[(size_t)(sy + j) * gw + sx + i];
                        cnt++;
                    }
                }
            }
            st->lam[(size_t)y * w + x] = acc / cnt;
        }
    }
}

static void svgf_step(zp_state_t *st, const zs_scene_t *s, int frame, const zs_frame_t *f, const zs_frame_t *pf)
{
    const int w = f->w, h = f->h;
    const size_t n = (size_t)w * h;
    const int adaptive = st->method == ZM_ASVGF && st->have;
    if (adaptive) {
        asvgf_gradient(st, s, frame, f, pf);
    }
    zf_guide_t g = guide_of(f);
    const zf_edges_t e = {0.05, 128, 0};
    double *col = st->filt, *m2 = st->tmp2; /* integrated colour, new moments */
    for (size_t p = 0; p < n; p++) {
        const double *c = f->layer + 3 * p;
        const double l = mean3(c);
        double hc[3], hm[2];
        int ok = 0;
        if (st->have) {
            const double *mv = f->mv_trad + 2 * p;
            ok = zf_fetch(st->hist, CH, w, h, mv[0], mv[1], pf->id, f->id[p], hc) &&
                 zf_fetch(st->mom, 2, w, h, mv[0], mv[1], pf->id, f->id[p], hm);
            if (ok) {
                int qx = (int)floor(mv[0]), qy = (int)floor(mv[1]);
                qx = qx < 0 ? 0 : (qx >= w ? w - 1 : qx);
                qy = qy < 0 ? 0 : (qy >= h ? h - 1 : qy);
                st->sig[p] = st->len[(size_t)qy * w + qx];
            }
        }
        const double len = ok ? fmin(st->sig[p] + 1.0, 255.0) : 1.0;
        const double a0 = fmax(0.2, 1.0 / len), a = adaptive ? (1 - st->lam[p]) * a0 + st->lam[p] : a0;
        for (int k = 0; k < 3; k++) {
            col[3 * p + k] = ok ? a * c[k] + (1 - a) * hc[k] : c[k];
        }
        m2[2 * p] = ok ? a * l + (1 - a) * hm[0] : l;
        m2[2 * p + 1] = ok ? a * l * l + (1 - a) * hm[1] : l * l;
        st->mvx[p] = len;
        st->rejected += !ok;
    }
    memcpy(st->len, st->mvx, n * sizeof(double));
    memcpy(st->mom, m2, n * 2 * sizeof(double));
    for (size_t p = 0; p < n; p++) {
        if (st->len[p] >= 4) {
            st->var[p] = fmax(0.0, st->mom[2 * p + 1] - st->mom[2 * p] * st->mom[2 * p]);
            continue;
        }
        /* fewer than 4 frames of history: the moments of a 7x7 neighbourhood */
        const int x = (int)(p % w), y = (int)(p / w);
        double s1 = 0, s2 = 0, ws = 0;
        for (int j = -3; j <= 3; j++) {
            for (int i = -3; i <= 3; i++) {
                int xx = x + i, yy = y + j;
                if (xx < 0 || yy < 0 || xx >= w || yy >= h) {
                    continue;
                }
                const size_t q = (size_t)yy * w + xx;
                const double l = mean3(f->layer + 3 * q);
                const double wk = (f->id[q] == f->id[p]) ? 1.0 : 0.0;
                s1 += wk * l;
                s2 += wk * l * l;
                ws += wk;
            }
        }
        s1 /= ws;
        st->var[p] = fmax(0.0, s2 / ws - s1 * s1) * 4.0 / st->len[p];
    }
    double *a = col, *b = st->out, *va = st->var, *vb = st->var2;
    for (int l = 0; l < 5; l++) {
        zf_svgf_level(a, va, CH, &g, &e, l, b, vb);
        if (l == 0) {
            memcpy(st->hist, b, n * CH * sizeof(double));
        }
        double *t = a;
        a = b;
        b = t;
        t = va;
        va = vb;
        vb = t;
    }
    if (a != st->out) {
        memcpy(st->out, a, n * CH * sizeof(double));
    }
    if (va != st->var) {
        memcpy(st->var, va, n * sizeof(double));
    }
    st->have = 1;
}

void zp_step(zp_state_t *st, const zs_scene_t *s, int frame, const zs_frame_t *f, const zs_frame_t *pf)
{
    const int w = f->w, h = f->h;
    const size_t n = (size_t)w * h;
    st->rejected = st->dual = 0;
    if (st->method == ZM_SVGF || st->method == ZM_ASVGF) {
        svgf_step(st, s, frame, f, pf);
        return;
    }
    zp_spatial(s, f, f->layer, st->filt, st->tmp);
    if (!st->have) {
        memcpy(st->hist, st->filt, n * CH * sizeof(double));
        memcpy(st->out, st->filt, n * CH * sizeof(double));
        st->have = 1;
        return;
    }
    /* vectors: previous positions (W*H*2) and alpha per pixel */
    double *mv = malloc(n * 2 * sizeof(double)), *av = malloc(n * sizeof(double));
    double *blend = st->tmp2;
    if (!mv || !av) {
        free(mv);
        free(av);
        return;
    }
    zs_cam_t cam, pcam;
    zs_camera(s, frame, w, h, &cam);
    zs_camera(s, frame - 1, w, h, &pcam);
    for (size_t p = 0; p < n; p++) {
        mv[2 * p] = f->mv_trad[2 * p];
        mv[2 * p + 1] = f->mv_trad[2 * p + 1];
        av[p] = st->alpha;
    }
    if (st->method == ZM_OURS && s->noisy == ZL_VIS) {
        shadow_vectors(st, s, f, pf, mv, av); /* uses tmp2 as scratch before the blend fills it */
    } else if ((st->method == ZM_OURS || st->method == ZM_SPEC) && s->noisy == ZL_GLOSSY) {
        const double *src = st->method == ZM_OURS ? f->mv_eff : f->mv_spec;
        for (size_t p = 0; p < n; p++) {
            if (f->id[p] >= 0 && s->obj[f->id[p]].ks > 0 && src[2 * p] > -1e8) {
                mv[2 * p] = src[2 * p];
                mv[2 * p + 1] = src[2 * p + 1];
            }
        }
        if (st->method == ZM_OURS && s->glossy_splat) {
            glossy_vectors_splat(st, s, f, mv);
        }
    } else if (st->method == ZM_OURS && s->noisy == ZL_INDIRECT) {
        for (int y = 0; y < h; y++) {
            for (int x = 0; x < w; x++) {
                st->dual += zp_dual_vector(s, frame, f, pf, &cam, &pcam, x, y, mv + 2 * ((size_t)y * w + x));
            }
        }
    }
    const double k = st->method == ZM_OURS ? st->clamp_k : 1.0;
    const int clamp = st->method != ZM_TRAD;
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const size_t p = (size_t)y * w + x;
            double hv[3], hc[3];
            /* the glossy layer exists on the glossy surface only: its
             * history never takes a tap from another object */
            const int ok = zf_fetch(st->hist, CH, w, h, mv[2 * p], mv[2 * p + 1],
                                    st->method == ZM_TRAD || s->noisy == ZL_GLOSSY ? pf->id : NULL, f->id[p], hv);
            double a = ok ? av[p] : 1.0;
            st->rejected += !ok;
            memcpy(hc, hv, sizeof hc);
            if (ok && clamp) {
                double mu[3], sd[3];
                zf_moments(st->clamp_filtered ? st->filt : f->layer, CH, w, h, x, y, st->clamp_r, mu, sd);
                for (int c = 0; c < 3; c++) {
                    hc[c] = fmin(fmax(hv[c], mu[c] - k * sd[c]), mu[c] + k * sd[c]);
                }
            }
            for (int c = 0; c < 3; c++) {
                blend[3 * p + c] = ok ? a * st->filt[3 * p + c] + (1 - a) * hc[c] : st->filt[3 * p + c];
            }
            if (st->method == ZM_OURS) {
                /* eqs. 7-8: the clean-up filter's sigma */
                const double wa = (a - st->alpha) * (a - st->alpha);
                const double h0 = mean3(hv), h1 = mean3(hc);
                const double wc = ok ? fabs(h1 - h0) / (fabs(h0) + EPS_WC) : 0.0;
                st->sig[p] = fmin(wa + wc, 5.0);
            }
        }
    }
    memcpy(st->hist, blend, n * CH * sizeof(double));
    if (st->method == ZM_OURS) {
        zf_guide_t g = guide_of(f);
        const zf_edges_t e = {0.05, 32, 0};
        zf_bilateral(blend, CH, &g, &e, 4, 0.0, st->sig, st->out, st->tmp);
    } else {
        memcpy(st->out, blend, n * CH * sizeof(double));
    }
    free(mv);
    free(av);
}
