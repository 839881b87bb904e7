/*
 * tdc_scene_parse.c - parser of the line-based scene format (see
 * docs/renderer.md, "Scene files").  Every error names the line:
 * "<file>:<line>: <what>", and the parse stops at the first error.
 */
#include "tdc_scene.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_TOKENS 48
#define DEG (M_PI / 180.0)

typedef struct {
    const char *src;
    int line;
    char *err;
    size_t errlen;
    int failed;
} pctx_t;

static int fail(pctx_t *c, const char *fmt, ...)
{
    if (c->failed) return -1;
    c->failed = 1;
    int n = snprintf(c->err, c->errlen, "%s:%d: ", c->src, c->line);
    if (n < 0) n = 0;
    if ((size_t)n < c->errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(c->err + n, c->errlen - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return -1;
}

/* Splits a line into tokens in place; "quoted strings" are one token.
 * Returns the count or -1 on an unterminated string / too many tokens. */
static int tokenize(pctx_t *c, char *line, char **tok)
{
    int n = 0;
    char *p = line;
    for (;;) {
        while (*p == ' ' || *p == '\t' || *p == '\r') p++;
        if (*p == '\0' || *p == '#') break;
        if (n == MAX_TOKENS) return fail(c, "too many tokens (at most %d)", MAX_TOKENS);
        if (*p == '"') {
            char *q = strchr(p + 1, '"');
            if (!q) return fail(c, "unterminated string");
            *q = '\0';
            tok[n++] = p + 1;
            p = q + 1;
            if (*p != '\0' && *p != ' ' && *p != '\t' && *p != '\r') return fail(c, "junk after string");
        } else {
            tok[n++] = p;
            while (*p && *p != ' ' && *p != '\t' && *p != '\r') p++;
            if (*p) *p++ = '\0';
        }
    }
    return n;
}

static int num(pctx_t *c, char **tok, int ntok, int i, double *out)
{
    if (i >= ntok) return fail(c, "missing number after '%s'", tok[i - 1]);
    char *end;
    errno = 0;
    double v = strtod(tok[i], &end);
    if (end == tok[i] || *end != '\0' || errno != 0 || !isfinite(v))
        return fail(c, "'%s' is not a finite number", tok[i]);
    *out = v;
    return 0;
}

static int nums(pctx_t *c, char **tok, int ntok, int i, int k, double *out)
{
    for (int j = 0; j < k; j++)
        if (num(c, tok, ntok, i + j, &out[j]) < 0) return -1;
    return 0;
}

static int integer(pctx_t *c, char **tok, int ntok, int i, int lo, int hi, int *out)
{
    double v;
    if (num(c, tok, ntok, i, &v) < 0) return -1;
    if (v != floor(v) || v < lo || v > hi) return fail(c, "'%s' must be an integer in [%d, %d]", tok[i], lo, hi);
    *out = (int)v;
    return 0;
}

static int name_ok(pctx_t *c, const char *what, const char *s)
{
    size_t n = strlen(s);
    if (n == 0 || n >= TDC_SCENE_NAME_LEN)
        return fail(c, "%s name must be 1..%d characters", what, TDC_SCENE_NAME_LEN - 1);
    for (size_t i = 0; i < n; i++)
        if (!isalnum((unsigned char)s[i]) && s[i] != '_' && s[i] != '-' && s[i] != '.')
            return fail(c, "%s name '%s' may only contain letters, digits, '_', '-', '.'", what, s);
    return 0;
}

static int find_material(const tdc_scene_t *s, const char *n)
{
    for (int i = 0; i < s->nmaterials; i++)
        if (!strcmp(s->materials[i].name, n)) return i;
    return -1;
}
static int find_object(const tdc_scene_t *s, const char *n)
{
    for (int i = 0; i < s->nobjects; i++)
        if (!strcmp(s->objects[i].name, n)) return i;
    return -1;
}
static int find_light(const tdc_scene_t *s, const char *n)
{
    for (int i = 0; i < s->nlights; i++)
        if (!strcmp(s->lights[i].name, n)) return i;
    return -1;
}

static int nonneg3(pctx_t *c, const double *v, const char *what)
{
    for (int i = 0; i < 3; i++)
        if (v[i] < 0) return fail(c, "%s must not be negative", what);
    return 0;
}

/* material NAME [diffuse R G B] [mirror K [roughness A]] [unlit] [checker|stripes S R G B]
 *          [text "STR" S R G B] [skyline S R G B] */
static int parse_material(pctx_t *c, tdc_scene_t *s, char **tok, int n)
{
    if (n < 2) return fail(c, "material needs a name");
    if (name_ok(c, "material", tok[1]) < 0) return -1;
    if (find_material(s, tok[1]) >= 0) return fail(c, "material '%s' defined twice", tok[1]);
    if (s->nmaterials == TDC_SCENE_MAX_MATERIALS)
        return fail(c, "too many materials (max %d)", TDC_SCENE_MAX_MATERIALS);
    tdc_material_t *m = &s->materials[s->nmaterials];
    memset(m, 0, sizeof *m);
    strcpy(m->name, tok[1]);
    m->diffuse[0] = m->diffuse[1] = m->diffuse[2] = 0.8;
    for (int i = 2; i < n;) {
        const char *k = tok[i];
        if (!strcmp(k, "diffuse")) {
            if (nums(c, tok, n, i + 1, 3, m->diffuse) < 0 || nonneg3(c, m->diffuse, "diffuse") < 0) return -1;
            i += 4;
        } else if (!strcmp(k, "mirror")) {
            if (num(c, tok, n, i + 1, &m->mirror) < 0) return -1;
            if (m->mirror < 0 || m->mirror > 1) return fail(c, "mirror reflectivity must be in [0, 1]");
            i += 2;
        } else if (!strcmp(k, "roughness")) {
            /* GGX alpha of the reflection lobe; needs a reflectivity (checked below) */
            if (num(c, tok, n, i + 1, &m->roughness) < 0) return -1;
            if (!(m->roughness >= 0 && m->roughness <= 1)) return fail(c, "roughness must be in [0, 1]");
            i += 2;
        } else if (!strcmp(k, "unlit")) {
            m->unlit = 1;
            i += 1;
        } else if (!strcmp(k, "checker") || !strcmp(k, "stripes") || !strcmp(k, "skyline") || !strcmp(k, "text")) {
            if (m->tex != TDC_TEX_NONE) return fail(c, "material '%s' has more than one texture", m->name);
            int at = i + 1;
            if (!strcmp(k, "text")) {
                if (at >= n) return fail(c, "text needs a string");
                if (strlen(tok[at]) == 0 || strlen(tok[at]) >= TDC_SCENE_TEXT_LEN)
                    return fail(c, "text must be 1..%d characters", TDC_SCENE_TEXT_LEN - 1);
                strcpy(m->text, tok[at]);
                at++;
                m->tex = TDC_TEX_TEXT;
            } else {
                m->tex = !strcmp(k, "checker")   ? TDC_TEX_CHECKER
                         : !strcmp(k, "stripes") ? TDC_TEX_STRIPES
                                                 : TDC_TEX_SKYLINE;
            }
            if (num(c, tok, n, at, &m->tex_scale) < 0) return -1;
            if (!(m->tex_scale > 0)) return fail(c, "texture scale must be > 0");
            if (nums(c, tok, n, at + 1, 3, m->color2) < 0 || nonneg3(c, m->color2, "texture colour") < 0) return -1;
            i = at + 4;
        } else {
            return fail(c, "unknown material attribute '%s'", k);
        }
    }
    if (m->roughness > 0 && !(m->mirror > 0)) return fail(c, "roughness needs a reflectivity (mirror K > 0)");
    s->nmaterials++;
    return 0;
}

/* Shape arguments: keyword value pairs the shape requires. */
static int parse_object(pctx_t *c, tdc_scene_t *s, char **tok, int n, const char *base_dir)
{
    if (n < 3) return fail(c, "object needs a name and a shape");
    if (name_ok(c, "object", tok[1]) < 0) return -1;
    if (find_object(s, tok[1]) >= 0) return fail(c, "object '%s' defined twice", tok[1]);
    if (s->nobjects == TDC_SCENE_MAX_OBJECTS) return fail(c, "too many objects (max %d)", TDC_SCENE_MAX_OBJECTS);
    tdc_object_t *o = &s->objects[s->nobjects];
    memset(o, 0, sizeof *o);
    strcpy(o->name, tok[1]);
    o->line = c->line;
    o->material = -1;
    o->nkeys = 1;
    o->keys[0].scale = 1.0;
    static const struct {
        const char *name;
        tdc_shape_t shape;
        const char *req[4];
        int defseg;
    } shapes[] = {
        {"sphere", TDC_SHAPE_SPHERE, {"radius"}, 0},
        {"rect", TDC_SHAPE_RECT, {"size2"}, 0},
        {"box", TDC_SHAPE_BOX, {"size3"}, 0},
        {"disc", TDC_SHAPE_DISC, {"radius"}, 64},
        {"cylinder", TDC_SHAPE_CYLINDER, {"radius", "height"}, 48},
        {"fence", TDC_SHAPE_FENCE, {"width", "gap", "height", "depth"}, 8},
        {"heightfield", TDC_SHAPE_HEIGHTFIELD, {"size2", "amplitude"}, 64},
        {"mesh", TDC_SHAPE_MESH, {"path"}, 0},
    };
    int si = -1;
    for (size_t i = 0; i < sizeof shapes / sizeof shapes[0]; i++)
        if (!strcmp(tok[2], shapes[i].name)) si = (int)i;
    if (si < 0) return fail(c, "unknown shape '%s' (sphere rect box disc cylinder fence heightfield mesh)", tok[2]);
    o->shape = shapes[si].shape;
    o->segments = shapes[si].defseg;
    int have[4] = {0, 0, 0, 0};
    for (int i = 3; i < n;) {
        const char *k = tok[i];
        int slot = -1;
        for (int r = 0; r < 4 && shapes[si].req[r]; r++) {
            const char *req = shapes[si].req[r];
            if (!strcmp(req, k) || (!strncmp(req, "size", 4) && !strcmp(k, "size")) ||
                (!strcmp(req, "path") && !strcmp(k, "file")))
                slot = r;
        }
        if (slot >= 0) {
            const char *req = shapes[si].req[slot];
            if (!strcmp(req, "path")) {
                if (i + 1 >= n) return fail(c, "missing file name after '%s'", k);
                const char *f = tok[i + 1];
                int w;
                if (f[0] == '/' || !base_dir)
                    w = snprintf(o->path, sizeof o->path, "%s", f);
                else
                    w = snprintf(o->path, sizeof o->path, "%s/%s", base_dir, f);
                if (w < 0 || (size_t)w >= sizeof o->path) return fail(c, "mesh path too long");
                i += 2;
            } else if (!strcmp(req, "size2") || !strcmp(req, "size3")) {
                int k3 = req[4] - '0';
                if (nums(c, tok, n, i + 1, k3, o->p) < 0) return -1;
                for (int j = 0; j < k3; j++)
                    if (!(o->p[j] > 0)) return fail(c, "size must be > 0");
                i += 1 + k3;
            } else {
                int pi = o->shape == TDC_SHAPE_HEIGHTFIELD ? 2 : slot;
                if (num(c, tok, n, i + 1, &o->p[pi]) < 0) return -1;
                if (o->shape == TDC_SHAPE_HEIGHTFIELD ? o->p[pi] < 0 : !(o->p[pi] > 0))
                    return fail(c, "%s must be %s", k, o->shape == TDC_SHAPE_HEIGHTFIELD ? ">= 0" : "> 0");
                i += 2;
            }
            have[slot] = 1;
        } else if (!strcmp(k, "segments") || !strcmp(k, "slats") || !strcmp(k, "cells")) {
            if (o->shape != TDC_SHAPE_DISC && o->shape != TDC_SHAPE_CYLINDER && o->shape != TDC_SHAPE_FENCE &&
                o->shape != TDC_SHAPE_HEIGHTFIELD)
                return fail(c, "'%s' does not apply to shape %s", k, tok[2]);
            if (integer(c, tok, n, i + 1, o->shape == TDC_SHAPE_FENCE ? 1 : 3, 4096, &o->segments) < 0) return -1;
            i += 2;
        } else if (!strcmp(k, "material")) {
            if (i + 1 >= n) return fail(c, "missing material name");
            o->material = find_material(s, tok[i + 1]);
            if (o->material < 0) return fail(c, "unknown material '%s' (define materials before objects)", tok[i + 1]);
            i += 2;
        } else if (!strcmp(k, "pos")) {
            if (nums(c, tok, n, i + 1, 3, o->keys[0].pos) < 0) return -1;
            i += 4;
        } else if (!strcmp(k, "rot")) {
            if (nums(c, tok, n, i + 1, 3, o->keys[0].rot) < 0) return -1;
            for (int j = 0; j < 3; j++) o->keys[0].rot[j] *= DEG;
            i += 4;
        } else if (!strcmp(k, "scale")) {
            if (num(c, tok, n, i + 1, &o->keys[0].scale) < 0) return -1;
            if (!(o->keys[0].scale > 0)) return fail(c, "scale must be > 0");
            i += 2;
        } else {
            return fail(c, "unknown attribute '%s' for %s", k, tok[2]);
        }
    }
    for (int r = 0; r < 4 && shapes[si].req[r]; r++)
        if (!have[r]) {
            const char *req = shapes[si].req[r];
            return fail(c, "%s needs '%s'", tok[2],
                        !strncmp(req, "size", 4) ? "size"
                        : !strcmp(req, "path")   ? "file"
                                                 : req);
        }
    if (o->material < 0) return fail(c, "object '%s' needs a material", o->name);
    if (o->shape == TDC_SHAPE_HEIGHTFIELD && o->segments > 2048) return fail(c, "heightfield cells must be <= 2048");
    s->nobjects++;
    return 0;
}

/* key OBJ T [pos X Y Z] [rot X Y Z] [scale S]: values not given carry over. */
static int parse_key(pctx_t *c, tdc_scene_t *s, char **tok, int n, int *keyed)
{
    if (n < 3) return fail(c, "key needs an object name and a time");
    int oi = find_object(s, tok[1]);
    if (oi < 0) return fail(c, "key for unknown object '%s'", tok[1]);
    tdc_object_t *o = &s->objects[oi];
    double t;
    if (num(c, tok, n, 2, &t) < 0) return -1;
    tdc_xform_key_t k;
    if (!keyed[oi]) {
        k = o->keys[0];
    } else {
        k = o->keys[o->nkeys - 1];
        if (!(t > k.t)) return fail(c, "key times of '%s' must increase (%g after %g)", o->name, t, k.t);
        if (o->nkeys == TDC_SCENE_MAX_KEYS)
            return fail(c, "too many keys for '%s' (max %d)", o->name, TDC_SCENE_MAX_KEYS);
    }
    k.t = t;
    for (int i = 3; i < n;) {
        if (!strcmp(tok[i], "pos")) {
            if (nums(c, tok, n, i + 1, 3, k.pos) < 0) return -1;
            i += 4;
        } else if (!strcmp(tok[i], "rot")) {
            if (nums(c, tok, n, i + 1, 3, k.rot) < 0) return -1;
            for (int j = 0; j < 3; j++) k.rot[j] *= DEG;
            i += 4;
        } else if (!strcmp(tok[i], "scale")) {
            if (num(c, tok, n, i + 1, &k.scale) < 0) return -1;
            if (!(k.scale > 0)) return fail(c, "scale must be > 0");
            i += 2;
        } else {
            return fail(c, "unknown key attribute '%s'", tok[i]);
        }
    }
    if (!keyed[oi]) {
        o->keys[0] = k;
        keyed[oi] = 1;
    } else {
        o->keys[o->nkeys++] = k;
    }
    return 0;
}

/* light NAME point pos X Y Z intensity R G B
 * light NAME rect pos X Y Z u X Y Z v X Y Z intensity R G B [samples N] */
static int parse_light(pctx_t *c, tdc_scene_t *s, char **tok, int n)
{
    if (n < 3) return fail(c, "light needs a name and a kind (point, rect)");
    if (name_ok(c, "light", tok[1]) < 0) return -1;
    if (find_light(s, tok[1]) >= 0) return fail(c, "light '%s' defined twice", tok[1]);
    if (s->nlights == TDC_SCENE_MAX_LIGHTS) return fail(c, "too many lights (max %d)", TDC_SCENE_MAX_LIGHTS);
    tdc_light_t *l = &s->lights[s->nlights];
    memset(l, 0, sizeof *l);
    strcpy(l->name, tok[1]);
    if (!strcmp(tok[2], "point"))
        l->kind = TDC_LIGHT_POINT;
    else if (!strcmp(tok[2], "rect"))
        l->kind = TDC_LIGHT_RECT;
    else
        return fail(c, "unknown light kind '%s' (point, rect)", tok[2]);
    l->samples = 4;
    l->nkeys = 1;
    int have_pos = 0, have_i = 0, have_u = 0, have_v = 0;
    for (int i = 3; i < n;) {
        const char *k = tok[i];
        if (!strcmp(k, "pos")) {
            if (nums(c, tok, n, i + 1, 3, l->keys[0].pos) < 0) return -1;
            have_pos = 1;
            i += 4;
        } else if (!strcmp(k, "intensity")) {
            if (nums(c, tok, n, i + 1, 3, l->intensity) < 0 || nonneg3(c, l->intensity, "intensity") < 0) return -1;
            have_i = 1;
            i += 4;
        } else if (l->kind == TDC_LIGHT_RECT && (!strcmp(k, "u") || !strcmp(k, "v"))) {
            if (nums(c, tok, n, i + 1, 3, k[0] == 'u' ? l->u : l->v) < 0) return -1;
            *(k[0] == 'u' ? &have_u : &have_v) = 1;
            i += 4;
        } else if (l->kind == TDC_LIGHT_RECT && !strcmp(k, "samples")) {
            if (integer(c, tok, n, i + 1, 1, 1024, &l->samples) < 0) return -1;
            i += 2;
        } else {
            return fail(c, "unknown attribute '%s' for %s light", k, tok[2]);
        }
    }
    if (!have_pos) return fail(c, "light '%s' needs 'pos'", l->name);
    if (!have_i) return fail(c, "light '%s' needs 'intensity'", l->name);
    if (l->kind == TDC_LIGHT_RECT && (!have_u || !have_v)) return fail(c, "rect light '%s' needs 'u' and 'v'", l->name);
    s->nlights++;
    return 0;
}

static int parse_lightkey(pctx_t *c, tdc_scene_t *s, char **tok, int n, int *keyed)
{
    if (n != 7 || strcmp(tok[3], "pos")) return fail(c, "usage: lightkey NAME T pos X Y Z");
    int li = find_light(s, tok[1]);
    if (li < 0) return fail(c, "lightkey for unknown light '%s'", tok[1]);
    tdc_light_t *l = &s->lights[li];
    double t, p[3];
    if (num(c, tok, n, 2, &t) < 0 || nums(c, tok, n, 4, 3, p) < 0) return -1;
    if (keyed[li]) {
        if (!(t > l->keys[l->nkeys - 1].t)) return fail(c, "lightkey times of '%s' must increase", l->name);
        if (l->nkeys == TDC_SCENE_MAX_KEYS) return fail(c, "too many keys for light '%s'", l->name);
        l->nkeys++;
    }
    keyed[li] = 1;
    l->keys[l->nkeys - 1].t = t;
    memcpy(l->keys[l->nkeys - 1].pos, p, sizeof p);
    return 0;
}

/* camera T pos X Y Z (look X Y Z | yaw DEG [pitch DEG]) [fov DEG] */
static int parse_camera(pctx_t *c, tdc_scene_t *s, char **tok, int n)
{
    if (n < 2) return fail(c, "camera needs a time");
    if (s->ncamkeys == TDC_SCENE_MAX_KEYS) return fail(c, "too many camera keys (max %d)", TDC_SCENE_MAX_KEYS);
    tdc_camera_key_t k;
    if (s->ncamkeys)
        k = s->cam[s->ncamkeys - 1];
    else {
        memset(&k, 0, sizeof k);
        k.fov = 45 * DEG;
    }
    if (num(c, tok, n, 1, &k.t) < 0) return -1;
    if (s->ncamkeys && !(k.t > s->cam[s->ncamkeys - 1].t)) return fail(c, "camera key times must increase");
    double look[3];
    int have_look = 0, have_pos = s->ncamkeys > 0;
    for (int i = 2; i < n;) {
        const char *kw = tok[i];
        if (!strcmp(kw, "pos")) {
            if (nums(c, tok, n, i + 1, 3, k.pos) < 0) return -1;
            have_pos = 1;
            i += 4;
        } else if (!strcmp(kw, "look")) {
            if (nums(c, tok, n, i + 1, 3, look) < 0) return -1;
            have_look = 1;
            i += 4;
        } else if (!strcmp(kw, "yaw") || !strcmp(kw, "pitch") || !strcmp(kw, "fov")) {
            double v;
            if (num(c, tok, n, i + 1, &v) < 0) return -1;
            if (kw[0] == 'y')
                k.yaw = v * DEG;
            else if (kw[0] == 'p') {
                if (fabs(v) >= 89.9) return fail(c, "pitch must be within (-89.9, 89.9) degrees");
                k.pitch = v * DEG;
            } else {
                if (!(v > 0.1 && v < 179)) return fail(c, "fov must be in (0.1, 179) degrees");
                k.fov = v * DEG;
            }
            i += 2;
        } else {
            return fail(c, "unknown camera attribute '%s'", kw);
        }
    }
    if (!have_pos) return fail(c, "the first camera key needs 'pos'");
    if (have_look) {
        double d[3] = {look[0] - k.pos[0], look[1] - k.pos[1], look[2] - k.pos[2]};
        double h = sqrt(d[0] * d[0] + d[2] * d[2]);
        if (h < 1e-9 * (fabs(d[1]) + 1e-300)) return fail(c, "camera may not look straight up or down");
        k.yaw = atan2(d[0], -d[2]);
        k.pitch = atan2(d[1], h);
    }
    s->cam[s->ncamkeys++] = k;
    return 0;
}

tdc_scene_status_t tdc_scene_parse(const char *text, const char *src_name, const char *base_dir, tdc_scene_t *s,
                                   char *err, size_t errlen)
{
    pctx_t c = {src_name ? src_name : "<scene>", 0, err, errlen, 0};
    if (errlen) err[0] = '\0';
    memset(s, 0, sizeof *s);
    s->width = 640;
    s->height = 360;
    s->fps = 240;
    s->duration = 1;
    s->ambient[0] = s->ambient[1] = s->ambient[2] = 0.05;
    /* Default name: the file's base name without extension, with anything
     * but [A-Za-z0-9_.-] replaced by '_'; it names output files
     * (tdc-render --png DIR/<name>-...), so it never holds a '/' (issue 19). */
    {
        const char *b = strrchr(c.src, '/');
        b = b ? b + 1 : c.src;
        size_t bn = strcspn(b, ".");
        if (bn == 0) bn = strlen(b);
        if (bn >= sizeof s->name) bn = sizeof s->name - 1;
        for (size_t i = 0; i < bn; i++)
            s->name[i] = isalnum((unsigned char)b[i]) || b[i] == '_' || b[i] == '-' || b[i] == '.' ? b[i] : '_';
        s->name[bn] = '\0';
        if (bn == 0) snprintf(s->name, sizeof s->name, "scene");
    }
    size_t len = strlen(text);
    char *buf = malloc(len + 1);
    int *okeyed = calloc(TDC_SCENE_MAX_OBJECTS, sizeof(int));
    int *lkeyed = calloc(TDC_SCENE_MAX_LIGHTS, sizeof(int));
    if (!buf || !okeyed || !lkeyed) {
        free(buf);
        free(okeyed);
        free(lkeyed);
        snprintf(err, errlen, "%s: out of memory", c.src);
        return TDC_SCENE_ERR_NOMEM;
    }
    memcpy(buf, text, len + 1);
    int header = 0, last_line = 0;
    char *line = buf;
    while (line && !c.failed) {
        char *nl = strchr(line, '\n');
        if (nl) *nl = '\0';
        c.line++;
        char *tok[MAX_TOKENS];
        int n = tokenize(&c, line, tok);
        if (n > 0) {
            last_line = c.line;
            const char *k = tok[0];
            if (!header) {
                if (strcmp(k, "tdc-scene") || n != 2 || strcmp(tok[1], "1"))
                    fail(&c, "first line must be 'tdc-scene 1'");
                header = 1;
            } else if (!strcmp(k, "name")) {
                if (n != 2 || strlen(tok[1]) >= sizeof s->name)
                    fail(&c, "usage: name NAME (< 64 characters)");
                else if (strspn(tok[1], "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-.") !=
                             strlen(tok[1]) ||
                         !strcmp(tok[1], ".") || !strcmp(tok[1], ".."))
                    /* it names output files (tdc-render --png DIR/<name>-...): no '/', not '..' */
                    fail(&c, "scene name '%s' may only contain letters, digits, '_', '-', '.' (not '.' or '..')",
                         tok[1]);
                else
                    strcpy(s->name, tok[1]);
            } else if (!strcmp(k, "resolution")) {
                if (n != 3)
                    fail(&c, "usage: resolution W H");
                else if (integer(&c, tok, n, 1, 1, 16384, &s->width) == 0)
                    integer(&c, tok, n, 2, 1, 16384, &s->height);
            } else if (!strcmp(k, "fps") || !strcmp(k, "duration")) {
                double v;
                if (n != 2)
                    fail(&c, "usage: %s VALUE", k);
                else if (num(&c, tok, n, 1, &v) == 0) {
                    if (!(v > 0))
                        fail(&c, "%s must be > 0", k);
                    else
                        *(k[0] == 'f' ? &s->fps : &s->duration) = v;
                }
            } else if (!strcmp(k, "background") || !strcmp(k, "ambient")) {
                double *d = k[0] == 'b' ? s->background : s->ambient;
                if (n != 4)
                    fail(&c, "usage: %s R G B", k);
                else if (nums(&c, tok, n, 1, 3, d) == 0)
                    nonneg3(&c, d, k);
            } else if (!strcmp(k, "material")) {
                parse_material(&c, s, tok, n);
            } else if (!strcmp(k, "object")) {
                parse_object(&c, s, tok, n, base_dir);
            } else if (!strcmp(k, "key")) {
                parse_key(&c, s, tok, n, okeyed);
            } else if (!strcmp(k, "light")) {
                parse_light(&c, s, tok, n);
            } else if (!strcmp(k, "lightkey")) {
                parse_lightkey(&c, s, tok, n, lkeyed);
            } else if (!strcmp(k, "camera")) {
                parse_camera(&c, s, tok, n);
            } else {
                fail(&c, "unknown keyword '%s'", k);
            }
        }
        line = nl ? nl + 1 : NULL;
    }
    free(buf);
    free(okeyed);
    free(lkeyed);
    c.line = last_line; /* end-of-file problems: name the last line */
    if (!c.failed && !header) fail(&c, "empty scene (first line must be 'tdc-scene 1')");
    if (!c.failed && s->ncamkeys == 0) fail(&c, "scene has no camera");
    if (!c.failed && s->nobjects == 0) fail(&c, "scene has no objects");
    return c.failed ? TDC_SCENE_ERR_SYNTAX : TDC_SCENE_OK;
}

tdc_scene_status_t tdc_scene_load(const char *path, tdc_scene_t *s, char *err, size_t errlen)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return TDC_SCENE_ERR_IO;
    }
    char *text = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (len + 4096 + 1 > cap) {
            cap = cap ? cap * 2 : 65536;
            char *t = realloc(text, cap);
            if (!t) {
                free(text);
                fclose(f);
                snprintf(err, errlen, "%s: out of memory", path);
                return TDC_SCENE_ERR_NOMEM;
            }
            text = t;
        }
        size_t r = fread(text + len, 1, 4096, f);
        len += r;
        if (r < 4096) break;
    }
    int ioerr = ferror(f);
    fclose(f);
    if (ioerr) {
        free(text);
        snprintf(err, errlen, "%s: read error", path);
        return TDC_SCENE_ERR_IO;
    }
    text[len] = '\0';
    if (memchr(text, '\0', len)) {
        free(text);
        snprintf(err, errlen, "%s: not a text file (NUL byte)", path);
        return TDC_SCENE_ERR_SYNTAX;
    }
    char dir[TDC_SCENE_PATH_LEN];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    if (slash) *slash = '\0';
    tdc_scene_status_t st = tdc_scene_parse(text, path, slash ? dir : NULL, s, err, errlen);
    free(text);
    return st;
}
