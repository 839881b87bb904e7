/*
 * test_render_scene.c - scene files (issue 6): the documented example and
 * every built-in scene parse and open; malformed files are rejected with a
 * message naming the file and line; keyframe evaluation.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tdc_cmocka.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/tdc_render.h"

static tdc_scene_t sc;

static void test_example_file(void **state)
{
    (void)state;
    char err[512];
    assert_int_equal(tdc_scene_load("render/scenes/example.scene", &sc, err, sizeof err), TDC_SCENE_OK);
    assert_string_equal(sc.name, "example");
    assert_int_equal(sc.nobjects, 6);
    assert_int_equal(sc.nlights, 2);
    assert_int_equal(sc.ncamkeys, 2);
    assert_int_equal(sc.width, 320);
    assert_true(sc.lights[1].kind == TDC_LIGHT_RECT && sc.lights[1].samples == 4);
    assert_true(sc.objects[2].shape == TDC_SHAPE_MESH);
    tdc_render_config_t cfg;
    tdc_render_default_config(&cfg);
    cfg.width = 32;
    cfg.height = 18;
    tdc_render_t *r = tdc_render_open(&sc, &cfg, err, sizeof err);
    assert_non_null(r);
    tdc_render_features_t f;
    tdc_render_get_features(r, &f);
    assert_true(f.mirrors && f.motion && f.camera_moves && f.objects_move && f.area_lights && f.moving_blocker);
    static float rgb[32 * 18 * 3];
    tdc_render_out_t out = {0};
    out.rgb = rgb;
    tdc_render_stats_t st;
    assert_int_equal(tdc_render_frame(r, 10, TDC_RENDER_FULL, &out, &st), 0);
    assert_true(st.ran[TDC_STAGE_REFLECT] && st.rays[TDC_RAY_REFLECT] > 0);
    tdc_render_close(r);
}

static void test_builtins(void **state)
{
    (void)state;
    char err[512];
    for (int i = 0; i < tdc_scene_builtin_count; i++) {
        const char *n = tdc_scene_builtin_names[i];
        if (tdc_scene_builtin(n, &sc, err, sizeof err) != TDC_SCENE_OK) fail_msg("%s: %s", n, err);
        tdc_render_config_t cfg;
        tdc_render_default_config(&cfg);
        cfg.width = 24;
        cfg.height = 16;
        tdc_render_t *r = tdc_render_open(&sc, &cfg, err, sizeof err);
        if (!r) fail_msg("%s: %s", n, err);
        tdc_render_features_t f;
        tdc_render_get_features(r, &f);
        printf("%-9s objects %3d triangles %7llu mirrors %d motion %d moving-blocker %d\n", n, sc.nobjects,
               (unsigned long long)f.triangles, f.mirrors, f.motion, f.moving_blocker);
        assert_true(f.motion); /* every stimulus moves */
        if (!strcmp(n, "bigmesh")) assert_true(f.triangles >= 500000);
        if (!strcmp(n, "mirror")) assert_true(f.mirrors);
        if (!strcmp(n, "fence")) assert_true(f.moving_blocker && !f.mirrors);
        if (!strcmp(n, "discs") || !strcmp(n, "text") || !strcmp(n, "panorama"))
            assert_true(!f.mirrors && !f.lights && !f.moving_blocker);
        static float rgb[24 * 16 * 3];
        tdc_render_out_t out = {0};
        out.rgb = rgb;
        assert_int_equal(tdc_render_frame(r, 3, TDC_RENDER_FULL, &out, NULL), 0);
        double sum = 0;
        for (int k = 0; k < 24 * 16 * 3; k++) {
            assert_true(isfinite(rgb[k]) && rgb[k] >= 0);
            sum += rgb[k];
        }
        assert_true(sum > 0); /* not black */
        tdc_render_close(r);
    }
}

/* Each bad file: expected line and a word of the message. */
static const struct {
    const char *text;
    int line;
    const char *needle;
} bad[] = {
    {"", 0, "empty scene"},
    {"tdc-scene 2\n", 1, "first line"},
    {"# c\n\ntdc-scene 1\nmaterial m\ncamera 0 pos 0 0 0\nobjekt a sphere radius 1 material m\n", 6, "unknown keyword"},
    {"tdc-scene 1\nfps 1.2.3\n", 2, "not a finite number"},
    {"tdc-scene 1\nfps -5\n", 2, "must be > 0"},
    {"tdc-scene 1\nresolution 640\n", 2, "usage"},
    {"tdc-scene 1\nresolution 0 100\n", 2, "integer"},
    {"tdc-scene 1\nbackground 1 1\n", 2, "usage"},
    {"tdc-scene 1\nmaterial m diffuse 1 -1 1\n", 2, "negative"},
    {"tdc-scene 1\nmaterial m mirror 2\n", 2, "[0, 1]"},
    {"tdc-scene 1\nmaterial m mirror 0.5 roughness 1.5\n", 2, "roughness must be in [0, 1]"},
    {"tdc-scene 1\nmaterial m mirror 0.5 roughness nan\n", 2, "number"},
    {"tdc-scene 1\nmaterial m roughness 0.2\n", 2, "needs a reflectivity"},
    {"tdc-scene 1\nmaterial m checker 0 1 1 1\n", 2, "> 0"},
    {"tdc-scene 1\nmaterial m text \"abc 1 1 1 1\n", 2, "unterminated"},
    {"tdc-scene 1\nmaterial m checker 1 1 1 1 stripes 1 1 1 1\n", 2, "more than one texture"},
    {"tdc-scene 1\nmaterial m shiny\n", 2, "unknown material attribute"},
    {"tdc-scene 1\nmaterial m\nmaterial m\n", 3, "defined twice"},
    {"tdc-scene 1\nobject a sphere radius 1 material nope\n", 2, "unknown material"},
    {"tdc-scene 1\nmaterial m\nobject a sphere radius -1 material m\n", 3, "> 0"},
    {"tdc-scene 1\nmaterial m\nobject a torus radius 1 material m\n", 3, "unknown shape"},
    {"tdc-scene 1\nmaterial m\nobject a box material m\n", 3, "needs 'size'"},
    {"tdc-scene 1\nmaterial m\nobject a box size 1 1 1\n", 3, "needs a material"},
    {"tdc-scene 1\nmaterial m\nobject a sphere radius 1 segments 5 material m\n", 3, "does not apply"},
    {"tdc-scene 1\nmaterial m\nobject a sphere radius 1 material m\nobject a sphere radius 1 material m\n", 4,
     "defined twice"},
    {"tdc-scene 1\nmaterial m\nobject a sphere radius 1 material m\nkey a 1 pos 0 0 0\nkey a 0.5 pos 1 1 1\n", 5,
     "must increase"},
    {"tdc-scene 1\nkey b 1 pos 0 0 0\n", 2, "unknown object"},
    {"tdc-scene 1\nmaterial m\nobject a sphere radius 1 material m\nkey a 1 spin 0 0 0\n", 4, "unknown key attribute"},
    {"tdc-scene 1\ncamera 0 look 0 0 -1\n", 2, "needs 'pos'"},
    {"tdc-scene 1\ncamera 0 pos 0 0 0 fov 180\n", 2, "fov"},
    {"tdc-scene 1\ncamera 0 pos 0 0 0 look 0 5 0\n", 2, "straight up"},
    {"tdc-scene 1\ncamera 1 pos 0 0 0\ncamera 1 pos 0 0 1\n", 3, "must increase"},
    {"tdc-scene 1\nlight l point intensity 1 1 1\n", 2, "needs 'pos'"},
    {"tdc-scene 1\nlight l spot pos 0 0 0 intensity 1 1 1\n", 2, "unknown light kind"},
    {"tdc-scene 1\nlight l rect pos 0 0 0 intensity 1 1 1 u 1 0 0\n", 2, "needs 'u' and 'v'"},
    {"tdc-scene 1\nlight l point pos 0 0 0 intensity 1 1 1\nlightkey l 0 pos 1 1\n", 3, "usage"},
    {"tdc-scene 1\nmaterial m\ncamera 0 pos 0 0 5\n", 3, "no objects"},
    {"tdc-scene 1\nmaterial m\nobject a sphere radius 1 material m\n", 3, "no camera"},
};

static void test_parser_errors(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char err[512], want[32];
        tdc_scene_status_t st = tdc_scene_parse(bad[i].text, "bad.scene", NULL, &sc, err, sizeof err);
        if (st != TDC_SCENE_ERR_SYNTAX) fail_msg("case %zu accepted: %s", i, bad[i].text);
        if (bad[i].line) {
            snprintf(want, sizeof want, "bad.scene:%d: ", bad[i].line);
            if (strncmp(err, want, strlen(want))) fail_msg("case %zu: '%s' does not start with '%s'", i, err, want);
        }
        if (!strstr(err, bad[i].needle)) fail_msg("case %zu: '%s' lacks '%s'", i, err, bad[i].needle);
    }
    printf("%zu malformed scenes rejected with line-numbered messages\n", sizeof bad / sizeof bad[0]);
}

static void write_file(const char *path, const char *text, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(text, 1, n, f), n);
    fclose(f);
}

static void test_file_errors(void **state)
{
    (void)state;
    char err[512];
    assert_int_equal(tdc_scene_load("/nonexistent/x.scene", &sc, err, sizeof err), TDC_SCENE_ERR_IO);
    assert_non_null(strstr(err, "cannot open"));
    char path[] = "/tmp/tdc_scene_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    write_file(path, "tdc-scene 1\n\0junk", 17);
    assert_int_equal(tdc_scene_load(path, &sc, err, sizeof err), TDC_SCENE_ERR_SYNTAX);
    assert_non_null(strstr(err, "NUL"));
    /* OBJ problems surface when the renderer builds the mesh */
    const char *scene =
        "tdc-scene 1\nmaterial m\ncamera 0 pos 0 0 5\nobject a mesh file /tmp/tdc_missing.obj material m\n";
    assert_int_equal(tdc_scene_parse(scene, "s", NULL, &sc, err, sizeof err), TDC_SCENE_OK);
    tdc_render_config_t cfg;
    tdc_render_default_config(&cfg);
    cfg.width = 8;
    cfg.height = 8;
    assert_null(tdc_render_open(&sc, &cfg, err, sizeof err));
    assert_non_null(strstr(err, "cannot open mesh"));
    write_file(path, "v 0 0 0\nv 1 0 0\nf 1 2 7\n", 24);
    char text[256];
    snprintf(text, sizeof text, "tdc-scene 1\nmaterial m\ncamera 0 pos 0 0 5\nobject a mesh file %s material m\n",
             path);
    assert_int_equal(tdc_scene_parse(text, "s", NULL, &sc, err, sizeof err), TDC_SCENE_OK);
    assert_null(tdc_render_open(&sc, &cfg, err, sizeof err));
    assert_non_null(strstr(err, ":3: face index 7 out of range"));
    /* a comment line over the reader's 4095 bytes whose tail, at 5 x 1023
     * bytes (where the old 1024-byte fgets split it), reads as a face:
     * refused with its line number, never split into a line "f 1 2 9" */
    {
        static char obj[8000];
        size_t n = (size_t)snprintf(obj, sizeof obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
        const size_t start = n;
        obj[n++] = '#';
        while (n < start + 5u * 1023u) obj[n++] = ' ';
        n += (size_t)snprintf(obj + n, sizeof obj - n, "f 1 2 9\nf 1 2 3\n");
        write_file(path, obj, n);
        assert_null(tdc_render_open(&sc, &cfg, err, sizeof err));
        assert_non_null(strstr(err, ":4: line longer than 4095 bytes"));
        /* a legal face line over the old 1024-byte limit: 64 vertices */
        n = 0;
        for (int k = 0; k < 64; k++)
            n += (size_t)snprintf(obj + n, sizeof obj - n, "v %d %d 0.000000000000\n", k % 8, k / 8);
        const size_t face = n;
        n += (size_t)snprintf(obj + n, sizeof obj - n, "f");
        for (int k = 0; k < 64; k++)
            n += (size_t)snprintf(obj + n, sizeof obj - n, " %d/%d/%d", k + 1, 1000000, 1000000);
        assert_true(n - face > 1024); /* the face line alone: 1089 bytes */
        n += (size_t)snprintf(obj + n, sizeof obj - n, "\n");
        write_file(path, obj, n);
        tdc_render_t *r = tdc_render_open(&sc, &cfg, err, sizeof err);
        assert_non_null(r);
        tdc_render_close(r);
    }
    remove(path);
    /* bad configuration */
    cfg.threads = 0;
    assert_null(tdc_render_open(&sc, &cfg, err, sizeof err));
}

static void test_keyframes(void **state)
{
    (void)state;
    char err[256];
    const char *t = "tdc-scene 1\nmaterial m\ncamera 0 pos 0 0 5 yaw 0\ncamera 2 pos 2 0 5 yaw 90\n"
                    "object a sphere radius 1 material m pos 1 2 3\nkey a 1 pos 0 0 0 scale 2\nkey a 3 pos 4 0 0\n";
    assert_int_equal(tdc_scene_parse(t, "k", NULL, &sc, err, sizeof err), TDC_SCENE_OK);
    double m[12];
    tdc_scene_object_matrix(&sc.objects[0], 0, m); /* clamped to the first key */
    assert_true(fabs(m[3]) < 1e-12 && fabs(m[0] - 2) < 1e-12);
    tdc_scene_object_matrix(&sc.objects[0], 2, m); /* halfway: scale carried over */
    assert_true(fabs(m[3] - 2) < 1e-12 && fabs(m[0] - 2) < 1e-12);
    tdc_scene_object_matrix(&sc.objects[0], 9, m);
    assert_true(fabs(m[3] - 4) < 1e-12);
    tdc_camera_key_t c;
    tdc_scene_camera_at(&sc, 1, &c);
    assert_true(fabs(c.pos[0] - 1) < 1e-12 && fabs(c.yaw - M_PI / 4) < 1e-12);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_example_file), cmocka_unit_test(test_builtins),  cmocka_unit_test(test_parser_errors),
    cmocka_unit_test(test_file_errors),  cmocka_unit_test(test_keyframes),
)
