/*
 * golden_assemble.c - bit-exact golden vectors of tile-ordered frame
 * assembly.  An integer "renderer" turns tdc_content frames into subframes:
 * per tile the pixel its ordering names (orderings from tdc_ordering_update
 * over the renderer's own motion buffer, exactly like the controller), with
 * the content's known motion as backward Q4 MVs; one vector has random MVs
 * over the full range, one drops subframes, one is static.  One checksum per
 * output frame: FNV-1a 64 over the RGB888 output, then the stage's ordering
 * bitmap.  Freestanding: static buffers (~60 KB), no stdio, no float.
 */
#include "golden.h"
#include "tdc_assemble.h"
#include "tdc_content.h"

#define GW_MAX 48
#define GH_MAX 32
#define GT_MAX (((GW_MAX + 1) / 2) * ((GH_MAX + 1) / 2))

static uint64_t g_arena[TDC_ASM_MEM_BYTES(GW_MAX, GH_MAX) / 8u + 1u];
static uint8_t g_frame[GW_MAX * GH_MAX * 3];
static int16_t g_mvbuf[GW_MAX * GH_MAX * 2];
static uint8_t g_pattern[TDC_PATTERN_BYTES(GW_MAX, GH_MAX)];
static uint8_t g_samples[GT_MAX * 3];
static int16_t g_mvs[GT_MAX * 2];
static tdc_asm_t g_st;

typedef struct {
    const char *name;
    tdc_content_t content;
    uint16_t w, h;
    uint16_t frames;
    int16_t mvx, mvy;  /* backward MV of the content, Q4 */
    uint8_t random_mv; /* random per-sample MVs instead */
    uint8_t drop_mod;  /* drop the subframe when frame % drop_mod == drop_mod-1 (0: never) */
} asm_vector_t;

static const asm_vector_t vectors[] = {
    /* edge moves +3 px/frame: the point now at x was at x - 3 */
    {"edge48x32", TDC_CONTENT_EDGE, 48, 32, 20, -48, 0, 0, 7},
    /* text scrolls up 2 px/frame: the point now at y was at y + 2 */
    {"text37x23", TDC_CONTENT_TEXT, 37, 23, 20, 0, 32, 0, 0},
    /* gradient value x + y + t: the point now at x was at x + 1 */
    {"gradient48x32", TDC_CONTENT_GRADIENT, 48, 32, 16, 16, 0, 0, 0},
    {"checker37x23", TDC_CONTENT_CHECKER, 37, 23, 20, 0, 0, 0, 5},
    {"noise-mv33x21", TDC_CONTENT_NOISE, 33, 21, 16, 0, 0, 1, 6},
};

static int16_t random_mv(uint32_t *rng)
{
    uint32_t r = tdc_golden_rand(rng);
    switch (r & 7u) {
    case 0: return 0;
    case 1: return -32768;
    case 2: return 32767;
    default: return (int16_t)((int32_t)((r >> 8) & 1023u) - 512); /* +-32 px */
    }
}

static void run_vector(tdc_golden_ctx_t *ctx, const asm_vector_t *v)
{
    tdc_asm_config_t cfg = {v->w, v->h};
    const uint32_t tx_n = (v->w + 1u) / 2u, ty_n = (v->h + 1u) / 2u;
    const uint32_t bm = TDC_PATTERN_BYTES(v->w, v->h);
    uint32_t rng = 0x2545F491u;
    if (tdc_asm_init(&g_st, &cfg, g_arena, sizeof(g_arena)) != TDC_OK) return;
    for (uint32_t i = 0; i < (uint32_t)v->w * v->h * 2u; i++) g_mvbuf[i] = 0;
    for (uint32_t i = 0; i < bm; i++) g_pattern[i] = 0;
    for (uint32_t f = 0; f < v->frames; f++) {
        const uint32_t k = f & 3u;
        int ok = 1;
        if (k == 0) tdc_ordering_update(g_mvbuf, v->w, v->h, g_pattern, f);
        tdc_content_frame(v->content, f, 11u, g_frame, v->w, v->h, v->w * 3);
        for (uint32_t ty = 0; ty < ty_n; ty++) {
            for (uint32_t tx = 0; tx < tx_n; tx++) {
                uint32_t ti = ty * tx_n + tx;
                unsigned pos = tdc_ordering_pixel(tdc_ordering_get(g_pattern, ti), k);
                uint32_t x = 2u * tx + (pos & 1u), y = 2u * ty + (pos >> 1);
                int16_t mx = v->random_mv ? random_mv(&rng) : v->mvx;
                int16_t my = v->random_mv ? random_mv(&rng) : v->mvy;
                uint32_t sx = x < v->w ? x : v->w - 1u, sy = y < v->h ? y : v->h - 1u;
                for (int c = 0; c < 3; c++)
                    g_samples[ti * 3u + (uint32_t)c] = g_frame[(sy * v->w + sx) * 3u + (uint32_t)c];
                g_mvs[ti * 2u] = mx;
                g_mvs[ti * 2u + 1u] = my;
                if (x < v->w && y < v->h) {
                    g_mvbuf[(y * v->w + x) * 2u] = mx;
                    g_mvbuf[(y * v->w + x) * 2u + 1u] = my;
                }
            }
        }
        int drop = v->drop_mod && f % v->drop_mod == v->drop_mod - 1u;
        if (!drop) {
            /* bits with the first subframe of a cycle; the random vector
             * sends them only every other cycle */
            const uint8_t *bits = k == 0 && !(v->random_mv && (f & 4u)) ? g_pattern : (const uint8_t *)0;
            ok &= tdc_asm_ingest(&g_st, f, g_samples, g_mvs, bits) == TDC_OK;
        }
        ok &= tdc_asm_assemble(&g_st, f) == TDC_OK;
        uint64_t h = tdc_fnv1a64(TDC_FNV64_INIT, tdc_asm_output(&g_st, (int *)0), (size_t)v->w * v->h * 3u);
        h = tdc_fnv1a64(h, tdc_asm_pattern(&g_st), bm);
        tdc_golden_emit(ctx, "assemble", v->name, f, ok ? h : TDC_GOLDEN_FAILED);
    }
}

void tdc_golden_assemble(tdc_golden_ctx_t *ctx);
void tdc_golden_assemble(tdc_golden_ctx_t *ctx)
{
    for (uint32_t i = 0; i < sizeof(vectors) / sizeof(vectors[0]); i++) run_vector(ctx, &vectors[i]);
}
