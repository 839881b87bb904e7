/*
 * tdc_fw_lcd.c - the LCD inverse as the board frame loop's output stage
 * (tdc_fw_family.h): after every family, on the eye's part of the frame
 * buffer in place, whole frames or the rows a band made final.
 */
#include "tdc_fw_family.h"

#if TDC_CFG_LCD
#include "tdc_lcd.h"

static uint64_t g_lcd_arena[FW_EYES][TDC_LCD_MEM_BYTES_MODE_BITS(FW_W, FW_H, TDC_CFG_LCD_MODE, TDC_CFG_LCD_PREV_BITS) /
                                     8u] TDC_EXTRAM;
static tdc_lcd_t g_lcd[FW_EYES];
static uint8_t g_ok;

/* The overdrive model is per refresh rate: hz, the stream's if the panel
 * has it, else the panel's nominal one. */
void tdc_fw_lcd_configure(uint16_t hz)
{
    g_ok = 1;
    for (uint32_t e = 0; e < FW_EYES; e++) {
        tdc_lcd_config_t cfg = {(uint16_t)FW_W, (uint16_t)FW_H, hz, TDC_CFG_LCD_MODE, (uint8_t)TDC_CFG_LCD_PREV_BITS};
        tdc_status_t st = tdc_lcd_init(&g_lcd[e], &cfg, &TDC_PANEL_SYMBOL, g_lcd_arena[e], sizeof g_lcd_arena[e]);
        if (st == TDC_ERR_PANEL && cfg.mode != TDC_LCD_MODE_EXACT) {
            cfg.mode = TDC_LCD_MODE_EXACT;
            st = tdc_lcd_init(&g_lcd[e], &cfg, &TDC_PANEL_SYMBOL, g_lcd_arena[e], sizeof g_lcd_arena[e]);
        }
        if (st != TDC_OK) {
            tdc_board_log("LCD inverse refused the panel profile: drive = wanted code");
            g_ok = 0;
        }
    }
}

int tdc_fw_lcd_frame(uint32_t e, uint8_t *fb, tdc_res_t *residual)
{
    return g_ok && tdc_lcd_frame(&g_lcd[e], fb, FW_STRIDE, fb, FW_STRIDE, residual) != TDC_OK;
}

int tdc_fw_lcd_rows(uint32_t e, uint8_t *fb, tdc_res_t *residual, uint32_t y0, uint32_t y1)
{
    return g_ok && y1 > y0 && tdc_lcd_rows(&g_lcd[e], fb, FW_STRIDE, fb, FW_STRIDE, residual, y0, y1) != TDC_OK;
}

void tdc_fw_lcd_frame_done(uint32_t e)
{
    if (g_ok) {
        tdc_lcd_frame_done(&g_lcd[e]);
    }
}

/* Rows of a dropped picture hold its history: the eye's LCD starts again
 * without history (never from a mixed one). */
int tdc_fw_lcd_reset(uint32_t e)
{
    if (!g_ok) {
        return 0;
    }
    tdc_lcd_reset(&g_lcd[e]);
    return 1;
}

void tdc_fw_lcd_log(void)
{
    uint64_t dropped = 0;
    for (uint32_t e = 0; e < FW_EYES; e++) {
        dropped += g_lcd[e].stats.residual_dropped;
    }
    tdc_fw_log_kv("LCD unreached light dropped (pixel-channels): ",
                  (uint32_t)(dropped > 0xffffffffu ? 0xffffffffu : dropped));
}
#else
typedef int tdc_fw_lcd_unused_t; /* no LCD inverse in this build: an empty object */
#endif
