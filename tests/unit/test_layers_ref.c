/*
 * test_layers_ref.c - fixed-point layered assembly (firmware/tdc_layers.h)
 * against the double-precision reference (ref/ref_layers.c), closed loop:
 * both run the same layered streams (tests/golden/tdc_layer_content.h) at an
 * odd size, with every layer set, both clamps, clean-up on and off,
 * splatting, falloff, moving shading, dropped subframes, random vectors.
 * Report per scenario: share of displayed bytes within 1 LSB of the
 * reference's 8-bit output, largest difference, largest distance to the
 * unrounded reference; the same for every layer's own frame.
 * Targets (team standard): >= 99.9 % within 1 LSB over all scenarios;
 * without clean-up no byte beyond 1 LSB (measured: all equal); with
 * clean-up at most 12 LSB in a layer's own frame: the fixed-point w_C
 * (within 1/256 of the exact ratio) can land on the other side of a 1/16 px
 * sigma step, and one step at a 204-LSB shadow edge moves a pixel by up to
 * ~9 LSB (sigma 0.5 -> 0.5625 px: neighbour weight 0.135 -> 0.206), which the
 * closed loop carries for a frame or two.  Measured: 99.995 % of all bytes
 * within 1 LSB, displayed frame max 5 LSB, layers max 12.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "golden/tdc_layer_content.h"
#include "ref_layers.h"
#include "tdc_layers.h"
#include "tdc_math.h"
#include "tdc_panels.h"

#define W 37
#define H 23
#define NT (((W + 1) / 2) * ((H + 1) / 2))

typedef struct {
    const char *name;
    uint16_t layers;
    int16_t sh_vx, sh_vy, vis_vx, gl_vx, gl_vy;
    uint8_t shadow_vectors, random_mv;
    uint8_t clamp_k, cleanup, splat;
    uint8_t drop_mod;
    int max_diff; /* asserted bound, LSB */
    uint8_t history; /* per-layer history (tdc_layer_hist) on the assembled layers */
} scen_t;

#define SH TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING)
#define VI TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY)
#define GL TDC_LAYER_PKT_TYPE(TDC_LAYER_GLOSSY)
#define IN TDC_LAYER_PKT_TYPE(TDC_LAYER_INDIRECT)
#define FO TDC_LAYER_PKT_FALLOFF

static const scen_t scens[] = {
    {"one layer, pan (1.5, 0.5) px", SH, 24, 8, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0},
    {"fence, ordinary vectors", SH | VI, 0, 0, 18, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0},
    {"fence, shadow vectors, 1 sigma", SH | VI, 0, 0, 18, 0, 0, 1, 0, 1, 0, 0, 0, 1, 0},
    {"fence, shadow vectors, 3 sigma", SH | VI, 0, 0, 18, 0, 0, 1, 0, 3, 0, 0, 0, 1, 0},
    {"fence, splat 2 + falloff + clean-up", SH | VI | FO, 0, 0, 18, 0, 0, 1, 0, 3, 1, 2, 0, 12, 0},
    {"fence fast 3.25 px, clean-up, 1 sigma", SH | VI | FO, 0, 0, 52, 0, 0, 1, 0, 1, 1, 1, 0, 12, 0},
    {"all layers, moving, clean-up", SH | VI | GL | IN | FO, 12, -6, 18, -30, 10, 1, 0, 3, 1, 2, 0, 12, 0},
    {"all layers + drops", SH | VI | GL | IN | FO, 12, 0, 18, 20, 0, 1, 0, 3, 1, 2, 5, 12, 0},
    {"random vectors, clean-up", SH | VI | GL | FO, 0, 0, 0, 0, 0, 1, 1, 3, 1, 1, 0, 12, 0},
    /* with history: eq. 2 over each assembled layer along the vectors the
     * assembly used, 3x3 clamp of the layer's own frame */
    {"history: one layer, pan, 1 sigma", SH, 24, 8, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1},
    {"history: fence, shadow vectors, 3 sigma", SH | VI | FO, 0, 0, 18, 0, 0, 1, 0, 3, 0, 2, 0, 1, 1},
    {"history: all layers + drops, clean-up", SH | VI | GL | IN | FO, 12, 0, 18, 20, 0, 1, 0, 3, 1, 2, 5, 12, 1},
    {"history: random vectors, clean-up", SH | VI | GL | FO, 0, 0, 0, 0, 0, 1, 1, 3, 1, 1, 0, 12, 1},
};

static uint8_t val[TDC_LAYER_MAX][NT * 3];
static int16_t mvs[TDC_LAYER_MAX][NT * 2];
static uint16_t wts[NT];
static uint8_t pattern[TDC_PATTERN_BYTES(W, H)];

typedef struct {
    uint64_t n, within1;
    int max_diff;
    double max_exact;
} err_t;

static void err_add(err_t *e, const uint8_t *a, const uint8_t *b, const double *exact, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        int d = abs((int)a[i] - (int)b[i]);
        e->n++;
        e->within1 += d <= 1;
        e->max_diff = d > e->max_diff ? d : e->max_diff;
        if (exact) {
            double x = fabs(a[i] - exact[i]);
            e->max_exact = x > e->max_exact ? x : e->max_exact;
        }
    }
}

static void run(const scen_t *s, err_t *all)
{
    const tdc_panel_t *panel = &tdc_panel_htc_vive;
    tdc_lasm_config_t cfg = {W, H, (uint16_t)(s->layers & TDC_LAYER_PKT_TYPES), s->clamp_k, s->cleanup,
                             s->splat, s->history, 3277, panel};
    const size_t bytes = tdc_lasm_get_size(&cfg);
    assert_true(bytes > 0 && bytes <= (s->history ? TDC_LASM_MEM_BYTES_HIST(W, H) : TDC_LASM_MEM_BYTES(W, H)));
    void *arena = aligned_alloc(8, (bytes + 7) & ~(size_t)7);
    tdc_lasm_t st;
    assert_int_equal(tdc_lasm_init(&st, &cfg, arena, bytes), TDC_OK);
    tdc_ref_lasm_config_t rc = {W, H, s->layers & TDC_LAYER_PKT_TYPES, s->clamp_k, s->cleanup, s->splat, 3277 / 32768.0,
                                {panel->gamma_micro[0] / 1e6, panel->gamma_micro[1] / 1e6, panel->gamma_micro[2] / 1e6},
                                s->history};
    tdc_ref_lasm_t *ref = tdc_ref_lasm_new(&rc);
    assert_non_null(ref);
    tdc_lcontent_t c = {W, H, s->layers, s->sh_vx, s->sh_vy, s->vis_vx, s->gl_vx, s->gl_vy,
                        s->shadow_vectors, s->random_mv, 5u};
    tdc_layer_frame_t lf;
    TDC_LAYER_FRAME_WIRE(lf, val, mvs, wts);
    err_t out = {0, 0, 0, 0}, lay = {0, 0, 0, 0};
    const uint32_t frames = 48;
    for (uint32_t f = 0; f < frames; f++) {
        if ((f & 3u) == 0) {
            /* orderings of the cycle: a hash pattern (both sides get the same bits) */
            for (size_t i = 0; i < sizeof pattern; i++) {
                pattern[i] = (uint8_t)(tdc_hash3((uint32_t)i, f, 77u) & 0xFFu);
            }
        }
        const int drop = s->drop_mod && (f % s->drop_mod) == s->drop_mod - 1u;
        if (!drop) {
            tdc_layer_content_subframe(&c, f, pattern, &lf);
            assert_int_equal(tdc_lasm_ingest(&st, f, &lf, pattern), TDC_OK);
            assert_int_equal(tdc_ref_lasm_ingest(ref, f, &lf, pattern), 0);
        }
        assert_int_equal(tdc_lasm_assemble(&st, f), TDC_OK);
        assert_int_equal(tdc_ref_lasm_assemble(ref, f), 0);
        if (f >= 4) { /* after the first cycle (both start from the same black) */
            int stride;
            err_add(&out, tdc_lasm_output(&st, &stride), tdc_ref_lasm_output(ref), tdc_ref_lasm_output_exact(ref),
                    (size_t)W * H * 3);
            for (unsigned t = 1; t <= TDC_LAYER_MAX; t++) {
                unsigned ch;
                const uint8_t *a = tdc_lasm_layer(&st, t, &ch);
                if (a) {
                    err_add(&lay, a, tdc_ref_lasm_layer(ref, t), NULL, (size_t)W * H * ch);
                }
            }
        }
    }
    printf("  %-38s out: %.4f %% within 1 LSB, max %d (|fixed - exact| <= %.2f); layers: %.4f %%, max %d; "
           "reprojected %llu clamped %llu weighted %llu cleaned %llu splatted %llu\n",
           s->name, 100.0 * out.within1 / out.n, out.max_diff, out.max_exact, 100.0 * lay.within1 / lay.n, lay.max_diff,
           (unsigned long long)st.stats.reprojected, (unsigned long long)st.stats.clamped,
           (unsigned long long)st.stats.weighted, (unsigned long long)st.stats.cleaned,
           (unsigned long long)st.stats.splatted);
    assert_true(out.max_diff <= s->max_diff);
    assert_true(lay.max_diff <= s->max_diff);
    all->n += out.n + lay.n;
    all->within1 += out.within1 + lay.within1;
    all->max_diff = out.max_diff > all->max_diff ? out.max_diff : all->max_diff;
    tdc_ref_lasm_free(ref);
    free(arena);
}

static void test_fixed_vs_double(void **state)
{
    (void)state;
    err_t all = {0, 0, 0, 0};
    printf("layered assembly, fixed point vs double reference (%dx%d, 48 frames):\n", W, H);
    for (size_t i = 0; i < sizeof scens / sizeof scens[0]; i++) {
        run(&scens[i], &all);
    }
    printf("  all: %.4f %% of %llu bytes within 1 LSB, max %d LSB\n", 100.0 * all.within1 / all.n,
           (unsigned long long)all.n, all.max_diff);
    assert_true(all.within1 * 1000 >= all.n * 999);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_fixed_vs_double)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
