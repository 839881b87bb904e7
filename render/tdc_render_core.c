/*
 * tdc_render_core.c - renderer lifetime, per-frame animation state, the
 * camera, Embree top-level scenes (one per frame parity, so frame f and
 * f - 1 are both available for motion-vector rays) and feature detection.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_ordering.h"
#include "tdc_render_internal.h"

void tdc_render_default_config(tdc_render_config_t *cfg)
{
    memset(cfg, 0, sizeof *cfg);
    cfg->threads = 2;
    cfg->seed = 1;
    cfg->max_bounces = 3;
    cfg->reflect_mv = 1;
    cfg->tex_filter = 1;
    cfg->fov_lod = TDC_FOV_LOD_FOOTPRINT;
    cfg->reduced_factor = 0.5;
    cfg->reduced_ss = 2;
    cfg->reduced_sigma = 2.5;
    cfg->gt_samples = 64;
}


/* Inverse of a 3x4 affine matrix; also the normal matrix (inverse transpose of the 3x3). */
static void invert_affine(const double m[12], double inv[12], double nm[9])
{
    double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9], k = m[10];
    double A = e * k - f * h, B = -(d * k - f * g), C = d * h - e * g;
    double det = a * A + b * B + c * C;
    double id = 1.0 / det;
    double r[9] = {A * id, -(b * k - c * h) * id, (b * f - c * e) * id,
                   B * id, (a * k - c * g) * id,  -(a * f - c * d) * id,
                   C * id, -(a * h - b * g) * id, (a * e - b * d) * id};
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            inv[i * 4 + j] = r[i * 3 + j];
            nm[i * 3 + j] = r[j * 3 + i];
        }
        inv[i * 4 + 3] = -(r[i * 3] * m[3] + r[i * 3 + 1] * m[7] + r[i * 3 + 2] * m[11]);
    }
}

static void make_cam(const tdc_scene_t *s, double t, int w, int h, rcam_t *c)
{
    tdc_camera_key_t k;
    tdc_scene_camera_at(s, t, &k);
    memcpy(c->pos, k.pos, sizeof c->pos);
    c->fwd[0] = cos(k.pitch) * sin(k.yaw);
    c->fwd[1] = sin(k.pitch);
    c->fwd[2] = -cos(k.pitch) * cos(k.yaw);
    double rl = sqrt(c->fwd[2] * c->fwd[2] + c->fwd[0] * c->fwd[0]);
    c->right[0] = -c->fwd[2] / rl;
    c->right[1] = 0;
    c->right[2] = c->fwd[0] / rl;
    c->up[0] = c->right[1] * c->fwd[2] - c->right[2] * c->fwd[1];
    c->up[1] = c->right[2] * c->fwd[0] - c->right[0] * c->fwd[2];
    c->up[2] = c->right[0] * c->fwd[1] - c->right[1] * c->fwd[0];
    c->tan_half = tan(k.fov / 2);
    c->aspect = (double)w / h;
    c->w = w;
    c->h = h;
    c->ax = 2.0 / w * c->tan_half * c->aspect;
    c->bx = -c->tan_half * c->aspect;
    c->ay = -2.0 / h * c->tan_half;
    c->by = c->tan_half;
    c->kx = 0.5 * w / (c->tan_half * c->aspect);
    c->ky = 0.5 * h / c->tan_half;
}


const rframe_t *tdc_r_frame(tdc_render_t *r, long frame)
{
    rframe_t *f = &r->fr[frame & 1];
    if (f->frame == frame) return f;
    const tdc_scene_t *s = r->scene;
    f->frame = frame;
    f->t = frame / s->fps;
    make_cam(s, f->t, r->W, r->H, &f->cam);
    for (int i = 0; i < s->nobjects; i++) {
        tdc_scene_object_matrix(&s->objects[i], f->t, f->m[i]);
        invert_affine(f->m[i], f->minv[i], f->nm[i]);
    }
    for (int i = 0; i < s->nlights; i++) tdc_scene_light_pos(&s->lights[i], f->t, f->light_pos[i]);
    return f;
}

RTCScene tdc_r_top(tdc_render_t *r, long frame)
{
    rtop_t *tp = &r->top[frame & 1];
    if (tp->frame == frame) return tp->top;
    const rframe_t *f = tdc_r_frame(r, frame);
    int changed = 0;
    for (int i = 0; i < r->scene->nobjects; i++) {
        if (tp->frame >= 0 && !r->obj[i].animated) continue;
        float m[12];
        for (int k = 0; k < 12; k++) m[k] = (float)f->m[i][k];
        rtcSetGeometryTransform(tp->inst[i], 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, m);
        rtcCommitGeometry(tp->inst[i]);
        changed = 1;
    }
    if (changed) rtcCommitScene(tp->top);
    tp->frame = frame;
    return tp->top;
}

static void detect_features(tdc_render_t *r)
{
    const tdc_scene_t *s = r->scene;
    tdc_render_features_t *f = &r->feat;
    memset(f, 0, sizeof *f);
    int lit = 0;
    for (int i = 0; i < s->nobjects; i++) {
        const tdc_material_t *m = &s->materials[s->objects[i].material];
        if (m->mirror > 0) f->mirrors = 1;
        if (!m->unlit) lit = 1;
        if (r->obj[i].animated) f->objects_move = 1;
        f->triangles += r->obj[i].prims;
    }
    f->camera_moves = tdc_scene_camera_animated(s);
    int lights_move = 0;
    for (int i = 0; i < s->nlights; i++) {
        if (s->lights[i].kind == TDC_LIGHT_RECT) f->area_lights = 1;
        if (tdc_scene_light_animated(&s->lights[i])) lights_move = 1;
    }
    f->lights = s->nlights > 0 && lit;
    f->motion = f->camera_moves || f->objects_move || lights_move;
    f->moving_blocker = f->lights && (f->objects_move || lights_move);
}

tdc_render_t *tdc_render_open(const tdc_scene_t *scene, const tdc_render_config_t *cfg, char *err, size_t errlen)
{
    if (cfg->threads < 1 || cfg->threads > 64 || cfg->max_bounces < 0 || cfg->max_bounces > TDC_R_MAX_BOUNCES ||
        !(cfg->reduced_factor > 0 && cfg->reduced_factor <= 1) || cfg->reduced_ss < 1 || cfg->reduced_ss > 8 ||
        !(cfg->reduced_sigma > 0) || cfg->gt_samples < 1 || cfg->gt_samples > 4096 || cfg->width < 0 ||
        cfg->height < 0 || cfg->width > 16384 || cfg->height > 16384) {
        snprintf(err, errlen, "tdc_render_open: configuration out of range");
        return NULL;
    }
    tdc_render_t *r = calloc(1, sizeof *r);
    if (!r) goto nomem;
    r->scene = malloc(sizeof *r->scene);
    if (!r->scene) goto nomem;
    memcpy(r->scene, scene, sizeof *scene);
    r->cfg = *cfg;
    r->W = cfg->width ? cfg->width : scene->width;
    r->H = cfg->height ? cfg->height : scene->height;
    r->fr[0].frame = r->fr[1].frame = -1000;
    r->cone_frame = -2; /* no cone history */
    r->gbuf_frame[0] = r->gbuf_frame[1] = -2; /* no G-buffer */
    r->mv_hist = calloc((size_t)r->W * r->H * 2, sizeof(int16_t));
    r->mv_hist_prev = calloc((size_t)r->W * r->H * 2, sizeof(int16_t));
    r->pattern = calloc(TDC_PATTERN_BYTES(r->W, r->H), 1);
    if (!r->mv_hist || !r->mv_hist_prev || !r->pattern) goto nomem;
    r->dev = rtcNewDevice(NULL);
    if (!r->dev) {
        snprintf(err, errlen, "tdc_render_open: rtcNewDevice failed (error %d)", (int)rtcGetDeviceError(NULL));
        tdc_render_close(r);
        return NULL;
    }
    for (int i = 0; i < scene->nobjects; i++) {
        r->obj[i].animated = tdc_scene_object_animated(&scene->objects[i]);
        if (tdc_r_build_object(r, i, err, errlen) < 0) {
            tdc_render_close(r);
            return NULL;
        }
    }
    for (int k = 0; k < 2; k++) {
        r->top[k].top = rtcNewScene(r->dev);
        r->top[k].frame = -1000;
        for (int i = 0; i < scene->nobjects; i++) {
            RTCGeometry g = rtcNewGeometry(r->dev, RTC_GEOMETRY_TYPE_INSTANCE);
            rtcSetGeometryInstancedScene(g, r->obj[i].scene);
            rtcSetGeometryTimeStepCount(g, 1);
            rtcAttachGeometryByID(r->top[k].top, g, (unsigned)i);
            r->top[k].inst[i] = g;
        }
    }
    if (rtcGetDeviceError(r->dev) != RTC_ERROR_NONE) {
        snprintf(err, errlen, "tdc_render_open: Embree error creating instances");
        tdc_render_close(r);
        return NULL;
    }
    detect_features(r);
    tdc_r_tex_prepare(r);
    return r;
nomem:
    snprintf(err, errlen, "tdc_render_open: out of memory");
    tdc_render_close(r);
    return NULL;
}

void tdc_render_close(tdc_render_t *r)
{
    if (!r) return;
    for (int k = 0; k < 2; k++) {
        if (!r->top[k].top) continue;
        for (int i = 0; i < r->scene->nobjects; i++)
            if (r->top[k].inst[i]) rtcReleaseGeometry(r->top[k].inst[i]);
        rtcReleaseScene(r->top[k].top);
    }
    if (r->scene)
        for (int i = 0; i < r->scene->nobjects; i++)
            if (r->obj[i].scene) rtcReleaseScene(r->obj[i].scene);
    if (r->dev) rtcReleaseDevice(r->dev);
    free(r->scene);
    free(r->mv_hist);
    free(r->mv_hist_prev);
    free(r->pattern);
    free(r->rec);
    free(r->fov_xy);
    free(r->fov_cone);
    free(r->cone_hist[0]);
    free(r->cone_hist[1]);
    free(r->gbuf[0]);
    free(r->gbuf[1]);
    for (int i = 0; i < 64; i++) free(r->sbuf[i]);
    free(r);
}

void tdc_render_output_size(const tdc_render_t *r, tdc_render_mode_t mode, int *w, int *h)
{
    switch (mode) {
    case TDC_RENDER_REDUCED:
        *w = (int)lround(r->W * r->cfg.reduced_factor);
        *h = (int)lround(r->H * r->cfg.reduced_factor);
        if (*w < 1) *w = 1;
        if (*h < 1) *h = 1;
        break;
    case TDC_RENDER_SUBFRAME:
        *w = TDC_TILES(r->W);
        *h = TDC_TILES(r->H);
        break;
    case TDC_RENDER_FOVEATED:
        *w = r->fov_n;
        *h = 1;
        break;
    default: *w = r->W; *h = r->H;
    }
}

int tdc_render_set_threads(tdc_render_t *r, int threads)
{
    if (threads < 1 || threads > 64) return -1;
    r->cfg.threads = threads;
    return 0;
}

void tdc_render_set_record(tdc_render_t *r, int on)
{
    r->cfg.record_rays = on != 0;
}

void tdc_render_set_jitter(tdc_render_t *r, double jx, double jy)
{
    r->full_jx = (float)(jx < -0.5 ? -0.5 : (jx > 0.5 ? 0.5 : jx));
    r->full_jy = (float)(jy < -0.5 ? -0.5 : (jy > 0.5 ? 0.5 : jy));
}

void tdc_render_set_reflect_mv(tdc_render_t *r, int on)
{
    r->cfg.reflect_mv = on != 0;
}

void tdc_render_set_fov_lod(tdc_render_t *r, int mode)
{
    r->cfg.fov_lod = mode; /* read by the next tdc_render_set_foveation */
}

void tdc_render_set_seed(tdc_render_t *r, uint32_t seed)
{
    r->cfg.seed = seed;
}

void tdc_render_get_features(const tdc_render_t *r, tdc_render_features_t *f)
{
    *f = r->feat;
}
const tdc_scene_t *tdc_render_scene(const tdc_render_t *r)
{
    return r->scene;
}
const uint8_t *tdc_render_pattern_bits(const tdc_render_t *r)
{
    return r->pattern;
}
const int16_t *tdc_render_mv_history(const tdc_render_t *r)
{
    return r->mv_hist;
}

void tdc_render_set_pattern_bits(tdc_render_t *r, const uint8_t *bits)
{
    memcpy(r->pattern, bits, TDC_PATTERN_BYTES(r->W, r->H));
}

int tdc_r_update_motion(tdc_render_t *r, long frame)
{
    const rframe_t *a = tdc_r_frame(r, frame);
    const rframe_t *b = tdc_r_frame(r, frame - 1);
    int any = 0;
    r->cam_moved = memcmp(a->cam.pos, b->cam.pos, sizeof a->cam.pos) ||
                   memcmp(a->cam.fwd, b->cam.fwd, sizeof a->cam.fwd) || a->cam.tan_half != b->cam.tan_half;
    any |= r->cam_moved;
    for (int i = 0; i < r->scene->nobjects; i++) {
        r->obj_same_m[i] = memcmp(a->m[i], b->m[i], sizeof a->m[i]) == 0;
        r->obj_same_rs[i] = memcmp(&a->m[i][0], &b->m[i][0], 3 * sizeof(double)) == 0 &&
                            memcmp(&a->m[i][4], &b->m[i][4], 3 * sizeof(double)) == 0 &&
                            memcmp(&a->m[i][8], &b->m[i][8], 3 * sizeof(double)) == 0;
        r->obj_moved[i] = r->obj[i].animated && !r->obj_same_m[i];
        any |= r->obj_moved[i];
    }
    for (int i = 0; i < r->scene->nlights; i++)
        if (memcmp(a->light_pos[i], b->light_pos[i], sizeof a->light_pos[i])) any = 1;
    return any;
}

int tdc_render_frame_static(tdc_render_t *r, uint32_t frame)
{
    if (!r->feat.motion) {
        r->cam_moved = 0;
        memset(r->obj_moved, 0, sizeof r->obj_moved);
        memset(r->obj_same_m, 0, sizeof r->obj_same_m); /* not compared: transform both */
        memset(r->obj_same_rs, 0, sizeof r->obj_same_rs);
        return 1;
    }
    return !tdc_r_update_motion(r, (long)frame);
}

void *tdc_render_embree_scene(tdc_render_t *r, uint32_t frame)
{
    return tdc_r_top(r, (long)frame);
}

const tdc_render_ray_t *tdc_render_recorded_rays(const tdc_render_t *r, size_t *count)
{
    *count = r->nrec;
    return r->rec;
}

const char *tdc_render_stage_name(tdc_render_stage_t s)
{
    static const char *const n[TDC_STAGE_COUNT] = {"scene",   "primary", "shade",    "reflect",
                                                   "mv",      "mv-reflect", "mv-shadow", "mv-dual",
                                                   "resolve", "ordering", "indirect"};
    return (unsigned)s < TDC_STAGE_COUNT ? n[s] : "?";
}

const char *tdc_render_mode_name(tdc_render_mode_t m)
{
    static const char *const n[] = {"full", "reduced", "subframe", "ground-truth", "foveated"};
    return (unsigned)m < 5 ? n[m] : "?";
}
