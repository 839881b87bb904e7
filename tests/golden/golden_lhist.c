/*
 * golden_lhist.c - bit-exact golden vectors of the per-layer history
 * (firmware/tdc_layer_hist.h) over the integer content of
 * tdc_lhist_content.h: a noisy colour layer panning with tracked vectors
 * (3 sigma clamp), a visibility layer with eq. 4 falloff (1 sigma), random
 * vectors leaving the frame (no clamp, alpha 0.2).  One checksum per frame:
 * FNV-1a 64 over the output, then the Q8 history.  Freestanding: static
 * buffers, no stdio, no float.
 */
#include "golden.h"
#include "tdc_layer_hist.h"
#include "tdc_lhist_content.h"

#define HW_MAX 31
#define HH_MAX 19

static uint64_t g_arena[TDC_LHIST_MEM_BYTES(HW_MAX, HH_MAX) / 8u];
static uint8_t g_x[HW_MAX * HH_MAX * 3];
static int16_t g_mv[HW_MAX * HH_MAX * 2];
static uint16_t g_g[HW_MAX * HH_MAX];
static tdc_lhist_t g_st;

typedef struct {
    const char *name;
    tdc_lhist_content_t c;
    uint8_t k;
    uint16_t alpha, frames;
} hvec_t;

static const hvec_t vectors[] = {
    {"pan-zeng31x19", {31, 19, 3, 30, 20, -6, 0, 0, 11u}, 3, 3277, 16},
    {"vis-falloff30x18", {30, 18, 1, 60, -12, 4, 0, 1, 12u}, 1, 3277, 16},
    {"random31x19", {31, 19, 3, 20, 0, 0, 300, 0, 13u}, 0, 6554, 12},
};

static void run_vector(tdc_golden_ctx_t *ctx, const hvec_t *v)
{
    const tdc_lhist_config_t cfg = {v->c.w, v->c.h, v->c.ch, v->k, v->alpha};
    const int ok0 = tdc_lhist_init(&g_st, &cfg, g_arena, sizeof g_arena) == TDC_OK;
    const size_t n = (size_t)v->c.w * v->c.h * v->c.ch;
    for (uint32_t f = 0; f < v->frames; f++) {
        int ok = ok0;
        if (ok) {
            tdc_lhist_content(&v->c, f, g_x, g_mv, g_g);
            ok = tdc_lhist_step(&g_st, g_x, g_mv, v->c.falloff ? g_g : (const uint16_t *)0) == TDC_OK;
        }
        uint64_t h = TDC_FNV64_INIT;
        if (ok) {
            h = tdc_fnv1a64(h, tdc_lhist_output(&g_st), n);
            h = tdc_fnv1a64(h, tdc_lhist_history_q8(&g_st), n * 2u);
        }
        tdc_golden_emit(ctx, "lhist", v->name, f, ok ? h : TDC_GOLDEN_FAILED);
    }
}

void tdc_golden_lhist(tdc_golden_ctx_t *ctx);
void tdc_golden_lhist(tdc_golden_ctx_t *ctx)
{
    for (uint32_t i = 0; i < sizeof(vectors) / sizeof(vectors[0]); i++) {
        run_vector(ctx, &vectors[i]);
    }
}
