/*
 * tdc_render_geom.c - turns scene shapes into Embree geometry in the
 * object's local space: spheres (RTC_GEOMETRY_TYPE_SPHERE_POINT), rects and
 * boxes (quads), discs, cylinders, fences, heightfields and OBJ meshes
 * (triangles).  Each object gets its own RTCScene, instanced into the top
 * scene with the object's per-frame transform (tdc_render_core.c).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_render_internal.h"
#include "tdc_tool.h"

typedef struct {
    float *v; /* xyz */
    unsigned nv, cv;
    unsigned *ix;    /* 3 or 4 per primitive */
    unsigned ni, ci; /* index count */
} meshbuf_t;

static int mb_vertex(meshbuf_t *m, double x, double y, double z)
{
    if (m->nv == m->cv) {
        unsigned c = m->cv ? m->cv * 2 : 256;
        float *v = realloc(m->v, (size_t)c * 3 * sizeof(float));
        if (!v) return -1;
        m->v = v;
        m->cv = c;
    }
    m->v[m->nv * 3 + 0] = (float)x;
    m->v[m->nv * 3 + 1] = (float)y;
    m->v[m->nv * 3 + 2] = (float)z;
    m->nv++;
    return 0;
}

static int mb_index(meshbuf_t *m, unsigned i)
{
    if (m->ni == m->ci) {
        unsigned c = m->ci ? m->ci * 2 : 1024;
        unsigned *x = realloc(m->ix, (size_t)c * sizeof(unsigned));
        if (!x) return -1;
        m->ix = x;
        m->ci = c;
    }
    m->ix[m->ni++] = i;
    return 0;
}

/* An axis-aligned box as 6 quads (outward winding). */
static int mb_box(meshbuf_t *m, double cx, double cy, double cz, double sx, double sy, double sz)
{
    static const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                     {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    static const int face[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}};
    unsigned base = m->nv;
    for (int i = 0; i < 8; i++)
        if (mb_vertex(m, cx + (corner[i][0] - 0.5) * sx, cy + (corner[i][1] - 0.5) * sy,
                      cz + (corner[i][2] - 0.5) * sz) < 0)
            return -1;
    for (int f = 0; f < 6; f++)
        for (int k = 0; k < 4; k++)
            if (mb_index(m, base + (unsigned)face[f][k]) < 0) return -1;
    return 0;
}

/* Wavelike terrain height (deterministic). */
static double terrain_height(double x, double z, double amp)
{
    return amp * (0.5 * sin(0.31 * x) * cos(0.27 * z) + 0.3 * sin(0.83 * x + 1.3) * sin(0.71 * z + 0.4) +
                  0.2 * cos(2.1 * x - 0.6 * z) * sin(1.7 * z));
}

/* Reads the v and f lines of an OBJ file; polygons are fan-triangulated,
 * negative (relative) indices are accepted.  Lines are read whole
 * (tdc_read_line): one longer than OBJ_LINE_MAX - 1 bytes or with a NUL is
 * refused with its line number, never split and its tail parsed as a line
 * of its own (a 64-vertex face "f v/vt/vn ..." with 7-digit indices is
 * about 1.5 KB, so the old 1024-byte fgets split legal lines too). */
#define OBJ_LINE_MAX 4096
static int obj_lines(FILE *f, char *line, const char *path, meshbuf_t *m, char *err, size_t errlen)
{
    unsigned ln = 0;
    int got;
    while ((got = tdc_read_line(f, line, OBJ_LINE_MAX, &ln)) != 0) {
        if (got < 0) {
            if (got == -2)
                snprintf(err, errlen, "%s: read error", path);
            else
                snprintf(err, errlen, "%s:%u: line longer than %d bytes or with a NUL byte", path, ln,
                         OBJ_LINE_MAX - 1);
            return -1;
        }
        if (line[0] == 'v' && line[1] == ' ') {
            double x, y, z;
            if (sscanf(line + 2, "%lf %lf %lf", &x, &y, &z) != 3 || !isfinite(x) || !isfinite(y) || !isfinite(z)) {
                snprintf(err, errlen, "%s:%u: bad vertex", path, ln);
                return -1;
            }
            if (mb_vertex(m, x, y, z) < 0) goto nomem;
        } else if (line[0] == 'f' && line[1] == ' ') {
            unsigned idx[64];
            int n = 0;
            char *p = line + 2;
            for (;;) {
                while (*p == ' ' || *p == '\t') p++;
                if (*p == '\0' || *p == '\n' || *p == '\r') break;
                char *end;
                long v = strtol(p, &end, 10);
                if (end == p || v == 0 || n == 64) {
                    snprintf(err, errlen, "%s:%u: bad face", path, ln);
                    return -1;
                }
                if (v < 0) v = (long)m->nv + v + 1;
                if (v < 1 || v > (long)m->nv) {
                    snprintf(err, errlen, "%s:%u: face index %ld out of range (1..%u)", path, ln, v, m->nv);
                    return -1;
                }
                idx[n++] = (unsigned)(v - 1);
                p = end;
                while (*p && *p != ' ' && *p != '\t' && *p != '\n' && *p != '\r') p++; /* skip /vt/vn */
            }
            if (n < 3) {
                snprintf(err, errlen, "%s:%u: face with fewer than 3 vertices", path, ln);
                return -1;
            }
            for (int k = 1; k + 1 < n; k++)
                if (mb_index(m, idx[0]) < 0 || mb_index(m, idx[k]) < 0 || mb_index(m, idx[k + 1]) < 0) goto nomem;
        }
    }
    if (m->ni == 0) {
        snprintf(err, errlen, "%s: no faces", path);
        return -1;
    }
    return 0;
nomem:
    snprintf(err, errlen, "%s: out of memory", path);
    return -1;
}

static int load_obj(const char *path, meshbuf_t *m, char *err, size_t errlen)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open mesh", path);
        return -1;
    }
    char *line = malloc(OBJ_LINE_MAX);
    int rc = -1;
    if (line)
        rc = obj_lines(f, line, path, m, err, errlen);
    else
        snprintf(err, errlen, "%s: out of memory", path);
    free(line);
    fclose(f);
    return rc;
}

int tdc_r_build_object(tdc_render_t *r, int i, char *err, size_t errlen)
{
    const tdc_object_t *o = &r->scene->objects[i];
    meshbuf_t m = {0};
    int quads = 0, rc = 0;
    RTCGeometry g;
    const double *p = o->p;
    switch (o->shape) {
    case TDC_SHAPE_SPHERE: {
        g = rtcNewGeometry(r->dev, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1);
        if (!v) goto embree_fail;
        v[0] = v[1] = v[2] = 0;
        v[3] = (float)p[0];
        r->obj[i].prims = 1;
        goto commit;
    }
    case TDC_SHAPE_RECT:
        quads = 1;
        rc |= mb_vertex(&m, -p[0] / 2, -p[1] / 2, 0) | mb_vertex(&m, p[0] / 2, -p[1] / 2, 0) |
              mb_vertex(&m, p[0] / 2, p[1] / 2, 0) | mb_vertex(&m, -p[0] / 2, p[1] / 2, 0);
        for (unsigned k = 0; k < 4; k++) rc |= mb_index(&m, k);
        break;
    case TDC_SHAPE_BOX:
        quads = 1;
        rc |= mb_box(&m, 0, 0, 0, p[0], p[1], p[2]);
        break;
    case TDC_SHAPE_FENCE:
        quads = 1;
        for (int k = 0; k < o->segments; k++) {
            double x = (k - (o->segments - 1) / 2.0) * (p[0] + p[1]);
            rc |= mb_box(&m, x, p[2] / 2, 0, p[0], p[2], p[3]);
        }
        break;
    case TDC_SHAPE_DISC:
        rc |= mb_vertex(&m, 0, 0, 0);
        for (int k = 0; k < o->segments; k++) {
            double a = 2 * M_PI * k / o->segments;
            rc |= mb_vertex(&m, p[0] * cos(a), p[0] * sin(a), 0);
        }
        for (int k = 0; k < o->segments; k++) {
            rc |= mb_index(&m, 0) | mb_index(&m, 1 + (unsigned)k);
            rc |= mb_index(&m, 1 + (unsigned)((k + 1) % o->segments));
        }
        break;
    case TDC_SHAPE_CYLINDER:
        for (int k = 0; k < o->segments; k++) {
            double a = 2 * M_PI * k / o->segments;
            rc |= mb_vertex(&m, p[0] * sin(a), 0, p[0] * cos(a)) | mb_vertex(&m, p[0] * sin(a), p[1], p[0] * cos(a));
        }
        for (int k = 0; k < o->segments; k++) {
            unsigned a0 = 2u * (unsigned)k, a1 = 2u * (unsigned)((k + 1) % o->segments);
            rc |= mb_index(&m, a0) | mb_index(&m, a1) | mb_index(&m, a0 + 1);
            rc |= mb_index(&m, a1) | mb_index(&m, a1 + 1) | mb_index(&m, a0 + 1);
        }
        break;
    case TDC_SHAPE_HEIGHTFIELD: {
        int n = o->segments;
        for (int z = 0; z <= n; z++)
            for (int x = 0; x <= n; x++) {
                double wx = (x / (double)n - 0.5) * p[0], wz = (z / (double)n - 0.5) * p[1];
                rc |= mb_vertex(&m, wx, terrain_height(wx, wz, p[2]), wz);
            }
        for (int z = 0; z < n; z++)
            for (int x = 0; x < n; x++) {
                unsigned a = (unsigned)(z * (n + 1) + x), b = a + 1, c = a + (unsigned)(n + 1), d = c + 1;
                rc |= mb_index(&m, a) | mb_index(&m, c) | mb_index(&m, b);
                rc |= mb_index(&m, b) | mb_index(&m, c) | mb_index(&m, d);
            }
        break;
    }
    case TDC_SHAPE_MESH:
        if (load_obj(o->path, &m, err, errlen) < 0) {
            free(m.v);
            free(m.ix);
            return -1;
        }
        break;
    default: snprintf(err, errlen, "object %s: unknown shape", o->name); return -1;
    }
    if (rc) {
        free(m.v);
        free(m.ix);
        snprintf(err, errlen, "object %s: out of memory", o->name);
        return -1;
    }
    {
        unsigned per = quads ? 4 : 3, nprim = m.ni / per;
        g = rtcNewGeometry(r->dev, quads ? RTC_GEOMETRY_TYPE_QUAD : RTC_GEOMETRY_TYPE_TRIANGLE);
        float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.nv);
        unsigned *ix = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, quads ? RTC_FORMAT_UINT4 : RTC_FORMAT_UINT3,
                                               per * sizeof(unsigned), nprim);
        if (!v || !ix) {
            free(m.v);
            free(m.ix);
            goto embree_fail;
        }
        memcpy(v, m.v, (size_t)m.nv * 3 * sizeof(float));
        memcpy(ix, m.ix, (size_t)nprim * per * sizeof(unsigned));
        free(m.v);
        free(m.ix);
        r->obj[i].prims = (uint64_t)nprim * (quads ? 2 : 1);
    }
commit:
    rtcCommitGeometry(g);
    r->obj[i].scene = rtcNewScene(r->dev);
    /* robust traversal: without it rays can slip through the shared edge of
     * the two triangles of a quad (seen along rect diagonals) */
    rtcSetSceneFlags(r->obj[i].scene, RTC_SCENE_FLAG_ROBUST);
    rtcAttachGeometry(r->obj[i].scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(r->obj[i].scene);
    if (rtcGetDeviceError(r->dev) != RTC_ERROR_NONE) {
        snprintf(err, errlen, "object %s: Embree error building its scene", o->name);
        return -1;
    }
    return 0;
embree_fail:
    rtcReleaseGeometry(g);
    snprintf(err, errlen, "object %s: Embree could not allocate its buffers", o->name);
    return -1;
}
