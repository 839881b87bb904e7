/*
 * test_render_stream.c - renderer -> link encoder -> .tdcs file -> firmware
 * link decoder (issue 6): every packet of full, TRM and subframe streams is
 * accepted, the decoded pixels and motion vectors are the renderer's, and a
 * static scene's stream says static (no motion flag, no MOTION packets).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tdc_cmocka.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "render/tdc_render.h"
#include "render/tdc_render_stream.h"
#include "tdc_link.h"
#include "test_link_util.h"

#define W 33 /* odd sizes: partial tiles, reduced size rounding */
#define H 25
#define TX ((W + 1) / 2)
#define TY ((H + 1) / 2)

static tdc_scene_t sc;
static uint8_t staging[TDC_LINK_STAGING_LAYERS_BYTES(W, H) + TDC_LINK_STAGING_BYTES(W, H)];
static uint8_t dfull[W * H * 3], dred[W * H * 3], dsub[TX * TY * 3], dpat[TDC_PATTERN_BYTES(W, H)];
static int16_t dmv[W * H * 2], dsmv[TX * TY * 2];
/* the decoder's layer planes (layered streams) */
static uint8_t dlval[TDC_LAYER_MAX][TX * TY * 3];
static int16_t dlmv[TDC_LAYER_MAX][TX * TY * 2];
static uint16_t dlw[TX * TY];
static tdc_layer_frame_t dlayers;

/* Feeds the whole file; returns packets accepted, counts per kind. */
static uint32_t decode_file(const char *path, uint32_t by_kind[TDC_LINK_KIND_LAST + 1], uint32_t *errors)
{
    static tdc_link_decoder_t dec;
    tdc_link_config_t cfg = {W, H, 1};
    tdc_link_buffers_t b = lt_buffers(staging, sizeof staging);
    b.full[0] = dfull;
    b.full_stride = W * 3;
    b.reduced[0] = dred;
    b.reduced_bytes = sizeof dred;
    b.subframe[0] = dsub;
    b.motion[0] = dmv;
    b.sample_motion[0] = dsmv;
    b.pattern[0] = dpat;
    for (int t = 0; t < TDC_LAYER_MAX; t++) {
        dlayers.value[t] = dlval[t];
        dlayers.mv[t] = dlmv[t];
    }
    dlayers.falloff = dlw;
    b.layers[0] = &dlayers;
    assert_int_equal(tdc_link_decoder_init(&dec, &cfg, &b), TDC_OK);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    static uint8_t buf[1 << 20];
    size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    size_t off = 0;
    while (off < n) {
        tdc_link_event_t ev;
        off += tdc_link_feed(&dec, buf + off, n - off, &ev);
    }
    const tdc_link_counters_t *c = tdc_link_counters(&dec);
    *errors = 0;
    for (int e = 1; e < TDC_LINK_ERR_COUNT; e++) *errors += c->errors[e];
    memcpy(by_kind, c->packets_by_kind, sizeof c->packets_by_kind);
    return c->packets_ok;
}

/* Built-in scene name at W x H; layered: with the shadow and dual vectors
 * the layers need, indirect light when indirect. */
static tdc_render_t *open_scene(const char *name, int layered, int indirect)
{
    char err[256];
    assert_int_equal(tdc_scene_builtin(name, &sc, err, sizeof err), TDC_SCENE_OK);
    tdc_render_config_t cfg;
    tdc_render_default_config(&cfg);
    cfg.width = W;
    cfg.height = H;
    cfg.shadow_mv = cfg.dual_mv = layered;
    cfg.indirect = indirect;
    tdc_render_t *r = tdc_render_open(&sc, &cfg, err, sizeof err);
    assert_non_null(r);
    return r;
}

static void run(tdc_rstream_kind_t kind, const char *scene, int frames, const uint32_t expect[TDC_LINK_KIND_LAST + 1],
                uint32_t *flags)
{
    char path[] = "/tmp/tdc_rstream_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    tdc_render_t *r = open_scene(scene, 0, 0);
    char err[256];
    tdc_render_stream_t *s = tdc_render_stream_create(path, r, kind, err, sizeof err);
    if (!s) fail_msg("%s", err);
    *flags = tdc_render_stream_flags(s);
    static float rgb[W * H * 3];
    static int16_t mv[W * H * 2];
    static uint8_t last8[W * H * 3];
    static int16_t lastmv[W * H * 2];
    int have_full = 0;
    for (int f = 0; f < frames; f++) {
        tdc_render_mode_t m = kind == TDC_RSTREAM_SUBFRAMES ? TDC_RENDER_SUBFRAME
                              : kind == TDC_RSTREAM_TRM && tdc_link_trm_kind((uint32_t)f, 0) == TDC_LINK_KIND_REDUCED
                                  ? TDC_RENDER_REDUCED
                                  : TDC_RENDER_FULL;
        tdc_render_out_t out = {0};
        out.rgb = rgb;
        out.mv = mv;
        assert_int_equal(tdc_render_frame(r, (uint32_t)f, m, &out, NULL), 0);
        assert_int_equal(tdc_render_stream_frame(s, (uint32_t)f, m, rgb, m == TDC_RENDER_REDUCED ? NULL : mv), 0);
        if (m == TDC_RENDER_FULL) {
            tdc_render_linear_to_rgb888(rgb, W * H, last8);
            memcpy(lastmv, mv, sizeof mv);
            have_full = 1;
        }
    }
    uint32_t np;
    uint64_t nb;
    assert_int_equal(tdc_render_stream_close(s, &np, &nb), 0);
    uint32_t kinds[TDC_LINK_KIND_LAST + 1], errors;
    uint32_t ok = decode_file(path, kinds, &errors);
    printf("%-9s kind %d: %u packets, %llu bytes written; decoder accepted %u, errors %u; flags 0x%04x\n", scene,
           (int)kind, np, (unsigned long long)nb, ok, errors, *flags);
    assert_int_equal(errors, 0);
    assert_int_equal(ok, np);
    for (int k = TDC_LINK_KIND_FIRST; k <= TDC_LINK_KIND_LAST; k++) assert_int_equal(kinds[k], expect[k]);
    if (have_full && kind == TDC_RSTREAM_FULL) {
        assert_memory_equal(dfull, last8, sizeof last8);
        if (*flags & TDC_LINK_STREAM_MOTION) assert_memory_equal(dmv, lastmv, sizeof lastmv);
    }
    remove(path);
    tdc_render_close(r);
}

/* One stream kind written by the renderer and read back: the packets of each
 * kind it must hold and the stream flags it must set. */
typedef struct {
    tdc_rstream_kind_t kind;
    const char *scene;
    int frames;
    uint32_t expect[TDC_LINK_KIND_LAST + 1];
    uint32_t flags;
} stream_case_t;

static stream_case_t k_full = {TDC_RSTREAM_FULL, "fence", 6,
                               {[TDC_LINK_KIND_STREAM] = 1, [TDC_LINK_KIND_FULL] = 6, [TDC_LINK_KIND_MOTION] = 6},
                               TDC_LINK_STREAM_MOTION};
static stream_case_t k_trm = {TDC_RSTREAM_TRM, "mirror", 6,
                              {[TDC_LINK_KIND_STREAM] = 1, [TDC_LINK_KIND_FULL] = 3, [TDC_LINK_KIND_REDUCED] = 3,
                               [TDC_LINK_KIND_MOTION] = 3},
                              TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_MIRRORS};
static stream_case_t k_subframes = {TDC_RSTREAM_SUBFRAMES, "discs", 8,
                                    {[TDC_LINK_KIND_STREAM] = 1, [TDC_LINK_KIND_SUBFRAME] = 8,
                                     [TDC_LINK_KIND_PATTERN] = 2, [TDC_LINK_KIND_MOTION] = 8},
                                    TDC_LINK_STREAM_SUBFRAMES | TDC_LINK_STREAM_SAMPLE_MV};

static void test_stream(void **state)
{
    const stream_case_t *c = *state;
    uint32_t flags;
    run(c->kind, c->scene, c->frames, c->expect, &flags);
    assert_int_equal(flags & c->flags, c->flags);
}

static void test_static_stream(void **state)
{
    (void)state;
    char path[] = "/tmp/tdc_rstream_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    char err[256];
    assert_int_equal(tdc_scene_parse("tdc-scene 1\nmaterial m checker 0.2 0 0 0\ncamera 0 pos 0 0 5\n"
                                     "object a sphere radius 1 material m\nlight l point pos 0 3 3 intensity 9 9 9\n",
                                     "static", NULL, &sc, err, sizeof err),
                     TDC_SCENE_OK);
    tdc_render_config_t cfg;
    tdc_render_default_config(&cfg);
    cfg.width = W;
    cfg.height = H;
    tdc_render_t *r = tdc_render_open(&sc, &cfg, err, sizeof err);
    assert_non_null(r);
    tdc_render_stream_t *s = tdc_render_stream_create(path, r, TDC_RSTREAM_FULL, err, sizeof err);
    assert_non_null(s);
    assert_int_equal(tdc_render_stream_flags(s) & TDC_LINK_STREAM_MOTION, 0);
    static float rgb[W * H * 3];
    static int16_t mv[W * H * 2];
    for (uint32_t f = 0; f < 3; f++) {
        tdc_render_out_t out = {0};
        out.rgb = rgb;
        out.mv = mv;
        tdc_render_stats_t st;
        assert_int_equal(tdc_render_frame(r, f, TDC_RENDER_FULL, &out, &st), 0);
        assert_int_equal(st.frame_static, 1);
        assert_int_equal(st.ran[TDC_STAGE_MV], 0);
        assert_int_equal(tdc_render_stream_frame(s, f, TDC_RENDER_FULL, rgb, mv), 0);
    }
    uint32_t np;
    assert_int_equal(tdc_render_stream_close(s, &np, NULL), 0);
    assert_int_equal(np, 4); /* STREAM + 3 FULL, no MOTION */
    uint32_t kinds[TDC_LINK_KIND_LAST + 1], errors;
    assert_int_equal(decode_file(path, kinds, &errors), 4);
    assert_int_equal(errors, 0);
    assert_int_equal(kinds[TDC_LINK_KIND_MOTION], 0);
    remove(path);
    tdc_render_close(r);
}

/* Layered subframes (issue 16): one LAYERS packet per subframe with the
 * layers the scene needs; every packet accepted by the firmware decoder,
 * the decoded planes of the last frame are the renderer's layers. */
static void layered(const char *scene, int frames, uint32_t want_set, int indirect)
{
    char path[] = "/tmp/tdc_rstream_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    char err[256];
    tdc_render_t *r = open_scene(scene, 1, indirect);
    tdc_render_stream_t *s = tdc_render_stream_create(path, r, TDC_RSTREAM_LAYERS, err, sizeof err);
    if (!s) fail_msg("%s", err);
    uint32_t set = tdc_render_stream_layer_set(s), flags = tdc_render_stream_flags(s);
    assert_int_equal(set, want_set);
    assert_true((flags & TDC_LINK_STREAM_LAYERS) && (flags & TDC_LINK_STREAM_SUBFRAMES));
    static float rgb[TX * TY * 3], sh[TX * TY * 3], vis[TX * TY], refl[TX * TY * 3], ind[TX * TY * 3], sw[TX * TY];
    static int16_t mv[TX * TY * 2], msf[TX * TY * 2], mrf[TX * TY * 2], msh[TX * TY * 2], mdu[TX * TY * 2];
    static uint8_t src[TX * TY];
    tdc_render_out_t out = {.rgb = rgb,
                            .mv = mv,
                            .mv_shadow = msh,
                            .shadow_weight = sw,
                            .mv_dual = mdu,
                            .shade = sh,
                            .vis = vis,
                            .refl = refl,
                            .mv_surf = msf,
                            .mv_refl = mrf,
                            .shadow_src = src,
                            .indirect = ind};
    for (int f = 0; f < frames; f++) {
        assert_int_equal(tdc_render_frame(r, 200 + (uint32_t)f, TDC_RENDER_SUBFRAME, &out, NULL), 0);
        assert_int_equal(tdc_render_stream_layers(s, 200 + (uint32_t)f, &out), 0);
    }
    uint32_t np;
    uint64_t nb;
    assert_int_equal(tdc_render_stream_close(s, &np, &nb), 0);
    uint32_t kinds[TDC_LINK_KIND_LAST + 1], errors;
    uint32_t ok = decode_file(path, kinds, &errors);
    printf("%-8s layered: layer set 0x%02x, %u packets, %llu bytes (%.2f B per sample per frame); decoder accepted "
           "%u, errors %u\n",
           scene, set, np, (unsigned long long)nb, (double)nb / (frames * TX * TY), ok, errors);
    assert_int_equal(errors, 0);
    assert_int_equal(ok, np);
    assert_int_equal(kinds[TDC_LINK_KIND_LAYERS], frames);
    assert_int_equal(kinds[TDC_LINK_KIND_SUBFRAME] + kinds[TDC_LINK_KIND_MOTION], 0);
    /* the last frame's planes */
    const int n = TX * TY;
    static uint8_t e8[TX * TY * 3];
    if (set & TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY)) {
        tdc_render_linear_to_rgb888(sh, n, e8);
        assert_memory_equal(dlval[TDC_LAYER_SHADING - 1], e8, n * 3);
        int shadowed = 0;
        for (int i = 0; i < n; i++) {
            assert_int_equal(dlval[TDC_LAYER_VISIBILITY - 1][i], (int)(vis[i] * 255 + 0.5f));
            const int16_t *want = src[i] ? &msh[2 * i] : &msf[2 * i];
            assert_int_equal(dlmv[TDC_LAYER_VISIBILITY - 1][2 * i], want[0]);
            assert_int_equal(dlmv[TDC_LAYER_VISIBILITY - 1][2 * i + 1], want[1]);
            assert_true(dlw[i] <= 32768 && (src[i] || dlw[i] == 32768));
            shadowed += src[i];
        }
        assert_true(shadowed > 0);
    }
    if (set & TDC_LAYER_PKT_TYPE(TDC_LAYER_GLOSSY)) {
        tdc_render_linear_to_rgb888(refl, n, e8);
        assert_memory_equal(dlval[TDC_LAYER_GLOSSY - 1], e8, n * 3);
        assert_memory_equal(dlmv[TDC_LAYER_GLOSSY - 1], mrf, n * 4);
    }
    if (set & TDC_LAYER_PKT_TYPE(TDC_LAYER_INDIRECT)) {
        tdc_render_linear_to_rgb888(ind, n, e8);
        assert_memory_equal(dlval[TDC_LAYER_INDIRECT - 1], e8, n * 3);
    }
    if (set == TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING)) { /* one layer: the frame itself */
        tdc_render_linear_to_rgb888(rgb, n, e8);
        assert_memory_equal(dlval[TDC_LAYER_SHADING - 1], e8, n * 3);
    }
    remove(path);
    tdc_render_close(r);
}

static void test_layered_streams(void **state)
{
    (void)state;
    const uint32_t SH = TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING), VI = TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY),
                   GL = TDC_LAYER_PKT_TYPE(TDC_LAYER_GLOSSY), IN = TDC_LAYER_PKT_TYPE(TDC_LAYER_INDIRECT),
                   FO = TDC_LAYER_PKT_FALLOFF;
    layered("blocker", 5, SH | VI | FO, 0);
    layered("glossy", 5, SH | VI | FO | GL, 0);
    layered("blocker", 3, SH | VI | FO | IN, 1);
    layered("discs", 5, SH, 0); /* no shadows, no reflections: one layer */
}

TDC_TEST_MAIN(
    cmocka_unit_test_prestate(test_stream, &k_full),
    cmocka_unit_test_prestate(test_stream, &k_trm),
    cmocka_unit_test_prestate(test_stream, &k_subframes),
    cmocka_unit_test(test_static_stream),
    cmocka_unit_test(test_layered_streams),
)
