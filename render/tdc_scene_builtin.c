/*
 * tdc_scene_builtin.c - built-in scenes: the papers' stimuli, written in
 * the scene file format and parsed by the same parser as files
 * (`tdc-render --print-scene NAME` prints them).
 *
 *   discs     moving high-contrast discs (TRM stimuli), unlit white on black
 *   text      scrolling text (TDRT/TRM text stimuli)
 *   panorama  panned panorama: camera yaw inside a skyline cylinder
 *   room      room with thin vertical features (bottles, taps, chair legs)
 *             under a horizontal camera pan (TDRT), point + area light
 *   mirror    animated object over a mirror floor (TDRT Fig. 5/6)
 *   fence     fence moving in front of a light, its shadow moving over a
 *             static floor (Zeng et al. Fig. 1/10)
 *   bigmesh   generated heightfield of 524288 triangles, camera pan (throughput)
 *   glossy    glossy (GGX, roughness 0.08) checkered floor reflecting a moving
 *             ball and a turning cube, still camera (Zeng §4.2, Fig. 11)
 *   blocker   a block moving and turning under a small area light (one
 *             shadow ray per pixel) over a textured floor, in front of a
 *             striped wall, still camera: a moving soft shadow and
 *             disocclusions (Zeng §4.1, §4.3)
 */
#include "tdc_scene.h"

#include <stdio.h>
#include <string.h>

static const char scene_discs[] = "tdc-scene 1\n"
                                  "name discs\n"
                                  "resolution 640 360\n"
                                  "fps 240\n"
                                  "duration 2\n"
                                  "background 0 0 0\n"
                                  "ambient 0 0 0\n"
                                  "material white unlit diffuse 1 1 1\n"
                                  "material grey unlit diffuse 0.2 0.2 0.2\n"
                                  "camera 0 pos 0 0 10 look 0 0 0 fov 30\n"
                                  "object d1 disc radius 0.35 segments 96 material white pos -3.5 1.2 0\n"
                                  "key d1 0 pos -3.5 1.2 0\n"
                                  "key d1 2 pos 3.5 1.2 0\n"
                                  "object d2 disc radius 0.2 segments 96 material white pos 3.5 0 0\n"
                                  "key d2 0 pos 3.5 0 0\n"
                                  "key d2 2 pos -3.5 0 0\n"
                                  "object d3 disc radius 0.5 segments 96 material white pos -2 -1.4 0\n"
                                  "key d3 0 pos -2 -1.4 0\n"
                                  "key d3 2 pos 2 -0.6 0\n"
                                  "object d4 disc radius 0.25 segments 96 material grey pos 0 0 -0.01\n";

static const char scene_text[] = "tdc-scene 1\n"
                                 "name text\n"
                                 "resolution 640 360\n"
                                 "fps 240\n"
                                 "duration 2\n"
                                 "background 0 0 0\n"
                                 "material page unlit diffuse 0.9 0.9 0.9 text \"TEMPORALLY DENSE DISPLAY CONTROLLER "
                                 "0123456789 - READ ME!\" 0.2 0.02 0.02 0.02\n"
                                 "camera 0 pos 0 0 6 look 0 0 0 fov 30\n"
                                 "object page rect size 16 2.4 material page pos 4 0 0\n"
                                 "key page 0 pos 4 0 0\n"
                                 "key page 2 pos -4 0 0\n";

static const char scene_panorama[] = "tdc-scene 1\n"
                                     "name panorama\n"
                                     "resolution 640 360\n"
                                     "fps 240\n"
                                     "duration 2\n"
                                     "background 0.35 0.5 0.8\n"
                                     "material city unlit diffuse 0.3 0.3 0.33 skyline 0.8 0.35 0.5 0.8\n"
                                     "camera 0 pos 0 0 0 yaw -20 pitch 0 fov 50\n"
                                     "camera 2 yaw 20\n"
                                     "object drum cylinder radius 10 height 12 segments 256 material city pos 0 -6 0\n";

static const char scene_room[] =
    "tdc-scene 1\n"
    "name room\n"
    "resolution 640 360\n"
    "fps 240\n"
    "duration 2\n"
    "background 0 0 0\n"
    "ambient 0.08 0.08 0.08\n"
    "material wall diffuse 0.7 0.68 0.62\n"
    "material floor diffuse 0.5 0.4 0.3 checker 0.5 0.35 0.27 0.2\n"
    "material wood diffuse 0.45 0.28 0.15\n"
    "material glass diffuse 0.1 0.45 0.15\n"
    "material brown diffuse 0.35 0.2 0.05\n"
    "material chrome diffuse 0.2 0.2 0.2 mirror 0.7\n"
    "material poster diffuse 0.9 0.9 0.85 stripes 0.06 0.05 0.05 0.1\n"
    "camera 0 pos -1.2 1.3 2.6 yaw 0 pitch -12 fov 55\n"
    "camera 2 pos 1.2 1.3 2.6\n"
    "object room box size 8 3 8 material wall pos 0 1.5 0\n"
    "object floor rect size 7.98 7.98 material floor pos 0 0.001 0 rot -90 0 0\n"
    "object poster rect size 1.6 1 material poster pos 0 1.7 -3.99\n"
    "object table box size 2.4 0.06 1 material wood pos 0 0.8 -1\n"
    "object leg1 box size 0.05 0.77 0.05 material wood pos -1.1 0.385 -1.4\n"
    "object leg2 box size 0.05 0.77 0.05 material wood pos 1.1 0.385 -1.4\n"
    "object leg3 box size 0.05 0.77 0.05 material wood pos -1.1 0.385 -0.6\n"
    "object leg4 box size 0.05 0.77 0.05 material wood pos 1.1 0.385 -0.6\n"
    "object bottle1 cylinder radius 0.04 height 0.32 material glass pos -0.8 0.83 -1.1\n"
    "object bottle2 cylinder radius 0.035 height 0.28 material brown pos -0.55 0.83 -0.9\n"
    "object bottle3 cylinder radius 0.045 height 0.35 material glass pos -0.2 0.83 -1.2\n"
    "object neck1 cylinder radius 0.012 height 0.12 material glass pos -0.8 1.15 -1.1\n"
    "object neck3 cylinder radius 0.012 height 0.1 material glass pos -0.2 1.18 -1.2\n"
    "object tap1 cylinder radius 0.008 height 0.3 material chrome pos 0.3 0.83 -1.3\n"
    "object tap2 cylinder radius 0.008 height 0.3 material chrome pos 0.45 0.83 -1.3\n"
    "object chairleg1 box size 0.03 0.45 0.03 material wood pos 0.6 0.225 -0.2\n"
    "object chairleg2 box size 0.03 0.45 0.03 material wood pos 1.0 0.225 -0.2\n"
    "object chairleg3 box size 0.03 0.95 0.03 material wood pos 0.6 0.475 0.2\n"
    "object chairleg4 box size 0.03 0.95 0.03 material wood pos 1.0 0.475 0.2\n"
    "object seat box size 0.45 0.03 0.45 material wood pos 0.8 0.46 0\n"
    "object slat1 box size 0.02 0.45 0.02 material wood pos 0.7 0.7 0.2\n"
    "object slat2 box size 0.02 0.45 0.02 material wood pos 0.8 0.7 0.2\n"
    "object slat3 box size 0.02 0.45 0.02 material wood pos 0.9 0.7 0.2\n"
    "light lamp point pos 0 2.8 0 intensity 5 5 4.6\n"
    "light window rect pos -3.9 1.8 -1 u 0 0 1.2 v 0 0.8 0 intensity 2 2.2 2.5 samples 2\n";

/* The stage of `mirror` and `glossy` (everything but the floor material). */
#define MIRROR_STAGE                                                                                                   \
    "material ball diffuse 0.9 0.2 0.1 checker 0.25 0.95 0.95 0.9\n"                                                   \
    "material cube diffuse 0.1 0.3 0.9\n"                                                                              \
    "material wall diffuse 0.8 0.8 0.8 stripes 0.5 0.2 0.2 0.2\n"                                                      \
    "camera 0 pos 0 1.6 5 look 0 0.4 0 fov 45\n"                                                                       \
    "object floor rect size 10 10 material floor rot -90 0 0\n"                                                        \
    "object wall rect size 10 4 material wall pos 0 2 -4\n"                                                            \
    "object ball sphere radius 0.5 material ball pos -2.5 0.7 0\n"                                                     \
    "key ball 0 pos -2.5 0.7 0 rot 0 0 0\n"                                                                            \
    "key ball 1 pos 0 1.2 0.5 rot 0 0 -180\n"                                                                          \
    "key ball 2 pos 2.5 0.7 0 rot 0 0 -360\n"                                                                          \
    "object cube box size 0.6 0.6 0.6 material cube pos 1.5 0.5 -1.5\n"                                                \
    "key cube 0 rot 0 0 0\n"                                                                                           \
    "key cube 2 rot 0 180 0\n"                                                                                         \
    "light sun point pos 2 6 4 intensity 50 50 48\n"

static const char scene_mirror[] = "tdc-scene 1\n"
                                   "name mirror\n"
                                   "resolution 640 360\n"
                                   "fps 240\n"
                                   "duration 2\n"
                                   "background 0.3 0.4 0.6\n"
                                   "ambient 0.1 0.1 0.1\n"
                                   "material floor diffuse 0.05 0.05 0.05 mirror 0.9\n"
                                   MIRROR_STAGE;

static const char scene_fence[] =
    "tdc-scene 1\n"
    "name fence\n"
    "resolution 640 360\n"
    "fps 240\n"
    "duration 2\n"
    "background 0.05 0.05 0.08\n"
    "ambient 0.12 0.12 0.12\n"
    "material ground diffuse 0.8 0.8 0.78 checker 1 0.6 0.6 0.58\n"
    "material paint diffuse 0.7 0.15 0.1\n"
    "camera 0 pos 0 4 5 look 0 0 0.5 fov 45\n"
    "object floor rect size 12 12 material ground rot -90 0 0\n"
    "object fence fence slats 8 width 0.12 gap 0.18 height 1.2 depth 0.05 material paint pos -0.8 0.3 -1\n"
    "key fence 0 pos -0.8 0.3 -1\n"
    "key fence 2 pos 0.8 0.3 -1\n"
    "light lamp point pos 0 3 -3.5 intensity 20 20 19\n";

static const char scene_bigmesh[] = "tdc-scene 1\n"
                                    "name bigmesh\n"
                                    "resolution 640 360\n"
                                    "fps 240\n"
                                    "duration 2\n"
                                    "background 0.5 0.65 0.9\n"
                                    "ambient 0.1 0.1 0.1\n"
                                    "material terrain diffuse 0.35 0.55 0.2 checker 2 0.3 0.45 0.18\n"
                                    "camera 0 pos 0 7 20 yaw -15 pitch -18 fov 50\n"
                                    "camera 2 yaw 15\n"
                                    "object land heightfield size 40 40 cells 512 amplitude 1.5 material terrain\n"
                                    "light sun point pos 10 30 10 intensity 1100 1050 1000\n";

static const char scene_glossy[] = "tdc-scene 1\n"
                                   "name glossy\n"
                                   "resolution 640 360\n"
                                   "fps 240\n"
                                   "duration 2\n"
                                   "background 0.3 0.4 0.6\n"
                                   "ambient 0.1 0.1 0.1\n"
                                   "material floor diffuse 0.3 0.3 0.3 checker 0.5 0.12 0.12 0.12 mirror 0.6 roughness 0.08\n"
                                   MIRROR_STAGE;

static const char scene_blocker[] = "tdc-scene 1\n"
                                    "name blocker\n"
                                    "resolution 640 360\n"
                                    "fps 240\n"
                                    "duration 2\n"
                                    "background 0.05 0.05 0.08\n"
                                    "ambient 0.1 0.1 0.1\n"
                                    "material ground diffuse 0.8 0.8 0.78 checker 0.5 0.45 0.45 0.43\n"
                                    "material wall diffuse 0.7 0.7 0.7 stripes 0.4 0.35 0.35 0.35\n"
                                    "material block diffuse 0.2 0.5 0.8\n"
                                    "camera 0 pos 0 3 6 look 0 0.6 0 fov 45\n"
                                    "object floor rect size 12 12 material ground rot -90 0 0\n"
                                    "object wall rect size 12 4 material wall pos 0 2 -3\n"
                                    "object block box size 0.8 0.8 0.8 material block pos -2 1 0.5\n"
                                    "key block 0 pos -2 1 0.5 rot 0 0 0\n"
                                    "key block 2 pos 2 1 0.5 rot 0 90 0\n"
                                    "light panel rect pos 0 4 1 u 0.6 0 0 v 0 0 0.6 intensity 30 30 29 samples 1\n";

const char *const tdc_scene_builtin_names[] = {"discs",  "text",  "panorama", "room",   "mirror",
                                               "fence",  "bigmesh", "glossy", "blocker"};
const int tdc_scene_builtin_count = 9;

const char *tdc_scene_builtin_text(const char *name)
{
    static const char *const texts[] = {scene_discs, scene_text,    scene_panorama, scene_room,   scene_mirror,
                                        scene_fence, scene_bigmesh, scene_glossy,   scene_blocker};
    for (int i = 0; i < tdc_scene_builtin_count; i++)
        if (!strcmp(name, tdc_scene_builtin_names[i])) return texts[i];
    return NULL;
}

tdc_scene_status_t tdc_scene_builtin(const char *name, tdc_scene_t *s, char *err, size_t errlen)
{
    const char *text = tdc_scene_builtin_text(name);
    if (!text) {
        snprintf(err, errlen, "unknown built-in scene '%s' (discs text panorama room mirror fence bigmesh glossy blocker)", name);
        return TDC_SCENE_ERR_UNKNOWN;
    }
    char src[64];
    snprintf(src, sizeof src, "builtin:%s", name);
    return tdc_scene_parse(text, src, NULL, s, err, errlen);
}
