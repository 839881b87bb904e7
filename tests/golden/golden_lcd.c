/*
 * golden_lcd.c - bit-exact golden vectors of the LCD stage: contents x
 * inverse modes (exact solve, 17x17 and 33x33 tables, reduced-precision
 * previous frame) x LCD panels and refresh rates, 7 frames each with a
 * stream reset before frame 5 (the first-frame path runs twice).  One
 * checksum per frame: FNV-1a 64 over the drive codes and the residual rho
 * (little-endian bytes), which the stage adds unreached light to.
 * Freestanding, static buffers (~25 KiB).
 */
#include "golden.h"
#include "tdc_content.h"
#include "tdc_lcd.h"
#include "tdc_panels.h"

#define GW 37 /* odd sizes on purpose */
#define GH 29
#define GN (GW * GH * 3)

static uint64_t g_arena[TDC_LCD_MEM_BYTES(GW, GH) / 8u];
static uint8_t g_in[GN];
static uint8_t g_out[GN];
static int32_t g_res[GN];

typedef struct {
    tdc_content_t content;
    const tdc_panel_t *panel;
    uint16_t rate;
    uint8_t mode;
    uint8_t bits;
} lcd_vector_t;

static void run_vector(tdc_golden_ctx_t *ctx, const lcd_vector_t *v)
{
    static const char *const mode_name[6] = {"gamma", "exact", "od17", "od33", "state", "pair"};
    char name[80];
    char *o = tdc_golden_put_str(name, tdc_content_name(v->content));
    *o++ = '-';
    o = tdc_golden_put_str(o, v->panel->name);
    *o++ = '-';
    o = tdc_golden_put_u32(o, v->rate);
    o = tdc_golden_put_str(o, "hz-");
    o = tdc_golden_put_str(o, mode_name[v->mode < 6u ? v->mode : 0u]);
    o = tdc_golden_put_str(o, "-b");
    o = tdc_golden_put_u32(o, v->bits);
    *o = 0;

    tdc_lcd_config_t cfg = {GW, GH, v->rate, v->mode, v->bits};
    tdc_lcd_t st;
    if (tdc_lcd_init(&st, &cfg, v->panel, g_arena, sizeof g_arena) != TDC_OK) {
        tdc_golden_emit(ctx, "lcd", name, 0, 0); /* a failing init shows as a mismatch */
        return;
    }
    for (uint32_t i = 0; i < GN; i++) {
        g_res[i] = (int32_t)(i * 2654435761u >> 12) - (1 << 19); /* a TRM-like residual to add to */
    }
    for (uint32_t t = 0; t < 7u; t++) {
        if (t == 5u) {
            tdc_lcd_reset(&st);
        }
        tdc_content_frame(v->content, t, 5u, g_in, GW, GH, GW * 3);
        const int ok = tdc_lcd_frame(&st, g_in, GW * 3u, g_out, GW * 3u, g_res) == TDC_OK;
        uint64_t h = tdc_fnv1a64(TDC_FNV64_INIT, g_out, sizeof g_out);
        for (uint32_t i = 0; i < GN; i++) {
            const uint32_t r = (uint32_t)g_res[i];
            const uint8_t b[4] = {(uint8_t)r, (uint8_t)(r >> 8), (uint8_t)(r >> 16), (uint8_t)(r >> 24)};
            h = tdc_fnv1a64(h, b, 4);
        }
        tdc_golden_emit(ctx, "lcd", name, t, ok ? h : TDC_GOLDEN_FAILED);
    }
}

void tdc_golden_lcd(tdc_golden_ctx_t *ctx);
void tdc_golden_lcd(tdc_golden_ctx_t *ctx)
{
    static const tdc_content_t contents[] = {TDC_CONTENT_TEXT, TDC_CONTENT_EDGE, TDC_CONTENT_NOISE, TDC_CONTENT_FLASH,
                                             TDC_CONTENT_GRADIENT};
    static const struct {
        uint8_t mode, bits;
    } modes[] = {{TDC_LCD_MODE_EXACT, 8},
                 {TDC_LCD_MODE_TABLE17, 8},
                 {TDC_LCD_MODE_TABLE33, 8},
                 {TDC_LCD_MODE_EXACT, 6},
                 {TDC_LCD_MODE_TABLE33, 5},
                 /* stateful measured tables (issue 18): new vectors, the ones above unchanged */
                 {TDC_LCD_MODE_STATEFUL, 8},
                 {TDC_LCD_MODE_STATEFUL, 6},
                 {TDC_LCD_MODE_STATEFUL_PAIR, 8},
                 {TDC_LCD_MODE_STATEFUL_PAIR, 5}};
    static const struct {
        const tdc_panel_t *panel;
        uint16_t rate;
    } panels[] = {{&tdc_panel_pg279q, 144}, {&tdc_panel_pg279q, 165}, {&tdc_panel_lcd_240, 240}};
    for (unsigned p = 0; p < sizeof panels / sizeof panels[0]; p++) {
        for (unsigned c = 0; c < sizeof contents / sizeof contents[0]; c++) {
            for (unsigned m = 0; m < sizeof modes / sizeof modes[0]; m++) {
                const lcd_vector_t v = {contents[c], panels[p].panel, panels[p].rate, modes[m].mode, modes[m].bits};
                run_vector(ctx, &v);
            }
        }
    }
}
