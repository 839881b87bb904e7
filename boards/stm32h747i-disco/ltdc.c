/*
 * ltdc.c - the LTDC of the STM32H747I-DISCO (RM0399 chapter "LCD-TFT
 * display controller (LTDC)"): pixel clock from PLL3, the panel's timings,
 * layer 1 as RGB888 scanning out the frame loop's buffer.
 *
 * Timing registers hold accumulated widths minus one (RM0399 LTDC_SSCR,
 * BPCR, AWCR, TWCR), e.g. AWCR.AAW = HSYNC + HBP + W - 1.  Until the first
 * frame arrives the layer is off and the panel shows the background colour
 * (LTDC_BCCR), the boot test pattern: a uniform dark blue.
 *
 * The LTDC's output reaches the glass through the DSI host in video mode
 * (dsi_panel.c).  Executed in tests/disco against an LTDC model; not yet
 * run on a board.
 */
#include <stdint.h>

#include "board.h"
#include "disco.h"

#define RCC(off) TDC_REG32(TDC_STM32_RCC + (off))
#define LTDC(off) TDC_REG32(TDC_STM32_LTDC + (off))

#define AHBP (TDC_DISCO_LCD_HSYNC + TDC_DISCO_LCD_HBP - 1u)
#define AVBP (TDC_DISCO_LCD_VSYNC + TDC_DISCO_LCD_VBP - 1u)
#define BOOT_BACKGROUND 0x00002060u /* RGB888: dark blue */

static int g_up;

static int pll3_on(void)
{
    /* RCC_PLLCKSELR.DIVM3 (HSE is already the source of every PLL). */
    RCC(0x28) = (RCC(0x28) & ~(0x3Fu << 20)) | (TDC_DISCO_PLL3_M << 20);
    /* RCC_PLLCFGR: PLL3RGE = 2 (4-8 MHz), wide VCO, integer; DIVR3EN. */
    RCC(0x2C) = (RCC(0x2C) & ~(0xFu << 8)) | (2u << 10) | (1u << 24);
    /* RCC_PLL3DIVR: N, R (factor - 1); P and Q unused (/2 each). */
    RCC(0x40) = (TDC_DISCO_PLL3_N - 1u) | (1u << 9) | (1u << 16) | ((TDC_DISCO_PLL3_R - 1u) << 24);
    RCC(0x00) |= 1u << 28; /* PLL3ON */
    for (uint32_t i = 0; i < 1000000u; i++) {
        if (RCC(0x00) & (1u << 29)) { /* PLL3RDY */
            return 1;
        }
    }
    return 0;
}

int tdc_disco_ltdc_init(void)
{
    if (!pll3_on()) {
        tdc_disco_log("stm32h747i-disco: PLL3 (pixel clock) did not lock: no panel output");
        return 0;
    }
    RCC(0xE4) |= 1u << 3; /* RCC_APB3ENR.LTDCEN */
    (void)RCC(0xE4);
    const uint32_t w = TDC_DISCO_LCD_W, h = TDC_DISCO_LCD_H;
    LTDC(0x08) = ((TDC_DISCO_LCD_HSYNC - 1u) << 16) | (TDC_DISCO_LCD_VSYNC - 1u); /* SSCR */
    LTDC(0x0C) = (AHBP << 16) | AVBP;                                           /* BPCR */
    LTDC(0x10) = ((AHBP + w) << 16) | (AVBP + h);                               /* AWCR */
    LTDC(0x14) = ((AHBP + w + TDC_DISCO_LCD_HFP) << 16) | (AVBP + h + TDC_DISCO_LCD_VFP); /* TWCR */
    LTDC(0x2C) = BOOT_BACKGROUND;                                               /* BCCR */
    /* Layer 1: full-screen window, RGB888, opaque (constant alpha 255,
     * BF1 = constant alpha, BF2 = 1 - constant alpha), enabled at the
     * first flip. */
    LTDC(0x88) = ((AHBP + w) << 16) | (AHBP + 1u); /* L1WHPCR */
    LTDC(0x8C) = ((AVBP + h) << 16) | (AVBP + 1u); /* L1WVPCR */
    LTDC(0x94) = 1u;                               /* L1PFCR: RGB888 */
    LTDC(0x98) = 255u;                             /* L1CACR */
    LTDC(0xA0) = (4u << 8) | 5u;                   /* L1BFCR */
    LTDC(0x24) = 1u;                               /* SRCR.IMR: load now */
    LTDC(0x18) |= 1u;                              /* GCR.LTDCEN (polarities active low) */
    g_up = 1;
    return 1;
}

int tdc_disco_ltdc_flip(const uint8_t *fb, uint32_t stride, uint32_t width, uint32_t height)
{
    if (!g_up) {
        return 0;
    }
    const uint32_t w = width < TDC_DISCO_LCD_W ? width : TDC_DISCO_LCD_W;
    const uint32_t h = height < TDC_DISCO_LCD_H ? height : TDC_DISCO_LCD_H;
    /* The LTDC reads SDRAM, not the D-cache: write the visible rows back. */
    tdc_disco_dcache_clean(fb, stride * h);
    LTDC(0xAC) = (uint32_t)(uintptr_t)fb;       /* L1CFBAR */
    LTDC(0xB0) = (stride << 16) | (w * 3u + 7u); /* L1CFBLR: pitch, line length + 7 (RM0399) */
    LTDC(0xB4) = h;                             /* L1CFBLNR */
    LTDC(0x84) = 1u;                            /* L1CR.LEN */
    LTDC(0x24) = 1u << 1;                       /* SRCR.VBR: take it at the next vertical blanking */
    return 1;
}

int tdc_disco_ltdc_vsync(void)
{
    return g_up ? (int)((LTDC(0x48) >> 2) & 1u) : -1; /* LTDC_CDSR.VSYNCS */
}
