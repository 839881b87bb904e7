/*
 * tdc_render_indirect.c - option `indirect` (issue 16, Zeng §4.3): one
 * diffuse indirect bounce per traced sample and its 6-cone record, and with
 * `indirect_reuse` the temporal reuse of incident radiance for occlusions.
 *
 *   bounce   a cosine-weighted direction around the normal (random
 *            dimensions 30, 31 of the sample's hash: free in every mode),
 *            one ray, the hit shaded by its own direct light (shadow rays
 *            included), the sky for a miss; the Lambertian estimator is
 *            (1 - k) base L (f cos / pdf = albedo)
 *   cones    L recorded into the cones of the normal's hemisphere that
 *            contain the direction (tdc_render_cones.h)
 *   reuse    FULL frames in sequence: the previous frame's cones at the
 *            sample's dual MV (the surface MV where it was not
 *            disoccluded; the primary one under a mirror), nearest pixel,
 *            are reused cone by cone with the overlap weights of eqs.
 *            9-10 (tdc_cones_reuse, the current frame's share 0.1 as the
 *            paper's alpha) and the pixel re-shaded from its cones (eq. 11
 *            with the cosine): reusing radiance per direction instead of a
 *            colour keeps a disoccluded surface with another normal from
 *            copying the occluder's shading (Zeng Fig. 6).  The history is
 *            27 floats per pixel, two frames (216 B/px; 448 MB at
 *            1920x1080), allocated on the first frame that asks for it.
 * The indirect light goes into rgb and the `indirect` layer; the option
 * changes images only when it is on.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_render_cones.h"
#include "tdc_render_trace.h"

#define IND_ALPHA 0.1 /* the current frame's share in the reuse (Zeng §3: alpha = 0.1) */

void tdc_r_pass_indirect(rthread_t *t, rsample_t *s, int n)
{
    const tdc_render_t *r = t->r;
    const tdc_scene_t *sc = r->scene;
    for (int i = 0; i < n; i++) {
        rsample_t *a = &s[i];
        a->ind[0] = a->ind[1] = a->ind[2] = 0;
        float *cur = t->cone_cur ? &t->cone_cur[((size_t)a->py * r->W + a->px) * TDC_R_CONE_FLOATS] : NULL;
        if (cur) memset(cur, 0, TDC_R_CONE_FLOATS * sizeof *cur);
        if (a->obj < 0) continue;
        const tdc_object_t *o = &sc->objects[a->obj];
        const tdc_material_t *m = &sc->materials[o->material];
        double kd = 1 - a->mirror;
        if (m->unlit || !(kd > 0)) continue;
        /* cosine-weighted direction in the normal's tangent frame */
        double u1 = tdc_r_rand(r->cfg.seed, t->frame, tdc_r_rng_key(a), a->k, 30);
        double u2 = tdc_r_rand(r->cfg.seed, t->frame, tdc_r_rng_key(a), a->k, 31);
        double T[3], B[3];
        tdc_r_onb(a->N, T, B);
        double rr = sqrt(u1), ph = 2 * M_PI * u2, cz = sqrt(1 - u1);
        double d[3];
        for (int c = 0; c < 3; c++) d[c] = rr * cos(ph) * T[c] + rr * sin(ph) * B[c] + cz * a->N[c];
        double L[3];
        tdc_r_trace_local(t, a->P, a->N, d, a, 16u, L);
        double base[3];
        /* the primary hit's footprint, as in the shade pass */
        double fw = tdc_r_sample_fw(t, a, a->hit_t * sqrt(a->dir[0] * a->dir[0] + a->dir[1] * a->dir[1] + a->dir[2] * a->dir[2]),
                                    a->dir, a->NQ, t->cur->minv[a->obj]);
        tdc_r_base_color(r, o, a->Q, a->NQ, fw, base);
        double alb[3] = {kd * base[0], kd * base[1], kd * base[2]};
        double ind[3] = {alb[0] * L[0], alb[1] * L[1], alb[2] * L[2]};
        if (cur) {
            double ca[TDC_CONES][3], cL[TDC_CONES][3] = {{0}}, cw[TDC_CONES] = {0};
            tdc_cones_axes(a->N, ca);
            tdc_cones_record(ca, d, L, cL, cw);
            const float *prev = NULL;
            if (t->cone_prev) {
                /* the pixel's correspondence in the previous frame */
                double v0 = 0, v1 = 0;
                if (t->have_mv) {
                    int dis = t->have_dual && a->disocc;
                    v0 = dis ? a->mvd[0] : a->refl_used ? a->mvsurf[0] : a->mv[0];
                    v1 = dis ? a->mvd[1] : a->refl_used ? a->mvsurf[1] : a->mv[1];
                }
                double qx = floor(a->x + v0), qy = floor(a->y + v1);
                if (qx >= 0 && qy >= 0 && qx < r->W && qy < r->H)
                    prev = &t->cone_prev[((size_t)qy * r->W + (size_t)qx) * TDC_R_CONE_FLOATS];
            }
            if (prev) {
                double pL[TDC_CONES][3], pw[TDC_CONES], pn[3], pa[TDC_CONES][3];
                for (int k = 0; k < TDC_CONES; k++) {
                    for (int c = 0; c < 3; c++) pL[k][c] = prev[3 * k + c];
                    pw[k] = prev[18 + k];
                }
                for (int c = 0; c < 3; c++) pn[c] = prev[24 + c];
                if ((float)a->N[0] == prev[24] && (float)a->N[1] == prev[25] && (float)a->N[2] == prev[26]) {
                    tdc_cones_reuse(ca, cL, cw, ca, pL, pw, IND_ALPHA); /* the same hemisphere (stored in float) */
                } else if (pn[0] != 0 || pn[1] != 0 || pn[2] != 0) {
                    tdc_cones_axes(pn, pa);
                    tdc_cones_reuse(ca, cL, cw, pa, pL, pw, IND_ALPHA);
                }
            }
            tdc_cones_shade(alb, cL, cw, ind);
            for (int k = 0; k < TDC_CONES; k++) {
                for (int c = 0; c < 3; c++) cur[3 * k + c] = (float)cL[k][c];
                cur[18 + k] = (float)cw[k];
            }
            for (int c = 0; c < 3; c++) cur[24 + c] = (float)a->N[c];
        }
        for (int c = 0; c < 3; c++) {
            a->ind[c] = ind[c];
            a->col[c] += ind[c];
        }
    }
}
