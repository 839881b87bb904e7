/*
 * tdc_panel.h - panel profile as the firmware sees it.  Profiles are text
 * files boards/panels/NAME.panel; hosttools/tablegen turns each into a C
 * file with a const tdc_panel_t and its integer tables (never typed by hand)
 * and a config header with compile-time sizes for static buffers.
 */
#ifndef TDC_PANEL_H
#define TDC_PANEL_H

#include "tdc_fixed.h"

typedef enum { TDC_PANEL_OLED = 0, TDC_PANEL_LCD = 1 } tdc_panel_type_t;

/* Encoder index: linear Q24 values are bucketed by their top bits. */
#define TDC_ENC_INDEX_BITS 12
#define TDC_ENC_INDEX_SIZE ((1 << TDC_ENC_INDEX_BITS) + 1)

/*
 * One channel's gamma tables, for an N-bit panel with C = 2^N codes:
 *  decode[k]     = round(2^24 * (k / (C-1))^gamma), k = 0..C-1, and
 *                  decode[C] = decode[C-1] so interpolation may read k+1.
 *  enc_thresh[k] = ceil(2^24 * ((k - 0.5) / (C-1))^gamma), k = 1..C-1;
 *                  enc_thresh[0] = 0.  Code k is chosen iff
 *                  enc_thresh[k] <= L < enc_thresh[k+1]: exactly the
 *                  double-precision round(C-1 * L^(1/gamma)).
 *  enc_index[b]  = largest k with enc_thresh[k] <= b << (24 - 12).
 */
typedef struct {
    const uint32_t *decode;
    const uint32_t *enc_thresh;
    const uint16_t *enc_index;
} tdc_gamma_table_t;

struct tdc_lcd_profile; /* defined by the LCD stage (tdc_lcd.h) */

#define TDC_PANEL_MAX_RATES 4

typedef struct {
    const char *name;
    tdc_panel_type_t type;
    uint16_t width; /* pixels per eye */
    uint16_t height;
    uint8_t eyes;                           /* 1 or 2 (side by side) */
    uint8_t bits;                           /* bits per channel of the drive value */
    uint16_t refresh_hz;                    /* nominal refresh */
    uint16_t ppd_x100;                      /* pixels per degree at the view centre x 100 (0: unknown); host
                              * simulator's viewing geometry (FLIP, eye), unused by the firmware */
    /* photometry and viewing distance (0: not in the profile); host simulator's
     * retinal signal (sim/eye/tdc_retina.h), unused by the firmware */
    uint32_t peak_mcdm2;  /* luminance of full drive, milli-cd/m^2 */
    uint32_t black_ucdm2; /* luminance of drive 0, micro-cd/m^2 */
    uint32_t distance_mm; /* viewing distance (HMD: of the lens's virtual image) */
    uint16_t rates_hz[TDC_PANEL_MAX_RATES]; /* supported refresh rates, 0-terminated */
    uint32_t gamma_micro[3];                /* per-channel gamma x 1e6: exactly the value the tables came from */
    tdc_gamma_table_t gamma[3];
    const struct tdc_lcd_profile *lcd; /* NULL for OLED */
} tdc_panel_t;

#endif /* TDC_PANEL_H */
