/*
 * tdc_trm_rows.c - TRM's per-row kernels in portable C: the reference the
 * AVX2 kernels are checked against and what the boards run.  Formats and
 * contracts in tdc_trm_kernels.h.
 */
#include "tdc_trm_kernels.h"

#include "tdc_math.h"

void tdc_trm_rowctx_init(tdc_trm_rowctx_t *k, const tdc_panel_t *panel, const uint16_t *ux, const uint32_t *wexp,
                         uint32_t width, uint32_t s_q8, const uint8_t *enc_comb, uint32_t enc_one_step)
{
    for (int c = 0; c < 3; c++) {
        k->dec[c] = panel->gamma[c].decode;
        k->thr[c] = panel->gamma[c].enc_thresh;
        k->idx[c] = panel->gamma[c].enc_index;
        k->enc_comb[c] = enc_comb ? enc_comb + (size_t)c * TDC_TRM_ENC_COMB : NULL;
    }
    k->ux = ux;
    k->wexp = wexp;
    k->width = width;
    k->s_q8 = s_q8;
    k->enc_one_step = enc_one_step;
}

/* tdc_trm_wexp_q30[]: defined by the generated header, in this file only. */
#include "tdc_trm_tables.h"

/* Half an output code in code Q16: the quantisation of a reduced frame. */
#define TDC_TRM_HALF_CODE_Q16 (1u << 15)

void tdc_trm_full_row_c(const tdc_trm_rowctx_t *k, const uint32_t *urow_in, const uint8_t *src_in, uint8_t *dst_in,
                        tdc_res_t *res_in, tdc_trm_full_counts_t *n)
{
    const uint32_t *restrict urow = urow_in;
    const uint8_t *restrict src = src_in;
    uint8_t *restrict dst = dst_in;
    tdc_res_t *restrict res = res_in;
    const uint16_t *restrict ux = k->ux;
    tdc_trm_gamma_t g[3];
    tdc_trm_gamma_locals(k, g);
    const uint32_t w = k->width;
    uint32_t nhi = 0, nlo = 0;
    for (uint32_t x = 0; x < w; x++) {
        const uint32_t i0 = 3u * ux[2u * x], f = ux[2u * x + 1u];
#pragma GCC unroll 3
        for (uint32_t c = 0; c < 3u; c++) {
            const tdc_lin_t lu = tdc_trm_dec_q16(&g[c], tdc_trm_hlerp(urow, i0 + c, f));
            const tdc_lin_t li = (tdc_lin_t)g[c].dec[src[3u * x + c]];
            /* beta = 2 LI - Lu in [-1, 2] (Q24): no overflow in int32 */
            tdc_trm_put_beta(&g[c], 2 * li - lu, &res[3u * x + c], &dst[3u * x + c], &nhi, &nlo);
        }
    }
    n->hi += nhi;
    n->lo += nlo;
}

void tdc_trm_reduced_row_c(const tdc_trm_rowctx_t *k, const uint32_t *urow_a_in, const uint32_t *urow_b_in,
                           const tdc_res_t *res_in, uint8_t *dst_in, tdc_trm_reduced_counts_t *n)
{
    const uint32_t *restrict urow_a = urow_a_in;
    const uint32_t *restrict urow_b = urow_b_in;
    const tdc_res_t *restrict res = res_in;
    uint8_t *restrict dst = dst_in;
    const uint16_t *restrict ux = k->ux;
    tdc_trm_gamma_t g[3];
    tdc_trm_gamma_locals(k, g);
    const uint32_t w = k->width;
    uint32_t computed = 0, skipped = 0, no_res = 0;
    for (uint32_t x = 0; x < w; x++) {
        const uint32_t i0 = 3u * ux[2u * x], f = ux[2u * x + 1u];
#pragma GCC unroll 3
        for (uint32_t c = 0; c < 3u; c++) {
            const uint32_t gb = tdc_trm_hlerp(urow_b, i0 + c, f);
            const tdc_lin_t alpha = tdc_trm_dec_q16(&g[c], gb);
            const int32_t rho = res[3u * x + c];
            int32_t shown = alpha;
            if (rho == 0) {
                no_res++; /* nothing to add: the weight is not needed */
            } else {
                uint32_t ga = tdc_trm_hlerp(urow_a, i0 + c, f);
                int32_t w_q15;
                /* Motion test at the link's precision: the reduced frame
                 * arrives in whole codes, so U(D(I_t)) is first moved half
                 * a code towards U(i).  A static pair (i = round D(I)) then
                 * has c = 0 exactly and skips the weight; the shrink is
                 * continuous, so no tie can flip it. */
                if (ga > gb + TDC_TRM_HALF_CODE_Q16) {
                    ga -= TDC_TRM_HALF_CODE_Q16;
                } else if (gb > ga + TDC_TRM_HALF_CODE_Q16) {
                    ga += TDC_TRM_HALF_CODE_Q16;
                } else {
                    ga = gb;
                }
                if (ga == gb) {
                    w_q15 = 32768; /* c = 0 known: static, exp(0) = 1 */
                    skipped++;
                } else {
                    w_q15 = tdc_trm_motion_weight_q15(k, tdc_trm_dec_q16(&g[c], ga), alpha);
                    computed++;
                }
                /* alpha' = alpha + w rho: Q15 * Q24 -> Q24; w <= 2^15 and
                 * |rho| <= 2^24, so the product cannot saturate: not
                 * tdc_fixed.h's saturating multiply, whose dead 64-bit
                 * clamp cost 132 bytes of Cortex-M7 code in this loop */
                shown = alpha + (int32_t)tdc_rshr_round64((int64_t)w_q15 * rho, 15);
            }
            shown = shown < 0 ? 0 : (shown > TDC_LIN_ONE ? TDC_LIN_ONE : shown);
            dst[3u * x + c] = (uint8_t)tdc_trm_enc(&g[c], shown);
        }
    }
    n->computed += computed;
    n->skipped += skipped;
    n->no_res += no_res;
}

/* Scaling and overflow: weights Q15 summing to 2^15 times values <= 65280
 * (code Q8) < 2^31; (acc + 2^14) >> 15 is code Q8 again. */
void tdc_trm_dvert_c(const uint16_t *const *rows, const uint16_t *w, uint32_t taps, uint32_t n, uint16_t *out)
{
    for (uint32_t i = 0; i < n; i++) {
        uint32_t acc = 0;
        for (uint32_t t = 0; t < taps; t++) {
            acc += w[t] * (uint32_t)rows[t][i];
        }
        out[i] = (uint16_t)((acc + (1u << 14)) >> 15);
    }
}

/* Horizontal pass of D over one full-res row (see tdc_trm_kernels.h).
 * Scaling and overflow: sum of weights 2^15 times codes <= 255 < 2^23;
 * result (acc + 2^6) >> 7 is code Q8 <= 65280. */
void tdc_trm_dhoriz_c(const uint8_t *row, uint32_t width, const int16_t *first, const uint16_t *w_all, uint32_t taps,
                      uint32_t rw, uint16_t *dst)
{
    const int32_t wmax = (int32_t)width - 1;
    for (uint32_t j = 0; j < rw; j++) {
        const int32_t k0 = first[j];
        const uint16_t *w = &w_all[j * taps];
        uint32_t a0 = 0, a1 = 0, a2 = 0;
        if (k0 >= 0 && k0 + (int32_t)taps - 1 <= wmax) {
            const uint8_t *p = row + 3 * k0;
            for (uint32_t t = 0; t < taps; t++, p += 3) {
                a0 += w[t] * (uint32_t)p[0];
                a1 += w[t] * (uint32_t)p[1];
                a2 += w[t] * (uint32_t)p[2];
            }
        } else {
            for (uint32_t t = 0; t < taps; t++) {
                const int32_t q = k0 + (int32_t)t;
                const uint8_t *p = row + 3 * (q < 0 ? 0 : (q > wmax ? wmax : q));
                a0 += w[t] * (uint32_t)p[0];
                a1 += w[t] * (uint32_t)p[1];
                a2 += w[t] * (uint32_t)p[2];
            }
        }
        dst[3u * j] = (uint16_t)((a0 + 64u) >> 7);
        dst[3u * j + 1u] = (uint16_t)((a1 + 64u) >> 7);
        dst[3u * j + 2u] = (uint16_t)((a2 + 64u) >> 7);
    }
}

/* U's vertical lerp (see tdc_trm_kernels.h).  Scaling: a 2^14 <= 65280 *
 * 2^14 < 2^30 and |b - a| f < 65280 * 2^14 < 2^30: exact in int32. */
void tdc_trm_uvert_c(const uint16_t *a, const uint16_t *b, uint32_t f, uint32_t n, uint32_t *dst)
{
    for (uint32_t i = 0; i < n; i++) {
        dst[i] = (uint32_t)((int32_t)a[i] * (1 << 14) + ((int32_t)b[i] - (int32_t)a[i]) * (int32_t)f);
    }
}

/* The same from 8-bit codes (code c = code Q8 c << 8): a 2^22 + (b - a) f
 * 2^8, both terms < 2^30. */
void tdc_trm_uvert_codes_c(const uint8_t *a, const uint8_t *b, uint32_t f, uint32_t n, uint32_t *dst)
{
    for (uint32_t i = 0; i < n; i++) {
        dst[i] = (uint32_t)((int32_t)a[i] * (1 << 22) + ((int32_t)b[i] - (int32_t)a[i]) * (int32_t)f * 256);
    }
}
