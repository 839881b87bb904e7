/*
 * tdc_scene_anim.c - keyframe evaluation: object transforms, light
 * positions and the camera, linear between keys, clamped outside them.
 */
#include "tdc_scene.h"

#include <math.h>
#include <string.h>

/* Index i and weight w so that value = (1 - w) key[i] + w key[i + 1]. */
static void bracket(const double *times, size_t stride, int n, double t, int *i, double *w)
{
#define T(k) (*(const double *)((const char *)times + (size_t)(k)*stride))
    if (n <= 1 || t <= T(0)) {
        *i = 0;
        *w = 0;
        return;
    }
    if (t >= T(n - 1)) {
        *i = n - 1;
        *w = 0;
        return;
    }
    int k = 0;
    while (k + 1 < n - 1 && T(k + 1) <= t) k++;
    *i = k;
    *w = (t - T(k)) / (T(k + 1) - T(k));
#undef T
}

static double lerp(double a, double b, double w)
{
    return a + (b - a) * w;
}

void tdc_scene_object_matrix(const tdc_object_t *o, double t, double m[12])
{
    int i;
    double w;
    bracket(&o->keys[0].t, sizeof o->keys[0], o->nkeys, t, &i, &w);
    const tdc_xform_key_t *a = &o->keys[i], *b = &o->keys[i + (w > 0 ? 1 : 0)];
    double p[3], r[3], s = lerp(a->scale, b->scale, w);
    for (int k = 0; k < 3; k++) {
        p[k] = lerp(a->pos[k], b->pos[k], w);
        r[k] = lerp(a->rot[k], b->rot[k], w);
    }
    double cx = cos(r[0]), sx = sin(r[0]), cy = cos(r[1]), sy = sin(r[1]), cz = cos(r[2]), sz = sin(r[2]);
    /* R = Rz * Ry * Rx */
    double R[9] = {cz * cy,
                   cz * sy * sx - sz * cx,
                   cz * sy * cx + sz * sx,
                   sz * cy,
                   sz * sy * sx + cz * cx,
                   sz * sy * cx - cz * sx,
                   -sy,
                   cy * sx,
                   cy * cx};
    for (int row = 0; row < 3; row++) {
        for (int col = 0; col < 3; col++) m[row * 4 + col] = R[row * 3 + col] * s;
        m[row * 4 + 3] = p[row];
    }
}

void tdc_scene_light_pos(const tdc_light_t *l, double t, double pos[3])
{
    int i;
    double w;
    bracket(&l->keys[0].t, sizeof l->keys[0], l->nkeys, t, &i, &w);
    int j = i + (w > 0 ? 1 : 0);
    for (int k = 0; k < 3; k++) pos[k] = lerp(l->keys[i].pos[k], l->keys[j].pos[k], w);
}

void tdc_scene_camera_at(const tdc_scene_t *s, double t, tdc_camera_key_t *out)
{
    int i;
    double w;
    bracket(&s->cam[0].t, sizeof s->cam[0], s->ncamkeys, t, &i, &w);
    const tdc_camera_key_t *a = &s->cam[i], *b = &s->cam[i + (w > 0 ? 1 : 0)];
    out->t = t;
    for (int k = 0; k < 3; k++) out->pos[k] = lerp(a->pos[k], b->pos[k], w);
    out->yaw = lerp(a->yaw, b->yaw, w);
    out->pitch = lerp(a->pitch, b->pitch, w);
    out->fov = lerp(a->fov, b->fov, w);
}

int tdc_scene_object_animated(const tdc_object_t *o)
{
    for (int i = 1; i < o->nkeys; i++) {
        const tdc_xform_key_t *a = &o->keys[0], *b = &o->keys[i];
        if (memcmp(a->pos, b->pos, sizeof a->pos) || memcmp(a->rot, b->rot, sizeof a->rot) || a->scale != b->scale)
            return 1;
    }
    return 0;
}

int tdc_scene_light_animated(const tdc_light_t *l)
{
    for (int i = 1; i < l->nkeys; i++)
        if (memcmp(l->keys[0].pos, l->keys[i].pos, sizeof l->keys[0].pos)) return 1;
    return 0;
}

int tdc_scene_camera_animated(const tdc_scene_t *s)
{
    for (int i = 1; i < s->ncamkeys; i++) {
        const tdc_camera_key_t *a = &s->cam[0], *b = &s->cam[i];
        if (memcmp(a->pos, b->pos, sizeof a->pos) || a->yaw != b->yaw || a->pitch != b->pitch || a->fov != b->fov)
            return 1;
    }
    return 0;
}
