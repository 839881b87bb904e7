/*
 * test_assemble_long.c - a full 10^5-frame run of a panning scene through
 * the assembly stage, small size (18x12, odd tile count), with the pan
 * changing speed and direction every 1000 frames (static spells, integer,
 * fractional, diagonal, fast, +-max), a dropped subframe every 97 frames and
 * the double reference alongside.  Asserts: the stage stays inside its fixed
 * arena (guard bytes), every frame within 2 LSB of the reference and
 * >= 99.9 % within 1 LSB overall, pattern disagreements with the renderer
 * only in the cycle after a dropped subframe, counters add up.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ref_assemble.h"
#include "tdc_assemble.h"

#define W 18
#define H 12
#define FRAMES 100000u
#define GUARD 256

static void test_long_pan(void **state)
{
    (void)state;
    static const int32_t vel[][2] = {{24, 0},  {0, 0},     {-40, 13}, {16, 16}, {0, -37},   {-3, 1},
                                     {200, 0}, {32767, 0}, {5, -56},  {0, 0},   {-18, -18}, {90, 45}};
    const size_t nv = sizeof(vel) / sizeof(vel[0]);
    tdc_asm_config_t cfg = {W, H};
    static uint64_t arena[(TDC_ASM_MEM_BYTES(W, H) + GUARD) / 8 + 1];
    size_t n = tdc_asm_get_size(&cfg);
    assert_true(n + GUARD <= sizeof(arena));
    memset((uint8_t *)arena + n, 0xC3, sizeof(arena) - n);
    tdc_asm_t st;
    assert_int_equal(tdc_asm_init(&st, &cfg, arena, n), TDC_OK);
    tdc_ref_asm_t *ref = tdc_ref_asm_new(W, H);
    uint8_t samples[(W / 2) * (H / 2) * 3], bits[TDC_PATTERN_BYTES(W, H)];
    int16_t mvs[(W / 2) * (H / 2) * 2];
    tdc_asm_err_t e;
    memset(&e, 0, sizeof(e));
    tdc_scene_t scene;
    uint32_t dropped = 0, last_drop = 0xFFFFFFFFu, disagree_cycles = 0;
    for (uint32_t f = 0; f < FRAMES; f++) {
        if (f % 1000u == 0) {
            /* New pan: a fresh renderer (keeps its orderings and motion
             * buffer in step with the stage's by carrying them over). */
            tdc_scene_t next;
            size_t i = (f / 1000u) % nv;
            assert_int_equal(tdc_scene_init(&next, TDC_SCENE_PAN, W, H, vel[i][0], vel[i][1], f), 0);
            if (f) {
                memcpy(next.mvbuf, scene.mvbuf, (size_t)W * H * 4);
                memcpy(next.pattern, scene.pattern, sizeof(bits));
                tdc_scene_free(&scene);
            }
            scene = next;
        }
        tdc_scene_subframe(&scene, f, samples, mvs, bits);
        int drop = f % 97u == 96u;
        const uint8_t *b = (f & 3u) == 0 ? bits : NULL;
        if (!drop) {
            uint32_t d0 = st.stats.pattern_disagreements;
            assert_int_equal(tdc_asm_ingest(&st, f, samples, mvs, b), TDC_OK);
            if (st.stats.pattern_disagreements != d0) {
                /* The stage decides from what it received: only a subframe
                 * lost in the previous cycle may make it disagree with the
                 * renderer (whose bits it then adopts). */
                if (last_drop == 0xFFFFFFFFu || f - last_drop > 4u)
                    fail_msg("frame %u: pattern disagreement without a dropped subframe", f);
                disagree_cycles++;
            }
            assert_int_equal(tdc_ref_asm_ingest(ref, f, samples, mvs, b), 0);
        } else {
            dropped++;
            last_drop = f;
        }
        assert_int_equal(tdc_asm_assemble(&st, f), TDC_OK);
        assert_int_equal(tdc_ref_asm_assemble(ref, f), 0);
        int before = e.max_abs;
        tdc_asm_err_add(&e, tdc_asm_output(&st, NULL), tdc_ref_asm_output(ref), NULL, (size_t)W * H * 3);
        if (e.max_abs > 2 && before <= 2) fail_msg("frame %u: %d LSB from the reference", f, e.max_abs);
    }
    for (size_t i = n; i < sizeof(arena); i++) assert_int_equal(((uint8_t *)arena)[i], 0xC3);
    const tdc_asm_stats_t *s = &st.stats;
    assert_int_equal(s->frames, FRAMES);
    assert_int_equal(s->subframes_missing, dropped);
    assert_int_equal(s->subframes + s->subframes_missing, FRAMES);
    assert_int_equal(s->new_dynamic + s->reprojected + s->static_averaged + s->static_kept, (uint64_t)FRAMES * W * H);
    assert_true(s->static_frames > 0 && s->reprojected > 0);
    double share = (double)(e.hist[0] + e.hist[1]) / (double)e.n;
    printf("long run: %u frames %dx%d, %u dropped, static frames %u, reprojected %llu, pattern disagreements %u "
           "(%u cycles, all after a drop); vs reference %.4f %% within 1 LSB, max %d LSB\n",
           FRAMES, W, H, dropped, s->static_frames, (unsigned long long)s->reprojected, s->pattern_disagreements,
           disagree_cycles, 100.0 * share, e.max_abs);
    assert_true(share >= 0.999);
    assert_true(e.max_abs <= 2);
    tdc_scene_free(&scene);
    tdc_ref_asm_free(ref);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_long_pan)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
