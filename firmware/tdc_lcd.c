/*
 * tdc_lcd.c - LCD temporal model inverse (exact integer solve) and the LCD
 * frame stage.  Model, cases and formats: tdc_lcd.h.
 */
#include "tdc_lcd.h"
#include "tdc_lcd_kernels.h"

#include "tdc_gamma.h"
#include "tdc_math.h"
#include "tdc_overdrive.h"

_Static_assert(sizeof(tdc_res_t) == 4, "the LCD stage adds Q24 light to a 32-bit residual");

#define V_ONE ((int64_t)TDC_LCD_V_ONE)

int32_t tdc_lcd_model_q24(const int32_t p_q24[4], uint32_t v_q16, uint32_t u_q16)
{
    /* Scaling and overflow: v, u <= 2^16 so v^2 + u^2 <= 2^33 and v u <= 2^32;
     * |p| <= 2^26 gives products < 2^59.  Q24 * Q32 >> 32 -> Q24. */
    const int64_t v = v_q16, u = u_q16;
    int64_t sq = tdc_rshr_round64((int64_t)p_q24[0] * (v * v + u * u), 32);
    int64_t cross = tdc_rshr_round64((int64_t)p_q24[1] * (v * u), 32);
    int64_t lin = tdc_mul_q16_32(p_q24[2], (int32_t)(v + u)); /* v + u <= 2^17, |result| < 2^27 */
    return tdc_sat32(sq + cross + lin + p_q24[3]);
}

/* round(n * 2^16 / d) for d != 0, |n| < 2^46: sign handled on magnitudes,
 * so no implementation-defined rounding of negative division. */
static int64_t div_q16_round(int64_t n, int64_t d)
{
    const int neg = (n < 0) != (d < 0);
    const uint64_t un = (uint64_t)(n < 0 ? -n : n) << 16;
    const uint64_t ud = (uint64_t)(d < 0 ? -d : d);
    const uint64_t q = (un + ud / 2u) / ud;
    return neg ? -(int64_t)q : (int64_t)q;
}

int tdc_lcd_quad_root_q16(int64_t a, int64_t b, int64_t c, uint32_t half_lsb_q16, int32_t *v_q16)
{
    const int64_t lo = -(int64_t)half_lsb_q16;
    const int64_t hi = V_ONE + half_lsb_q16;
    if (a == 0) {
        /* p1 = 0: linear b v + c = 0; b == 0 means M does not depend on v. */
        if (b == 0) {
            return 0;
        }
        const int64_t r = div_q16_round(-c, b);
        if (r >= lo && r <= hi) {
            *v_q16 = (int32_t)(r < 0 ? 0 : (r > V_ONE ? V_ONE : r));
            return 1;
        }
        return 0;
    } else {
        /* Scaling and overflow: |a|, |b|, |c| < 2^29 (Q24 with |p| <= 4, m <= 1)
         * so b^2 < 2^58 and |4 a c| < 2^60: the Q48 discriminant fits int64. */
        const int64_t disc = b * b - 4 * a * c;
        if (disc < 0) {
            return 0; /* no real root */
        }
        const int64_t s = (int64_t)tdc_isqrt64((uint64_t)disc); /* Q24, floor */
        /* q2 = 2q = -(b + sgn(b) s): no cancellation.  Roots q2 / (2a) and
         * 2c / q2.  The increasing-branch root (2 a v + b = +s) is 2c / q2 for
         * b >= 0 and q2 / (2a) for b < 0. */
        const int64_t q2 = b >= 0 ? -(b + s) : (s - b);
        /* Increasing-branch root first; the other only if that one is out of
         * range (saves a 64-bit division in the common case). */
        for (int k = 0; k < 2; k++) {
            const int use_cq = (b >= 0) == (k == 0);
            int64_t r;
            if (use_cq) {
                if (q2 == 0) {
                    continue;
                }
                r = div_q16_round(2 * c, q2);
            } else {
                r = div_q16_round(q2, 2 * a);
            }
            if (r >= lo && r <= hi) {
                *v_q16 = (int32_t)(r < 0 ? 0 : (r > V_ONE ? V_ONE : r));
                return 1;
            }
        }
        return 0;
    }
}

/*
 * Unreachable target: the drive among {0, 1, vertex} whose merged value is
 * nearest m.  M(v) - m has one sign over [0, 1] here, so the nearest is
 * the minimum or the maximum of the quadratic, which is at an end or at
 * the vertex -b / (2a).  steady != 0 evaluates M(v, v), else M(v, u).
 */
static void nearest_unreachable(const int32_t p[4], uint32_t u_q16, int steady, int64_t a, int64_t b, uint32_t m_q16,
                                tdc_lcd_solution_t *out)
{
    int64_t cand[3] = {0, V_ONE, -1};
    if (a != 0) {
        int64_t vx = div_q16_round(-b, 2 * a);
        if (vx > 0 && vx < V_ONE) {
            cand[2] = vx;
        }
    }
    const int64_t m_q24 = (int64_t)m_q16 << 8;
    int64_t best_err = INT64_MAX;
    int64_t best_m = 0;
    int32_t best_v = 0;
    for (int k = 0; k < 3; k++) {
        if (cand[k] < 0) {
            continue;
        }
        const uint32_t v = (uint32_t)cand[k];
        const int64_t mv = tdc_lcd_model_q24(p, v, steady ? v : u_q16);
        const int64_t err = mv >= m_q24 ? mv - m_q24 : m_q24 - mv;
        if (err < best_err) {
            best_err = err;
            best_m = mv;
            best_v = (int32_t)v;
        }
    }
    out->v_q16 = best_v;
    out->kind = best_m > m_q24 ? TDC_LCD_CLAMP_LOW : TDC_LCD_CLAMP_HIGH;
}

void tdc_lcd_solve_q16(const int32_t p[4], uint32_t u_q16, uint32_t m_q16, uint32_t half_lsb_q16,
                       tdc_lcd_solution_t *out)
{
    /* a v^2 + b v + c = 0 in Q24: a = p1, b = p2 u + p3, c = M(0, u) - m. */
    const int64_t u = u_q16;
    const int64_t a = p[0];
    const int64_t b = (int64_t)tdc_mul_q16_32(p[1], (int32_t)u) + p[2]; /* u <= 2^16: |p2 u| < 2^26 */
    const int64_t c = (int64_t)tdc_lcd_model_q24(p, 0u, u_q16) - ((int64_t)m_q16 << 8);
    int32_t v;
    if (tdc_lcd_quad_root_q16(a, b, c, half_lsb_q16, &v)) {
        out->v_q16 = v;
        out->kind = TDC_LCD_ROOT;
        return;
    }
    nearest_unreachable(p, u_q16, 0, a, b, m_q16, out);
}

void tdc_lcd_solve_steady_q16(const int32_t p[4], uint32_t m_q16, uint32_t half_lsb_q16, tdc_lcd_solution_t *out)
{
    /* M(v, v) = (2 p1 + p2) v^2 + 2 p3 v + p4. */
    const int64_t a = 2 * (int64_t)p[0] + p[1];
    const int64_t b = 2 * (int64_t)p[2];
    const int64_t c = (int64_t)p[3] - ((int64_t)m_q16 << 8);
    int32_t v;
    if (tdc_lcd_quad_root_q16(a, b, c, half_lsb_q16, &v)) {
        out->v_q16 = v;
        out->kind = TDC_LCD_ROOT;
        return;
    }
    nearest_unreachable(p, 0u, 1, a, b, m_q16, out);
}

/* ------------------------------------------------------------------ */

/* 8-bit code -> Q16: round(k * 65536 / 255) = 257 k + round(k / 255). */
static inline uint32_t code8_to_q16(uint32_t k)
{
    return k * 257u + (k >> 7);
}

/* Q16 -> nearest 8-bit code. */
static inline uint32_t q16_to_code8(uint32_t v)
{
    uint32_t c = (v * 255u + 32768u) >> 16;
    return c > 255u ? 255u : c;
}

/*
 * Linear light P (Q24, [0, 2^24]) -> gamma-compressed value m in Q16.
 * k = the code with decode[k] <= P < decode[k+1]; within the bucket the
 * curve is interpolated linearly (error < 0.3 code in the darkest bucket,
 * < 0.01 code above code 8).  Scaling: (P - decode[k]) < step, times
 * recip = 2^32 / step gives < 2^32 (64-bit product), >> 16 -> Q16 fraction.
 */
static inline uint32_t lin_to_m_q16(const tdc_gamma_table_t *t, const uint32_t *recip, uint32_t p)
{
    uint32_t k = tdc_gamma_encode(t, (tdc_lin_t)p, 255u);
    if (k > 0u && t->decode[k] > p) {
        k--;
    }
    if (k >= 255u) {
        return TDC_LCD_V_ONE;
    }
    uint32_t frac = (uint32_t)(((uint64_t)(p - t->decode[k]) * recip[k]) >> 16);
    if (frac > 65535u) {
        frac = 65535u;
    }
    return ((k << 16) + frac + 127u) / 255u;
}

/*
 * An unreachable target: the pair shows Ls = M(code, u)^g (M clamped to
 * [0, 1], decoded through the panel's gamma table), so the frame-pair SUM
 * misses wl + el - 2 Ls (returned, Q24).  *e_code gets the code of the light
 * refresh t delivered, 2 Ls - el (clamped), assuming t-1 delivered el.
 * Scaling and overflow: ms <= 2^24, ms * 255 < 2^32 (uint64 anyway);
 * wl, el, ls <= 2^24 so the sums stay below 2^26.
 */
static int32_t unreached_light_q24(const int32_t p[4], const tdc_gamma_table_t *gt, uint32_t code, uint32_t u_q16,
                                   uint32_t wl, uint32_t el, uint32_t *e_code)
{
    int32_t ms = tdc_clamp32(tdc_lcd_model_q24(p, code8_to_q16(code), u_q16), 0, TDC_LIN_ONE);
    /* Q24 -> code Q8: ms * 255 * 256 / 2^24 = ms * 255 >> 16, rounded. */
    const uint32_t ms_q8 = (uint32_t)(((uint64_t)(uint32_t)ms * 255u + 32768u) >> 16);
    const int32_t ls = tdc_gamma_decode_gval(gt, ms_q8);
    *e_code = tdc_gamma_encode(gt, tdc_clamp32(2 * ls - (int32_t)el, 0, TDC_LIN_ONE), 255u);
    return (int32_t)(wl + el) - 2 * ls;
}

size_t tdc_lcd_history_bytes(uint32_t width, uint32_t height, unsigned prev_bits)
{
    return 2u * TDC_LCD_PACKED_BYTES((size_t)width * height * 3u, prev_bits);
}

size_t tdc_lcd_cfg_history_bytes(const tdc_lcd_config_t *cfg)
{
    if (!cfg || cfg->mode == TDC_LCD_MODE_GAMMA) {
        return 0;
    }
    const size_t one = TDC_LCD_PACKED_BYTES((size_t)cfg->width * cfg->height * 3u, cfg->prev_bits);
    if (cfg->mode == TDC_LCD_MODE_STATEFUL_PAIR) {
        return one + (size_t)cfg->width * cfg->height * 3u;
    }
    return cfg->mode == TDC_LCD_MODE_STATEFUL ? one : 2u * one;
}

static int lcd_config_valid(const tdc_lcd_config_t *cfg)
{
    return cfg && cfg->width != 0 && cfg->height != 0 && cfg->width <= TDC_LCD_MAX_DIM &&
           cfg->height <= TDC_LCD_MAX_DIM && cfg->mode <= TDC_LCD_MODE_STATEFUL_PAIR && cfg->prev_bits >= 4 &&
           cfg->prev_bits <= 8;
}

/* The one layout (tdc_lcd.h TDC_LCD_ARENA); NULL views in a dry run and for
 * the blocks the mode does not use. */
static void lcd_carve(tdc_lcd_t *st, const tdc_lcd_config_t *cfg, tdc_arena_t *arena)
{
    TDC_LCD_ARENA(TDC_ARENA_CARVE, cfg->width, cfg->height, cfg->prev_bits, cfg->mode)
}

void tdc_lcd_set_simd(tdc_lcd_t *st, int enable)
{
    st->st_row8 = enable && tdc_lcd_avx2_available() ? tdc_lcd_st_row8_avx2 : tdc_lcd_st_row8_c;
}

size_t tdc_lcd_get_size(const tdc_lcd_config_t *cfg)
{
    if (!lcd_config_valid(cfg)) {
        return 0;
    }
    tdc_lcd_t dry;
    tdc_arena_t arena;
    tdc_arena_dry(&arena);
    lcd_carve(&dry, cfg, &arena);
    return tdc_arena_size(&arena);
}

tdc_status_t tdc_lcd_init(tdc_lcd_t *st, const tdc_lcd_config_t *cfg, const tdc_panel_t *panel, void *mem,
                          size_t mem_bytes)
{
    tdc_arena_t arena;
    if (!st || !panel || !lcd_config_valid(cfg) || !tdc_arena_over(&arena, mem, mem_bytes)) {
        return TDC_ERR_ARG; /* null, bad mode or prev_bits, mem not aligned to TDC_ARENA_ALIGN */
    }
    if (panel->type != TDC_PANEL_LCD || !panel->lcd || panel->bits != 8) {
        return TDC_ERR_PANEL;
    }
    const tdc_lcd_rate_t *rate = 0;
    for (unsigned k = 0; k < panel->lcd->nrates && k < TDC_PANEL_MAX_RATES; k++) {
        if (panel->lcd->rate[k].rate_hz == cfg->refresh_hz) {
            rate = &panel->lcd->rate[k];
        }
    }
    if (!rate) {
        return TDC_ERR_PANEL;
    }
    const int16_t *od = cfg->mode == TDC_LCD_MODE_TABLE17   ? rate->od17
                        : cfg->mode == TDC_LCD_MODE_TABLE33 ? rate->od33
                                                            : 0;
    if ((cfg->mode == TDC_LCD_MODE_TABLE17 || cfg->mode == TDC_LCD_MODE_TABLE33) && !od) {
        return TDC_ERR_PANEL;
    }
    st->table_fault = TDC_LCD_TABLE_OK;
    if (TDC_LCD_MODE_IS_STATEFUL(cfg->mode)) {
        st->table_fault = (uint8_t)tdc_lcd_st_validate(rate);
        if (st->table_fault != TDC_LCD_TABLE_OK) {
            return TDC_ERR_PANEL;
        }
    }
    if (mem_bytes < tdc_lcd_get_size(cfg)) { /* the same carve, dry: nothing is touched on error */
        return TDC_ERR_SIZE;
    }
    lcd_carve(st, cfg, &arena);
    st->cfg = *cfg;
    st->panel = panel;
    st->rate = rate;
    st->od = od;
    st->od_n = cfg->mode == TDC_LCD_MODE_TABLE33 ? 33u : 17u;
    st->half_lsb_q16 = 32768u / 255u;
    tdc_od_quant_tables(cfg->prev_bits, st->q_enc, st->q_dec);
    st->stats = (tdc_lcd_stats_t){0};
    st->have_history = 0;
    st->st_phase = 0;
    tdc_lcd_set_simd(st, 1);
    if (TDC_LCD_MODE_IS_STATEFUL(cfg->mode)) {
        tdc_lcd_st_build(st);
        return TDC_OK;
    }
    for (unsigned ch = 0; ch < 3u; ch++) {
        const uint32_t *dec = panel->gamma[ch].decode;
        for (uint32_t k = 0; k < 256u; k++) {
            /* round(2^32 / step), saturated; step >= 1 for any gamma <= 4 at 8 bits. */
            const uint32_t step = k < 255u ? dec[k + 1u] - dec[k] : 0u;
            uint64_t r = step ? ((((uint64_t)1) << 32) + step / 2u) / step : 0u;
            st->m_step_recip[ch * 256u + k] = r > 0xffffffffu ? 0xffffffffu : (uint32_t)r;
        }
    }
    return TDC_OK;
}

void tdc_lcd_reset(tdc_lcd_t *st)
{
    if (st) {
        st->have_history = 0;
        st->st_phase = 0;
    }
}

tdc_status_t tdc_lcd_frame(tdc_lcd_t *st, const uint8_t *wanted, uint32_t in_stride, uint8_t *drive,
                           uint32_t out_stride, tdc_res_t *residual)
{
    const tdc_status_t r = tdc_lcd_rows(st, wanted, in_stride, drive, out_stride, residual, 0, st ? st->cfg.height : 0u);
    if (r == TDC_OK) {
        tdc_lcd_frame_done(st);
    }
    return r;
}

void tdc_lcd_frame_done(tdc_lcd_t *st)
{
    st->stats.frames++;
    if (st->cfg.mode == TDC_LCD_MODE_GAMMA) {
        return; /* no history */
    }
    if (!st->have_history) {
        st->stats.first_frames++;
    }
    st->have_history = 1;
    if (TDC_LCD_MODE_IS_STATEFUL(st->cfg.mode)) {
        st->st_phase ^= 1u;
    }
}

tdc_status_t tdc_lcd_rows(tdc_lcd_t *st, const uint8_t *wanted, uint32_t in_stride, uint8_t *drive,
                          uint32_t out_stride, tdc_res_t *residual, uint32_t y0, uint32_t y1)
{
    if (!st || !wanted || !drive || in_stride < st->cfg.width * 3u || out_stride < st->cfg.width * 3u ||
        y0 > y1 || y1 > st->cfg.height) {
        return TDC_ERR_ARG;
    }
    const uint32_t w3 = st->cfg.width * 3u;
    if (TDC_LCD_MODE_IS_STATEFUL(st->cfg.mode)) {
        tdc_lcd_st_rows(st, wanted, in_stride, drive, out_stride, residual, y0, y1);
        return TDC_OK;
    }
    if (st->cfg.mode == TDC_LCD_MODE_GAMMA) {
        /* Plain gamma inverse: the wanted code is the drive; no history needed. */
        for (uint32_t y = y0; y < y1; y++) {
            const uint8_t *in = wanted + (size_t)y * in_stride;
            uint8_t *out = drive + (size_t)y * out_stride;
            if (in != out) {
                for (uint32_t i = 0; i < w3; i++) {
                    out[i] = in[i];
                }
            }
        }
        return TDC_OK;
    }
    const int32_t *p = st->rate->p_q24;
    const unsigned bits = st->cfg.prev_bits;
    const int first = !st->have_history;
    const uint32_t half = st->half_lsb_q16;
    uint64_t n_root = 0, n_low = 0, n_high = 0, n_res = 0, n_drop = 0;
    for (uint32_t y = y0; y < y1; y++) {
        const uint8_t *in = wanted + (size_t)y * in_stride;
        uint8_t *out = drive + (size_t)y * out_stride;
        size_t s = (size_t)y * w3;
        unsigned ch = 0;
        for (uint32_t i = 0; i < w3; i++, s++) {
            const uint32_t w = in[i];
            const tdc_gamma_table_t *gt = &st->panel->gamma[ch];
            uint32_t code, e_code = w;
            tdc_lcd_solution_t sol;
            if (first) {
                /* No history: steady state M(v, v) = w, no residual. */
                tdc_lcd_solve_steady_q16(p, code8_to_q16(w), half, &sol);
                code = q16_to_code8((uint32_t)sol.v_q16);
                n_root += sol.kind == TDC_LCD_ROOT;
            } else {
                uint32_t d, e;
                if (bits == 8u) {
                    d = st->prev_drive[s];
                    e = st->prev_light[s];
                } else {
                    d = st->q_dec[tdc_od_unpack(st->prev_drive, s, bits)];
                    e = st->q_dec[tdc_od_unpack(st->prev_light, s, bits)];
                }
                const uint32_t wl = gt->decode[w];
                const uint32_t el = gt->decode[e];
                const uint32_t pair = (wl + el + 1u) >> 1; /* wanted pair mean, Q24 */
                const uint32_t m = lin_to_m_q16(gt, st->m_step_recip + ch * 256u, pair);
                const uint32_t u = code8_to_q16(d);
                tdc_lcd_case_t kind;
                if (st->od) {
                    code = st->od_n == 33u ? tdc_od_lookup_inline(st->od, 33u, u, m, 255u)
                                           : tdc_od_lookup_inline(st->od, 17u, u, m, 255u);
                    kind = TDC_LCD_ROOT;
                    if (code == 0u || code == 255u) {
                        /* At a table end the target may be out of reach. */
                        int32_t ms = tdc_lcd_model_q24(p, code8_to_q16(code), u);
                        int32_t mq = (int32_t)(m << 8);
                        if (code == 255u && ms < mq) {
                            kind = TDC_LCD_CLAMP_HIGH;
                        } else if (code == 0u && ms > mq) {
                            kind = TDC_LCD_CLAMP_LOW;
                        }
                    }
                } else {
                    tdc_lcd_solve_q16(p, u, m, half, &sol);
                    code = q16_to_code8((uint32_t)sol.v_q16);
                    kind = sol.kind;
                }
                if (kind == TDC_LCD_ROOT) {
                    n_root++;
                } else {
                    n_low += kind == TDC_LCD_CLAMP_LOW;
                    n_high += kind == TDC_LCD_CLAMP_HIGH;
                    const int32_t miss = unreached_light_q24(p, gt, code, u, wl, el, &e_code);
                    if (residual && miss != 0) {
                        residual[s] = tdc_clamp32(tdc_add_sat32(residual[s], miss), -TDC_LIN_ONE, TDC_LIN_ONE);
                        n_res++;
                    } else if (miss != 0) {
                        n_drop++; /* explicitly dropped: counted */
                    }
                }
            }
            out[i] = (uint8_t)code;
            if (bits == 8u) {
                st->prev_drive[s] = (uint8_t)code;
                st->prev_light[s] = (uint8_t)e_code;
            } else {
                tdc_od_pack(st->prev_drive, s, bits, st->q_enc[code]);
                tdc_od_pack(st->prev_light, s, bits, st->q_enc[e_code]);
            }
            ch = ch == 2u ? 0u : ch + 1u;
        }
    }
    st->stats.roots += n_root;
    st->stats.clamped_low += n_low;
    st->stats.clamped_high += n_high;
    st->stats.residual_added += n_res;
    st->stats.residual_dropped += n_drop;
    return TDC_OK;
}
