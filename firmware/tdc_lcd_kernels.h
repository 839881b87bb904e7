/*
 * tdc_lcd_kernels.h - the stateful LCD inverse's hot run (8-bit state, no
 * pair debt), as a kernel pair: the portable C version (what the boards
 * run, tdc_lcd_state.c) and an x86-64 AVX2 version with gathers
 * (tdc_lcd_avx2.c) for host builds, checked bit for bit against each other
 * by tests/checkasm/checkasm_lcd.c.  tdc_lcd_init() picks the AVX2 run when
 * the CPU has AVX2.
 *
 * The run: from sub-pixel i (pixel aligned) of a row of w3 sub-pixels, in
 * steps of 8 pixels (24 sub-pixels; c = s mod 3, q = state[s], w = in[s])
 *     e = lut[c * 65536 + (q << 8 | w)];  out[s] = e & 255;  state[s] = e >> 8
 * while no drive of the step is 0 or 255 (only there can a target be out
 * of reach, which needs the old state: the caller runs such a step through
 * the stage's full loop).  Returns the first sub-pixel of the first step not
 * processed (one with a drive of 0 or 255, or the last w3 - i < 24
 * sub-pixels), or w3; nothing from there on is written.  lut: 3 x 65536
 * entries followed by 2 readable bytes (the AVX2 gathers load 32 bits per
 * 16-bit entry; in the stage's arena the reach limits follow, tdc_lcd.h).
 */
#ifndef TDC_LCD_KERNELS_H
#define TDC_LCD_KERNELS_H

#include <stdint.h>

#define TDC_LCD_RUN8_STEP 24u /* sub-pixels per step */

typedef uint32_t tdc_lcd_st_run8_fn(const uint16_t *lut, const uint8_t *in, uint8_t *out, uint8_t *state, uint32_t i,
                                    uint32_t w3);

tdc_lcd_st_run8_fn tdc_lcd_st_run8_c;
tdc_lcd_st_run8_fn tdc_lcd_st_run8_avx2; /* the C run on targets without AVX2 */

/* 1 when this build has the AVX2 run and the CPU runs it. */
int tdc_lcd_avx2_available(void);

#endif /* TDC_LCD_KERNELS_H */
