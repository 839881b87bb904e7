/*
 * test_layers.c - behaviour of the layered tile assembly
 * (firmware/tdc_layers.h), each rule on a small hand-made stream:
 *   - a layer's own SHADOW vector is not overridden by a longer surface
 *     vector next to it; a SURFACE layer takes the 3x3 longest;
 *   - the shadow layer's history weight is the falloff G (G = 0: the new
 *     neighbours' mean; G = 1: the reprojected history);
 *   - 3-sigma clamps less than 1-sigma;
 *   - the clean-up runs only where history was clamped or down-weighted,
 *     and only when enabled;
 *   - splatting gives lit pixels next to a moving shadow its vector;
 *   - recombination: lit = shading, shadow darkens, glossy adds;
 *   - a static floor under a moving shadow keeps its texture (the point of
 *     layers: the single-colour path drags it);
 *   - errors: arguments, arena, panel, sequence, layers not kept.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "tdc_cmocka.h"

#include "golden/tdc_layer_content.h"
#include "tdc_layers.h"
#include "tdc_panels.h"

#define W 16
#define H 12
#define TX (W / 2)
#define TY (H / 2)
#define NT (TX * TY)

static uint64_t arena[TDC_LASM_MEM_BYTES(W, H) / 8 + 1];
static uint8_t val[TDC_LAYER_MAX][NT * 3];
static int16_t mvs[TDC_LAYER_MAX][NT * 2];
static uint16_t wts[NT];
static uint8_t pattern[TDC_PATTERN_BYTES(W, H)];
static tdc_layer_frame_t lf;
static tdc_lasm_t st;

#define SH TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING)
#define VI TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY)
#define GL TDC_LAYER_PKT_TYPE(TDC_LAYER_GLOSSY)

static void init(uint16_t layers, uint8_t k, uint8_t cleanup, uint8_t splat)
{
    tdc_lasm_config_t cfg = {W, H, layers, k, cleanup, splat, 0, 3277, &tdc_panel_htc_vive};
    assert_int_equal(tdc_lasm_init(&st, &cfg, arena, sizeof arena), TDC_OK);
    TDC_LAYER_FRAME_WIRE(lf, val, mvs, wts);
    memset(pattern, 0, sizeof pattern);
}

/* A packet header for the layer set, kinds by type. */
static void header(uint16_t present, const uint8_t kinds[TDC_LAYER_MAX])
{
    lf.present = present;
    lf.hdr.tiles_x = TX;
    lf.hdr.tiles_y = TY;
    lf.hdr.count = 0;
    for (unsigned t = 1; t <= TDC_LAYER_MAX; t++) {
        if (present & TDC_LAYER_PKT_TYPE(t)) {
            lf.hdr.type[lf.hdr.count] = (uint8_t)t;
            lf.hdr.mv_kind[lf.hdr.count] = kinds[t - 1];
            lf.hdr.count++;
        }
    }
}

static void step(uint32_t f)
{
    assert_int_equal(tdc_lasm_ingest(&st, f, &lf, pattern), TDC_OK);
    assert_int_equal(tdc_lasm_assemble(&st, f), TDC_OK);
}

static const uint8_t *layer(unsigned t)
{
    unsigned ch;
    return tdc_lasm_layer(&st, t, &ch);
}

static void test_errors(void **state)
{
    (void)state;
    tdc_lasm_config_t cfg = {W, H, SH | VI, 1, 1, 2, 0, 3277, &tdc_panel_htc_vive};
    assert_true(tdc_lasm_get_size(&cfg) <= TDC_LASM_MEM_BYTES(W, H));
    tdc_lasm_config_t all = cfg;
    all.layers = 0xF;
    assert_int_equal(tdc_lasm_get_size(&all), TDC_LASM_MEM_BYTES(W, H)); /* the bound is the full set */
    /* memory per pixel as stated: all layers 94 B/px, SHADING + VISIBILITY 48 B/px (+ rounding, tables) */
    assert_true(TDC_LASM_MEM_BYTES(W, H) >= (size_t)W * H * TDC_LASM_BYTES_PER_PIXEL_MAX);
    assert_true(TDC_LASM_MEM_BYTES(W, H) <= (size_t)W * H * TDC_LASM_BYTES_PER_PIXEL_MAX + 2048);
    assert_true(tdc_lasm_get_size(&cfg) <= (size_t)W * H * 48u + 2048);
    tdc_lasm_config_t bad = cfg;
    bad.layers = VI; /* no shading */
    assert_int_equal(tdc_lasm_get_size(&bad), 0);
    assert_int_equal(tdc_lasm_init(&st, &bad, arena, sizeof arena), TDC_ERR_ARG);
    bad = cfg;
    bad.clamp_k = 2;
    assert_int_equal(tdc_lasm_init(&st, &bad, arena, sizeof arena), TDC_ERR_ARG);
    bad = cfg;
    bad.splat_radius = TDC_LASM_SPLAT_MAX + 1;
    assert_int_equal(tdc_lasm_init(&st, &bad, arena, sizeof arena), TDC_ERR_ARG);
    bad = cfg;
    bad.width = TDC_LASM_MAX_DIM + 1;
    assert_int_equal(tdc_lasm_init(&st, &bad, arena, sizeof arena), TDC_ERR_ARG);
    assert_int_equal(tdc_lasm_init(&st, &cfg, (uint8_t *)arena + 4, sizeof arena - 8), TDC_ERR_ARG);
    assert_int_equal(tdc_lasm_init(&st, &cfg, arena, tdc_lasm_get_size(&cfg) - 8), TDC_ERR_SIZE);
    /* history: the bound is the full set with history, 148 B/px (+ rounding,
     * tables); it adds nothing when off; history > 1 and alpha 0 refused */
    tdc_lasm_config_t hall = all;
    hall.history = 1;
    assert_int_equal(tdc_lasm_get_size(&hall), TDC_LASM_MEM_BYTES_HIST(W, H));
    assert_true(TDC_LASM_MEM_BYTES_HIST(W, H) >= (size_t)W * H * TDC_LASM_HIST_BYTES_PER_PIXEL_MAX);
    assert_true(TDC_LASM_MEM_BYTES_HIST(W, H) <= (size_t)W * H * TDC_LASM_HIST_BYTES_PER_PIXEL_MAX + 2048);
    bad = hall;
    bad.history = 2;
    assert_int_equal(tdc_lasm_get_size(&bad), 0);
    bad = hall;
    bad.alpha_q15 = 0;
    assert_int_equal(tdc_lasm_get_size(&bad), 0);
    tdc_panel_t p10 = tdc_panel_htc_vive;
    p10.bits = 10;
    bad = cfg;
    bad.panel = &p10;
    assert_int_equal(tdc_lasm_init(&st, &bad, arena, sizeof arena), TDC_ERR_PANEL);

    init(SH | VI, 1, 0, 0);
    static const uint8_t k[4] = {TDC_LAYER_MV_SURFACE, TDC_LAYER_MV_SHADOW, TDC_LAYER_MV_GLOSSY, 1};
    header(SH | VI, k);
    assert_int_equal(tdc_lasm_ingest(&st, 1, &lf, pattern), TDC_ERR_FRAME);
    assert_int_equal(tdc_lasm_assemble(&st, 1), TDC_ERR_FRAME);
    header(SH | GL, k); /* glossy not kept */
    assert_int_equal(tdc_lasm_ingest(&st, 0, &lf, pattern), TDC_ERR_LAYER);
    header(SH | VI, k);
    lf.hdr.tiles_x = TX + 1;
    assert_int_equal(tdc_lasm_ingest(&st, 0, &lf, pattern), TDC_ERR_LAYER);
    header(SH | VI, k);
    assert_int_equal(tdc_lasm_ingest(&st, 0, &lf, pattern), TDC_OK);
    assert_int_equal(tdc_lasm_ingest(&st, 0, &lf, pattern), TDC_ERR_FRAME); /* twice */
    assert_int_equal(tdc_lasm_assemble(&st, 0), TDC_OK);
    assert_int_equal(tdc_lasm_assemble(&st, 1), TDC_OK); /* a lost subframe is allowed */
    assert_null(tdc_lasm_layer(&st, TDC_LAYER_GLOSSY, NULL));
    assert_null(tdc_lasm_layer(&st, 0, NULL));
}

/* Recombination: lit = shading; V = 0 = black; glossy adds light. */
static void test_recombine(void **state)
{
    (void)state;
    static const uint8_t k[4] = {TDC_LAYER_MV_SURFACE, TDC_LAYER_MV_SHADOW, TDC_LAYER_MV_GLOSSY, 1};
    init(SH | VI | GL, 1, 0, 0);
    header(SH | VI | GL, k);
    for (uint32_t f = 0; f < 4; f++) {
        for (int i = 0; i < NT; i++) {
            val[0][3 * i] = 200, val[0][3 * i + 1] = 100, val[0][3 * i + 2] = 50;
            val[1][i] = (i % TX) < TX / 2 ? 255 : 0; /* left lit, right in shadow */
            val[2][3 * i] = val[2][3 * i + 1] = val[2][3 * i + 2] = (i / TX) < TY / 2 ? 0 : 120;
        }
        memset(mvs, 0, sizeof mvs);
        step(f);
    }
    int stride;
    const uint8_t *o = tdc_lasm_output(&st, &stride);
    /* top-left: lit, no glossy: exactly the shading */
    assert_int_equal(o[0], 200);
    assert_int_equal(o[1], 100);
    assert_int_equal(o[2], 50);
    /* top-right: shadow, no glossy: black */
    const uint8_t *tr = o + (W - 1) * 3;
    assert_int_equal(tr[0] + tr[1] + tr[2], 0);
    /* bottom-right: shadow + glossy 120: the glossy code alone */
    const uint8_t *br = o + ((H - 1) * W + W - 1) * 3;
    assert_int_equal(br[0], 120);
    /* bottom-left: lit + glossy: brighter than shading alone, in every channel */
    const uint8_t *bl = o + (H - 1) * W * 3;
    assert_true(bl[0] > 200 && bl[1] > 100 && bl[2] > 50);
}

/* Moving bars of shadow over a static textured floor for 16 frames: with
 * layers + shadow vectors the floor texture stays where it is. */
static void test_floor_not_dragged(void **state)
{
    (void)state;
    tdc_lcontent_t c = {W, H, SH | VI, 0, 0, 18, 0, 0, 1, 0, 3};
    init(SH | VI, 3, 0, 2);
    for (uint32_t f = 0; f < 24; f++) {
        tdc_layer_content_subframe(&c, f, pattern, &lf);
        step(f);
    }
    /* the shading layer is the static floor: each pixel = its own sample (no motion) */
    tdc_lcontent_t c0 = c;
    uint8_t ref[W * H * 3];
    for (uint32_t f = 20; f < 24; f++) { /* the last cycle traced every pixel once */
        tdc_layer_content_subframe(&c0, f, pattern, &lf);
        for (int t = 0; t < NT; t++) {
            const unsigned pos = tdc_ordering_pixel(tdc_ordering_get(pattern, (uint32_t)t), f & 3u);
            const int px = 2 * (t % TX) + (int)(pos & 1u), py = 2 * (t / TX) + (int)(pos >> 1);
            memcpy(ref + (py * W + px) * 3, val[0] + 3 * t, 3);
        }
    }
    /* the window mean of 4 identical samples is the sample */
    assert_memory_equal(layer(TDC_LAYER_SHADING), ref, sizeof ref);
    assert_true(st.stats.reprojected > 0); /* the shadow layer did move */
}

/* Own vectors: a SHADOW-kind layer keeps a pixel's zero vector beside
 * moving ones; a SURFACE-kind layer takes the neighbour's longest. */
static void test_own_vector(void **state)
{
    (void)state;
    for (int kindi = 0; kindi < 2; kindi++) {
        const uint8_t k[4] = {TDC_LAYER_MV_SURFACE, kindi ? TDC_LAYER_MV_SHADOW : TDC_LAYER_MV_SURFACE, 1, 1};
        init(SH | VI, 1, 0, 0);
        header(SH | VI, k);
        /* frames 0..3: every pixel traced once, V = 255 everywhere; tile 0's
         * sample (frame 0: pixel (0,0)) carries a vector in frame 4 */
        for (uint32_t f = 0; f < 8; f++) {
            memset(mvs, 0, sizeof mvs);
            memset(val, 0, sizeof val);
            for (int i = 0; i < NT; i++) {
                val[1][i] = 255;
            }
            if (f == 4) {
                mvs[1][2 * 9] = 64; /* tile (1,1): pixel (2,2) moves */
            }
            step(f);
        }
        /* pixel (3,3) (tile (1,1), traced at frame 7) and (1,1): old static ones next to (2,2) */
        const uint64_t repro = st.stats.reprojected;
        if (kindi) {
            assert_int_equal(repro, 3); /* only (2,2) itself, old in frames 5, 6, 7 */
        } else {
            assert_true(repro > 4); /* the 3x3 rule spreads the vector */
        }
    }
}

/* Falloff: G = 0 on every sample makes an old shadow pixel the mean of its
 * new neighbours; G = 1 keeps the reprojected history. */
static void test_falloff(void **state)
{
    (void)state;
    static const uint8_t k[4] = {TDC_LAYER_MV_SURFACE, TDC_LAYER_MV_SHADOW, 1, 1};
    for (int gi = 0; gi < 2; gi++) {
        init(SH | VI, 3, 0, 0);
        header(SH | VI | TDC_LAYER_PKT_FALLOFF, k);
        for (uint32_t f = 0; f < 8; f++) {
            for (int i = 0; i < NT; i++) {
                /* history 40, then new samples 100 / 200 by tile column (mean 150, sigma 50) */
                val[1][i] = (uint8_t)(f < 4 ? 40 : ((i % TX) & 1 ? 100 : 200));
                mvs[1][2 * i] = 16;                        /* everything in moving shadow */
                mvs[1][2 * i + 1] = 0;
                wts[i] = gi ? TDC_LAYER_W_ONE : 0;
            }
            step(f);
            if (f == 4) {
                const uint8_t *v = layer(TDC_LAYER_VISIBILITY);
                /* pixel (3,3): old (traced at frame 3), all its new neighbours 200 */
                if (gi) {
                    /* G = 1: the reprojected history 40, inside the 3-sigma box [0, 300] */
                    assert_int_equal(v[3 * W + 3], 40);
                    assert_int_equal(st.stats.weighted, 0);
                } else {
                    /* G = 0: the new neighbours' mean */
                    assert_int_equal(v[3 * W + 3], 150);
                    assert_true(st.stats.weighted > 0);
                }
            }
        }
    }
}

/* 1 sigma clamps more than 3 sigma; clean-up only where clamped, only when on. */
static void test_clamp_and_cleanup(void **state)
{
    (void)state;
    uint64_t clamped[2], cleaned[2];
    for (int z = 0; z < 2; z++) {
        tdc_lcontent_t c = {W, H, SH | VI | GL, 0, 0, 18, 24, 8, 1, 0, 3};
        init(SH | VI | GL, z ? 3 : 1, 1, 2);
        for (uint32_t f = 0; f < 32; f++) {
            tdc_layer_content_subframe(&c, f, pattern, &lf);
            step(f);
        }
        clamped[z] = st.stats.clamped;
        cleaned[z] = st.stats.cleaned;
        assert_true(cleaned[z] > 0 && cleaned[z] <= st.stats.clamped + st.stats.weighted);
    }
    assert_true(clamped[1] < clamped[0]);
    tdc_lcontent_t c = {W, H, SH | VI | GL, 0, 0, 18, 24, 8, 1, 0, 3};
    init(SH | VI | GL, 1, 0, 2);
    for (uint32_t f = 0; f < 32; f++) {
        tdc_layer_content_subframe(&c, f, pattern, &lf);
        step(f);
    }
    assert_int_equal(st.stats.cleaned, 0);
    assert_true(st.stats.clamped > 0); /* clamped, but nothing cleaned (the history differs: clean-up feeds back) */
}

/* Splatting: a lit pixel next to in-shadow pixels with shadow vectors gets
 * their vector (and is reprojected), without splatting it stays static. */
static void test_splat(void **state)
{
    (void)state;
    uint64_t rep[2];
    for (int s = 0; s < 2; s++) {
        tdc_lcontent_t c = {W, H, SH | VI, 0, 0, 18, 0, 0, 1, 0, 3};
        init(SH | VI, 3, 0, s ? 2 : 0);
        for (uint32_t f = 0; f < 16; f++) {
            tdc_layer_content_subframe(&c, f, pattern, &lf);
            step(f);
        }
        rep[s] = st.stats.reprojected;
        if (s) {
            assert_true(st.stats.splatted > 0);
        } else {
            assert_int_equal(st.stats.splatted, 0);
        }
    }
    assert_true(rep[1] > rep[0]);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_errors),         cmocka_unit_test(test_recombine),
    cmocka_unit_test(test_floor_not_dragged), cmocka_unit_test(test_own_vector),
    cmocka_unit_test(test_falloff),        cmocka_unit_test(test_clamp_and_cleanup),
    cmocka_unit_test(test_splat),
)
