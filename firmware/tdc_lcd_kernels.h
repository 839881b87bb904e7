/*
 * tdc_lcd_kernels.h - the stateful LCD inverse's hot run (8-bit state, no
 * pair debt), as a kernel pair: the portable C version (what the boards
 * run, tdc_lcd_state.c) and an x86-64 AVX2 version with gathers
 * (tdc_lcd_avx2.c) for host builds, checked bit for bit against each other
 * by tests/checkasm/checkasm_lcd.c.  tdc_lcd_init() picks the AVX2 run when
 * the CPU has AVX2.
 *
 * The run, over sub-pixels i .. w3 - 1 of a row (i a multiple of 3: pixel
 * aligned; c = s mod 3, q = state[s], w = in[s]):
 *     e = lut[c * 65536 + (q << 8 | w)];  out[s] = e & 255;  state[s] = e >> 8
 * and for every sub-pixel out of reach -- a drive of 0 or 255 (only there
 * can a target be out of reach) and w > whi[c * 256 + q] or
 * w < wlo[c * 256 + q] -- a call miss(ctx, s, q, w) with its old state, in
 * ascending s, so the caller adds the light it could not deliver.
 * Memory read beyond the tables (the AVX2 gathers load 32 bits per
 * element): 2 bytes after lut's last entry, 3 bytes before whi and before
 * wlo.  In the stage's arena (tdc_lcd.h) those are the neighbouring blocks
 * st_lhi, st_llo and st_whi; a test must pad likewise.
 */
#ifndef TDC_LCD_KERNELS_H
#define TDC_LCD_KERNELS_H

#include <stdint.h>

typedef void tdc_lcd_st_miss_fn(void *ctx, uint32_t s, uint32_t q, uint32_t w);
typedef void tdc_lcd_st_run8_fn(const uint16_t *lut, const uint8_t *whi, const uint8_t *wlo, const uint8_t *in,
                                uint8_t *out, uint8_t *state, uint32_t i, uint32_t w3, tdc_lcd_st_miss_fn *miss,
                                void *ctx);

tdc_lcd_st_run8_fn tdc_lcd_st_run8_c;
tdc_lcd_st_run8_fn tdc_lcd_st_run8_avx2; /* the C run on targets without AVX2 */

/* 1 when this build has the AVX2 run and the CPU runs it. */
int tdc_lcd_avx2_available(void);

#endif /* TDC_LCD_KERNELS_H */
