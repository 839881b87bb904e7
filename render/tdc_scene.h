/*
 * tdc_scene.h - scene description of the companion renderer: materials,
 * shapes, keyframed objects, lights and a keyframed camera.  Scenes are text
 * files (format: docs/renderer.md and render/scenes/README.md); built-in scenes
 * are the same text compiled in.  Host code (double precision).
 *
 * Units: world units are arbitrary (metres in the built-ins), times in
 * seconds, angles in degrees in the file and radians in memory.
 */
#ifndef TDC_SCENE_H
#define TDC_SCENE_H

#include <stddef.h>

#define TDC_SCENE_MAX_MATERIALS 64
#define TDC_SCENE_MAX_OBJECTS 256
#define TDC_SCENE_MAX_LIGHTS 16
#define TDC_SCENE_MAX_KEYS 64
#define TDC_SCENE_NAME_LEN 32
#define TDC_SCENE_TEXT_LEN 96
#define TDC_SCENE_PATH_LEN 512

typedef enum {
    TDC_TEX_NONE = 0,
    TDC_TEX_CHECKER, /* squares of side `scale` alternating diffuse / color2 */
    TDC_TEX_STRIPES, /* stripes of period `scale` along u (vertical stripes), half duty */
    TDC_TEX_TEXT,    /* 5x7 glyphs of `text`, glyph cell height `scale`, color2 ink on diffuse */
    TDC_TEX_SKYLINE  /* procedural city skyline for panoramas, building width `scale` */
} tdc_tex_kind_t;

typedef struct {
    char name[TDC_SCENE_NAME_LEN];
    double diffuse[3]; /* albedo (linear), or radiance when unlit */
    double color2[3];  /* second texture colour */
    double mirror;     /* reflectivity 0..1 (0 = no reflection ray) */
    double roughness;  /* GGX alpha of the reflection lobe, [0, 1]: 0 = perfect mirror (Zeng §4.2) */
    int unlit;         /* 1: radiance = texture colour, no lighting, no shadows */
    tdc_tex_kind_t tex;
    double tex_scale; /* world units (object space) */
    char text[TDC_SCENE_TEXT_LEN];
} tdc_material_t;

typedef enum {
    TDC_SHAPE_SPHERE = 0,  /* radius p[0]; Embree sphere point */
    TDC_SHAPE_RECT,        /* w p[0] x h p[1] in local XY, normal +Z; Embree quad */
    TDC_SHAPE_BOX,         /* sx p[0], sy p[1], sz p[2] centred; Embree quads */
    TDC_SHAPE_DISC,        /* radius p[0], `segments` triangles, local XY */
    TDC_SHAPE_CYLINDER,    /* radius p[0], height p[1] (y from 0), open, `segments` */
    TDC_SHAPE_FENCE,       /* `segments` slats: width p[0], gap p[1], height p[2], depth p[3]; boxes */
    TDC_SHAPE_HEIGHTFIELD, /* size p[0] x p[1] in XZ, `segments` cells per side, amplitude p[2] */
    TDC_SHAPE_MESH         /* triangles of an OBJ file `path` */
} tdc_shape_t;

/* A transform keyframe: translation, Euler rotation (radians, applied
 * X then Y then Z), uniform scale.  World = T * Rz * Ry * Rx * S * local. */
typedef struct {
    double t;
    double pos[3];
    double rot[3];
    double scale;
} tdc_xform_key_t;

typedef struct {
    char name[TDC_SCENE_NAME_LEN];
    tdc_shape_t shape;
    double p[4];
    int segments;
    char path[TDC_SCENE_PATH_LEN];
    int material;
    int nkeys; /* >= 1 (the placement is key 0 at t = 0) */
    tdc_xform_key_t keys[TDC_SCENE_MAX_KEYS];
    int line; /* line of the definition, for messages */
} tdc_object_t;

typedef enum { TDC_LIGHT_POINT = 0, TDC_LIGHT_RECT } tdc_light_kind_t;

typedef struct {
    char name[TDC_SCENE_NAME_LEN];
    tdc_light_kind_t kind;
    double intensity[3]; /* point: radiance of a white facing surface at distance 1 */
    double u[3], v[3];   /* rect: edge vectors, centred on the position */
    int samples;         /* rect: shadow samples per shading point (stratified) */
    int nkeys;
    struct {
        double t;
        double pos[3];
    } keys[TDC_SCENE_MAX_KEYS];
} tdc_light_t;

typedef struct {
    double t;
    double pos[3];
    double yaw, pitch; /* radians; yaw 0 looks along -Z, +yaw turns toward +X */
    double fov;        /* vertical field of view, radians */
} tdc_camera_key_t;

typedef struct {
    char name[64];
    int width, height;    /* default output size */
    double fps;           /* refresh rate: frame f is at time f / fps */
    double duration;      /* seconds (informational; animation clamps outside keys) */
    double background[3]; /* radiance of rays that miss */
    double ambient[3];    /* ambient irradiance factor added to lit surfaces */
    int nmaterials, nobjects, nlights, ncamkeys;
    tdc_material_t materials[TDC_SCENE_MAX_MATERIALS];
    tdc_object_t objects[TDC_SCENE_MAX_OBJECTS];
    tdc_light_t lights[TDC_SCENE_MAX_LIGHTS];
    tdc_camera_key_t cam[TDC_SCENE_MAX_KEYS];
} tdc_scene_t;

typedef enum {
    TDC_SCENE_OK = 0,
    TDC_SCENE_ERR_IO = -1,     /* file could not be read */
    TDC_SCENE_ERR_SYNTAX = -2, /* malformed file: message names the line */
    TDC_SCENE_ERR_NOMEM = -3,
    TDC_SCENE_ERR_UNKNOWN = -4 /* unknown built-in scene name */
} tdc_scene_status_t;

/* Parses scene text.  `src_name` is used in messages ("<src_name>:<line>:
 * <what>"), `base_dir` resolves relative mesh paths (NULL = cwd).  On error
 * returns a negative status with the message in err; *s is then unusable. */
tdc_scene_status_t tdc_scene_parse(const char *text, const char *src_name, const char *base_dir, tdc_scene_t *s,
                                   char *err, size_t errlen);
/* Reads and parses a scene file. */
tdc_scene_status_t tdc_scene_load(const char *path, tdc_scene_t *s, char *err, size_t errlen);
/* Built-in scenes (discs, text, panorama, room, mirror, fence, bigmesh, glossy, blocker). */
tdc_scene_status_t tdc_scene_builtin(const char *name, tdc_scene_t *s, char *err, size_t errlen);
/* The text of a built-in scene (NULL if unknown), and the list of names. */
const char *tdc_scene_builtin_text(const char *name);
extern const char *const tdc_scene_builtin_names[];
extern const int tdc_scene_builtin_count;

/* Animation evaluation at time t (clamped to the key range, linear between
 * keys).  m: row-major 3x4 object-to-world matrix. */
void tdc_scene_object_matrix(const tdc_object_t *o, double t, double m[12]);
void tdc_scene_light_pos(const tdc_light_t *l, double t, double pos[3]);
void tdc_scene_camera_at(const tdc_scene_t *s, double t, tdc_camera_key_t *out);
/* 1 if the object's / light's / camera's keys are not all equal. */
int tdc_scene_object_animated(const tdc_object_t *o);
int tdc_scene_light_animated(const tdc_light_t *l);
int tdc_scene_camera_animated(const tdc_scene_t *s);

#endif /* TDC_SCENE_H */
