/*
 * golden_layers.c - bit-exact golden vectors of the layered tile assembly
 * (firmware/tdc_layers.h) over the integer layered stream of
 * tdc_layer_content.h: one layer panning, the fence with ordinary and with
 * shadow vectors (splatting, falloff), with the clean-up, every layer with
 * dropped subframes, random vectors over the whole range; and with the
 * per-layer history on (cfg.history: the fence with shadow vectors, every
 * layer with drops, the layers recombined from the history outputs).  Orderings: a
 * hash pattern per cycle.  One checksum per frame: FNV-1a 64 over the
 * displayed RGB888 frame, then every kept layer's frame.  Freestanding:
 * static buffers (~90 KB), no stdio, no float.
 */
#include "golden.h"
#include "tdc_layer_content.h"
#include "tdc_layers.h"
#include "tdc_math.h"
#include "tdc_panels.h"

#define LW_MAX 32
#define LH_MAX 20
#define LT_MAX (((LW_MAX + 1) / 2) * ((LH_MAX + 1) / 2))

static uint64_t g_arena[TDC_LASM_MEM_BYTES_HIST(LW_MAX, LH_MAX) / 8u + 1u];
static uint8_t g_val[TDC_LAYER_MAX][LT_MAX * 3];
static int16_t g_mv[TDC_LAYER_MAX][LT_MAX * 2];
static uint16_t g_w[LT_MAX];
static uint8_t g_pat[TDC_PATTERN_BYTES(LW_MAX, LH_MAX)];
static tdc_lasm_t g_st;

#define SH TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING)
#define VI TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY)
#define GL TDC_LAYER_PKT_TYPE(TDC_LAYER_GLOSSY)
#define IN TDC_LAYER_PKT_TYPE(TDC_LAYER_INDIRECT)
#define FO TDC_LAYER_PKT_FALLOFF

typedef struct {
    const char *name;
    tdc_lcontent_t c;
    uint8_t clamp_k, cleanup, splat, drop_mod;
    uint16_t frames;
    uint8_t history;
} lvec_t;

static const lvec_t vectors[] = {
    {"one32x20", {32, 20, SH, 24, 8, 0, 0, 0, 0, 0, 1u}, 1, 0, 0, 0, 16, 0},
    {"fence-ordinary32x20", {32, 20, SH | VI, 0, 0, 18, 0, 0, 0, 0, 2u}, 1, 0, 0, 0, 20, 0},
    {"fence-zeng32x20", {32, 20, SH | VI | FO, 0, 0, 18, 0, 0, 1, 0, 3u}, 3, 0, 2, 0, 20, 0},
    {"fence-cleanup31x19", {31, 19, SH | VI | FO, 0, 0, 52, 0, 0, 1, 0, 4u}, 3, 1, 2, 0, 20, 0},
    {"all-drops31x19", {31, 19, SH | VI | GL | IN | FO, 12, -6, 18, -30, 10, 1, 0, 5u}, 1, 1, 1, 5, 24, 0},
    {"random31x19", {31, 19, SH | VI | GL | FO, 0, 0, 0, 0, 0, 1, 1, 6u}, 3, 1, 4, 0, 16, 0},
    {"hist-fence-zeng32x20", {32, 20, SH | VI | FO, 0, 0, 18, 0, 0, 1, 0, 3u}, 3, 0, 2, 0, 20, 1},
    {"hist-all-drops31x19", {31, 19, SH | VI | GL | IN | FO, 12, -6, 18, -30, 10, 1, 0, 5u}, 1, 1, 1, 5, 24, 1},
};

static void run_vector(tdc_golden_ctx_t *ctx, const lvec_t *v)
{
    const tdc_lasm_config_t cfg = {v->c.w, v->c.h, (uint16_t)(v->c.layers & TDC_LAYER_PKT_TYPES), v->clamp_k,
                                   v->cleanup, v->splat, v->history, 3277, &tdc_panel_htc_vive};
    const uint32_t bm = TDC_PATTERN_BYTES(v->c.w, v->c.h);
    const int ok0 = tdc_lasm_init(&g_st, &cfg, g_arena, sizeof g_arena) == TDC_OK;
    tdc_layer_frame_t lf;
    TDC_LAYER_FRAME_WIRE(lf, g_val, g_mv, g_w);
    for (uint32_t f = 0; f < v->frames; f++) {
        int ok = ok0;
        if ((f & 3u) == 0) {
            for (uint32_t i = 0; i < bm; i++) {
                g_pat[i] = (uint8_t)(tdc_hash3(i, f, 77u) & 0xFFu);
            }
        }
        if (ok0) {
            const int drop = v->drop_mod && f % v->drop_mod == v->drop_mod - 1u;
            if (!drop) {
                tdc_layer_content_subframe(&v->c, f, g_pat, &lf);
                ok &= tdc_lasm_ingest(&g_st, f, &lf, g_pat) == TDC_OK;
            }
            ok &= tdc_lasm_assemble(&g_st, f) == TDC_OK;
        }
        uint64_t h = TDC_FNV64_INIT;
        if (ok) {
            h = tdc_fnv1a64(h, tdc_lasm_output(&g_st, (int *)0), (size_t)v->c.w * v->c.h * 3u);
            for (unsigned t = 1; t <= TDC_LAYER_MAX; t++) {
                unsigned ch;
                const uint8_t *l = tdc_lasm_layer(&g_st, t, &ch);
                if (l) {
                    h = tdc_fnv1a64(h, l, (size_t)v->c.w * v->c.h * ch);
                }
            }
        }
        tdc_golden_emit(ctx, "layers", v->name, f, ok ? h : TDC_GOLDEN_FAILED);
    }
}

void tdc_golden_layers(tdc_golden_ctx_t *ctx);
void tdc_golden_layers(tdc_golden_ctx_t *ctx)
{
    for (uint32_t i = 0; i < sizeof(vectors) / sizeof(vectors[0]); i++) {
        run_vector(ctx, &vectors[i]);
    }
}
