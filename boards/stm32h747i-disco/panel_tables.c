/*
 * panel_tables.c - the command tables of the DISCO's MB1166 panel, one per
 * controller, sent by dsi_panel.c after the ID read, then the MIPI DCS
 * start-up both share.
 *
 * Format (disco.h, tdc_disco_panel_cmd_t): one row per register write,
 *   { register, parameter count, wait in ms after it, { parameters } }.
 * A register above 0xFF is an OTM8009A "command 2" address written as the
 * data sheet names it (C480h = register C4h, parameter 80h): the Orise
 * address shift (DCS 00h with the low byte) goes first, then the high byte
 * with the parameters.  0-1 parameters go as a DCS short write (0x05, 0x15),
 * more as a DCS long write (0x39).
 *
 * Sources: register addresses and names from the OTM8009A data sheet
 * (Orise Tech; command set 2) and the NT35510 data sheet (Novatek;
 * manufacturer command set pages 0 and 1); the values that set up this
 * panel (voltages, GOA timing, gamma) are the MB1166 figures of ST's
 * STM32H747I-DISCO board support (otm8009a.c / nt35510.c, read, not
 * copied), compared with Linux's panel-orisetech-otm8009a.c (ST's driver
 * for the same controller: the registers it writes carry the same values;
 * it leaves out the first C1A1h = 08h and C6B1h).  Where ST's BSP order and the
 * data sheet disagree the data sheet wins: the OTM8009A gamma tables
 * (E100h, E200h) belong to command set 2, so they go before the set is
 * closed, as Linux has them (ST's BSP writes them after).
 * tests/disco/test_disco.py holds these figures a second time, in the data
 * sheets' notation, and checks the bytes on the DSI link against them.
 *
 * Content-adaptive brightness (DCS 55h) stays off (its reset value,
 * written again): it scales the backlight with the picture, so the light a
 * code gives would depend on the frame, which the LCD model cannot follow.
 */
#include "disco.h"

/* OTM8009A (MB1166 before revision A09), command set 2. */
const tdc_disco_panel_cmd_t tdc_disco_otm8009a_table[] = {
    {0xFF00u, 3u, 0u, {0x80u, 0x09u, 0x01u}},  /* CMD2 enable 1: enter command 2, EXTC */
    {0xFF80u, 2u, 0u, {0x80u, 0x09u}},         /* CMD2 enable 2: Orise mode (address shift) */
    {0xC480u, 1u, 10u, {0x30u}},               /* SD_PCH_CTRL: source at GND in porches */
    {0xC48Au, 1u, 10u, {0x40u}},               /* not documented (ST: needed on this glass) */
    {0xC5B1u, 1u, 0u, {0xA9u}},                /* PWR_CTRL4 +1: GVDD test mode on */
    {0xC591u, 1u, 0u, {0x34u}},                /* PWR_CTRL2 +1: pump 4 VGH 13 V, pump 5 VGL -9 V */
    {0xC0B4u, 1u, 0u, {0x50u}},                /* P_DRV_M: column inversion */
    {0xD900u, 1u, 0u, {0x4Eu}},                /* VCOMDC */
    {0xC181u, 1u, 0u, {0x66u}},                /* OSC_ADJ: 65 Hz idle/normal oscillator */
    {0xC1A1u, 1u, 0u, {0x08u}},                /* RGB_VID_SET: video mode internal */
    {0xC592u, 1u, 0u, {0x01u}},                /* PWR_CTRL2 +2: pumps 4 and 5 x6 */
    {0xC595u, 1u, 0u, {0x34u}},                /* PWR_CTRL2 +5: pump 4 clock 1/2 line */
    {0xD800u, 2u, 0u, {0x79u, 0x79u}},         /* GVDDSET: GVDD, NGVDD */
    {0xC594u, 1u, 0u, {0x33u}},                /* PWR_CTRL2 +4 (reset value, rewritten) */
    {0xC0A3u, 1u, 0u, {0x1Bu}},                /* SD_CTRL +1: source driver timing */
    {0xC582u, 1u, 0u, {0x83u}},                /* PWR_CTRL1 +2 */
    {0xC481u, 1u, 0u, {0x83u}},                /* SD_PCH_CTRL +1: source precharge */
    {0xC1A1u, 1u, 0u, {0x0Eu}},                /* RGB_VID_SET */
    {0xB3A6u, 2u, 0u, {0x00u, 0x01u}},         /* PANSET: panel type */
    {0xCE80u, 6u, 0u, {0x85u, 0x01u, 0x00u, 0x84u, 0x01u, 0x00u}}, /* GOAVST */
    {0xCEA0u, 14u, 0u, {0x18u, 0x04u, 0x03u, 0x39u, 0x00u, 0x00u, 0x00u,   /* GOACLKA1, A2 */
                        0x18u, 0x03u, 0x03u, 0x3Au, 0x00u, 0x00u, 0x00u}},
    {0xCEB0u, 14u, 0u, {0x18u, 0x02u, 0x03u, 0x3Bu, 0x00u, 0x00u, 0x00u,   /* GOACLKA3, A4 */
                        0x18u, 0x01u, 0x03u, 0x3Cu, 0x00u, 0x00u, 0x00u}},
    {0xCFC0u, 10u, 0u, {0x01u, 0x01u, 0x20u, 0x20u, 0x00u, 0x00u, 0x01u, 0x02u, 0x00u, 0x00u}}, /* GOAECLK */
    {0xCFD0u, 1u, 0u, {0x00u}},                /* not documented */
    {0xCB80u, 10u, 0u, {0}},                   /* PANCTRLSET1..8: which GOA outputs drive */
    {0xCB90u, 15u, 0u, {0}},
    {0xCBA0u, 15u, 0u, {0}},
    {0xCBB0u, 10u, 0u, {0}},
    {0xCBC0u, 15u, 0u, {0x00u, 0x04u, 0x04u, 0x04u, 0x04u, 0x04u}},
    {0xCBD0u, 15u, 0u, {0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x04u, 0x04u, 0x04u, 0x04u, 0x04u}},
    {0xCBE0u, 10u, 0u, {0}},
    {0xCBF0u, 10u, 0u, {0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu}},
    {0xCC80u, 10u, 0u, {0x00u, 0x26u, 0x09u, 0x0Bu, 0x01u, 0x25u}}, /* PANU2D1..3: scan up to down */
    {0xCC90u, 15u, 0u, {0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x00u,
                        0x26u, 0x0Au, 0x0Cu, 0x02u}},
    {0xCCA0u, 15u, 0u, {0x25u}},
    {0xCCB0u, 10u, 0u, {0x00u, 0x25u, 0x0Cu, 0x0Au, 0x02u, 0x26u}}, /* PAND2U1..3: down to up */
    {0xCCC0u, 15u, 0u, {0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x00u,
                        0x25u, 0x0Bu, 0x09u, 0x01u}},
    {0xCCD0u, 15u, 0u, {0x26u}},
    {0xC581u, 1u, 0u, {0x66u}},                /* PWR_CTRL1 +1: pump 1 min/max */
    {0xF5B6u, 1u, 0u, {0x06u}},                /* not documented */
    {0xC6B1u, 1u, 0u, {0x06u}},                /* PWM_PARA3: LEDPWM 19.5 kHz */
    {0xE100u, 16u, 0u, {0x00u, 0x09u, 0x0Fu, 0x0Eu, 0x07u, 0x10u, 0x0Bu, 0x0Au,   /* GMCT2.2P: gamma + */
                        0x04u, 0x07u, 0x0Bu, 0x08u, 0x0Fu, 0x10u, 0x0Au, 0x01u}},
    {0xE200u, 16u, 0u, {0x00u, 0x09u, 0x0Fu, 0x0Eu, 0x07u, 0x10u, 0x0Bu, 0x0Au,   /* GMCT2.2N: gamma - */
                        0x04u, 0x07u, 0x0Bu, 0x08u, 0x0Fu, 0x10u, 0x0Au, 0x01u}},
    {0xFF00u, 3u, 0u, {0xFFu, 0xFFu, 0xFFu}},  /* CMD2 enable 1 = FF: leave command 2 */
    {0x00u, 0u, 0u, {0}},                      /* DCS nop: back to the standard set */
};
const uint32_t tdc_disco_otm8009a_rows = sizeof tdc_disco_otm8009a_table / sizeof tdc_disco_otm8009a_table[0];

/* NT35510 (MB1166-A09): manufacturer command set, page 1 (power) then
 * page 0 (display control).  Page select: F0h with the key 55 AA 52 08
 * and the page number. */
const tdc_disco_panel_cmd_t tdc_disco_nt35510_table[] = {
    {0xF0u, 5u, 0u, {0x55u, 0xAAu, 0x52u, 0x08u, 0x01u}}, /* MAUCCTR: page 1 */
    {0xB0u, 3u, 0u, {0x03u, 0x03u, 0x03u}},  /* SETAVDD: 5.2 V */
    {0xB6u, 3u, 0u, {0x46u, 0x46u, 0x46u}},  /* BT1CTR: AVDD ratio */
    {0xB1u, 3u, 0u, {0x03u, 0x03u, 0x03u}},  /* SETAVEE: -5.2 V */
    {0xB7u, 3u, 0u, {0x36u, 0x36u, 0x36u}},  /* BT2CTR: AVEE ratio */
    {0xB2u, 3u, 0u, {0x00u, 0x00u, 0x02u}},  /* SETVCL: -2.5 V */
    {0xB8u, 3u, 0u, {0x26u, 0x26u, 0x26u}},  /* BT3CTR: VCL ratio */
    {0xBFu, 1u, 0u, {0x01u}},                /* VGHCTR: VGH from the free pump */
    {0xB3u, 3u, 0u, {0x09u, 0x09u, 0x09u}},  /* SETVGH: 15 V */
    {0xB9u, 3u, 0u, {0x36u, 0x36u, 0x36u}},  /* BT4CTR: VGH ratio */
    {0xB5u, 3u, 0u, {0x08u, 0x08u, 0x08u}},  /* SETVGL: -10 V */
    {0xBAu, 3u, 0u, {0x26u, 0x26u, 0x26u}},  /* BT5CTR: VGLX ratio */
    {0xBCu, 3u, 0u, {0x00u, 0x80u, 0x00u}},  /* SETVGP: VGMP 4.5 V, VGSP 0 V */
    {0xBDu, 3u, 0u, {0x00u, 0x80u, 0x00u}},  /* SETVGN: VGMN -4.5 V, VGSN 0 V */
    {0xBEu, 2u, 0u, {0x00u, 0x50u}},         /* SETVCMOFF: VCOM -1.325 V */
    {0xF0u, 5u, 0u, {0x55u, 0xAAu, 0x52u, 0x08u, 0x00u}}, /* MAUCCTR: page 0 */
    {0xB1u, 2u, 0u, {0xFCu, 0x00u}},         /* DOPCTR: display options */
    {0xB6u, 1u, 0u, {0x03u}},                /* SDHDTCTR: source output hold time */
    {0xB5u, 1u, 0u, {0x50u}},                /* DPRSLCTR: 480 x 800 */
    {0xB7u, 2u, 0u, {0x00u, 0x00u}},         /* GSEQCTR: gate EQ */
    {0xB8u, 4u, 0u, {0x01u, 0x02u, 0x02u, 0x02u}}, /* SDEQCTR: source EQ, mode 2 */
    {0xBCu, 3u, 0u, {0x00u, 0x00u, 0x00u}},  /* INVCTR: column inversion */
    {0xCCu, 3u, 0u, {0x03u, 0x00u, 0x00u}},  /* (page 0 CCh: ST's figure, unnamed) */
    /* 200 ms before the DCS start-up: ST measured that MADCTL is not taken
     * earlier on this glass. */
    {0xBAu, 1u, 200u, {0x01u}},              /* SDVPCTR: source output in porch */
};
const uint32_t tdc_disco_nt35510_rows = sizeof tdc_disco_nt35510_table / sizeof tdc_disco_nt35510_table[0];

/* MIPI DCS 1.1 start-up, both controllers, landscape RGB888 800 x 480. */
const tdc_disco_panel_cmd_t tdc_disco_dcs_startup[] = {
    {0x11u, 0u, 120u, {0}},                       /* exit_sleep_mode; 120 ms (the longer of the two parts) */
    {0x3Au, 1u, 0u, {0x77u}},                     /* set_pixel_format: 24 bit/pixel */
    {0x36u, 1u, 0u, {0x60u}},                     /* set_address_mode: MV | MX, landscape */
    {0x2Au, 4u, 0u, {0x00u, 0x00u, 0x03u, 0x1Fu}}, /* set_column_address: 0..799 */
    {0x2Bu, 4u, 0u, {0x00u, 0x00u, 0x01u, 0xDFu}}, /* set_page_address: 0..479 */
    {0x35u, 1u, 0u, {0x00u}},                     /* set_tear_on: vertical blanking only */
    {0x51u, 1u, 0u, {0xFFu}},                     /* write_display_brightness: full */
    {0x53u, 1u, 0u, {0x2Cu}},                     /* write_control_display: BCTRL, DD, BL */
    {0x55u, 1u, 0u, {0x00u}},                     /* write_CABC: off */
    {0x29u, 0u, 0u, {0}},                         /* set_display_on */
    {0x2Cu, 0u, 0u, {0}},                         /* write_memory_start: the video stream follows */
};
const uint32_t tdc_disco_dcs_startup_rows = sizeof tdc_disco_dcs_startup / sizeof tdc_disco_dcs_startup[0];
