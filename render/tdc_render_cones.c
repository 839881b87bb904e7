/*
 * tdc_render_cones.c - 6-cone incident radiance (Zeng §4.3, eqs. 9-11):
 * layout, overlap, recording, temporal reuse, re-shading.  See the header.
 */
#include "tdc_render_cones.h"

#include <math.h>

#include "tdc_render_internal.h"

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void tdc_cones_axes(const double n[3], double axes[TDC_CONES][3])
{
    double t[3], b[3];
    tdc_r_onb(n, t, b);
    for (int c = 0; c < 3; c++) axes[0][c] = n[c];
    /* sin 60, cos 60 and cos, sin of 72 k degrees */
    static const double st = 0.86602540378443865, ct = 0.5;
    static const double cp[5] = {1, 0.30901699437494742, -0.80901699437494742, -0.80901699437494742,
                                 0.30901699437494742};
    static const double sp[5] = {0, 0.95105651629515357, 0.58778525229247313, -0.58778525229247313,
                                 -0.95105651629515357};
    for (int k = 1; k < TDC_CONES; k++)
        for (int c = 0; c < 3; c++) axes[k][c] = ct * n[c] + st * (cp[k - 1] * t[c] + sp[k - 1] * b[c]);
}

double tdc_cones_overlap(double alpha, double half)
{
    if (!(alpha > 0)) return 2 * M_PI * (1 - cos(half));
    if (alpha >= 2 * half) return 0;
    /* eq. 10 with equal cones: gamma = atan((cos h - cos a cos h) / (sin a cos h)) = a / 2 */
    double ch = cos(half);
    double g = atan((ch - cos(alpha) * ch) / (sin(alpha) * ch));
    double sb = sin(g) / sin(half), tp = tan(g) / tan(half);
    double beta = acos(sb > 1 ? 1 : sb), phi = acos(tp > 1 ? 1 : tp);
    return 4 * (beta - phi * ch); /* eq. 9 */
}

int tdc_cones_record(const double axes[TDC_CONES][3], const double d[3], const double L[3],
                     double cone_L[TDC_CONES][3], double cone_w[TDC_CONES])
{
    int n = 0, best = 0;
    double bc = -2;
    for (int k = 0; k < TDC_CONES; k++) {
        double c = dot3(axes[k], d);
        if (c > bc) {
            bc = c;
            best = k;
        }
        if (c >= TDC_CONE_COS_HALF) {
            for (int i = 0; i < 3; i++) cone_L[k][i] += L[i];
            cone_w[k] += 1;
            n++;
        }
    }
    if (!n) { /* a gap near the horizon: the nearest cone */
        for (int i = 0; i < 3; i++) cone_L[best][i] += L[i];
        cone_w[best] += 1;
        n = 1;
    }
    return n;
}

/* Overlap of two pi/3 cones as a share of one cone, tabulated (the reuse
 * runs 36 pairs per pixel; the formula's transcendental calls made it ~4 s
 * per 640x360 frame) over u = sin(alpha / 2) = sqrt((1 - cos alpha) / 2),
 * in which it is smooth (linear at alpha = 0, where it is steep in cos
 * alpha): OV_N intervals of u from 0 to sin(half), linear interpolation
 * (error < 1e-4 of a cone, test). */
#define OV_N 4096
static double overlap_share(double c)
{
    static double tab[OV_N + 1], u1, c0;
    static int init;
    if (!__atomic_load_n(&init, __ATOMIC_ACQUIRE)) {
        const double half = acos(TDC_CONE_COS_HALF), full = tdc_cones_overlap(0, half);
        u1 = sin(half);
        c0 = cos(2 * half);
        for (int i = 0; i <= OV_N; i++) tab[i] = tdc_cones_overlap(2 * asin(u1 * i / OV_N), half) / full;
        __atomic_store_n(&init, 1, __ATOMIC_RELEASE);
    }
    if (c >= 1) return 1;
    if (!(c > c0)) return 0; /* most pairs: apart by more than two half-angles */
    double u = sqrt((1 - c) * 0.5);
    if (!(u < u1)) return 0;
    double x = u / u1 * OV_N;
    int i = (int)x;
    if (i >= OV_N) return 0;
    return tab[i] + (x - i) * (tab[i + 1] - tab[i]);
}

double tdc_cones_overlap_share(double cos_alpha)
{
    return overlap_share(cos_alpha);
}

void tdc_cones_reuse(const double ca[TDC_CONES][3], double cL[TDC_CONES][3], double cw[TDC_CONES],
                     const double pa[TDC_CONES][3], const double pL[TDC_CONES][3], const double pw[TDC_CONES],
                     double a)
{
    /* the same hemisphere (most pixels: the same surface): the overlaps of
     * a layout with itself, the same for every normal (the axes are one
     * layout turned by an orthonormal frame) */
    static double self[TDC_CONES][TDC_CONES];
    static int init;
    if (!__atomic_load_n(&init, __ATOMIC_ACQUIRE)) {
        const double z[3] = {0, 0, 1};
        double ax[TDC_CONES][3];
        tdc_cones_axes(z, ax);
        for (int j = 0; j < TDC_CONES; j++)
            for (int k = 0; k < TDC_CONES; k++) self[j][k] = overlap_share(dot3(ax[j], ax[k]));
        __atomic_store_n(&init, 1, __ATOMIC_RELEASE);
    }
    int same = ca[0][0] == pa[0][0] && ca[0][1] == pa[0][1] && ca[0][2] == pa[0][2];
    for (int j = 0; j < TDC_CONES; j++) {
        double hs[3] = {0, 0, 0}, hw = 0;
        for (int k = 0; k < TDC_CONES; k++) {
            if (!(pw[k] > 0)) continue;
            double om = same ? self[j][k] : overlap_share(dot3(ca[j], pa[k])); /* share of cone j */
            if (!(om > 0)) continue;
            for (int i = 0; i < 3; i++) hs[i] += om * pw[k] * pL[k][i];
            hw += om * pw[k];
        }
        double wc = a * cw[j], wh = (1 - a) * hw, wt = wc + wh;
        if (!(wt > 0)) continue;
        for (int i = 0; i < 3; i++) cL[j][i] = (wc * cL[j][i] + (1 - a) * hs[i]) / wt;
        cw[j] = wt;
    }
}

/* Cosine-weighted solid angle of each cone over the hemisphere (the five
 * ring cones reach 3.6 deg below the horizon: clipped), by a fixed
 * midpoint quadrature; the same for every normal. */
static void cone_cos_weights(double C[TDC_CONES])
{
    static double tab[TDC_CONES];
    static int init;
    if (!__atomic_load_n(&init, __ATOMIC_ACQUIRE)) {
        const double n[3] = {0, 0, 1};
        double ax[TDC_CONES][3], acc[TDC_CONES] = {0};
        tdc_cones_axes(n, ax);
        const int nt = 720, np = 1440;
        for (int i = 0; i < nt; i++) {
            double th = (i + 0.5) * (M_PI / 2) / nt, s = sin(th), c = cos(th);
            double dw = s * (M_PI / 2 / nt) * (2 * M_PI / np);
            for (int j = 0; j < np; j++) {
                double ph = (j + 0.5) * 2 * M_PI / np;
                double d[3] = {s * cos(ph), s * sin(ph), c};
                for (int k = 0; k < TDC_CONES; k++)
                    if (dot3(ax[k], d) >= TDC_CONE_COS_HALF) acc[k] += c * dw;
            }
        }
        for (int k = 0; k < TDC_CONES; k++) tab[k] = acc[k];
        __atomic_store_n(&init, 1, __ATOMIC_RELEASE);
    }
    for (int k = 0; k < TDC_CONES; k++) C[k] = tab[k];
}

void tdc_cones_shade(const double albedo[3], const double L[TDC_CONES][3], const double w[TDC_CONES],
                     double out[3])
{
    double C[TDC_CONES], s[3] = {0, 0, 0}, cs = 0;
    cone_cos_weights(C);
    for (int k = 0; k < TDC_CONES; k++) {
        if (!(w[k] > 0)) continue;
        for (int i = 0; i < 3; i++) s[i] += L[k][i] * C[k];
        cs += C[k];
    }
    for (int i = 0; i < 3; i++) out[i] = cs > 0 ? albedo[i] / M_PI * s[i] * (M_PI / cs) : 0;
}
