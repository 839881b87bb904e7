/*
 * test_arena.c - the stage scaffold (firmware/tdc_arena.h): for every stage
 * with caller-owned memory (TRM, LCD inverse, tile assembly, foveated remap), every panel
 * and the extreme sizes, the three views of one arena agree:
 *   get_size(cfg)        the dry-run carve,
 *   init()'s layout      every view pointer where the stage's layout list
 *                        puts it, 8-aligned, in order, ending at get_size,
 *                        and nothing written past get_size bytes by init
 *                        and by frames,
 *   *_MEM_BYTES(...)     the compile-time bound boards size static
 *                        buffers with: >= get_size for every configuration
 *                        it covers, == get_size at the bound's geometry.
 * Plus the one alignment rule: an arena not aligned to TDC_ARENA_ALIGN is
 * TDC_ERR_ARG, one byte short is TDC_ERR_SIZE, for every stage.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "tdc_cmocka.h"

#include "tdc_arena.h"
#include "tdc_assemble.h"
#include "tdc_fov.h"
#include "tdc_fov_lr.h"
#include "tdc_layer_hist.h"
#include "tdc_layers.h"
#include "tdc_lcd.h"
#include "tdc_panels.h"
#include "tdc_trm.h"

#define GUARD 64u
#define CANARY 0xA5u

/* A compile-time use, as a board makes it (constant expressions). */
static uint64_t g_static_trm[TDC_TRM_MEM_BYTES(64, 48, 1, 2) / 8u];
static uint64_t g_static_lcd[TDC_LCD_MEM_BYTES(64, 48) / 8u];
static uint64_t g_static_asm[TDC_ASM_MEM_BYTES(64, 48) / 8u];
static uint64_t g_static_fov[TDC_FOV_MEM_BYTES(64, 48, 1) / 8u];
_Static_assert(TDC_TRM_MEM_BYTES(64, 48, 1, 2) % TDC_ARENA_ALIGN == 0, "bounds are multiples of the alignment");
_Static_assert(TDC_LCD_MEM_BYTES(64, 48) % TDC_ARENA_ALIGN == 0, "bounds are multiples of the alignment");
_Static_assert(TDC_ASM_MEM_BYTES(64, 48) % TDC_ARENA_ALIGN == 0, "bounds are multiples of the alignment");
_Static_assert(TDC_FOV_MEM_BYTES(64, 48, 1) % TDC_ARENA_ALIGN == 0, "bounds are multiples of the alignment");
_Static_assert(TDC_FOV_MEM_BYTES(64, 48, 0) < TDC_FOV_MEM_BYTES(64, 48, 1), "the history is the TAA part");

static const tdc_panel_t *const g_panels[] = {
#define PANEL_PTR(p) &p,
    TDC_PANEL_LIST(PANEL_PTR)
#undef PANEL_PTR
};
#define NPANELS (sizeof g_panels / sizeof g_panels[0])

/* An arena of n bytes (8-aligned, malloc) followed by GUARD canary bytes. */
typedef struct {
    uint8_t *mem;
    size_t n;
} arena_t;

static void arena_new(arena_t *a, size_t n)
{
    a->n = n;
    a->mem = malloc(n + GUARD);
    assert_non_null(a->mem);
    assert_int_equal((uintptr_t)a->mem % TDC_ARENA_ALIGN, 0);
    memset(a->mem, 0x5A, n);
    memset(a->mem + n, CANARY, GUARD);
}

static void arena_check_guard(const arena_t *a, const char *what)
{
    for (size_t i = 0; i < GUARD; i++) {
        if (a->mem[a->n + i] != CANARY) {
            fail_msg("%s: byte %zu past the %zu-byte arena was written", what, i, a->n);
        }
    }
}

/* Walks a stage's layout list over init's view pointers (WALK expands the
 * list against the state `st` into the walker `wk`): each block must sit
 * exactly where the list puts it (offset from the base = sum of the rounded
 * sizes before it), empty blocks are NULL, and the list ends at get_size. */
typedef struct {
    const uint8_t *base;
    size_t off;
    const char *stage;
} walk_t;

static void walk_block(walk_t *w, const char *name, const void *p, size_t bytes)
{
    const size_t r = TDC_ARENA_ROUND(bytes);
    if (r == 0) {
        if (p != NULL) {
            fail_msg("%s: empty block %s is not NULL", w->stage, name);
        }
        return;
    }
    if ((const uint8_t *)p != w->base + w->off) {
        fail_msg("%s: block %s at offset %td, the layout list puts it at %zu", w->stage, name,
                 (const uint8_t *)p - w->base, w->off);
    }
    assert_int_equal(w->off % TDC_ARENA_ALIGN, 0);
    w->off += r;
}
#define WALK(member, type, count) walk_block(&wk, #member, (const void *)st->member, sizeof(type) * (size_t)(count));

static void walk_end(const walk_t *w, size_t n)
{
    const size_t used = w->off ? w->off : TDC_ARENA_ALIGN;
    if (used != n) {
        fail_msg("%s: init's layout uses %zu bytes, get_size says %zu", w->stage, used, n);
    }
}

/* The checks every stage's init gets, in a fresh n-byte arena a: the one
 * alignment rule (a base 4 bytes off alignment is TDC_ERR_ARG, one byte
 * short TDC_ERR_SIZE, exactly n TDC_OK), then init's view pointers (of
 * `st`, in scope) walked against LIST (the stage's *_ARENA list expanded
 * with WALK, or code around it), and nothing written past n.  init is
 * called as init(ARGS..., mem, bytes), ARGS a parenthesised list. */
#define ARGS_OF(...) __VA_ARGS__
#define CHECK_ARENA_INIT(a, n, stage, init, ARGS, LIST)                     \
    do {                                                                    \
        arena_new(&(a), n);                                                 \
        assert_int_equal(init(ARGS_OF ARGS, (a).mem + 4, n), TDC_ERR_ARG);  \
        assert_int_equal(init(ARGS_OF ARGS, (a).mem, (n)-1), TDC_ERR_SIZE); \
        assert_int_equal(init(ARGS_OF ARGS, (a).mem, n), TDC_OK);           \
        walk_t wk = {(a).mem, 0, stage};                                    \
        LIST;                                                               \
        walk_end(&wk, n);                                                   \
        arena_check_guard(&(a), stage " init");                             \
    } while (0)

/* ------------------------------------------------------------------ TRM */

static const uint16_t g_ratios[][2] = {{1, 4}, {1, 3}, {1, 2}, {2, 3}, {3, 4}, {7, 8}, {1, 1}};
#define NRATIOS (sizeof g_ratios / sizeof g_ratios[0])
static const uint16_t g_sigmas[] = {64, 640, TDC_TRM_MAX_SIGMA_Q8};

static void trm_cfg(tdc_trm_config_t *c, uint32_t w, uint32_t h, const uint16_t r[2], uint16_t sigma)
{
    tdc_trm_default_config(c, (uint16_t)w, (uint16_t)h, 120);
    c->r_num = r[0];
    c->r_den = r[1];
    c->sigma_q8 = sigma;
}

/* get_size against the bound for every ratio up to the bound's and every
 * sigma; equal at the bound's own ratio and the largest sigma. */
static void trm_sizes(uint32_t w, uint32_t h)
{
    for (unsigned b = 0; b < NRATIOS; b++) {
        const size_t bound = TDC_TRM_MEM_BYTES((size_t)w, (size_t)h, g_ratios[b][0], g_ratios[b][1]);
        for (unsigned r = 0; r <= b; r++) {
            for (unsigned s = 0; s < 3; s++) {
                tdc_trm_config_t c;
                trm_cfg(&c, w, h, g_ratios[r], g_sigmas[s]);
                const size_t n = tdc_trm_get_size(&c);
                if (n == 0 || n % TDC_ARENA_ALIGN != 0 || n > bound) {
                    fail_msg("TRM %ux%u r %u/%u sigma %u: get_size %zu, bound at r %u/%u %zu", w, h, c.r_num, c.r_den,
                             c.sigma_q8, n, g_ratios[b][0], g_ratios[b][1], bound);
                }
                if (r == b && s == 2 && r + 1 < NRATIOS && n != bound) {
                    fail_msg("TRM %ux%u r %u/%u: the bound %zu is not the layout at its own geometry (%zu)", w, h,
                             c.r_num, c.r_den, bound, n);
                }
            }
        }
    }
}

/* TRM's layout list; a pass-through stage (r = 1) has no blocks. */
#define TRM_WALK_LIST                                                                      \
    if (!st->passthrough) {                                                                \
        TDC_TRM_ARENA(WALK, c.width, c.height, st->rw, st->rh, st->dtaps, c.keep_residual) \
    }

/* init over exactly get_size bytes: the layout, the one alignment rule,
 * one byte short; frames when asked (small sizes). */
static void trm_layout(const tdc_panel_t *panel, uint32_t w, uint32_t h, const uint16_t r[2], uint16_t sigma,
                       int frames)
{
    tdc_trm_config_t c;
    trm_cfg(&c, w, h, r, sigma);
    const size_t n = tdc_trm_get_size(&c);
    assert_true(n > 0);
    arena_t a;
    tdc_trm_t trm, *st = &trm;
    CHECK_ARENA_INIT(a, n, "TRM", tdc_trm_init, (st, &c, panel), TRM_WALK_LIST);
    if (frames && !st->passthrough) {
        const size_t fb = (size_t)w * h * 3u;
        uint8_t *in = malloc(fb), *out = malloc(fb), *red = malloc(fb);
        for (size_t i = 0; i < fb; i++) {
            in[i] = (uint8_t)(i * 37u + (i >> 5));
        }
        assert_int_equal(tdc_trm_downsample(st, in, w * 3u, red, st->rw * 3u), TDC_OK);
        assert_int_equal(tdc_trm_full(st, in, w * 3u, out, w * 3u), TDC_OK);
        assert_int_equal(tdc_trm_reduced(st, red, st->rw * 3u, out, w * 3u), TDC_OK);
        tdc_trm_set_simd(st, 0);
        assert_int_equal(tdc_trm_full(st, in, w * 3u, out, w * 3u), TDC_OK);
        assert_int_equal(tdc_trm_reduced(st, red, st->rw * 3u, out, w * 3u), TDC_OK);
        arena_check_guard(&a, "TRM frames");
        free(in);
        free(out);
        free(red);
    }
    free(a.mem);
}

static void test_trm_arena(void **state)
{
    (void)state;
    static const uint32_t small[][2] = {{1, 1}, {1, 7}, {7, 1}, {2, 2}, {33, 17}, {64, 48}, {97, 61}};
    for (unsigned i = 0; i < sizeof small / sizeof small[0]; i++) {
        trm_sizes(small[i][0], small[i][1]);
        for (unsigned r = 0; r < NRATIOS; r++) {
            for (unsigned s = 0; s < 3; s++) {
                trm_layout(&tdc_panel_htc_vive, small[i][0], small[i][1], g_ratios[r], g_sigmas[s], s == 1);
            }
        }
    }
    for (unsigned p = 0; p < NPANELS; p++) {
        trm_sizes(g_panels[p]->width, g_panels[p]->height);
        trm_layout(g_panels[p], g_panels[p]->width, g_panels[p]->height, g_ratios[2], 640, 0);
    }
    /* The largest eye the stage takes; one more is invalid (0). */
    trm_sizes(8192, 8192);
    trm_sizes(1, 8192);
    tdc_trm_config_t c;
    trm_cfg(&c, 8193, 16, g_ratios[2], 640);
    assert_int_equal(tdc_trm_get_size(&c), 0);
    /* A static arena sized by the bound takes the configuration. */
    trm_cfg(&c, 64, 48, g_ratios[2], TDC_TRM_MAX_SIGMA_Q8);
    tdc_trm_t st;
    assert_int_equal(tdc_trm_init(&st, &c, &tdc_panel_htc_vive, g_static_trm, sizeof g_static_trm), TDC_OK);
    assert_int_equal(tdc_trm_get_size(&c), sizeof g_static_trm);
}

/* ------------------------------------------------------------------ LCD */

static const tdc_panel_t *lcd_panel(void)
{
    for (unsigned p = 0; p < NPANELS; p++) {
        if (g_panels[p]->type == TDC_PANEL_LCD && g_panels[p]->lcd) {
            return g_panels[p];
        }
    }
    return NULL;
}

static void lcd_one_mode(const tdc_panel_t *panel, uint32_t w, uint32_t h, unsigned bits, int init, int frames,
                         tdc_lcd_mode_t mode)
{
    const tdc_lcd_config_t c = {(uint16_t)w, (uint16_t)h, panel && panel->lcd ? panel->lcd->rate[0].rate_hz : 0,
                                (uint8_t)mode, (uint8_t)bits};
    const size_t n = tdc_lcd_get_size(&c), bound = TDC_LCD_MEM_BYTES((size_t)w, (size_t)h);
    const size_t mode_bound = TDC_LCD_MEM_BYTES_MODE((size_t)w, (size_t)h, mode);
    if (n == 0 || n % TDC_ARENA_ALIGN != 0 || n > bound || n > mode_bound || (bits == 8u && n != mode_bound)) {
        fail_msg("LCD %ux%u %u bits mode %d: get_size %zu, bound %zu (mode %zu)", w, h, bits, (int)mode, n, bound,
                 mode_bound);
    }
    if (!init) {
        return;
    }
    arena_t a;
    tdc_lcd_t lcd, *st = &lcd;
    CHECK_ARENA_INIT(a, n, "LCD", tdc_lcd_init, (st, &c, panel),
                     TDC_LCD_ARENA(WALK, c.width, c.height, c.prev_bits, c.mode));
    if (frames) {
        const size_t fb = (size_t)w * h * 3u;
        uint8_t *in = malloc(fb), *out = malloc(fb);
        tdc_res_t *res = calloc(fb, sizeof *res);
        for (unsigned f = 0; f < 3; f++) {
            for (size_t i = 0; i < fb; i++) {
                in[i] = (uint8_t)((i + f) & 1u ? 255u : (i * 29u) >> 3);
            }
            assert_int_equal(tdc_lcd_frame(st, in, w * 3u, out, w * 3u, res), TDC_OK);
        }
        arena_check_guard(&a, "LCD frames");
        free(in);
        free(out);
        free(res);
    }
    free(a.mem);
}

/* Every layout: exact/table (two history buffers), stateful, pair mode. */
static void lcd_one(const tdc_panel_t *panel, uint32_t w, uint32_t h, unsigned bits, int init, int frames)
{
    lcd_one_mode(panel, w, h, bits, init, frames, TDC_LCD_MODE_EXACT);
    const int st = panel && panel->lcd && panel->lcd->rate[0].st_n;
    lcd_one_mode(panel, w, h, bits, init && st, frames, TDC_LCD_MODE_STATEFUL);
    lcd_one_mode(panel, w, h, bits, init && st, frames, TDC_LCD_MODE_STATEFUL_PAIR);
    /* the bound holds the larger of the two: equality for one of them at 8 bits */
    if (bits == 8u) {
        const tdc_lcd_config_t a = {(uint16_t)w, (uint16_t)h, 144, TDC_LCD_MODE_EXACT, 8},
                               b = {(uint16_t)w, (uint16_t)h, 144, TDC_LCD_MODE_STATEFUL_PAIR, 8};
        const size_t na = tdc_lcd_get_size(&a), nb = tdc_lcd_get_size(&b);
        assert_true(TDC_LCD_MEM_BYTES((size_t)w, (size_t)h) == (na > nb ? na : nb));
    }
}

static void test_lcd_arena(void **state)
{
    (void)state;
    const tdc_panel_t *lcd = lcd_panel();
    assert_non_null(lcd);
    static const uint32_t small[][2] = {{1, 1}, {1, 5}, {3, 1}, {33, 17}, {64, 48}};
    for (unsigned i = 0; i < sizeof small / sizeof small[0]; i++) {
        for (unsigned b = 4; b <= 8; b++) {
            lcd_one(lcd, small[i][0], small[i][1], b, 1, 1);
        }
    }
    for (unsigned p = 0; p < NPANELS; p++) {
        for (unsigned b = 4; b <= 8; b++) {
            const int is_lcd = g_panels[p]->type == TDC_PANEL_LCD && g_panels[p]->lcd;
            lcd_one(is_lcd ? g_panels[p] : lcd, g_panels[p]->width, g_panels[p]->height, b, b == 8 || b == 5, 0);
        }
    }
    lcd_one(lcd, TDC_LCD_MAX_DIM, TDC_LCD_MAX_DIM, 8, 0, 0);
    lcd_one(lcd, 1, TDC_LCD_MAX_DIM, 4, 0, 0);
    /* beyond the bound: refused by get_size and init (a 32-bit size_t would
     * wrap at 65535 x 65535: 12.9 G samples) */
    for (unsigned k = 0; k < 3; k++) {
        const uint16_t big[3][2] = {{TDC_LCD_MAX_DIM + 1u, 1}, {1, TDC_LCD_MAX_DIM + 1u}, {65535, 65535}};
        for (unsigned m = TDC_LCD_MODE_GAMMA; m <= TDC_LCD_MODE_STATEFUL_PAIR; m++) {
            const tdc_lcd_config_t cb = {big[k][0], big[k][1], lcd->lcd->rate[0].rate_hz, (uint8_t)m, 8};
            tdc_lcd_t sb;
            assert_int_equal(tdc_lcd_get_size(&cb), 0);
            assert_int_equal(tdc_lcd_init(&sb, &cb, lcd, g_static_lcd, sizeof g_static_lcd), TDC_ERR_ARG);
        }
    }
    const tdc_lcd_config_t c = {64, 48, lcd->lcd->rate[0].rate_hz, TDC_LCD_MODE_EXACT, 8};
    tdc_lcd_t st;
    assert_int_equal(tdc_lcd_init(&st, &c, lcd, g_static_lcd, sizeof g_static_lcd), TDC_OK);
}

/* ------------------------------------------------------------- assembly */

static void asm_one(uint32_t w, uint32_t h, int init, int frames)
{
    const tdc_asm_config_t c = {(uint16_t)w, (uint16_t)h};
    const size_t n = tdc_asm_get_size(&c), bound = TDC_ASM_MEM_BYTES((size_t)w, (size_t)h);
    if (n == 0 || n % TDC_ARENA_ALIGN != 0 || n != bound) {
        fail_msg("assembly %ux%u: get_size %zu, bound %zu", w, h, n, bound);
    }
    if (!init) {
        return;
    }
    arena_t a;
    tdc_asm_t as, *st = &as;
    CHECK_ARENA_INIT(a, n, "assembly", tdc_asm_init, (st, &c),
                     TDC_ASM_ARENA(WALK, c.width, c.height, (size_t)st->tiles_x * st->tiles_y,
                                   TDC_PATTERN_BYTES(c.width, c.height)));
    if (frames) {
        const size_t tiles = (size_t)st->tiles_x * st->tiles_y;
        uint8_t *samples = malloc(tiles * 3u);
        int16_t *mvs = malloc(tiles * 2u * sizeof *mvs);
        for (uint32_t f = 0; f < 9; f++) {
            for (size_t i = 0; i < tiles * 3u; i++) {
                samples[i] = (uint8_t)(i * 13u + f * 50u);
            }
            for (size_t i = 0; i < tiles * 2u; i++) {
                mvs[i] = (int16_t)(f < 4 ? 0 : (int)((i * 7u) % 61u) - 30);
            }
            assert_int_equal(tdc_asm_ingest(st, f, samples, mvs, NULL), TDC_OK);
            assert_int_equal(tdc_asm_assemble(st, f), TDC_OK);
        }
        arena_check_guard(&a, "assembly frames");
        free(samples);
        free(mvs);
    }
    free(a.mem);
}

static void test_asm_arena(void **state)
{
    (void)state;
    static const uint32_t small[][2] = {{1, 1}, {1, 9}, {9, 1}, {2, 2}, {3, 3}, {33, 17}, {64, 48}};
    for (unsigned i = 0; i < sizeof small / sizeof small[0]; i++) {
        asm_one(small[i][0], small[i][1], 1, 1);
    }
    for (unsigned p = 0; p < NPANELS; p++) {
        asm_one(g_panels[p]->width, g_panels[p]->height, 1, 0);
    }
    asm_one(TDC_ASM_MAX_DIM, TDC_ASM_MAX_DIM, 0, 0);
    asm_one(1, TDC_ASM_MAX_DIM, 0, 0);
    const tdc_asm_config_t big = {TDC_ASM_MAX_DIM + 1, 4};
    assert_int_equal(tdc_asm_get_size(&big), 0);
    const tdc_asm_config_t c = {64, 48};
    tdc_asm_t st;
    assert_int_equal(tdc_asm_init(&st, &c, g_static_asm, sizeof g_static_asm), TDC_OK);
}

/* ------------------------------------------------------ foveated remap */

static void fov_one(uint32_t w, uint32_t h, int taa, int init, int frames)
{
    const tdc_fov_config_t c = {(uint16_t)w, (uint16_t)h, (uint8_t)taa};
    const size_t n = tdc_fov_get_size(&c), bound = TDC_FOV_MEM_BYTES((size_t)w, (size_t)h, taa);
    if (n == 0 || n % TDC_ARENA_ALIGN != 0 || n != bound) {
        fail_msg("fov %ux%u taa %d: get_size %zu, bound %zu", w, h, taa, n, bound);
    }
    if (!init) {
        return;
    }
    arena_t a;
    tdc_fov_t fs, *st = &fs;
    CHECK_ARENA_INIT(a, n, "fov", tdc_fov_init, (st, &c), TDC_FOV_ARENA(WALK, c.width, c.height, c.taa));
    if (frames) {
        const uint16_t lw = (uint16_t)(w > 6 ? w * 555 / 1000 : w), lh = (uint16_t)(h > 6 ? h * 555 / 1000 : h);
        uint8_t *lp = malloc((size_t)lw * lh * 3u), *img = malloc((size_t)w * h * 3u);
        int16_t *mv = malloc((size_t)lw * lh * 2u * sizeof *mv);
        for (size_t i = 0; i < (size_t)lw * lh * 3u; i++) lp[i] = (uint8_t)(i * 29u);
        for (size_t i = 0; i < (size_t)lw * lh * 2u; i++) mv[i] = (int16_t)((int)(i % 41u) - 20);
        for (size_t i = 0; i < (size_t)w * h * 3u; i++) img[i] = (uint8_t)(i * 7u);
        for (int f = 0; f < 3; f++) {
            const tdc_fov_params_t p = {
                (int32_t)(w * 100u + 50u * (uint32_t)f), (int32_t)(h * 140u), 1024, 4077, lw, lh, {0, 0}, 0, 0};
            assert_int_equal(
                tdc_fov_frame(st, &p, lp, (size_t)lw * 3u, mv, (size_t)lw * 2u, img, w * 3u, 11111, img, w * 3u),
                TDC_OK);
        }
        arena_check_guard(&a, "fov frames");
        free(lp);
        free(img);
        free(mv);
    }
    free(a.mem);
}

static void test_fov_arena(void **state)
{
    (void)state;
    static const uint32_t small[][2] = {{4, 4}, {4, 9}, {9, 4}, {33, 17}, {64, 48}};
    for (unsigned i = 0; i < sizeof small / sizeof small[0]; i++) {
        for (int taa = 0; taa < 2; taa++) {
            fov_one(small[i][0], small[i][1], taa, 1, 1);
        }
    }
    for (unsigned p = 0; p < NPANELS; p++) {
        for (int taa = 0; taa < 2; taa++) {
            fov_one(g_panels[p]->width, g_panels[p]->height, taa, 1, 0);
        }
    }
    fov_one(TDC_FOV_MAX_SIZE, TDC_FOV_MAX_SIZE, 1, 0, 0);
    fov_one(TDC_FOV_MIN_SIZE, TDC_FOV_MAX_SIZE, 1, 0, 0);
    const tdc_fov_config_t bad[] = {{3, 4, 0}, {4, 3, 1}, {TDC_FOV_MAX_SIZE + 1, 4, 0}, {4, 4, 2}};
    for (unsigned i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(tdc_fov_get_size(&bad[i]), 0);
    }
    const tdc_fov_config_t c = {64, 48, 1};
    tdc_fov_t st;
    assert_int_equal(tdc_fov_init(&st, &c, g_static_fov, sizeof g_static_fov), TDC_OK);
    assert_int_equal(tdc_fov_get_size(&c), sizeof g_static_fov);
}

/* log-rectilinear scratch (tdc_fov_lr.h): the compile-time bound is what
 * get_size says, the layout is the one list, frames stay inside it */
static void fov_lr_one(uint32_t w, int frames)
{
    const size_t n = tdc_fov_lr_get_size((uint16_t)w), bound = TDC_FOV_LR_MEM_BYTES((size_t)w);
    if (n == 0 || n % TDC_ARENA_ALIGN != 0 || n != bound) {
        fail_msg("fov lr %u: get_size %zu, bound %zu", w, n, bound);
    }
    arena_t a;
    tdc_fov_lr_t lrs, *st = &lrs;
    CHECK_ARENA_INIT(a, n, "fov lr", tdc_fov_lr_init, (st, (uint16_t)w), TDC_FOV_LR_ARENA(WALK, w));
    if (frames) {
        const uint32_t h = 37u;
        const tdc_fov_config_t c = {(uint16_t)w, (uint16_t)h, 0};
        const size_t fn = tdc_fov_get_size(&c); /* the stage's own scratch (radial table, row buffers) */
        uint64_t *fmem = malloc(fn);
        tdc_fov_t fs;
        assert_int_equal(tdc_fov_init(&fs, &c, fmem, fn), TDC_OK);
        assert_int_equal(tdc_fov_lr_attach(&fs, st), TDC_OK);
        const uint16_t lw = (uint16_t)w, lh = (uint16_t)h; /* delta 1: the widest buffer */
        uint8_t *lp = malloc((size_t)lw * lh * 3u), *img = malloc((size_t)w * h * 3u);
        for (size_t i = 0; i < (size_t)lw * lh * 3u; i++) lp[i] = (uint8_t)(i * 29u);
        for (size_t i = 0; i < (size_t)w * h * 3u; i++) img[i] = (uint8_t)(i * 7u);
        for (int f = 0; f < 3; f++) {
            /* the gaze moves off the screen (by 0.78 W) in frame 2 */
            const tdc_fov_params_t p = {(int32_t)(w * 100u) - (int32_t)((uint32_t)f * w * 150u),
                                        (int32_t)(h * 140u),
                                        256,
                                        4077,
                                        lw,
                                        lh,
                                        {16u, 65535u},
                                        TDC_FOV_LOG_RECT,
                                        0};
            assert_int_equal(tdc_fov_frame(&fs, &p, lp, (size_t)lw * 3u, NULL, 0, img, w * 3u, 11111, img, w * 3u),
                             TDC_OK);
        }
        arena_check_guard(&a, "fov lr frames");
        free(lp);
        free(img);
        free(fmem);
    }
    free(a.mem);
}

static void test_fov_lr_arena(void **state)
{
    (void)state;
    static const uint32_t small[] = {4, 9, 33, 64};
    for (unsigned i = 0; i < sizeof small / sizeof small[0]; i++) {
        fov_lr_one(small[i], 1);
    }
    for (unsigned p = 0; p < NPANELS; p++) {
        fov_lr_one(g_panels[p]->width, 0);
    }
    fov_lr_one(TDC_FOV_MAX_SIZE, 0);
    assert_int_equal(tdc_fov_lr_get_size(TDC_FOV_MIN_SIZE - 1u), 0);
    assert_int_equal(tdc_fov_lr_get_size(TDC_FOV_MAX_SIZE + 1u), 0);
}

/* ------------------------------------------------------------ the carver */

static void test_carver(void **state)
{
    (void)state;
    tdc_arena_t a;
    uint64_t mem[4];
    tdc_arena_dry(&a);
    assert_null(tdc_arena_take(&a, 1));
    assert_null(tdc_arena_take(&a, 0));
    assert_int_equal(tdc_arena_size(&a), 8);
    tdc_arena_dry(&a);
    assert_int_equal(tdc_arena_size(&a), TDC_ARENA_ALIGN); /* empty layout: not 0 (0 = invalid) */
    assert_int_equal(tdc_arena_over(&a, (uint8_t *)mem + 1, 16), 0);
    assert_int_equal(tdc_arena_over(&a, NULL, 16), 0);
    assert_int_equal(tdc_arena_over(&a, mem, sizeof mem), 1);
    assert_ptr_equal(tdc_arena_take(&a, 3), (void *)mem);
    assert_ptr_equal(tdc_arena_take(&a, 9), (void *)&mem[1]);
    assert_ptr_equal(tdc_arena_take(&a, 8), (void *)&mem[3]);
    assert_null(tdc_arena_take(&a, 1)); /* past the end: NULL, counted */
    assert_int_equal(tdc_arena_size(&a), 40);
    tdc_arena_dry(&a);
    tdc_arena_take(&a, SIZE_MAX - 2u); /* rounding wraps: invalid */
    assert_int_equal(tdc_arena_size(&a), 0);
    tdc_arena_dry(&a);
    tdc_arena_take(&a, SIZE_MAX / 2u);
    tdc_arena_take(&a, SIZE_MAX / 2u + 16u); /* the sum wraps: invalid */
    assert_int_equal(tdc_arena_size(&a), 0);
}

/* ------------------------------------------------- layered assembly */

static void lasm_one(uint32_t w, uint32_t h, uint16_t layers, int init, int frames, uint8_t history)
{
    const tdc_lasm_config_t c = {(uint16_t)w, (uint16_t)h, layers, 3, 1, 2, history, 3277, &tdc_panel_htc_vive};
    const size_t n = tdc_lasm_get_size(&c);
    const size_t bound = history ? TDC_LASM_MEM_BYTES_HIST((size_t)w, (size_t)h) : TDC_LASM_MEM_BYTES((size_t)w, (size_t)h);
    if (n == 0 || n % TDC_ARENA_ALIGN != 0 || n > bound || (layers == 0xFu && n != bound)) {
        fail_msg("layered assembly %ux%u layers 0x%x: get_size %zu, bound %zu", w, h, layers, n, bound);
    }
    if (!init) {
        return;
    }
    arena_t a;
    tdc_lasm_t ls, *st = &ls;
    CHECK_ARENA_INIT(a, n, "layered assembly", tdc_lasm_init, (st, &c),
                     TDC_LASM_ARENA(WALK, c.width, c.height, TDC_PATTERN_BYTES(c.width, c.height), st->ch[0], st->ch[1],
                                    st->ch[2], st->ch[3], c.history));
    if (frames) {
        const size_t tiles = TDC_TILE_COUNT(w, h);
        tdc_layer_frame_t lf;
        memset(&lf, 0, sizeof lf);
        lf.present = layers;
        lf.hdr.tiles_x = (uint16_t)TDC_TILES(w);
        lf.hdr.tiles_y = (uint16_t)TDC_TILES(h);
        for (unsigned t = 1; t <= TDC_LAYER_MAX; t++) {
            lf.value[t - 1] = malloc(tiles * 3u);
            lf.mv[t - 1] = malloc(tiles * 4u);
            if (layers & TDC_LAYER_PKT_TYPE(t)) {
                lf.hdr.type[lf.hdr.count] = (uint8_t)t;
                lf.hdr.mv_kind[lf.hdr.count++] = t == TDC_LAYER_VISIBILITY ? TDC_LAYER_MV_SHADOW : TDC_LAYER_MV_SURFACE;
            }
        }
        for (uint32_t f = 0; f < 9; f++) {
            for (unsigned t = 0; t < TDC_LAYER_MAX; t++) {
                for (size_t i = 0; i < tiles * 3u; i++) {
                    lf.value[t][i] = (uint8_t)(i * 13u + f * 50u + t);
                }
                for (size_t i = 0; i < tiles * 2u; i++) {
                    lf.mv[t][i] = (int16_t)(f < 4 ? 0 : (int)((i * 7u + t) % 61u) - 30);
                }
            }
            assert_int_equal(tdc_lasm_ingest(st, f, &lf, NULL), TDC_OK);
            assert_int_equal(tdc_lasm_assemble(st, f), TDC_OK);
        }
        arena_check_guard(&a, "layered assembly frames");
        for (unsigned t = 0; t < TDC_LAYER_MAX; t++) {
            free(lf.value[t]);
            free(lf.mv[t]);
        }
    }
    free(a.mem);
}

static void test_lasm_arena(void **state)
{
    (void)state;
    static const uint32_t small[][2] = {{1, 1}, {1, 5}, {3, 1}, {33, 17}, {64, 48}};
    static const uint16_t sets[] = {0x1u, 0x3u, 0x5u, 0xFu};
    for (unsigned i = 0; i < sizeof small / sizeof small[0]; i++) {
        for (unsigned k = 0; k < sizeof sets / sizeof sets[0]; k++) {
            lasm_one(small[i][0], small[i][1], sets[k], 1, 1, 0);
            lasm_one(small[i][0], small[i][1], sets[k], 1, 1, 1);
        }
    }
    for (unsigned p = 0; p < NPANELS; p++) {
        lasm_one(g_panels[p]->width, g_panels[p]->height, 0x3u, 0, 0, 0);
        lasm_one(g_panels[p]->width, g_panels[p]->height, 0xFu, 0, 0, 0);
        lasm_one(g_panels[p]->width, g_panels[p]->height, 0xFu, 0, 0, 1);
    }
    lasm_one(TDC_LASM_MAX_DIM, TDC_LASM_MAX_DIM, 0xFu, 0, 0, 0);
    lasm_one(TDC_LASM_MAX_DIM, TDC_LASM_MAX_DIM, 0xFu, 0, 0, 1);
    lasm_one(1, TDC_LASM_MAX_DIM, 0x1u, 0, 0, 0);
}

/* ------------------------------------------------- per-layer history */

static void lhist_one(uint32_t w, uint32_t h, uint8_t ch, int init)
{
    const tdc_lhist_config_t c = {(uint16_t)w, (uint16_t)h, ch, 3, 3277};
    const size_t n = tdc_lhist_get_size(&c), bound = TDC_LHIST_MEM_BYTES((size_t)w, (size_t)h);
    if (n == 0 || n % TDC_ARENA_ALIGN != 0 || n > bound || (ch == 3u && n != bound)) {
        fail_msg("layer history %ux%u ch %u: get_size %zu, bound %zu", w, h, ch, n, bound);
    }
    if (!init) {
        return;
    }
    arena_t a;
    tdc_lhist_t ls, *st = &ls;
    CHECK_ARENA_INIT(a, n, "layer history", tdc_lhist_init, (st, &c),
                     TDC_LHIST_ARENA(WALK, c.width, c.height, c.channels));
    uint8_t *x = malloc((size_t)w * h * ch);
    int16_t *mv = malloc((size_t)w * h * 4u);
    assert_non_null(x);
    assert_non_null(mv);
    for (uint32_t f = 0; f < 4; f++) {
        for (size_t i = 0; i < (size_t)w * h * ch; i++) {
            x[i] = (uint8_t)(i * 13u + f * 50u);
        }
        for (size_t i = 0; i < (size_t)w * h * 2u; i++) {
            mv[i] = (int16_t)((int)((i * 7u + f) % 61u) - 30);
        }
        assert_int_equal(tdc_lhist_step(st, x, mv, NULL), TDC_OK);
    }
    arena_check_guard(&a, "layer history frames");
    free(x);
    free(mv);
    free(a.mem);
}

static void test_lhist_arena(void **state)
{
    (void)state;
    static const uint32_t small[][2] = {{1, 1}, {1, 5}, {3, 1}, {33, 17}};
    for (unsigned i = 0; i < sizeof small / sizeof small[0]; i++) {
        lhist_one(small[i][0], small[i][1], 1, 1);
        lhist_one(small[i][0], small[i][1], 3, 1);
    }
    for (unsigned p = 0; p < NPANELS; p++) {
        lhist_one(g_panels[p]->width, g_panels[p]->height, 3, 0);
    }
    lhist_one(TDC_LHIST_MAX_DIM, TDC_LHIST_MAX_DIM, 3, 0);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_lasm_arena), cmocka_unit_test(test_lhist_arena),
    cmocka_unit_test(test_carver),    cmocka_unit_test(test_trm_arena), cmocka_unit_test(test_lcd_arena),
    cmocka_unit_test(test_asm_arena), cmocka_unit_test(test_fov_arena), cmocka_unit_test(test_fov_lr_arena),
)
