/*
 * dsi_panel.c - the DISCO's MIPI-DSI link and its panel (MB1166: OTM8009A
 * controller on older revisions, NT35510 on MB1166-A09).
 *
 * DSI host (RM0399 chapter "DSI Host (DSI)", a Synopsys DesignWare core
 * behind ST's wrapper): regulator, PLL (board.h), D-PHY with 2 data lanes,
 * video mode in burst, RGB888 from the LTDC; commands to the panel in
 * low-power mode.  Video timings go to the host in lane byte clocks:
 * pixels x lane byte clock / pixel clock, rounded down.
 *
 * Panel: reset line PG3 (active low), backlight enable PJ12 (the pins
 * ST's STM32H747I-DISCO BSP names; its tearing-effect pin PJ2 is unused).
 * The controller is told apart by its ID registers (DCS read_ID1 0xDA =
 * 0x40: OTM8009A; read_ID2 0xDB = 0x80: NT35510, the values ST's BSP and
 * Zephyr's driver test).  Each then gets its own register table (power,
 * GOA timing, gamma: panel_tables.c), and both the same MIPI DCS start-up
 * (exit_sleep_mode, 120 ms, pixel format, landscape, window, tear on,
 * brightness, display on).  An unknown controller gets the DCS start-up
 * only, and the log says so.
 *
 * vsync stays on the LTDC (ltdc.c): in video mode the panel follows the
 * host's timing, so the LTDC's vertical sync is the panel's.
 *
 * Executed in tests/disco against a DSI-host and panel model; not yet run
 * on a board.
 */
#include <stdint.h>

#include "board.h"
#include "disco.h"

#define RCC(off) TDC_REG32(TDC_STM32_RCC + (off))
#define DSI(off) TDC_REG32(TDC_STM32_DSI + (off))
#define GPIO(port, off) TDC_REG32(TDC_STM32_GPIO(port) + (off))
enum { PORT_G = 6, PORT_J = 9 };
#define RESET_PIN 3u     /* PG3 */
#define BACKLIGHT_PIN 12u /* PJ12 */

/* Host registers (RM0399 DSI register map). */
enum {
    DSI_CR = 0x04, DSI_CCR = 0x08, DSI_LVCIDR = 0x0C, DSI_LCOLCR = 0x10, DSI_LPCR = 0x14, DSI_LPMCR = 0x18,
    DSI_PCR = 0x2C, DSI_MCR = 0x34, DSI_VMCR = 0x38, DSI_VPCR = 0x3C, DSI_VCCR = 0x40, DSI_VNPCR = 0x44,
    DSI_VHSACR = 0x48, DSI_VHBPCR = 0x4C, DSI_VLCR = 0x50, DSI_VVSACR = 0x54, DSI_VVBPCR = 0x58,
    DSI_VVFPCR = 0x5C, DSI_VVACR = 0x60, DSI_CMCR = 0x68, DSI_GHCR = 0x6C, DSI_GPDR = 0x70, DSI_GPSR = 0x74,
    DSI_CLCR = 0x94, DSI_CLTCR = 0x98, DSI_DLTCR = 0x9C, DSI_PCTLR = 0xA0, DSI_PCONFR = 0xA4,
    DSI_IER0 = 0xC4, DSI_IER1 = 0xC8, DSI_WCFGR = 0x400, DSI_WCR = 0x404, DSI_WISR = 0x40C,
    DSI_WPCR0 = 0x418, DSI_WRPCR = 0x430
};
#define GPSR_CMDFE (1u << 0)
#define GPSR_PWRFE (1u << 2)
#define GPSR_PRDFE (1u << 4)
#define GPSR_RCB (1u << 6)
#define COLOR_24BIT 5u
#define LANE_BYTE_HZ (TDC_DISCO_DSI_LANE_HZ / 8u)
/* Pixels -> lane byte clocks (the host's unit for horizontal timing). */
#define TO_LBC(px) ((uint32_t)(((uint64_t)(px) * LANE_BYTE_HZ) / TDC_DISCO_LCD_PCLK_HZ))

/* Bounded wait on a register. */
static int wait_reg(uint32_t off, uint32_t mask, uint32_t want)
{
    for (uint32_t i = 0; i < 1000000u; i++) {
        if ((DSI(off) & mask) == want) {
            return 1;
        }
    }
    return 0;
}

/* Delay by the DWT cycle counter (running since tdc_board_init), bounded
 * in iterations too, so a stopped counter cannot hang the start-up. */
static void delay_ms(uint32_t ms)
{
    const uint32_t cycles = ms * (TDC_BOARD_CPU_HZ / 1000u);
    const uint32_t t0 = TDC_REG32(TDC_CM_DWT_CYCCNT);
    for (uint32_t i = 0; i < cycles / 2u; i++) {
        if (TDC_REG32(TDC_CM_DWT_CYCCNT) - t0 >= cycles) {
            return;
        }
    }
}

static void pin_output(uint32_t port, uint32_t pin, uint32_t level)
{
    GPIO(port, 0x18) = level ? (1u << pin) : (1u << (pin + 16u)); /* BSRR first: no glitch */
    GPIO(port, 0x00) = (GPIO(port, 0x00) & ~(3u << (2u * pin))) | (1u << (2u * pin));
}

/* One DCS packet in low-power mode: short with 0 or 1 parameter, long
 * (0x39) otherwise; the payload goes to the FIFO before the header. */
static int dcs_write(uint8_t cmd, const uint8_t *p, uint32_t n)
{
    if (!wait_reg(DSI_GPSR, GPSR_CMDFE, GPSR_CMDFE)) {
        return 0;
    }
    if (n == 0u) {
        DSI(DSI_GHCR) = 0x05u | ((uint32_t)cmd << 8);
    } else if (n == 1u) {
        DSI(DSI_GHCR) = 0x15u | ((uint32_t)cmd << 8) | ((uint32_t)p[0] << 16);
    } else {
        uint32_t word = cmd, k = 1u;
        for (uint32_t i = 0; i < n; i++, k++) {
            if (k == 4u) {
                DSI(DSI_GPDR) = word;
                word = 0u;
                k = 0u;
            }
            word |= (uint32_t)p[i] << (8u * k);
        }
        DSI(DSI_GPDR) = word;
        DSI(DSI_GHCR) = 0x39u | (((n + 1u) & 0xFFu) << 8) | (((n + 1u) >> 8) << 16);
    }
    return 1;
}

/* DCS read of one byte: maximum return packet size 1 (0x37), then the
 * read request (0x06); the answer comes back over a bus turnaround. */
static int dcs_read1(uint8_t cmd, uint8_t *out)
{
    if (!wait_reg(DSI_GPSR, GPSR_CMDFE, GPSR_CMDFE)) {
        return 0;
    }
    DSI(DSI_GHCR) = 0x37u | (1u << 8);
    DSI(DSI_GHCR) = 0x06u | ((uint32_t)cmd << 8);
    if (!wait_reg(DSI_GPSR, GPSR_RCB | GPSR_PRDFE, 0u)) {
        return 0;
    }
    *out = (uint8_t)DSI(DSI_GPDR);
    return 1;
}

/* A command table (panel_tables.c): each row as one DCS write, an
 * OTM8009A command-2 address preceded by its address shift, then the
 * row's wait. */
static int send_table(const tdc_disco_panel_cmd_t *t, uint32_t rows)
{
    int ok = 1;
    for (uint32_t i = 0; i < rows; i++) {
        if (t[i].reg > 0xFFu) {
            const uint8_t shift = (uint8_t)(t[i].reg & 0xFFu);
            ok &= dcs_write(0x00u, &shift, 1u);
        }
        ok &= dcs_write((uint8_t)(t[i].reg >> (t[i].reg > 0xFFu ? 8u : 0u)), t[i].p, t[i].n);
        if (t[i].wait_ms != 0u) {
            delay_ms(t[i].wait_ms);
        }
    }
    return ok;
}

int tdc_disco_dsi_init(void)
{
    RCC(0xE0) |= (1u << PORT_G) | (1u << PORT_J); /* RCC_AHB4ENR: GPIOG, GPIOJ */
    RCC(0xE4) |= 1u << 4;                         /* RCC_APB3ENR.DSIEN */
    (void)RCC(0xE4);
    /* Panel in reset, backlight off, while the link comes up. */
    pin_output(PORT_J, BACKLIGHT_PIN, 0u);
    pin_output(PORT_G, RESET_PIN, 0u);

    DSI(DSI_WRPCR) = 1u << 24; /* REGEN */
    if (!wait_reg(DSI_WISR, 1u << 12, 1u << 12)) { /* RRS */
        return 0;
    }
    const uint32_t odf_code = TDC_DISCO_DSI_ODF == 1u ? 0u : TDC_DISCO_DSI_ODF == 2u ? 1u : TDC_DISCO_DSI_ODF == 4u ? 2u : 3u;
    DSI(DSI_WRPCR) = (1u << 24) | (TDC_DISCO_DSI_NDIV << 2) | (TDC_DISCO_DSI_IDF << 11) | (odf_code << 16);
    DSI(DSI_WRPCR) |= 1u; /* PLLEN */
    if (!wait_reg(DSI_WISR, 1u << 8, 1u << 8)) { /* PLLLS */
        return 0;
    }
    DSI(DSI_PCTLR) = (1u << 2) | (1u << 1); /* CKE, DEN */
    DSI(DSI_CLCR) = 1u;                     /* DPCC: clock lane in high speed */
    DSI(DSI_PCONFR) = (10u << 8) | 1u;      /* SW_TIME 10, NL = 2 lanes */
    /* Escape clock = lane byte clock / 4 = 15.6 MHz (<= 20 MHz). */
    DSI(DSI_CCR) = 4u;
    /* 4 x unit interval in ns: UI = 1 / 500 MHz = 2 ns. */
    DSI(DSI_WPCR0) = (4000000000u / (TDC_DISCO_DSI_LANE_HZ / 1000u)) / 1000u;
    DSI(DSI_IER0) = 0u;
    DSI(DSI_IER1) = 0u;
    /* D-PHY transition times in lane byte clocks (35 x 16 ns = 560 ns each
     * way, as ST's DISCO set-up), no read time limit. */
    DSI(DSI_CLTCR) = (35u << 16) | 35u;
    DSI(DSI_DLTCR) = (35u << 24) | (35u << 16);

    /* Video mode from the LTDC: RGB888, burst, low power in every blanking
     * period so commands can go out there. */
    DSI(DSI_MCR) = 0u;
    DSI(DSI_WCFGR) = COLOR_24BIT << 1; /* DSIM = 0 (video), COLMUX */
    DSI(DSI_LVCIDR) = 0u;
    DSI(DSI_LCOLCR) = COLOR_24BIT;
    DSI(DSI_LPCR) = 0u;
    DSI(DSI_VMCR) = 2u | (0x3Fu << 8) | (1u << 15); /* VMT burst, LPVSAE..LPHFPE, LPCE */
    DSI(DSI_VPCR) = TDC_DISCO_LCD_W;
    DSI(DSI_VCCR) = 0u;
    DSI(DSI_VNPCR) = 0u;
    DSI(DSI_VHSACR) = TO_LBC(TDC_DISCO_LCD_HSYNC);
    DSI(DSI_VHBPCR) = TO_LBC(TDC_DISCO_LCD_HBP);
    DSI(DSI_VLCR) = TO_LBC(TDC_DISCO_LCD_HSYNC + TDC_DISCO_LCD_HBP + TDC_DISCO_LCD_W + TDC_DISCO_LCD_HFP);
    DSI(DSI_VVSACR) = TDC_DISCO_LCD_VSYNC;
    DSI(DSI_VVBPCR) = TDC_DISCO_LCD_VBP;
    DSI(DSI_VVFPCR) = TDC_DISCO_LCD_VFP;
    DSI(DSI_VVACR) = TDC_DISCO_LCD_H;
    DSI(DSI_LPMCR) = (64u << 16) | 16u; /* LPSIZE, VLPSIZE (bytes) */
    /* Every command type in low power; bus turnaround for reads. */
    DSI(DSI_CMCR) = (0x7Fu << 8) | (0xFu << 16) | (1u << 24);
    DSI(DSI_PCR) = 1u << 2; /* BTAE */
    return 1;
}

/* Starts the link (the LTDC must already run: the host then locks to its
 * timing), identifies the controller, sends its table and the DCS
 * start-up. */
int tdc_disco_panel_on(void)
{
    DSI(DSI_CR) = 1u;        /* EN */
    DSI(DSI_WCR) = 1u << 3;  /* DSIEN */
    /* Reset pulse: >= 10 us low, then 120 ms before the first command
     * (the longest reset-complete time of the two controllers). */
    delay_ms(1u);
    pin_output(PORT_G, RESET_PIN, 1u);
    delay_ms(120u);

    uint8_t id1 = 0u, id2 = 0u;
    if (!dcs_read1(0xDAu, &id1)) {
        tdc_disco_log("stm32h747i-disco: panel did not answer read_ID1 over DSI");
        return 0;
    }
    const tdc_disco_panel_cmd_t *table = 0;
    uint32_t rows = 0u;
    if (id1 == 0x40u) {
        tdc_disco_log("stm32h747i-disco: panel controller OTM8009A (ID1 0x40)");
        table = tdc_disco_otm8009a_table;
        rows = tdc_disco_otm8009a_rows;
    } else if (dcs_read1(0xDBu, &id2) && id2 == 0x80u) {
        tdc_disco_log("stm32h747i-disco: panel controller NT35510 (ID2 0x80)");
        table = tdc_disco_nt35510_table;
        rows = tdc_disco_nt35510_rows;
    } else {
        tdc_disco_log_hex("stm32h747i-disco: unknown panel controller, ID1 ", id1);
    }

    int ok = 1;
    if (table != 0) {
        ok &= send_table(table, rows);
    }
    ok &= send_table(tdc_disco_dcs_startup, tdc_disco_dcs_startup_rows);
    pin_output(PORT_J, BACKLIGHT_PIN, 1u);
    return ok;
}
