/*
 * tdc_lcd_state.c - the stateful LCD inverse (TDC_LCD_MODE_STATEFUL):
 * measured transition tables, a per-pixel state estimate, unreachable light
 * into rho.  Tables and their convention: tdc_lcd.h; why: docs/lcd.md §2.
 *
 * Per sub-pixel and refresh, with q the pixel's state (prev_bits code of the
 * state's 8-bit code) and w the wanted code:
 *     e = lut[c][q][w];  drive = e & 255;  q' = e >> 8
 *     w > whi[c][q]: rho += decode(w) - lhi[c][q]  (light not delivered)
 *     w < wlo[c][q]: rho += decode(w) - llo[c][q]  (light delivered too much)
 * lut is built at init by bilinear interpolation of the profile's 17 x 17 or
 * 33 x 33 tables (drive = OD(state, wanted); next state = ST(state, drive)),
 * so the frame loop is one 16-bit load, two byte loads and a compare per
 * sub-pixel.  First frame after init/reset: drive = w, state = w (assumed
 * settled: the real history is unknown).
 *
 * STATEFUL_PAIR: the eye fuses TRM's (full, reduced) pair (Talbot-Plateau),
 * so light the FIRST refresh of a pair (even frames since init/reset) could
 * not deliver (out of reach: wanted light minus the reach limit) is owed to
 * the second: debt[s], companded to int8; the second refresh targets
 * decode(w) + debt (re-encoded to a wanted code through the panel's gamma
 * thresholds).  Carrying the drive's quantisation error as well (through a
 * forward light table) was tried and measured no better (quick report,
 * pg279q static 0.628 % vs 0.628 %), so only the out-of-reach light is owed.  What the second
 * refresh cannot deliver goes to rho as in STATEFUL; the first's does not
 * (it is carried here instead of through TRM's motion-weighted residual).
 *
 * Memory: per pixel 3 * prev_bits bits (3 bytes at 8 bits: half of the
 * exact/table modes' two buffers), + 3 bytes of debt in STATEFUL_PAIR; fixed
 * 3 * 2^prev_bits * (512 + 10) bytes (392 KiB at 8 bits, 24.5 KiB at 4 bits).
 */
#include "tdc_gamma.h"
#include "tdc_lcd.h"
#include "tdc_lcd_kernels.h"
#include "tdc_overdrive.h"

#define ST_MAX (255u << TDC_LCD_ST_FRAC) /* largest Q4 code */

/* Q16 fraction bits of a node step: n - 1 = 2^(16 - fb) (n = 17, 33, 65). */
static unsigned st_frac_bits(unsigned n)
{
    return n == 65u ? 10u : (n == 33u ? 11u : 12u);
}

/*
 * Bilinear interpolation of an n x n Q4 table at (a, b), both Q16 in
 * [0, 65536] (node i at i / (n - 1)), rounded ONCE to the nearest 8-bit code
 * (0..255).  Rounding to Q4 first and then to a code (as before) rounded the
 * values in [k + 15/32, k + 1/2) up: a +1 code bias on ~3 % of the dense
 * lookup that measured 0.1415 % instead of 0.1156 % static RMS error on
 * lcd-240 (docs/lcd.md §2a).
 * Scaling and overflow: entries <= 4080 < 2^12, fraction <= 2^fb <= 2^12, so a
 * row value scaled by 2^fb < 2^24 (int32), the second stage < 2^36 (int64).
 * All terms are non-negative except the differences, and the result is a
 * convex combination of entries, so it stays in [0, 4080 * 2^(2 fb)].
 */
static uint32_t interp_code(const uint16_t *t, unsigned n, uint32_t a, uint32_t b)
{
    const unsigned fb = st_frac_bits(n);
    const uint32_t fmask = (1u << fb) - 1u;
    unsigned ia = a >> fb, ib = b >> fb;
    int32_t fa = (int32_t)(a & fmask), fbb = (int32_t)(b & fmask);
    if (ia >= n - 1u) {
        ia = n - 2u;
        fa = (int32_t)fmask + 1;
    }
    if (ib >= n - 1u) {
        ib = n - 2u;
        fbb = (int32_t)fmask + 1;
    }
    const uint16_t *r0 = t + (size_t)ia * n + ib, *r1 = r0 + n;
    const int32_t p = (int32_t)((uint32_t)r0[0] << fb) + ((int32_t)r0[1] - (int32_t)r0[0]) * fbb;
    const int32_t q = (int32_t)((uint32_t)r1[0] << fb) + ((int32_t)r1[1] - (int32_t)r1[0]) * fbb;
    const int64_t d = (int64_t)p * ((int64_t)1 << fb) + (int64_t)(q - p) * fa; /* Q4 * 2^(2 fb), >= 0 */
    const unsigned sh = 2u * fb + TDC_LCD_ST_FRAC;                             /* to whole codes */
    const uint32_t c = (uint32_t)((d + ((int64_t)1 << (sh - 1u))) >> sh);
    return c > 255u ? 255u : c;
}

/* 8-bit code -> Q16 (as tdc_lcd.c: round(k * 65536 / 255)). */
static uint32_t code_q16(uint32_t k)
{
    return k * 257u + (k >> 7);
}

tdc_lcd_table_fault_t tdc_lcd_st_validate(const tdc_lcd_rate_t *rate)
{
    const unsigned n = rate->st_n;
    if (n != 17u && n != 33u && n != 65u) {
        return TDC_LCD_TABLE_MISSING;
    }
    for (unsigned c = 0; c < 3u; c++) {
        const uint16_t *od = rate->st_od[c], *nx = rate->st_next[c], *rc = rate->st_reach[c];
        if (!od || !nx || !rc) {
            return TDC_LCD_TABLE_MISSING;
        }
        for (unsigned i = 0; i < n; i++) {
            for (unsigned j = 0; j < n; j++) {
                if (od[i * n + j] > ST_MAX || nx[i * n + j] > ST_MAX) {
                    return TDC_LCD_TABLE_RANGE;
                }
                if (j && od[i * n + j] < od[i * n + j - 1u]) {
                    return TDC_LCD_TABLE_MONOTONE;
                }
            }
            const uint32_t lo = rc[i], hi = rc[n + i];
            /* node state in Q4: i * 255 * 16 / (n - 1) */
            const uint32_t s = (i * ST_MAX + (n - 1u) / 2u) / (n - 1u);
            if (lo > ST_MAX || hi > ST_MAX || lo > hi || lo > s + 8u || hi + 8u < s) {
                return TDC_LCD_TABLE_REACH;
            }
        }
    }
    return TDC_LCD_TABLE_OK;
}

/*
 * Debt code (int8, -127..127) <-> light (Q24): fine steps of 2^12 (1/4096 of
 * white: the drive's own quantisation is ~1/1000) up to |64|, then steps of
 * 2^18 up to 2^24 at |127| (the shortfall of a transition out of reach).
 */
static int32_t debt_decode(int32_t c)
{
    const int32_t a = c < 0 ? -c : c;
    const int32_t v = a <= 64 ? a << 12 : (a - 63) << 18;
    return c < 0 ? -v : v;
}

static int8_t debt_encode(int32_t e)
{
    const int32_t a = e < 0 ? -e : e;
    int32_t c = a <= (64 << 12) ? (a + (1 << 11)) >> 12 : 63 + ((a + (1 << 17)) >> 18);
    c = c > 127 ? 127 : c;
    return (int8_t)(e < 0 ? -c : c);
}

void tdc_lcd_st_build(tdc_lcd_t *st)
{
    const tdc_lcd_rate_t *rate = st->rate;
    const unsigned n = rate->st_n, bits = st->cfg.prev_bits;
    const uint32_t nq = 1u << bits;
    const unsigned fb = st_frac_bits(n);
    for (unsigned c = 0; c < 3u; c++) {
        const tdc_gamma_table_t *gt = &st->panel->gamma[c];
        for (uint32_t q = 0; q < nq; q++) {
            const uint32_t s16 = code_q16(st->q_dec[q]);
            /* Reach from this state, interpolated along the state axis. */
            unsigned i = s16 >> fb;
            uint32_t f = s16 & ((1u << fb) - 1u);
            if (i >= n - 1u) {
                i = n - 2u;
                f = 1u << fb;
            }
            const uint16_t *rc = rate->st_reach[c];
            const uint32_t lo = (rc[i] * ((1u << fb) - f) + rc[i + 1u] * f + (1u << (fb - 1u))) >> fb;
            const uint32_t hi = (rc[n + i] * ((1u << fb) - f) + rc[n + i + 1u] * f + (1u << (fb - 1u))) >> fb;
            /* Wanted code w is out of reach when it lies more than half a code
             * beyond the limit: w * 16 > hi + 8, i.e. w > (hi + 8) / 16. */
            const size_t k = (size_t)c * nq + q;
            uint32_t whi = (hi + 8u) >> 4, wlo = lo > 8u ? (lo - 8u + 15u) >> 4 : 0u;
            whi = whi > 255u ? 255u : whi;
            wlo = wlo > 255u ? 255u : wlo;
            st->st_whi[k] = (uint8_t)whi;
            st->st_wlo[k] = (uint8_t)wlo;
            /* Q4 code -> Q8 code for the gamma interpolation: << 4. */
            st->st_lhi[k] = tdc_gamma_decode_gval(gt, hi << 4);
            st->st_llo[k] = tdc_gamma_decode_gval(gt, lo << 4);
            uint16_t *row = st->st_lut + k * 256u;
            for (uint32_t w = 0; w < 256u; w++) {
                uint32_t drive = interp_code(rate->st_od[c], n, s16, code_q16(w));
                /* Out of reach: the limit drive, whatever the interpolation
                 * between a clamped and an unclamped node gave (so the frame
                 * loop needs to test the limits only for drives 0 and 255). */
                drive = w > whi ? 255u : (w < wlo ? 0u : drive);
                const uint32_t next = interp_code(rate->st_next[c], n, s16, code_q16(drive));
                row[w] = (uint16_t)(drive | ((uint32_t)st->q_enc[next] << 8));
            }
        }
    }
    for (int32_t code = 0; st->st_ddec && code < 256; code++) {
        st->st_ddec[code] = debt_decode(code < 128 ? code : code - 256); /* index = (uint8_t)debt */
    }
    for (unsigned c = 0; c < 3u; c++) {
        for (uint32_t k = 0; k < 256u; k++) {
            st->st_dec[c * 256u + k] = (int32_t)st->panel->gamma[c].decode[k]; /* <= 2^24 */
        }
    }
}

/* The residual of a sub-pixel out of reach, counted. */
static void st_miss(tdc_lcd_st_counts_t *n, tdc_res_t *residual, size_t s, int32_t miss)
{
    if (miss > 0) {
        n->clamped_high++;
    } else {
        n->clamped_low++;
    }
    if (residual && miss != 0) {
        residual[s] = tdc_clamp32(tdc_add_sat32(residual[s], miss), -TDC_LIN_ONE, TDC_LIN_ONE);
        n->residual_added++;
    }
}

/*
 * The tables of one channel as locals of the loop.  Why: every output and
 * state store goes through a uint8_t pointer, which may alias anything, so
 * tables read through the stage struct would be reloaded after each store
 * (measured on Cortex-M7: 173 instructions per pixel before, see docs/lcd.md).
 */
typedef struct {
    const uint16_t *lut;      /* [2^bits][256] */
    const uint8_t *whi, *wlo; /* [2^bits] */
    const int32_t *lhi, *llo; /* [2^bits] */
    const int32_t *dec;       /* [256]: decode of the channel */
    const tdc_gamma_table_t *gt; /* the pair mode's re-encoding; NULL in the C row kernel */
} st_chan_t;

/* The light a sub-pixel misses at state q, wanted code w (want in Q24): 0 if in reach. */
static inline int32_t st_out_of_reach(const st_chan_t *ch, uint32_t q, uint32_t w, int32_t want)
{
    if (w > ch->whi[q]) {
        return want - ch->lhi[q];
    }
    if (w < ch->wlo[q]) {
        return want - ch->llo[q];
    }
    return 0;
}

/* A pair's second refresh, 8-bit state, for a sub-pixel that is owed light:
 * the wanted light plus the debt, re-encoded to a wanted code. */
static void st_one8(tdc_lcd_st_counts_t *n, const int32_t *ddec, const st_chan_t *k, uint32_t w, uint8_t *out,
                    uint8_t *state, const int8_t *debt, size_t s, tdc_res_t *residual, uint32_t *nmiss)
{
    int32_t want = k->dec[w];
    if (*debt != 0) {
        /* |debt| <= 2^24: want + debt within +-2^25, no overflow. */
        want = tdc_clamp32(want + ddec[(uint8_t)*debt], 0, TDC_LIN_ONE);
        w = tdc_gamma_encode(k->gt, want, 255u);
    }
    const uint32_t q = *state;
    const uint32_t e = k->lut[(q << 8) | w];
    *out = (uint8_t)e;
    *state = (uint8_t)(e >> 8);
    const int32_t miss = st_out_of_reach(k, q, w, want);
    if (miss != 0) {
        st_miss(n, residual, s, miss);
        (*nmiss)++;
    }
}

/* 8-bit state: the hot loop.  A target out of reach always gets drive 0 or
 * 255 (the dense table clamps), so the reach limits are read only for those
 * drives: one 16-bit lookup and a test of the drive per sub-pixel.  The
 * three channels' lookups sit at constant offsets (2^16 entries) from one
 * base.  debt: NULL, or the pair mode's debt row (owe: first refresh of a
 * pair, else second; ddec its decode).  Returns the sub-pixels out of reach. */
#if defined(__GNUC__)
#define ST_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define ST_ALWAYS_INLINE inline
#endif
static ST_ALWAYS_INLINE uint32_t st_row8(tdc_lcd_st_counts_t *n, const int32_t *ddec, const st_chan_t ch[3],
                                         const uint8_t *in, uint8_t *out, uint8_t *state, int8_t *debt, int owe,
                                         uint32_t w3, size_t s0, tdc_res_t *residual)
{
    const uint16_t *lut = ch[0].lut;
    uint32_t nmiss = 0;
    if (debt && owe) {
        /* a pair's first refresh: nothing owed unless a target is out of reach below */
        for (uint32_t i = 0; i < w3; i++) {
            debt[i] = 0;
        }
    }
    for (uint32_t i = 0; i < w3; i += 3u) {
        if (debt && !owe && (debt[i] | debt[i + 1u] | debt[i + 2u]) != 0) {
            /* a pair's second refresh pays what is owed (rare: after a target out of reach) */
            for (unsigned c = 0; c < 3u; c++) {
                st_one8(n, ddec, &ch[c], in[i + c], out + i + c, state + i + c, debt + i + c, s0 + i + c, residual,
                        &nmiss);
            }
            continue;
        }
        const uint32_t w0 = in[i], w1 = in[i + 1u], w2 = in[i + 2u];
        const uint32_t q0 = state[i], q1 = state[i + 1u], q2 = state[i + 2u];
        const uint32_t e0 = lut[(q0 << 8) | w0];
        const uint32_t e1 = lut[65536u + ((q1 << 8) | w1)];
        const uint32_t e2 = lut[131072u + ((q2 << 8) | w2)];
        out[i] = (uint8_t)e0;
        out[i + 1u] = (uint8_t)e1;
        out[i + 2u] = (uint8_t)e2;
        state[i] = (uint8_t)(e0 >> 8);
        state[i + 1u] = (uint8_t)(e1 >> 8);
        state[i + 2u] = (uint8_t)(e2 >> 8);
        /* drive 0 or 255: (drive + 1) mod 256 <= 1 */
        if ((((e0 + 1u) & 255u) <= 1u) | (((e1 + 1u) & 255u) <= 1u) | (((e2 + 1u) & 255u) <= 1u)) {
            const uint32_t qs[3] = {q0, q1, q2}, ws[3] = {w0, w1, w2};
            for (unsigned c = 0; c < 3u; c++) {
                const int32_t want = ch[c].dec[ws[c]];
                const int32_t miss = st_out_of_reach(&ch[c], qs[c], ws[c], want);
                if (miss == 0) {
                    continue;
                }
                nmiss++;
                if (owe) {
                    debt[i + c] = debt_encode(miss);
                    n->clamped_high += miss > 0;
                    n->clamped_low += miss < 0;
                } else {
                    st_miss(n, residual, s0 + i + c, miss);
                }
            }
        }
    }
    return nmiss;
}

/* The channel views of the 8-bit-state tables (tdc_lcd_kernels.h layout). */
static void st_chans8(const tdc_lcd_st_tabs_t *t, const tdc_gamma_table_t *gt, st_chan_t ch[3])
{
    for (unsigned c = 0; c < 3u; c++) {
        const size_t k = (size_t)c * 256u;
        ch[c] = (st_chan_t){t->lut + k * 256u, t->whi + k, t->wlo + k, t->lhi + k, t->llo + k, t->dec + k,
                            gt ? gt + c : 0};
    }
}

/* The row kernel (tdc_lcd_kernels.h) in portable C: st_row8 without debt,
 * what the boards run (65.7 instructions per pixel on the Cortex-M7) and the
 * reference of the AVX2 row (tests/checkasm/checkasm_lcd.c). */
uint32_t tdc_lcd_st_row8_c(const tdc_lcd_st_tabs_t *t, const uint8_t *in, uint8_t *out, uint8_t *state, uint32_t w3,
                           int32_t *res, tdc_lcd_st_counts_t *n)
{
    st_chan_t ch[3];
    st_chans8(t, 0, ch);
    return st_row8(n, 0, ch, in, out, state, 0, 0, w3, 0, res);
}

static uint32_t st_row8_pair(tdc_lcd_st_counts_t *n, const int32_t *ddec, const st_chan_t ch[3], const uint8_t *in,
                             uint8_t *out, uint8_t *state, int8_t *debt, int owe, uint32_t w3, size_t s0,
                             tdc_res_t *residual)
{
    return owe ? st_row8(n, ddec, ch, in, out, state, debt, 1, w3, s0, residual)
               : st_row8(n, ddec, ch, in, out, state, debt, 0, w3, s0, residual);
}

/* Any state precision below 8 bits, pair mode or not. */
static uint32_t st_row_general(tdc_lcd_t *st, tdc_lcd_st_counts_t *cnt, const st_chan_t ch[3], const uint8_t *in,
                               uint8_t *out, uint8_t *state, int8_t *debt, int owe, int pay, unsigned bits, uint32_t w3,
                               size_t s0, tdc_res_t *residual)
{
    uint32_t nmiss = 0;
    size_t s = s0;
    for (uint32_t i = 0; i < w3; i += 3u) {
        for (uint32_t c = 0; c < 3u; c++, s++) {
            const st_chan_t *k = &ch[c];
            uint32_t w = in[i + c];
            int32_t want = k->dec[w];
            if (pay && debt[s] != 0) {
                /* |debt| <= 2^24: want + debt within +-2^25, no overflow. */
                want = tdc_clamp32(want + st->st_ddec[(uint8_t)debt[s]], 0, TDC_LIN_ONE);
                w = tdc_gamma_encode(k->gt, want, 255u);
            }
            const uint32_t q = bits == 8u ? state[s] : tdc_od_unpack(state, s, bits);
            const uint32_t e = k->lut[(q << 8) | w];
            out[i + c] = (uint8_t)e;
            if (bits == 8u) {
                state[s] = (uint8_t)(e >> 8);
            } else {
                tdc_od_pack(state, s, bits, e >> 8);
            }
            const int32_t miss = st_out_of_reach(k, q, w, want);
            if (owe) {
                /* out of reach: owed to the pair's second refresh */
                debt[s] = debt_encode(miss);
                if (miss != 0) {
                    cnt->clamped_high += miss > 0;
                    cnt->clamped_low += miss < 0;
                    nmiss++;
                }
            } else if (miss != 0) {
                st_miss(cnt, residual, s, miss);
                nmiss++;
            }
        }
    }
    return nmiss;
}

void tdc_lcd_st_rows(tdc_lcd_t *st, const uint8_t *wanted, uint32_t in_stride, uint8_t *drive, uint32_t out_stride,
                     tdc_res_t *residual, uint32_t y0, uint32_t y1)
{
    const uint32_t w3 = st->cfg.width * 3u;
    const unsigned bits = st->cfg.prev_bits;
    const uint32_t nq = 1u << bits;
    uint8_t *state = st->prev_drive;
    int8_t *debt = st->st_debt;
    /* Pair mode: the first refresh of a pair records what it could not
     * deliver, the second adds it to its own wanted light. */
    const int owe = debt && st->st_phase == 0u, pay = debt && st->st_phase != 0u;
    st_chan_t ch[3];
    for (unsigned c = 0; c < 3u; c++) {
        const size_t k = (size_t)c * nq;
        ch[c] = (st_chan_t){st->st_lut + k * 256u, st->st_whi + k,         st->st_wlo + k,          st->st_lhi + k,
                            st->st_llo + k,        st->st_dec + c * 256u, &st->panel->gamma[c]};
    }
    const tdc_lcd_st_tabs_t tabs = {st->st_lut, st->st_whi, st->st_wlo, st->st_lhi, st->st_llo, st->st_dec};
    tdc_lcd_st_counts_t cnt = {0, 0, 0};
    uint64_t missed = 0;
    for (uint32_t y = y0; y < y1; y++) {
        const uint8_t *in = wanted + (size_t)y * in_stride;
        uint8_t *out = drive + (size_t)y * out_stride;
        const size_t s0 = (size_t)y * w3;
        if (!st->have_history) {
            for (uint32_t i = 0; i < w3; i++) {
                const uint32_t w = in[i];
                out[i] = (uint8_t)w;
                if (bits == 8u) {
                    state[s0 + i] = (uint8_t)w;
                } else {
                    tdc_od_pack(state, s0 + i, bits, st->q_enc[w]);
                }
                if (debt) {
                    debt[s0 + i] = 0;
                }
            }
            continue;
        }
        if (bits == 8u && !debt) {
            /* the row kernel: C (boards) or AVX2, chosen at init */
            missed += st->st_row8(&tabs, in, out, state + s0, w3, residual ? residual + s0 : 0, &cnt);
        } else if (bits == 8u) {
            missed += st_row8_pair(&cnt, st->st_ddec, ch, in, out, state + s0, debt + s0, owe, w3, s0, residual);
        } else {
            missed += st_row_general(st, &cnt, ch, in, out, state, debt, owe, pay, bits, w3, s0, residual);
        }
    }
    st->stats.clamped_low += cnt.clamped_low;
    st->stats.clamped_high += cnt.clamped_high;
    st->stats.residual_added += cnt.residual_added;
    if (st->have_history) {
        st->stats.roots += (uint64_t)w3 * (y1 - y0) - missed;
    }
}
