/*
 * golden_trmgaze.c - bit-exact golden vectors of gaze-aware TRM in its on
 * state (firmware/tdc_trm_gaze.h): contents x sizes x ratios x gaze maps,
 * full/reduced pairs, one checksum per output frame (FNV-1a 64 over the
 * drive codes, the full frames' recomputed rho and the reduced frame's
 * input).  The off state is TRM's own vectors (golden_trm.c), unchanged.
 * Freestanding, static buffers.
 */
#include "golden.h"
#include "golden_trm.h"
#include "tdc_content.h"
#include "tdc_panels.h"
#include "tdc_trm.h"
#include "tdc_trm_gaze.h"

#define GW_MAX 64
#define GH_MAX 48
#define GT 8u /* tile of these vectors: several tiles even at 17 x 9 */

static uint64_t g_arena[TDC_TRM_MEM_BYTES(GW_MAX, GH_MAX, 1, 1) / 8u + 1u];
static uint64_t g_garena[TDC_TRM_GAZE_MEM_BYTES(GW_MAX, GH_MAX, GT) / 8u + 1u];
static uint8_t g_in[GW_MAX * GH_MAX * 3];
static uint8_t g_out[GW_MAX * GH_MAX * 3];
static uint8_t g_red[GW_MAX * GH_MAX * 3];
static tdc_res_t g_rho_row[GW_MAX * 3];
static int16_t g_mv[2u * TDC_TRM_GAZE_TILES_X(GW_MAX, GT) * TDC_TRM_GAZE_TILES_Y(GH_MAX, GT)];

/* Gaze maps: FIX fixed gaze on content moving 3 px/frame (k = kmin
 * everywhere), RAMP tile motions from 0 to 2.5 px/frame across the frame
 * with the gaze tracking the slowest (every k of the ramp), DRIFT motion
 * and gaze differing by 1 px/frame (k between). */
enum { MAP_FIX, MAP_RAMP, MAP_DRIFT };
static const char *const k_map_names[] = {"fix", "ramp", "drift"};

static void fill_map(int map, uint32_t tx, uint32_t ty, int16_t *gx, int16_t *gy)
{
    for (uint32_t j = 0; j < ty; j++) {
        for (uint32_t i = 0; i < tx; i++) {
            int16_t *p = &g_mv[2u * (j * tx + i)];
            if (map == MAP_FIX) {
                p[0] = 48; /* 3 px/frame */
                p[1] = 0;
            } else if (map == MAP_RAMP) {
                p[0] = (int16_t)(40u * i / (tx > 1u ? tx - 1u : 1u)); /* 0 .. 2.5 px/frame */
                p[1] = (int16_t)(-8 * (int32_t)(j & 1u));
            } else {
                p[0] = 16;
                p[1] = 16;
            }
        }
    }
    *gx = 0;
    *gy = (int16_t)(map == MAP_DRIFT ? 8 : 0);
}

typedef struct {
    tdc_content_t content;
    uint16_t w, h, rn, rd;
    int map;
    uint16_t kmin_q15;
    const tdc_panel_t *panel;
} gaze_vector_t;

static void run_vector(tdc_golden_ctx_t *ctx, const gaze_vector_t *v)
{
    char name[80];
    char *o = tdc_golden_put_head(name, tdc_content_name(v->content), v->w, v->h, v->rn, v->rd);
    *o++ = '-';
    o = tdc_golden_put_str(o, k_map_names[v->map]);
    o = tdc_golden_put_str(o, "-kmin");
    o = tdc_golden_put_u32(o, v->kmin_q15);
    tdc_golden_put_panel(o, v->panel->name);

    tdc_trm_config_t cfg;
    tdc_golden_trm_config(&cfg, v->w, v->h, v->rn, v->rd);
    tdc_trm_gaze_config_t gc;
    tdc_trm_gaze_default_config(&gc, v->w, v->h);
    gc.tile = GT;
    gc.kmin_q15 = v->kmin_q15;
    tdc_trm_t trm;
    tdc_trm_gaze_t gaze;
    if (tdc_trm_init(&trm, &cfg, v->panel, g_arena, sizeof g_arena) != TDC_OK ||
        tdc_trm_gaze_init(&gaze, &gc, g_garena, sizeof g_garena) != TDC_OK || tdc_trm_set_gaze(&trm, &gaze) != TDC_OK) {
        tdc_golden_emit(ctx, "trmgaze", name, 0, 0); /* shows as a mismatch */
        return;
    }
    int16_t gx, gy;
    fill_map(v->map, gaze.tx, gaze.ty, &gx, &gy);
    const uint32_t stride = 3u * v->w;
    for (uint32_t t = 0; t < 6u; t++) {
        tdc_content_frame(v->content, t, 11u, g_in, v->w, v->h, (int)stride);
        int ok = 1;
        if ((t & 1u) == 0u) {
            ok &= tdc_trm_gaze_update(&gaze, g_mv, gaze.tx * gaze.ty, gx, gy) == TDC_OK;
        }
        const uint64_t h = tdc_golden_trm_step(&trm, t, g_in, g_out, g_red, g_rho_row, v->w, v->h, &ok);
        tdc_golden_emit(ctx, "trmgaze", name, t, ok ? h : TDC_GOLDEN_FAILED);
    }
}

void tdc_golden_trmgaze(tdc_golden_ctx_t *ctx);

void tdc_golden_trmgaze(tdc_golden_ctx_t *ctx)
{
    static const tdc_content_t contents[] = {TDC_CONTENT_EDGE, TDC_CONTENT_TEXT, TDC_CONTENT_NOISE,
                                             TDC_CONTENT_CHECKER, TDC_CONTENT_GRADIENT, TDC_CONTENT_FLASH};
    static const uint16_t sizes[][2] = {{33, 21}, {64, 48}, {17, 9}};
    static const uint16_t ratios[][2] = {{1, 2}, {1, 4}};
    static const uint16_t kmins[] = {0u, 8192u};
    for (unsigned c = 0; c < sizeof contents / sizeof contents[0]; c++) {
        for (unsigned s = 0; s < 3u; s++) {
            for (unsigned m = 0; m < 3u; m++) {
                const unsigned r = (c + s + m) % 2u, k = (c + m) % 2u;
                gaze_vector_t v = {contents[c], sizes[s][0], sizes[s][1], ratios[r][0], ratios[r][1], (int)m,
                                   kmins[k], ((c + s) & 1u) ? &tdc_panel_rift_cv1 : &tdc_panel_htc_vive};
                run_vector(ctx, &v);
            }
        }
    }
}
