/*
 * tdc_lcd_kernels.h - the stateful LCD inverse's row (8-bit state, no pair
 * debt), as a kernel pair: the portable C row (what the boards run,
 * tdc_lcd_state.c) and an x86-64 AVX2 row with gathers (tdc_lcd_avx2.c) for
 * host builds, checked bit for bit against each other (outputs, states,
 * residual, counters) and benchmarked by tests/checkasm/checkasm_lcd.c.
 * tdc_lcd_init() picks the AVX2 row when the CPU has AVX2.
 *
 * The row: for each sub-pixel s of a row of w3 (c = s mod 3, q = state[s],
 * w = in[s]):
 *     e = lut[c * 65536 + (q << 8 | w)];  out[s] = e & 255;  state[s] = e >> 8
 *     k = c * 256 + q
 *     w > whi[k]: miss = dec[c * 256 + w] - lhi[k]    (light not delivered)
 *     w < wlo[k]: miss = dec[c * 256 + w] - llo[k]    (delivered too much)
 *     miss != 0: clamped_high / clamped_low += 1 (miss > 0 / < 0); with a
 *                residual row: res[s] = clamp(sat(res[s] + miss), +-2^24),
 *                residual_added += 1
 * Returns the number of sub-pixels with miss != 0.
 *
 * Readable slack the AVX2 gathers need (32-bit loads of narrower entries):
 * 2 bytes after lut (3 x 65536 entries), 3 bytes after whi and wlo (3 x 256
 * each); the stage's arena provides them (tdc_lcd.h TDC_LCD_ARENA).
 */
#ifndef TDC_LCD_KERNELS_H
#define TDC_LCD_KERNELS_H

#include <stdint.h>

/* The tables of the 8-bit-state row, all [3][...] with the channel major. */
typedef struct {
    const uint16_t *lut;      /* [3][256 states][256 wanted]: drive | next state << 8 */
    const uint8_t *whi, *wlo; /* [3][256 states]: wanted codes above / below are out of reach */
    const int32_t *lhi, *llo; /* [3][256 states]: light (Q24) at the reach limits */
    const int32_t *dec;       /* [3][256 codes]: the panel's decode (Q24 linear light) */
} tdc_lcd_st_tabs_t;

/* Counters a row adds to (the stage's tdc_lcd_stats_t fields). */
typedef struct {
    uint64_t clamped_low, clamped_high, residual_added;
} tdc_lcd_st_counts_t;

typedef uint32_t tdc_lcd_st_row8_fn(const tdc_lcd_st_tabs_t *t, const uint8_t *in, uint8_t *out, uint8_t *state,
                                    uint32_t w3, int32_t *res, tdc_lcd_st_counts_t *n);

tdc_lcd_st_row8_fn tdc_lcd_st_row8_c;
tdc_lcd_st_row8_fn tdc_lcd_st_row8_avx2; /* the C row on targets without AVX2 */

/* 1 when this build has the AVX2 row and the CPU runs it. */
int tdc_lcd_avx2_available(void);

#endif /* TDC_LCD_KERNELS_H */
