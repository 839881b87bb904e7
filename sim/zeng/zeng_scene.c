/*
 * zeng_scene.c - analytic scenes, tracer, 1-sample layers, ground truth and
 * the motion vectors of Zeng et al. (zeng_scene.h).
 */
#include "zeng/zeng_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "zeng/zeng_rng.h"

#define EPS 1e-7

static void v_set(double o[3], double x, double y, double z)
{
    o[0] = x;
    o[1] = y;
    o[2] = z;
}
static double v_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void v_cross(const double a[3], const double b[3], double o[3])
{
    double t[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    memcpy(o, t, sizeof t);
}
static void v_norm(double a[3])
{
    double l = sqrt(v_dot(a, a));
    if (l > 0) {
        a[0] /= l;
        a[1] /= l;
        a[2] /= l;
    }
}
static void v_axpy(double o[3], const double a[3], double k, const double b[3])
{
    for (int c = 0; c < 3; c++) {
        o[c] = a[c] + k * b[c];
    }
}

static const char *const k_names[ZS_NSCENES] = {"fence", "glossy", "occlusion", "pinkroom", "lights", "apples"};

const char *zs_scene_name(int kind) { return kind >= 0 && kind < ZS_NSCENES ? k_names[kind] : "?"; }

int zs_scene_by_name(const char *name)
{
    for (int k = 0; k < ZS_NSCENES; k++) {
        if (!strcmp(name, k_names[k])) {
            return k;
        }
    }
    return -1;
}

static zs_obj_t *add(zs_scene_t *s, int type, double a0, double a1, double a2, double b0, double b1, double b2,
                     double r, double g, double b)
{
    zs_obj_t *o = &s->obj[s->nobj++];
    memset(o, 0, sizeof *o);
    o->type = type;
    v_set(o->a, a0, a1, a2);
    v_set(o->b, b0, b1, b2);
    v_set(o->albedo, r, g, b);
    memcpy(o->albedo2, o->albedo, sizeof o->albedo);
    return o;
}

static void stripes(zs_obj_t *o, double r, double g, double b, double period)
{
    v_set(o->albedo2, r, g, b);
    o->tex_scale = period;
}

/* Fig. 8's fence: nine slats 0.35 wide every 0.8 and a rail, moving 0.05
 * units a frame sideways, before a floor and a back wall. */
static void fence(zs_scene_t *s)
{
    zs_obj_t *o;
    stripes(add(s, ZS_PLANE, 0, 0, 0, 0, 1, 0, 0.75, 0.72, 0.68), 0.6, 0.6, 0.62, 0.7);
    add(s, ZS_PLANE, 0, 0, -3, 0, 0, 1, 0.6, 0.62, 0.7);
    for (int k = 0; k < 9; k++) {
        double x = -4.4 + 0.8 * k;
        o = add(s, ZS_BOX, x, 0.25, -1.05, x + 0.35, 1.3, -0.95, 0.55, 0.35, 0.2);
        v_set(o->vel, 0.05, 0, 0);
    }
    o = add(s, ZS_BOX, -4.0, 0.95, -1.1, 2.4, 1.05, -1.05, 0.5, 0.3, 0.2);
    v_set(o->vel, 0.05, 0, 0);
}

void zs_scene_init(zs_scene_t *s, int kind)
{
    memset(s, 0, sizeof *s);
    s->kind = kind;
    s->vfov = 50.0 * M_PI / 180.0;
    s->spread = 1.0;
    zs_obj_t *o;
    switch (kind) {
    case ZS_FENCE:
        /* Fig. 8: the fence (slats 0.35 wide every 0.8) moves fast (0.05
         * units a frame, ~1.7 px at 160x120; its shadow on the floor ~3 px)
         * between a 0.3 x 0.3 area light behind it and the floor in front
         * of it. */
        s->noisy = ZL_VIS;
        fence(s);
        v_set(s->cam0, 0, 1.7, 2.6);
        v_set(s->target, 0, 0, -0.6);
        v_set(s->light_c, 0, 2.2, -2.2);
        v_set(s->light_e1, 0.3, 0, 0);
        v_set(s->light_e2, 0, 0, 0.3);
        v_set(s->light_le, 420, 400, 380);
        s->ambient = 0.06;
        break;
    case ZS_LIGHTS:
        /* Fig. 10: the fence seen from higher up and to the right, under
         * three 0.3 x 0.3 lights behind it (x -1.5, 0, +1.5) moving their
         * own ways: the middle one 0.06 a frame to the left, the left one
         * 0.05 to the right, the right one 0.04 towards the fence.  Each
         * slat's three shadows move at three speeds (the fence's own 0.05
         * plus each light's parallax) and cross one another, so one pixel
         * sees several shadows moving differently (Zeng §7, "Failure due to
         * mixed information": "Another example is in Fig. 10"). */
        s->noisy = ZL_VIS;
        fence(s);
        v_set(s->cam0, 1.6, 2.5, 2.3);
        v_set(s->target, -0.2, 0, -0.9);
        v_set(s->light_c, 0, 2.2, -2.2);
        v_set(s->light_e1, 0.3, 0, 0);
        v_set(s->light_e2, 0, 0, 0.3);
        v_set(s->light_vel, -0.06, 0, 0);
        v_set(s->light_le, 170, 160, 150);
        s->nlights = 3;
        v_set(s->light_d[1], -1.5, 0, 0.1);
        v_set(s->light_dv[1], 0.11, 0, 0); /* +0.05 a frame */
        v_set(s->light_d[2], 1.5, -0.1, -0.1);
        v_set(s->light_dv[2], 0.06, 0, 0.04); /* (0, 0, +0.04) a frame */
        s->ambient = 0.06;
        break;
    case ZS_APPLES:
        /* Fig. 9: "the Apples scene with highly curved apples and cloth on
         * the desk, and a rapidly moving area light on the right": a desk
         * (the floor plane) under a cloth whose folds are three low domes
         * (large spheres sunk into the desk, 0.12-0.18 high), five apples
         * (spheres r 0.13-0.18, two rolling 0.02 a frame) on and between
         * the folds, a back wall, and a 0.4 x 0.4 light 1.1 up at the right
         * sweeping 0.1 units a frame from back to front.  Every shadow but
         * the wall's falls on a curved receiver or across one. */
        s->noisy = ZL_VIS;
        add(s, ZS_PLANE, 0, 0, 0, 0, 1, 0, 0.55, 0.38, 0.25); /* desk */
        add(s, ZS_PLANE, 0, 0, -2.2, 0, 0, 1, 0.7, 0.7, 0.68);
        add(s, ZS_SPHERE, -0.5, -0.52, -0.8, 0.7, 0, 0, 0.85, 0.85, 0.9); /* cloth folds */
        add(s, ZS_SPHERE, 0.35, -0.48, -1.1, 0.6, 0, 0, 0.85, 0.85, 0.9);
        add(s, ZS_SPHERE, 0.1, -0.62, -0.1, 0.75, 0, 0, 0.85, 0.85, 0.9);
        add(s, ZS_SPHERE, -0.55, 0.34, -0.8, 0.16, 0, 0, 0.8, 0.1, 0.08); /* apples */
        add(s, ZS_SPHERE, 0.35, 0.28, -1.1, 0.16, 0, 0, 0.45, 0.75, 0.15);
        add(s, ZS_SPHERE, 0.15, 0.26, -0.15, 0.13, 0, 0, 0.85, 0.2, 0.1);
        o = add(s, ZS_SPHERE, -1.2, 0.18, -0.2, 0.18, 0, 0, 0.75, 0.6, 0.1);
        v_set(o->vel, 0.02, 0, 0);
        o = add(s, ZS_SPHERE, 0.9, 0.15, -0.45, 0.15, 0, 0, 0.8, 0.15, 0.12);
        v_set(o->vel, -0.02, 0, 0);
        v_set(s->cam0, -0.2, 1.3, 1.6);
        v_set(s->target, 0.0, 0.15, -0.6);
        v_set(s->light_c, 1.6, 1.1, -1.8);
        v_set(s->light_e1, 0.4, 0, 0);
        v_set(s->light_e2, 0, 0, 0.4);
        v_set(s->light_vel, 0, 0, 0.1);
        v_set(s->light_le, 40, 38, 36);
        s->ambient = 0.06;
        break;
    case ZS_GLOSSY:
        /* Fig. 11: a static scene over a glossy floor, the camera translating
         * fast sideways (0.06 units a frame, the floor's reflections move
         * against the floor by several pixels a frame). */
        s->noisy = ZL_GLOSSY;
        o = add(s, ZS_PLANE, 0, 0, 0, 0, 1, 0, 0.06, 0.06, 0.07);
        o->ks = 0.8;
        o->rough = 0.08;
        stripes(add(s, ZS_PLANE, 0, 0, -4, 0, 0, 1, 0.7, 0.7, 0.75), 0.3, 0.3, 0.35, 0.5);
        stripes(add(s, ZS_BOX, -1.15, 0, -1.75, -0.65, 0.8, -1.25, 0.9, 0.15, 0.1), 0.95, 0.9, 0.85, 0.2);
        add(s, ZS_SPHERE, 0.4, 0.35, -1.0, 0.35, 0, 0, 0.15, 0.8, 0.2);
        add(s, ZS_SPHERE, 1.3, 0.5, -2.3, 0.5, 0, 0, 0.15, 0.3, 0.95);
        stripes(add(s, ZS_BOX, 0.0, 0, -3.1, 0.45, 1.5, -2.65, 0.95, 0.85, 0.1), 0.2, 0.2, 0.2, 0.25);
        v_set(s->cam0, -1.2, 0.9, 2.0);
        v_set(s->cam_vel, 0.1, 0.03, 0);
        v_set(s->target, -0.3, 0.3, -1.5);
        v_set(s->target_vel, 0.1, 0, 0);
        v_set(s->light_c, 0, 3.0, 1.0);
        v_set(s->light_e1, 0.3, 0, 0);
        v_set(s->light_e2, 0, 0, 0.3);
        v_set(s->light_le, 300, 300, 300);
        s->ambient = 0.15;
        break;
    case ZS_PINKROOM:
        /* Fig. 1 left (the pink room) with Fig. 9's "rapidly moving area
         * light": pink floor and walls meeting in two corners, a table on
         * four legs, a stool, a shelf by the left wall, a sphere half
         * under the table's edge and a rolling one, a 0.5 x 0.5 light 2.3
         * above the floor sweeping 0.08 units a frame.  The shadows bend over the corners and wrap onto the
         * spheres, where eq. 3's locally flat receiver fails and eq. 4's
         * cosine falloff must catch it (Zeng §6: "even when the locally flat
         * plane assumption is violated"). */
        s->noisy = ZL_VIS;
        add(s, ZS_PLANE, 0, 0, 0, 0, 1, 0, 0.8, 0.5, 0.55);
        add(s, ZS_PLANE, 0, 0, -2.4, 0, 0, 1, 0.85, 0.55, 0.62);
        add(s, ZS_PLANE, -2.3, 0, 0, 1, 0, 0, 0.82, 0.48, 0.6);
        add(s, ZS_BOX, -1.3, 0.72, -1.6, 0.1, 0.8, -0.8, 0.75, 0.7, 0.72); /* table top */
        for (int k = 0; k < 4; k++) {
            const double x = k & 1 ? 0.0 : -1.25, z = k & 2 ? -0.9 : -1.55;
            add(s, ZS_BOX, x, 0, z, x + 0.06, 0.72, z + 0.06, 0.75, 0.7, 0.72);
        }
        add(s, ZS_BOX, 0.7, 0, -0.4, 1.15, 0.45, 0.05, 0.55, 0.75, 0.8);   /* stool */
        add(s, ZS_BOX, -2.05, 0, -1.3, -1.8, 1.5, -0.9, 0.6, 0.45, 0.4);  /* shelf by the left wall */
        add(s, ZS_SPHERE, 0.42, 0.33, -1.25, 0.33, 0, 0, 0.9, 0.85, 0.6); /* half under the table's edge */
        o = add(s, ZS_SPHERE, -1.5, 0.22, -0.2, 0.22, 0, 0, 0.35, 0.5, 0.9);
        v_set(o->vel, 0.04, 0, 0);
        v_set(s->cam0, 0.9, 1.55, 2.4);
        v_set(s->target, -0.6, 0.45, -1.2);
        v_set(s->light_c, 1.3, 2.3, 0.0);
        v_set(s->light_e1, 0.5, 0, 0);
        v_set(s->light_e2, 0, 0, 0.5);
        v_set(s->light_vel, -0.08, 0, 0);
        v_set(s->light_le, 70, 66, 64);
        s->ambient = 0.06;
        break;
    default:
        /* Figs. 1 right / 12: objects moving left to right in front of a
         * striped wall, still camera; only the indirect light is shown. */
        s->kind = ZS_OCCLUSION;
        s->noisy = ZL_INDIRECT;
        stripes(add(s, ZS_PLANE, 0, 0, -2, 0, 0, 1, 0.85, 0.8, 0.7), 0.55, 0.65, 0.85, 0.6);
        add(s, ZS_PLANE, 0, 0, 0, 0, 1, 0, 0.6, 0.6, 0.6);
        o = add(s, ZS_BOX, -2.2, 0, -1.3, -1.5, 1.0, -0.7, 0.8, 0.25, 0.2);
        v_set(o->vel, 0.05, 0, 0);
        o = add(s, ZS_BOX, -0.6, 0, -0.6, -0.15, 0.55, -0.15, 0.2, 0.6, 0.85);
        v_set(o->vel, 0.035, 0, 0);
        o = add(s, ZS_SPHERE, -1.2, 1.45, -1.2, 0.3, 0, 0, 0.9, 0.85, 0.2);
        v_set(o->vel, 0.06, 0, 0);
        v_set(s->cam0, 0, 1.0, 2.4);
        v_set(s->target, 0, 0.6, -1.0);
        v_set(s->light_c, 0, 3.0, 1.0);
        v_set(s->light_e1, 0.3, 0, 0);
        v_set(s->light_e2, 0, 0, 0.3);
        s->ambient = 0;
        break;
    }
}

void zs_obj_offset(const zs_scene_t *s, int id, int frame, double off[3])
{
    for (int c = 0; c < 3; c++) {
        off[c] = id >= 0 ? s->obj[id].vel[c] * frame : 0.0;
    }
}

void zs_light_offset(const zs_scene_t *s, int frame, double off[3])
{
    for (int c = 0; c < 3; c++) {
        off[c] = s->light_vel[c] * frame;
    }
}

int zs_nlights(const zs_scene_t *s) { return s->nlights > 1 ? s->nlights : 1; }

void zs_light_k_offset(const zs_scene_t *s, int k, int frame, double off[3])
{
    for (int c = 0; c < 3; c++) {
        off[c] = k == 0 ? s->light_vel[c] * frame : s->light_d[k][c] + (s->light_vel[c] + s->light_dv[k][c]) * frame;
    }
}

void zs_camera(const zs_scene_t *s, int frame, int w, int h, zs_cam_t *c)
{
    double t[3];
    v_axpy(c->pos, s->cam0, frame, s->cam_vel);
    v_axpy(t, s->target, frame, s->target_vel);
    for (int k = 0; k < 3; k++) {
        c->f[k] = t[k] - c->pos[k];
    }
    v_norm(c->f);
    const double up[3] = {0, 1, 0};
    v_cross(c->f, up, c->r);
    v_norm(c->r);
    v_cross(c->r, c->f, c->u);
    c->fpx = 0.5 * h / tan(0.5 * s->vfov);
    c->w = w;
    c->h = h;
}

int zs_project(const zs_cam_t *c, const double p[3], int w, double xy[2])
{
    double d[3];
    for (int k = 0; k < 3; k++) {
        d[k] = w ? p[k] - c->pos[k] : p[k];
    }
    double z = v_dot(d, c->f);
    if (z <= 1e-9) {
        return 0;
    }
    xy[0] = 0.5 * c->w + c->fpx * v_dot(d, c->r) / z;
    xy[1] = 0.5 * c->h - c->fpx * v_dot(d, c->u) / z;
    return 1;
}

static void cam_ray(const zs_cam_t *c, double px, double py, double d[3])
{
    for (int k = 0; k < 3; k++) {
        d[k] = c->fpx * c->f[k] + (px - 0.5 * c->w) * c->r[k] - (py - 0.5 * c->h) * c->u[k];
    }
    v_norm(d);
}

double zs_intersect(const zs_scene_t *s, int frame, const double o[3], const double d[3], double tmax, int *id,
                    double n[3])
{
    double best = tmax;
    int bid = -1;
    double bn[3] = {0, 0, 0};
    for (int i = 0; i < s->nobj; i++) {
        const zs_obj_t *ob = &s->obj[i];
        double off[3];
        zs_obj_offset(s, i, frame, off);
        if (ob->type == ZS_PLANE) {
            double q[3] = {ob->a[0] + off[0], ob->a[1] + off[1], ob->a[2] + off[2]};
            double dn = v_dot(d, ob->b);
            if (fabs(dn) < 1e-12) {
                continue;
            }
            double t = (v_dot(q, ob->b) - v_dot(o, ob->b)) / dn;
            if (t > EPS && t < best) {
                best = t;
                bid = i;
                memcpy(bn, ob->b, sizeof bn);
            }
        } else if (ob->type == ZS_BOX) {
            double t0 = EPS, t1 = best;
            int ax = -1;
            double sg = 0;
            int hit = 1;
            for (int k = 0; k < 3 && hit; k++) {
                double lo = ob->a[k] + off[k] - o[k], hi = ob->b[k] + off[k] - o[k];
                if (fabs(d[k]) < 1e-15) {
                    hit = lo <= 0 && hi >= 0;
                    continue;
                }
                double ta = lo / d[k], tb = hi / d[k];
                double sa = -1;
                if (ta > tb) {
                    double x = ta;
                    ta = tb;
                    tb = x;
                    sa = 1;
                }
                if (ta > t0) {
                    t0 = ta;
                    ax = k;
                    sg = sa;
                }
                if (tb < t1) {
                    t1 = tb;
                }
                hit = t0 <= t1;
            }
            if (hit && ax >= 0 && t0 < best) {
                best = t0;
                bid = i;
                v_set(bn, 0, 0, 0);
                bn[ax] = sg;
            }
        } else {
            double cpos[3] = {ob->a[0] + off[0] - o[0], ob->a[1] + off[1] - o[1], ob->a[2] + off[2] - o[2]};
            double bq = v_dot(cpos, d), cq = v_dot(cpos, cpos) - ob->b[0] * ob->b[0];
            double disc = bq * bq - cq;
            if (disc < 0) {
                continue;
            }
            double sq = sqrt(disc), t = bq - sq;
            if (t <= EPS) {
                t = bq + sq;
            }
            if (t > EPS && t < best) {
                best = t;
                bid = i;
                for (int k = 0; k < 3; k++) {
                    bn[k] = (o[k] + t * d[k] - ob->a[k] - off[k]) / ob->b[0];
                }
            }
        }
    }
    *id = bid;
    if (n) {
        memcpy(n, bn, sizeof bn);
    }
    return bid >= 0 ? best : INFINITY;
}

static void albedo_at(const zs_scene_t *s, int id, int frame, const double p[3], double out[3])
{
    const zs_obj_t *ob = &s->obj[id];
    if (ob->tex_scale > 0) {
        double off[3];
        zs_obj_offset(s, id, frame, off);
        double u = (p[0] - off[0] + p[2] - off[2] + p[1] - off[1]) / ob->tex_scale;
        const double *a = (u - floor(u)) < 0.5 ? ob->albedo : ob->albedo2;
        memcpy(out, a, 3 * sizeof(double));
    } else {
        memcpy(out, ob->albedo, 3 * sizeof(double));
    }
}

static void sky(const double d[3], double out[3])
{
    const double sun[3] = {-0.45, 0.7, 0.55};
    double sl = 1.0 / sqrt(v_dot(sun, sun));
    double sd = fmax(0.0, v_dot(d, sun) * sl);
    double sp = pow(sd, 8.0);
    if (d[1] < 0) {
        v_set(out, 0.3, 0.26, 0.22);
        return;
    }
    double t = d[1];
    out[0] = (1 - t) * 1.0 + t * 0.35 + 2.0 * sp;
    out[1] = (1 - t) * 0.85 + t * 0.55 + 1.8 * sp;
    out[2] = (1 - t) * 0.7 + t * 1.0 + 1.5 * sp;
}

/* Unshadowed direct light from light k's centre, per unit albedo: Le A
 * cos_s cos_l / (pi d^2). */
static double direct_k(const zs_scene_t *s, int frame, int lk, const double p[3], const double n[3])
{
    double loff[3], lc[3], ln[3], l[3];
    zs_light_k_offset(s, lk, frame, loff);
    v_axpy(lc, s->light_c, 1.0, loff);
    v_cross(s->light_e1, s->light_e2, ln);
    double area = sqrt(v_dot(ln, ln));
    v_norm(ln);
    for (int k = 0; k < 3; k++) {
        l[k] = lc[k] - p[k];
    }
    double d2 = v_dot(l, l);
    v_norm(l);
    double cs = v_dot(n, l), cl = -v_dot(ln, l);
    if (cs <= 0 || cl <= 0) {
        return 0;
    }
    return area * cs * cl / (M_PI * d2);
}

/* The shading layer: the lights' unshadowed direct light summed. */
static double direct(const zs_scene_t *s, int frame, const double p[3], const double n[3])
{
    double e = 0.0;
    for (int k = 0; k < zs_nlights(s); k++) {
        e += direct_k(s, frame, k, p, n);
    }
    return e;
}

/* Radiance leaving a surface point towards the viewer (the glossy layer's
 * reflected objects): its unshadowed diffuse light plus ambient. */
static void radiance(const zs_scene_t *s, int frame, int id, const double p[3], const double n[3], double out[3])
{
    double a[3];
    albedo_at(s, id, frame, p, a);
    double e = direct(s, frame, p, n);
    for (int k = 0; k < 3; k++) {
        out[k] = a[k] * (e * s->light_le[k] + s->ambient);
    }
}

static void light_point(const zs_scene_t *s, int frame, int lk, double u, double v, double out[3])
{
    double off[3];
    zs_light_k_offset(s, lk, frame, off);
    for (int k = 0; k < 3; k++) {
        out[k] = s->light_c[k] + off[k] + (u - 0.5) * s->light_e1[k] + (v - 0.5) * s->light_e2[k];
    }
}

static void basis(const double n[3], double t1[3], double t2[3])
{
    double a[3] = {1, 0, 0};
    if (fabs(n[0]) > 0.9) {
        v_set(a, 0, 1, 0);
    }
    v_cross(n, a, t1);
    v_norm(t1);
    v_cross(n, t1, t2);
}

/* A lobe direction around the mirror direction r from two uniforms. */
static void lobe_dir(const double r[3], double rough, double u, double v, double out[3], double g[2])
{
    double t1[3], t2[3];
    basis(r, t1, t2);
    double rad = sqrt(-2.0 * log(fmax(u, 1e-300)));
    g[0] = rad * cos(2 * M_PI * v);
    g[1] = rad * sin(2 * M_PI * v);
    for (int k = 0; k < 3; k++) {
        out[k] = r[k] + rough * (g[0] * t1[k] + g[1] * t2[k]);
    }
    v_norm(out);
}

static void cos_dir(const double n[3], double u, double v, double out[3])
{
    double t1[3], t2[3];
    basis(n, t1, t2);
    double r = sqrt(u), ph = 2 * M_PI * v, z = sqrt(fmax(0.0, 1 - u));
    for (int k = 0; k < 3; k++) {
        out[k] = r * cos(ph) * t1[k] + r * sin(ph) * t2[k] + z * n[k];
    }
}

static void offset_origin(double o[3], const double p[3], const double n[3])
{
    v_axpy(o, p, 1e-6, n);
}

double zs_light_vis(const zs_scene_t *s, int frame, int lk, const double p[3], const double n[3], double u, double v,
                    double lp[3], double bpt[3], int *bid)
{
    double o[3], d[3];
    light_point(s, frame, lk, u, v, lp);
    offset_origin(o, p, n);
    for (int k = 0; k < 3; k++) {
        d[k] = lp[k] - o[k];
    }
    double dist = sqrt(v_dot(d, d));
    v_norm(d);
    int id;
    double t = zs_intersect(s, frame, o, d, dist - 1e-6, &id, NULL);
    if (id >= 0) {
        v_axpy(bpt, o, t, d);
        *bid = id;
        return 0.0;
    }
    *bid = -1;
    return 1.0;
}

/* One visibility sample from p: u picks light *lk in proportion to its
 * unshadowed light at p (the visibility layer's weights, so that shade *
 * E[V] is the shadowed light summed over the lights) and, rescaled, with v
 * the point on it. */
static double vis_sample(const zs_scene_t *s, int frame, const double p[3], const double n[3], double u, double v,
                         double lp[3], double bpt[3], int *bid, int *lk)
{
    int k = 0;
    const int nl = zs_nlights(s);
    if (nl > 1) {
        double wk[ZS_MAX_LIGHTS], tot = 0;
        for (int q = 0; q < nl; q++) {
            tot += wk[q] = direct_k(s, frame, q, p, n);
        }
        if (tot > 0) {
            double t = u * tot;
            while (k < nl - 1 && (wk[k] <= 0 || t >= wk[k])) {
                t -= wk[k];
                k++;
            }
            while (wk[k] <= 0) { /* rounding ran past the last lit light */
                k--;
            }
            u = fmin(fmax(t / wk[k], 0.0), 0.999999999);
        } else {
            k = (int)(u * nl);
            u = u * nl - k;
        }
    }
    *lk = k;
    return zs_light_vis(s, frame, k, p, n, u, v, lp, bpt, bid);
}

static void glossy_sample(const zs_scene_t *s, int frame, const double p[3], const double n[3], const double vd[3],
                          const zs_obj_t *ob, double u, double v, double out[3], double hit[3], int *hid,
                          double dir[3])
{
    double r[3], g[2], o[3], hn[3];
    v_axpy(r, vd, -2.0 * v_dot(vd, n), n);
    lobe_dir(r, ob->rough, u, v, dir, g);
    if (v_dot(dir, n) <= 0) {
        v_set(out, 0, 0, 0);
        *hid = -2;
        return;
    }
    offset_origin(o, p, n);
    double t = zs_intersect(s, frame, o, dir, INFINITY, hid, hn);
    if (*hid >= 0) {
        v_axpy(hit, o, t, dir);
        radiance(s, frame, *hid, hit, hn, out);
    } else {
        sky(dir, out);
    }
    for (int k = 0; k < 3; k++) {
        out[k] *= ob->ks;
    }
}

/* Incoming radiance along one cosine-weighted direction (the demodulated
 * indirect layer's estimator: irradiance / pi). */
static void indirect_sample(const zs_scene_t *s, int frame, const double p[3], const double n[3], double u, double v,
                            double out[3])
{
    double d[3], o[3], hn[3];
    cos_dir(n, u, v, d);
    offset_origin(o, p, n);
    int id;
    double t = zs_intersect(s, frame, o, d, INFINITY, &id, hn);
    if (id < 0) {
        sky(d, out);
        return;
    }
    double hp[3], a[3];
    v_axpy(hp, o, t, d);
    albedo_at(s, id, frame, hp, a);
    /* one diffuse bounce under the sky's mean radiance (~0.6) */
    for (int k = 0; k < 3; k++) {
        out[k] = 0.6 * a[k] * (0.5 + 0.5 * hn[1]);
    }
}

int zs_frame_alloc(zs_frame_t *f, int w, int h)
{
    memset(f, 0, sizeof *f);
    f->w = w;
    f->h = h;
    size_t n = (size_t)w * h;
    f->id = malloc(n * sizeof(int));
    f->pos = malloc(n * 3 * sizeof(double));
    f->nrm = malloc(n * 3 * sizeof(double));
    f->alb = malloc(n * 3 * sizeof(double));
    f->depth = malloc(n * sizeof(double));
    f->shade = malloc(n * 3 * sizeof(double));
    f->layer = malloc(n * 3 * sizeof(double));
    f->mv_trad = malloc(n * 2 * sizeof(double));
    f->mv_eff = malloc(n * 2 * sizeof(double));
    f->mv_spec = malloc(n * 2 * sizeof(double));
    f->in_shadow = malloc(n);
    f->pen = calloc(n, sizeof(double));
    f->hitd = malloc(n * sizeof(double));
    if (!f->hitd || !f->id || !f->pos || !f->nrm || !f->alb || !f->depth || !f->shade || !f->layer || !f->mv_trad || !f->mv_eff ||
        !f->mv_spec || !f->in_shadow || !f->pen) {
        zs_frame_free(f);
        return -1;
    }
    return 0;
}

void zs_frame_free(zs_frame_t *f)
{
    free(f->id);
    free(f->pos);
    free(f->nrm);
    free(f->alb);
    free(f->depth);
    free(f->shade);
    free(f->layer);
    free(f->mv_trad);
    free(f->mv_eff);
    free(f->mv_spec);
    free(f->in_shadow);
    free(f->pen);
    free(f->hitd);
    memset(f, 0, sizeof *f);
}

int zs_shadow_prev(const double l[3], const double dl[3], const double b[3], const double db[3], const double s[3],
                   const double ds[3], const double n[3], double out[3])
{
    double lp[3], bp[3], sp[3], d[3];
    for (int k = 0; k < 3; k++) {
        lp[k] = l[k] - dl[k];
        bp[k] = b[k] - db[k];
        sp[k] = s[k] - ds[k];
        d[k] = bp[k] - lp[k];
    }
    double dn = v_dot(d, n);
    if (fabs(dn) < 1e-12) {
        return 0;
    }
    double t = (v_dot(sp, n) - v_dot(lp, n)) / dn;
    v_axpy(out, lp, t, d);
    return 1;
}

double zs_alpha_v(double theta, double alpha)
{
    double x = theta - 0.5 * M_PI;
    return 1.0 - exp(-x * x / (2 * 0.1 * 0.1)) * (1.0 - alpha);
}

void zs_mirror(const double p[3], const double q[3], const double n[3], double out[3])
{
    double d = v_dot(p, n) - v_dot(q, n);
    v_axpy(out, p, -2.0 * d, n);
}

/* Eq. 5: the previous-frame pixel of a lobe hit h (object hid, -1 sky
 * along dir) seen in the plane (point p, normal n) of object id, spread by
 * the lobe (sigma rough) when g != NULL. */
static void virtual_image_mv(const zs_scene_t *s, int frame, const zs_cam_t *pc, int id, const double p[3],
                             const double n[3], int hid, const double h[3], const double dir[3], double rough,
                             const double g[2], double out[2])
{
    double dp[3], q[3];
    zs_obj_offset(s, id, frame, dp);
    double dp0[3];
    zs_obj_offset(s, id, frame - 1, dp0);
    for (int k = 0; k < 3; k++) {
        q[k] = p[k] - (dp[k] - dp0[k]);
    }
    if (hid < 0) {
        double dv[3];
        v_axpy(dv, dir, -2.0 * v_dot(dir, n), n);
        if (!zs_project(pc, dv, 0, out)) {
            out[0] = out[1] = -1e9;
        }
        return;
    }
    double dh[3], dh0[3], hp[3], hv[3];
    zs_obj_offset(s, hid, frame, dh);
    zs_obj_offset(s, hid, frame - 1, dh0);
    for (int k = 0; k < 3; k++) {
        hp[k] = h[k] - (dh[k] - dh0[k]);
    }
    zs_mirror(hp, q, n, hv);
    double mu[2];
    if (!zs_project(pc, hv, 1, mu)) {
        out[0] = out[1] = -1e9;
        return;
    }
    out[0] = mu[0];
    out[1] = mu[1];
    if (!g) {
        return;
    }
    /* s^C: where the line camera -> virtual image meets the plane; the lobe
     * from hv towards s^C, perturbed by sigma along two axes, meets the
     * plane at the ends of the footprint's axes (paper: "tracking the
     * endpoints of major and minor axes"). */
    double cd[3], sc[3];
    for (int k = 0; k < 3; k++) {
        cd[k] = hv[k] - pc->pos[k];
    }
    double den = v_dot(cd, n);
    if (fabs(den) < 1e-12) {
        return;
    }
    double t = (v_dot(q, n) - v_dot(pc->pos, n)) / den;
    v_axpy(sc, pc->pos, t, cd);
    double d0[3], t1[3], t2[3];
    for (int k = 0; k < 3; k++) {
        d0[k] = sc[k] - hv[k];
    }
    v_norm(d0);
    basis(d0, t1, t2);
    const double *ax[2] = {t1, t2};
    for (int a = 0; a < 2; a++) {
        double dd[3], e[3], xy[2];
        v_axpy(dd, d0, rough, ax[a]);
        double dn = v_dot(dd, n);
        if (fabs(dn) < 1e-12) {
            continue;
        }
        double te = (v_dot(q, n) - v_dot(hv, n)) / dn;
        v_axpy(e, hv, te, dd);
        if (zs_project(pc, e, 1, xy)) {
            out[0] += g[a] * (xy[0] - mu[0]);
            out[1] += g[a] * (xy[1] - mu[1]);
        }
    }
}

/* The primary ray through pixel (x, y)'s centre: its direction d, and when
 * it hits (the object's id returned, else -1) the point p and the normal n
 * turned towards the viewer. */
static int primary_hit(const zs_scene_t *s, int frame, const zs_cam_t *c, int x, int y, double d[3], double p[3],
                       double n[3])
{
    int id;
    cam_ray(c, x + 0.5, y + 0.5, d);
    const double t = zs_intersect(s, frame, c->pos, d, INFINITY, &id, n);
    if (id < 0) {
        return -1;
    }
    v_axpy(p, c->pos, t, d);
    if (v_dot(n, d) > 0) {
        for (int k = 0; k < 3; k++) {
            n[k] = -n[k];
        }
    }
    return id;
}

/* One sample of the scene's noisy layer at a primary hit (id, p, n, view
 * direction d) from the uniforms (u, v); the value a miss (id < 0) or a
 * surface without the layer shows. */
static void layer_sample(const zs_scene_t *s, int frame, int id, const double p[3], const double n[3],
                         const double d[3], double u, double v, double out[3])
{
    if (id < 0) {
        const double one = s->noisy == ZL_GLOSSY ? 0.0 : 1.0;
        v_set(out, one, one, one);
    } else if (s->noisy == ZL_VIS) {
        double lp[3], bp[3];
        int bid, lk;
        const double vis = vis_sample(s, frame, p, n, u, v, lp, bp, &bid, &lk);
        v_set(out, vis, vis, vis);
    } else if (s->noisy == ZL_GLOSSY) {
        v_set(out, 0, 0, 0);
        if (s->obj[id].ks > 0) {
            double hit[3], dir[3];
            int hid;
            glossy_sample(s, frame, p, n, d, &s->obj[id], u, v, out, hit, &hid, dir);
        }
    } else {
        indirect_sample(s, frame, p, n, u, v, out);
    }
}

void zs_render(const zs_scene_t *s, int frame, uint64_t seed, zs_frame_t *f)
{
    const int w = f->w, h = f->h;
    zs_cam_t c, pc;
    zs_camera(s, frame, w, h, &c);
    zs_camera(s, frame - 1, w, h, &pc);
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const size_t i = (size_t)y * w + x;
            double d[3], n[3];
            double *p = f->pos + 3 * i, *lay = f->layer + 3 * i;
            const int id = primary_hit(s, frame, &c, x, y, d, p, n);
            f->id[i] = id;
            f->in_shadow[i] = 0;
            v_set(lay, 0, 0, 0);
            f->hitd[i] = INFINITY;
            f->mv_eff[2 * i] = f->mv_spec[2 * i] = -1e9;
            f->mv_eff[2 * i + 1] = f->mv_spec[2 * i + 1] = -1e9;
            if (id < 0) {
                v_axpy(p, c.pos, 1e6, d);
                v_set(f->nrm + 3 * i, 0, 0, 0);
                sky(d, f->alb + 3 * i);
                v_set(f->shade + 3 * i, 0, 0, 0);
                f->depth[i] = 1e6;
                if (!zs_project(&pc, d, 0, f->mv_trad + 2 * i)) {
                    f->mv_trad[2 * i] = f->mv_trad[2 * i + 1] = -1e9;
                }
                if (s->noisy == ZL_INDIRECT || s->noisy == ZL_VIS) {
                    v_set(lay, 1, 1, 1);
                }
                continue;
            }
            memcpy(f->nrm + 3 * i, n, sizeof n);
            albedo_at(s, id, frame, p, f->alb + 3 * i);
            f->depth[i] = (v_dot(p, c.f) - v_dot(c.pos, c.f));
            const zs_obj_t *ob = &s->obj[id];
            double e = direct(s, frame, p, n);
            for (int k = 0; k < 3; k++) {
                f->shade[3 * i + k] = (1.0 - ob->ks) * f->alb[3 * i + k] * (e * s->light_le[k] + s->ambient);
            }
            /* eq. 1: the surface's own previous position */
            double pp[3], off[3], off0[3];
            zs_obj_offset(s, id, frame, off);
            zs_obj_offset(s, id, frame - 1, off0);
            for (int k = 0; k < 3; k++) {
                pp[k] = p[k] - (off[k] - off0[k]);
            }
            if (!zs_project(&pc, pp, 1, f->mv_trad + 2 * i)) {
                f->mv_trad[2 * i] = f->mv_trad[2 * i + 1] = -1e9;
            }
            const uint64_t key = zr_key(seed, (uint64_t)frame, i);
            const double u = zr_u01(key, 0), v = zr_u01(key, 1);
            if (s->noisy == ZL_VIS) {
                double lp[3], bp[3];
                int bid, lk;
                double vis = vis_sample(s, frame, p, n, u, v, lp, bp, &bid, &lk);
                v_set(lay, vis, vis, vis);
                if (bid >= 0) {
                    /* eq. 3, with the sampled light's own motion (§4.1:
                     * "for each light sample, we compute its motion
                     * vector") */
                    double dl[3], dl0[3], db[3], db0[3], sp[3];
                    zs_light_k_offset(s, lk, frame, dl);
                    zs_light_k_offset(s, lk, frame - 1, dl0);
                    zs_obj_offset(s, bid, frame, db);
                    zs_obj_offset(s, bid, frame - 1, db0);
                    for (int k = 0; k < 3; k++) {
                        dl[k] -= dl0[k];
                        db[k] -= db0[k];
                        off[k] -= off0[k];
                    }
                    if (zs_shadow_prev(lp, dl, bp, db, p, off, n, sp) && zs_project(&pc, sp, 1, f->mv_eff + 2 * i)) {
                        f->in_shadow[i] = 1;
                        /* PCSS (Fernando 2005): penumbra = light size x
                         * receiver-blocker / blocker-light distance, in
                         * pixels at this depth (the shadow filter's size,
                         * Zeng §4.1 after [HA19]) */
                        double rb = 0, bl = 0;
                        for (int q = 0; q < 3; q++) {
                            rb += (bp[q] - p[q]) * (bp[q] - p[q]);
                            bl += (lp[q] - bp[q]) * (lp[q] - bp[q]);
                        }
                        const double ls = sqrt(v_dot(s->light_e1, s->light_e1));
                        f->pen[i] = ls * sqrt(rb / bl) * c.fpx / f->depth[i];
                    }
                }
            } else if (s->noisy == ZL_GLOSSY && ob->ks > 0) {
                double hit[3], dir[3], g[2];
                int hid;
                glossy_sample(s, frame, p, n, d, ob, u, v, lay, hit, &hid, dir);
                if (hid >= 0) {
                    f->hitd[i] = sqrt((hit[0] - p[0]) * (hit[0] - p[0]) + (hit[1] - p[1]) * (hit[1] - p[1]) +
                                      (hit[2] - p[2]) * (hit[2] - p[2]));
                }
                if (hid != -2) {
                    g[0] = s->spread * zr_gauss(key, 2);
                    g[1] = s->spread * zr_gauss(key, 3);
                    virtual_image_mv(s, frame, &pc, id, p, n, hid, hit, dir, ob->rough, g, f->mv_eff + 2 * i);
                }
                /* the specular baseline's vector: one more (mirror) ray */
                double r[3], o[3], hn[3];
                v_axpy(r, d, -2.0 * v_dot(d, n), n);
                offset_origin(o, p, n);
                double ts = zs_intersect(s, frame, o, r, INFINITY, &hid, hn);
                if (hid >= 0) {
                    v_axpy(hit, o, ts, r);
                }
                virtual_image_mv(s, frame, &pc, id, p, n, hid, hit, r, 0, NULL, f->mv_spec + 2 * i);
            } else if (s->noisy == ZL_INDIRECT) {
                indirect_sample(s, frame, p, n, u, v, lay);
            }
        }
    }
}

void zs_sample(const zs_scene_t *s, int frame, int w, int h, int x, int y, uint64_t seed, int rng_frame,
               size_t rng_pixel, double out[3])
{
    zs_cam_t c;
    zs_camera(s, frame, w, h, &c);
    double d[3], n[3], p[3];
    const int id = primary_hit(s, frame, &c, x, y, d, p, n);
    const uint64_t key = zr_key(seed, (uint64_t)rng_frame, rng_pixel);
    layer_sample(s, frame, id, p, n, d, zr_u01(key, 0), zr_u01(key, 1), out);
}

void zs_ground_truth(const zs_scene_t *s, int frame, int w, int h, int spp, double *out)
{
    int k = (int)lround(sqrt((double)spp));
    zs_cam_t c;
    zs_camera(s, frame, w, h, &c);
/* gcc builds thread it over rows (mk/zeng.mk), from 128x128 up: smaller
 * frames (the unit test's) spend their time in barriers on a loaded host */
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) if (w * h >= 16384)
#endif
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const size_t i = (size_t)y * w + x;
            double d[3], n[3], p[3], acc[3] = {0, 0, 0};
            const int id = primary_hit(s, frame, &c, x, y, d, p, n);
            if (id < 0 || (s->noisy == ZL_GLOSSY && s->obj[id].ks <= 0)) {
                layer_sample(s, frame, id, p, n, d, 0.5, 0.5, out + 3 * i); /* constant: 1 or 0 */
                continue;
            }
            const uint64_t key = zr_key(0x6a09e667f3bcc909ull, (uint64_t)frame, i);
            for (int a = 0; a < k; a++) {
                for (int b = 0; b < k; b++) {
                    const unsigned j = (unsigned)(a * k + b);
                    double sm[3];
                    layer_sample(s, frame, id, p, n, d, (a + zr_u01(key, 2 * j)) / k, (b + zr_u01(key, 2 * j + 1)) / k,
                                 sm);
                    for (int q = 0; q < 3; q++) {
                        acc[q] += sm[q];
                    }
                }
            }
            for (int q = 0; q < 3; q++) {
                out[3 * i + q] = acc[q] / (k * k);
            }
        }
    }
}

void zs_composite(const zs_scene_t *s, const zs_frame_t *f, const double *layer, double *rgb)
{
    const size_t n = (size_t)f->w * f->h;
    for (size_t i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++) {
            double v = layer[3 * i + k];
            double o;
            if (f->id[i] < 0) {
                o = f->alb[3 * i + k];
            } else if (s->noisy == ZL_VIS) {
                o = f->shade[3 * i + k] * v + 0.0;
            } else if (s->noisy == ZL_GLOSSY) {
                o = f->shade[3 * i + k] + v;
            } else {
                o = f->alb[3 * i + k] * v;
            }
            rgb[3 * i + k] = o;
        }
    }
}
