/*
 * tdc_trm.c - temporal resolution multiplexing in fixed point (see
 * tdc_trm.h for the equations and formats).
 *
 * Data path of a full-resolution frame (per channel):
 *   codes --D--> dprev (reduced, code Q8) --U--> g (code Q8) --lin--> Lu (Q24)
 *   codes --lin--> LI (Q24);  beta = 2 LI - Lu;  out = enc(clamp(beta));
 *   rho = beta - clamp(beta) in Q24.
 * The per-pixel work of a row is in tdc_trm_rows.c (portable C) and
 * tdc_trm_avx2.c (host SIMD, same bytes); see tdc_trm_kernels.h.
 * D is evaluated only at the reduced sample centres (a polyphase Gaussian):
 * a horizontal pass per full-res row into a ring of rows, then a vertical
 * pass per reduced row, so scratch memory is a few rows, not a frame.
 * U is separable too: one vertically interpolated reduced row per output
 * row, then one horizontal lerp per output pixel.
 */
#include "tdc_trm.h"

#include <string.h>

#include "tdc_math.h"
#include "tdc_trm_kernels.h"

#define TDC_TRM_MAX_DIM 8192

/* ---------------------------------------------------------------------
 * Configuration and arena layout
 * ------------------------------------------------------------------- */

static int trm_config_valid(const tdc_trm_config_t *cfg)
{
    if (!cfg || cfg->width == 0u || cfg->height == 0u || cfg->width > TDC_TRM_MAX_DIM ||
        cfg->height > TDC_TRM_MAX_DIM) {
        return 0;
    }
    if (cfg->r_den == 0u || cfg->r_num > cfg->r_den || 4u * cfg->r_num < cfg->r_den) {
        return 0;
    }
    return cfg->sigma_q8 >= 64u && cfg->sigma_q8 <= TDC_TRM_MAX_SIGMA_Q8;
}

static uint16_t trm_reduced_dim(uint32_t n, uint32_t num, uint32_t den)
{
    return (uint16_t)tdc_reduced_dim(n, num, den); /* r <= 1: at most n, a uint16 width */
}

static uint16_t trm_taps(uint16_t sigma_q8)
{
    return (uint16_t)TDC_TRM_TAPS(sigma_q8);
}

/* The geometry a configuration implies (cfg valid): everything the arena
 * layout depends on. */
static void trm_geometry(tdc_trm_t *st, const tdc_trm_config_t *cfg)
{
    st->cfg = *cfg;
    st->rw = trm_reduced_dim(cfg->width, cfg->r_num, cfg->r_den);
    st->rh = trm_reduced_dim(cfg->height, cfg->r_num, cfg->r_den);
    st->dtaps = trm_taps(cfg->sigma_q8);
    st->passthrough = (uint8_t)(cfg->r_num == cfg->r_den || !cfg->reduced_in_stream);
}

/* The one layout (tdc_trm.h TDC_TRM_ARENA): views of st carved from arena
 * (NULL in a dry run).  Pass-through keeps no state: a stream of full
 * frames needs no arena. */
static void trm_carve(tdc_trm_t *st, tdc_arena_t *arena)
{
    if (!st->passthrough) {
        TDC_TRM_ARENA(TDC_ARENA_CARVE, st->cfg.width, st->cfg.height, st->rw, st->rh, st->dtaps, st->cfg.keep_residual)
    }
}

size_t tdc_trm_get_size(const tdc_trm_config_t *cfg)
{
    if (!trm_config_valid(cfg)) {
        return 0;
    }
    tdc_trm_t dry = {0};
    tdc_arena_t arena;
    tdc_arena_dry(&arena);
    trm_geometry(&dry, cfg);
    trm_carve(&dry, &arena);
    return tdc_arena_size(&arena);
}

void tdc_trm_default_config(tdc_trm_config_t *cfg, uint16_t width, uint16_t height, uint16_t refresh_hz)
{
    cfg->width = width;
    cfg->height = height;
    cfg->r_num = 1;
    cfg->r_den = 2;
    cfg->sigma_q8 = 640; /* 2.5 full-res pixels, TRM paper §4.3 */
    cfg->refresh_hz = refresh_hz;
    cfg->min_refresh_hz = 90; /* paper §4.1/§9 */
    cfg->s_q8 = 10u * 256u;
    cfg->reduced_in_stream = 1;
    cfg->keep_residual = 0;
}

/* ---------------------------------------------------------------------
 * Kernel tables (init only)
 * ------------------------------------------------------------------- */

/*
 * Gaussian weights of D for n_out reduced samples over n_in full-res
 * samples.  Reduced sample j is centred at x = (j + 0.5) n_in / n_out - 0.5
 * (full-res pixel units, Q16).  Weights exp(-d^2 / (2 sigma^2)) in Q15 via
 * tdc_exp_neg_q16, then normalised so each kernel sums to exactly 32768:
 * flat fields pass unchanged (all-white stays exactly white).
 */
static void trm_build_kernels(uint32_t n_in, uint32_t n_out, uint16_t sigma_q8, uint16_t taps, int16_t *first,
                              uint16_t *weights)
{
    const int64_t radius_q16 = (int64_t)3 * sigma_q8 * 256;     /* 3 sigma, Q16 */
    const uint64_t two_sigma2_q16 = 2ull * sigma_q8 * sigma_q8; /* 2 sigma^2, Q16 */
    for (uint32_t j = 0; j < n_out; j++) {
        /* x = ((2j + 1) n_in / (2 n_out) - 0.5), Q16 */
        int64_t x_q16 = (int64_t)(((2ull * j + 1u) * n_in * 65536ull) / (2ull * n_out)) - 32768;
        int64_t lo_q16 = x_q16 - radius_q16;
        int32_t k0 = (int32_t)tdc_asr64(lo_q16 + 65535, 16); /* ceil(lo) */
        first[j] = (int16_t)k0;
        uint32_t w[TDC_TRM_MAX_TAPS];
        uint32_t sum = 0;
        for (uint32_t t = 0; t < taps; t++) {
            int64_t d_q16 = (int64_t)(k0 + (int32_t)t) * 65536 - x_q16;
            uint64_t ad = (uint64_t)(d_q16 < 0 ? -d_q16 : d_q16);
            if ((int64_t)ad > radius_q16) {
                w[t] = 0;
            } else {
                uint64_t e_q16 = (ad * ad) / two_sigma2_q16; /* Q32 / Q16 = Q16 */
                w[t] = (uint32_t)tdc_exp_neg_q16(e_q16 > 0xffffffffull ? 0xffffffffu : (uint32_t)e_q16);
            }
            sum += w[t];
        }
        uint32_t norm_sum = 0, tmax = 0;
        for (uint32_t t = 0; t < taps; t++) {
            uint32_t v = (uint32_t)(((uint64_t)w[t] * 32768u + sum / 2u) / sum);
            weights[j * taps + t] = (uint16_t)v;
            norm_sum += v;
            if (v > weights[j * taps + tmax]) {
                tmax = t;
            }
        }
        /* put the rounding remainder on the largest tap: sum exactly 32768 */
        weights[j * taps + tmax] = (uint16_t)((int32_t)weights[j * taps + tmax] + 32768 - (int32_t)norm_sum);
    }
}

/* Bilinear U: full-res sample x reads reduced position
 * u = (x + 0.5) n_red / n_full - 0.5, clamped to [0, n_red - 1]. */
static void trm_build_upsample(uint32_t n_full, uint32_t n_red, uint16_t *idx_frac)
{
    const int64_t umax = (int64_t)(n_red - 1u) * 65536;
    for (uint32_t x = 0; x < n_full; x++) {
        int64_t u = (int64_t)(((2ull * x + 1u) * n_red * 65536ull) / (2ull * n_full)) - 32768;
        u = u < 0 ? 0 : (u > umax ? umax : u);
        idx_frac[2u * x] = (uint16_t)(u >> 16);
        idx_frac[2u * x + 1u] = (uint16_t)(((uint64_t)u & 0xffffu) >> 2); /* Q14 */
    }
}

tdc_status_t tdc_trm_init(tdc_trm_t *st, const tdc_trm_config_t *cfg, const tdc_panel_t *panel, void *mem,
                          size_t mem_bytes)
{
    if (!st || !cfg || !panel || !mem) {
        return TDC_ERR_ARG;
    }
    if (cfg->r_den == 0u || cfg->r_num > cfg->r_den || 4u * cfg->r_num < cfg->r_den) {
        return TDC_ERR_RATIO;
    }
    if (!trm_config_valid(cfg)) {
        return TDC_ERR_ARG;
    }
    if (panel->bits != 8u) {
        return TDC_ERR_PANEL;
    }
    const int reduces = cfg->r_num != cfg->r_den && cfg->reduced_in_stream;
    if (reduces && cfg->refresh_hz < cfg->min_refresh_hz) {
        return TDC_ERR_REFRESH_LOW;
    }
    tdc_arena_t arena;
    if (!tdc_arena_over(&arena, mem, mem_bytes)) {
        return TDC_ERR_ARG; /* not aligned to TDC_ARENA_ALIGN */
    }
    if (mem_bytes < tdc_trm_get_size(cfg)) { /* the same carve, dry: nothing is touched on error */
        return TDC_ERR_SIZE;
    }
    *st = (tdc_trm_t){0};
    trm_geometry(st, cfg);
    trm_carve(st, &arena);
    st->panel = panel;
    st->ux_f = st->ux_i; /* interleaved (index, fraction) pairs */
    st->uy_f = st->uy_i;
    st->simd = (uint8_t)tdc_trm_avx2_available();
    if (st->passthrough) {
        st->simd = 0;
        return TDC_OK;
    }
    trm_build_kernels(cfg->width, st->rw, cfg->sigma_q8, st->dtaps, st->dx_first, st->dx_w);
    trm_build_kernels(cfg->height, st->rh, cfg->sigma_q8, st->dtaps, st->dy_first, st->dy_w);
    trm_build_upsample(cfg->width, st->rw, st->ux_i);
    trm_build_upsample(cfg->height, st->rh, st->uy_i);
    st->wexp = tdc_trm_wexp_q30; /* for the per-pixel weight (tdc_trm_weight); const, generated */
    st->enc_one_step = 0;
    if (st->simd && st->enc_comb) {
        st->enc_one_step = (uint8_t)tdc_trm_avx2_build_encode(panel, st->enc_comb);
    }
    st->simd = (uint8_t)(st->simd && st->enc_comb);
    tdc_trm_reset(st);
    return TDC_OK;
}

void tdc_trm_reset(tdc_trm_t *st)
{
    if (st->residual) {
        size_t n = (size_t)st->cfg.width * st->cfg.height * 3u;
        for (size_t i = 0; i < n; i++) {
            st->residual[i] = 0;
        }
    }
    st->have_full = 0;
}

void tdc_trm_invalidate(tdc_trm_t *st)
{
    if (st) {
        st->have_full = 0;
    }
}

/* ---------------------------------------------------------------------
 * D: polyphase Gaussian, full-res codes -> reduced code Q8
 * ------------------------------------------------------------------- */

static int32_t clampi(int32_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

/* D: in (W x H codes) -> dst (rw x rh x 3, code Q8), the rows *jy_done..
 * whose kernel lies within the first `avail` input rows; *loaded = highest
 * full-res row in the ring (-1 before the first).  Rows are taken in order
 * whatever avail is, so the result does not depend on how they arrive.
 * Vertical pass scaling: 2^15 * 65280 < 2^31; (acc + 2^14) >> 15. */
static void trm_d_rows(const tdc_trm_t *st, tdc_gval_t *ring, uint32_t jy_end, const uint8_t *in, uint32_t stride,
                       tdc_gval_t *dst, uint8_t *out8, uint32_t out8_stride, uint32_t avail, int32_t *loaded_io,
                       uint32_t *jy_done)
{
    const int32_t hmax = (int32_t)st->cfg.height - 1;
    const uint32_t taps = st->dtaps;
    const uint32_t rw3 = 3u * st->rw;
    int32_t loaded = *loaded_io; /* highest full-res row in the ring */
    uint32_t jy = *jy_done;
    for (; jy < jy_end; jy++) {
        const int32_t k0 = st->dy_first[jy];
        const int32_t need = clampi(k0 + (int32_t)taps - 1, 0, hmax);
        if ((uint32_t)need >= avail) {
            break; /* its last input row has not arrived */
        }
        while (loaded < need) {
            loaded++;
            const uint8_t *row = in + (size_t)loaded * stride;
            uint16_t *slot = &ring[((uint32_t)loaded % taps) * rw3];
            /* direct calls, not a function pointer: the recursion check
             * follows the call graph */
            if (st->simd) {
                tdc_trm_dhoriz_avx2(row, st->cfg.width, st->dx_first, st->dx_w, taps, st->rw, slot);
            } else {
                TDC_TRM_DHORIZ_BOARD(row, st->cfg.width, st->dx_first, st->dx_w, taps, st->rw, slot);
            }
        }
        const uint16_t *w = &st->dy_w[jy * taps];
        const tdc_gval_t *rows[TDC_TRM_MAX_TAPS];
        for (uint32_t t = 0; t < taps; t++) {
            rows[t] = &ring[((uint32_t)clampi(k0 + (int32_t)t, 0, hmax) % taps) * rw3];
        }
        /* into D(I) (dst), or one row at a time rounded to codes (out8,
         * tdc_trm_downsample: the U row buffer is free then) */
        tdc_gval_t *o = out8 ? (tdc_gval_t *)(void *)st->urow : &dst[jy * rw3];
        if (st->simd) {
            tdc_trm_dvert_avx2((const uint16_t *const *)rows, w, taps, rw3, o);
        } else {
            TDC_TRM_DVERT_BOARD((const uint16_t *const *)rows, w, taps, rw3, o);
        }
        if (out8) {
            uint8_t *d = out8 + (size_t)jy * out8_stride;
            for (uint32_t i = 0; i < rw3; i++) {
                const uint32_t v = ((uint32_t)o[i] + 128u) >> 8;
                d[i] = (uint8_t)(v > 255u ? 255u : v);
            }
        }
    }
    *loaded_io = loaded;
    *jy_done = jy;
}

/* The whole D at once. */
static void trm_apply_d(tdc_trm_t *st, const uint8_t *in, uint32_t stride, tdc_gval_t *dst, uint8_t *out8,
                        uint32_t out8_stride)
{
    int32_t loaded = -1;
    uint32_t jy = 0;
    trm_d_rows(st, st->ring, st->rh, in, stride, dst, out8, out8_stride, st->cfg.height, &loaded, &jy);
}

/* The reduced row below the one U of full-res row y reads first (the last
 * reduced row U(row y) needs). */
static uint32_t trm_u_last(const tdc_trm_t *st, uint32_t y)
{
    const uint32_t i0 = st->uy_i[2u * y];
    return i0 + 1u < st->rh ? i0 + 1u : i0;
}

/* ---------------------------------------------------------------------
 * U: bilinear, reduced code Q8 -> full-res code Q8
 * ------------------------------------------------------------------- */

/* Vertically interpolate the reduced rows around full-res row y into dst,
 * exactly: a * 2^14 + (b - a) f is code Q22 with no rounding (|b - a| <=
 * 65280, f < 2^14: < 2^30).  dst holds rw + 1 entries per channel, the last
 * duplicated, so the horizontal lerp may read index + 1 without a branch. */
static void trm_u_row(const tdc_trm_t *st, const tdc_gval_t *src, uint32_t y, uint32_t *dst)
{
    const uint32_t rw3 = 3u * st->rw;
    const uint32_t i0 = st->uy_i[2u * y], f = st->uy_i[2u * y + 1u];
    const uint32_t i1 = i0 + 1u < st->rh ? i0 + 1u : i0;
    const tdc_gval_t *a = &src[i0 * rw3], *b = &src[i1 * rw3];
    if (st->simd) {
        tdc_trm_uvert_avx2(a, b, f, rw3, dst);
    } else {
        tdc_trm_uvert_c(a, b, f, rw3, dst);
    }
    dst[rw3] = dst[rw3 - 3u];
    dst[rw3 + 1u] = dst[rw3 - 2u];
    dst[rw3 + 2u] = dst[rw3 - 1u];
}

/* As trm_u_row for a reduced frame of 8-bit codes as it arrives: a code c
 * is code Q8 c << 8, so this is the same value without a Q8 copy of the
 * frame (a * 2^22 + (b - a) f 2^8 < 2^30). */
static void trm_u_row_codes(const tdc_trm_t *st, const uint8_t *src, uint32_t stride, uint32_t y, uint32_t *dst)
{
    const uint32_t rw3 = 3u * st->rw;
    const uint32_t i0 = st->uy_i[2u * y], f = st->uy_i[2u * y + 1u];
    const uint32_t i1 = i0 + 1u < st->rh ? i0 + 1u : i0;
    const uint8_t *a = src + (size_t)i0 * stride, *b = src + (size_t)i1 * stride;
    if (st->simd) {
        tdc_trm_uvert_codes_avx2(a, b, f, rw3, dst);
    } else {
        tdc_trm_uvert_codes_c(a, b, f, rw3, dst);
    }
    dst[rw3] = dst[rw3 - 3u];
    dst[rw3 + 1u] = dst[rw3 - 2u];
    dst[rw3 + 2u] = dst[rw3 - 1u];
}

/* ---------------------------------------------------------------------
 * Frames
 * ------------------------------------------------------------------- */

void tdc_trm_set_simd(tdc_trm_t *st, int enable)
{
    st->simd = (uint8_t)(enable && tdc_trm_avx2_available() && st->enc_comb != NULL);
}

int32_t tdc_trm_weight(const tdc_trm_t *st, uint32_t x_q16)
{
    return tdc_trm_weight_q15(st->wexp, x_q16);
}

/* The row kernels' view of the state (tdc_trm_kernels.h). */
static void trm_rowctx(const tdc_trm_t *st, tdc_trm_rowctx_t *k)
{
    tdc_trm_rowctx_init(k, st->panel, st->ux_i, st->wexp, st->cfg.width, st->cfg.s_q8, st->enc_comb, st->enc_one_step);
}

/* beta of full-res row y from codes src and the kept D(I): dst = shown
 * codes (codes = 0: not needed, the AVX2 kernel skips them), res = rho.  The one place both the full frame and the recompute
 * of rho for a reduced frame run (same kernel: same bytes). */
static void trm_beta_row(const tdc_trm_t *st, const tdc_trm_rowctx_t *k, uint32_t y, const uint32_t *urow, const uint8_t *src,
                         uint8_t *dst, tdc_res_t *res, tdc_trm_full_counts_t *n, int codes)
{
    if (st->gaze && tdc_trm_gaze_row_active(st->gaze, y)) {
        tdc_trm_gaze_full_row(k, st->gaze, y, urow, src, dst, res, n); /* tdc_trm_gaze.h */
        return;
    }
    if (st->simd && !codes) {
        tdc_trm_rho_row_avx2(k, urow, src, dst, res, n); /* codes discarded: not encoded */
    } else if (st->simd) {
        tdc_trm_full_row_avx2(k, urow, src, dst, res, n);
    } else {
        TDC_TRM_FULL_ROW_BOARD(k, urow, src, dst, res, n);
    }
}

/* A row worker's buffers carved from its memory (tdc_trm_rowbuf_init). */
#define TDC_ROWBUF_CARVE(member, type, count) b->member = (type *)tdc_arena_take(&arena, sizeof(type) * (size_t)(count));

/* Output row y of a full frame (D(I) rows it needs done) with row buffers
 * b; clamps counted into n[0], n[1].  Reads the kept state, writes row y of
 * the output and of icodes (or the stored residual) and b only: rows run on
 * several cores at once with their own b (tdc_trm_band). */
static void trm_full_out_row(const tdc_trm_t *st, const tdc_trm_rowctx_t *k, uint32_t y, const tdc_trm_rowbuf_t *b,
                             uint64_t n[3])
{
    const uint32_t w3 = 3u * st->cfg.width;
    const uint8_t *src = st->inc.in + (size_t)y * st->inc.in_stride;
    uint8_t *dst = st->inc.out + (size_t)y * st->inc.out_stride;
    if (st->passthrough) {
        memmove(dst, src, w3); /* in may be out */
        return;
    }
    tdc_trm_full_counts_t c = {0, 0};
    trm_u_row(st, st->dprev, y, b->urow);
    tdc_res_t *res = b->rrow;
    if (st->icodes) {
        /* keep I_t (in may be out: copy before the row is overwritten);
         * rho of this row is not kept, it is recomputed when needed */
        uint8_t *keep = st->icodes + (size_t)y * w3;
        memcpy(keep, src, w3);
        src = keep;
    } else {
        res = &st->residual[(size_t)y * w3];
    }
    trm_beta_row(st, k, y, b->urow, src, dst, res, &c, 1);
    n[0] += c.hi;
    n[1] += c.lo;
}

/* A frame in progress (full: kind 1, reduced: 2) on these buffers. */
static void trm_inc_open(tdc_trm_t *st, uint8_t kind, const uint8_t *in, uint32_t in_stride, uint8_t *out,
                         uint32_t out_stride)
{
    memset(&st->inc, 0, sizeof st->inc);
    st->inc.kind = kind;
    st->inc.in = in;
    st->inc.out = out;
    st->inc.in_stride = in_stride;
    st->inc.out_stride = out_stride;
    st->inc.loaded = -1;
}

tdc_status_t tdc_trm_full_begin(tdc_trm_t *st, const uint8_t *in, uint32_t in_stride, uint8_t *out,
                                uint32_t out_stride)
{
    if (!st || !in || !out || in_stride < 3u * st->cfg.width || out_stride < 3u * st->cfg.width) {
        return TDC_ERR_ARG;
    }
    trm_inc_open(st, 1u, in, in_stride, out, out_stride);
    if (!st->passthrough) {
        st->have_full = 0; /* D(I) and the kept codes are being replaced */
    }
    return TDC_OK;
}

tdc_status_t tdc_trm_full_rows(tdc_trm_t *st, uint32_t avail, uint32_t *done)
{
    if (!st || st->inc.kind != 1u) {
        return TDC_ERR_STATE;
    }
    const uint32_t h = st->cfg.height;
    avail = avail < h ? avail : h;
    uint32_t y = st->inc.y;
    if (st->passthrough) {
        const tdc_trm_rowbuf_t none = {NULL, NULL, NULL, NULL};
        for (; y < avail; y++) {
            trm_full_out_row(st, NULL, y, &none, st->inc.n);
        }
    } else {
        trm_d_rows(st, st->ring, st->rh, st->inc.in, st->inc.in_stride, st->dprev, NULL, 0, avail, &st->inc.loaded,
                   &st->inc.dy);
        tdc_trm_rowctx_t k;
        trm_rowctx(st, &k);
        const tdc_trm_rowbuf_t own = tdc_trm_rowbuf_own(st);
        /* row y: arrived, no longer needed by D (in may be out), its U rows done */
        for (; y < avail && (st->inc.loaded >= (int32_t)y || st->inc.dy == st->rh) && trm_u_last(st, y) < st->inc.dy;
             y++) {
            trm_full_out_row(st, &k, y, &own, st->inc.n);
        }
    }
    st->inc.y = y;
    if (done) {
        *done = y;
    }
    return TDC_OK;
}

tdc_status_t tdc_trm_full_end(tdc_trm_t *st, uint32_t seq)
{
    uint32_t done = 0;
    const tdc_status_t r = tdc_trm_full_rows(st, st ? st->cfg.height : 0u, &done);
    if (r != TDC_OK) {
        return r;
    }
    st->inc.kind = 0;
    if (done != st->cfg.height) {
        return TDC_ERR_STATE; /* unreachable: every row is there */
    }
    if (st->passthrough) {
        st->stats.passthrough_frames++;
    } else {
        st->stats.clamped_high += st->inc.n[0];
        st->stats.clamped_low += st->inc.n[1];
        st->stats.full_frames++;
        st->have_full = 1;
    }
    st->full_seq = seq;
    return TDC_OK;
}

tdc_status_t tdc_trm_full(tdc_trm_t *st, const uint8_t *in, uint32_t in_stride, uint8_t *out, uint32_t out_stride)
{
    const tdc_status_t r = tdc_trm_full_begin(st, in, in_stride, out, out_stride);
    return r != TDC_OK ? r : tdc_trm_full_end(st, st->full_seq);
}

tdc_status_t tdc_trm_full_seq(tdc_trm_t *st, const uint8_t *in, uint32_t in_stride, uint8_t *out, uint32_t out_stride,
                              uint32_t seq)
{
    const tdc_status_t r = tdc_trm_full_begin(st, in, in_stride, out, out_stride);
    return r != TDC_OK ? r : tdc_trm_full_end(st, seq);
}

/* rho of row y into the row buffer b (recompute) or a pointer into the
 * stored residual; urow holds U(D(I_t)) of row y. */
static const tdc_res_t *trm_rho_row(const tdc_trm_t *st, const tdc_trm_rowctx_t *k, uint32_t y, const uint32_t *urow,
                                    const tdc_trm_rowbuf_t *b)
{
    const uint32_t w3 = 3u * st->cfg.width;
    if (!st->icodes) {
        return &st->residual[(size_t)y * w3];
    }
    tdc_trm_full_counts_t n = {0, 0};
    trm_beta_row(st, k, y, urow, st->icodes + (size_t)y * w3, b->crow, b->rrow, &n, 0);
    return b->rrow;
}

tdc_status_t tdc_trm_residual_row(tdc_trm_t *st, uint32_t y, tdc_res_t *out)
{
    if (!st || !out || y >= st->cfg.height) {
        return TDC_ERR_ARG;
    }
    if (st->passthrough || !st->have_full) {
        return TDC_ERR_STATE;
    }
    tdc_trm_rowctx_t k;
    trm_rowctx(st, &k);
    const tdc_trm_rowbuf_t own = tdc_trm_rowbuf_own(st);
    trm_u_row(st, st->dprev, y, own.urow);
    const tdc_res_t *r = trm_rho_row(st, &k, y, own.urow, &own);
    for (uint32_t i = 0; i < 3u * st->cfg.width; i++) {
        out[i] = r[i];
    }
    return TDC_OK;
}

/* Reduced frame; with_state = 0 shows alpha alone (no residual). */
static tdc_status_t trm_reduced_args(const tdc_trm_t *st, const uint8_t *in_reduced, uint32_t in_stride,
                                     const uint8_t *out, uint32_t out_stride)
{
    if (!st || !in_reduced || !out || out_stride < 3u * st->cfg.width) {
        return TDC_ERR_ARG;
    }
    if (st->passthrough) {
        return TDC_ERR_STATE; /* this stream was configured without reduced frames */
    }
    if (in_stride < 3u * st->rw) {
        return TDC_ERR_ARG;
    }
    return TDC_OK;
}

/* Opens a reduced frame (arguments checked), with the kept state or, when
 * !with_state, as alpha alone. */
static void trm_reduced_open(tdc_trm_t *st, const uint8_t *in_reduced, uint32_t in_stride, uint8_t *out,
                             uint32_t out_stride, int with_state)
{
    trm_inc_open(st, 2u, in_reduced, in_stride, out, out_stride);
    st->inc.paired = (uint8_t)with_state;
}

/* The row buffer of an unpaired reduced frame (alpha alone): rho = 0 in
 * b's rho row (the kernel then never reads U(D(I_t)), zeroed too), or, in
 * the stored-residual layout, each row's own rho row cleared as it is
 * shown (that state is stale anyway). */
static void trm_reduced_unpaired_rows(const tdc_trm_t *st, const tdc_trm_rowbuf_t *b)
{
    const uint32_t rw3 = 3u * st->rw;
    for (uint32_t i = 0; st->icodes && i < 3u * st->cfg.width; i++) {
        b->rrow[i] = 0;
    }
    for (uint32_t i = 0; i < rw3 + 3u; i++) {
        b->urow[i] = 0; /* defined, though no kernel needs it where rho = 0 */
    }
}

/* Output row y of a reduced frame (the reduced rows its U reads there)
 * with row buffers b (unpaired: prepared by trm_reduced_unpaired_rows);
 * weight counters into n.  As trm_full_out_row, rows run concurrently with
 * their own b. */
static void trm_reduced_out_row(const tdc_trm_t *st, const tdc_trm_rowctx_t *k, uint32_t y, const tdc_trm_rowbuf_t *b,
                                uint64_t n[3])
{
    const uint32_t rw3 = 3u * st->rw;
    uint32_t *urow_a = b->urow;            /* U(D(I_t)), code Q22 */
    uint32_t *urow_b = b->urow + rw3 + 3u; /* U(i_t+1) */
    tdc_trm_reduced_counts_t c = {0, 0, 0};
    const tdc_res_t *rho;
    if (st->inc.paired) {
        trm_u_row(st, st->dprev, y, urow_a);
        rho = trm_rho_row(st, k, y, urow_a, b);
    } else if (st->icodes) {
        rho = b->rrow;
    } else {
        tdc_res_t *r = &st->residual[(size_t)y * 3u * st->cfg.width];
        for (uint32_t i = 0; i < 3u * st->cfg.width; i++) {
            r[i] = 0;
        }
        rho = r;
    }
    trm_u_row_codes(st, st->inc.in, st->inc.in_stride, y, urow_b);
    uint8_t *out = st->inc.out + (size_t)y * st->inc.out_stride;
    if (st->simd) {
        tdc_trm_reduced_row_avx2(k, urow_a, urow_b, rho, out, &c);
    } else {
        TDC_TRM_REDUCED_ROW_BOARD(k, urow_a, urow_b, rho, out, &c);
    }
    n[0] += c.computed;
    n[1] += c.skipped;
    n[2] += c.no_res;
}

tdc_status_t tdc_trm_reduced_rows(tdc_trm_t *st, uint32_t avail, uint32_t *done)
{
    if (!st || st->inc.kind != 2u) {
        return TDC_ERR_STATE;
    }
    tdc_trm_rowctx_t k;
    trm_rowctx(st, &k);
    const tdc_trm_rowbuf_t own = tdc_trm_rowbuf_own(st);
    uint32_t y = st->inc.y;
    /* row y once the reduced rows its U reads are there */
    for (; y < st->cfg.height && trm_u_last(st, y) < avail; y++) {
        if (y == 0u && !st->inc.paired) {
            trm_reduced_unpaired_rows(st, &own);
        }
        trm_reduced_out_row(st, &k, y, &own, st->inc.n);
    }
    st->inc.y = y;
    if (done) {
        *done = y;
    }
    return TDC_OK;
}

tdc_status_t tdc_trm_reduced_end(tdc_trm_t *st)
{
    uint32_t done = 0;
    const tdc_status_t r = tdc_trm_reduced_rows(st, st ? st->rh : 0u, &done);
    if (r != TDC_OK) {
        return r;
    }
    st->inc.kind = 0;
    if (done != st->cfg.height) {
        return TDC_ERR_STATE; /* unreachable: every reduced row is there */
    }
    st->stats.weight_computed += st->inc.n[0];
    st->stats.weight_skipped += st->inc.n[1];
    st->stats.residual_skipped += st->inc.n[2];
    st->stats.reduced_frames++;
    return TDC_OK;
}

tdc_status_t tdc_trm_reduced(tdc_trm_t *st, const uint8_t *in_reduced, uint32_t in_stride, uint8_t *out,
                             uint32_t out_stride)
{
    const tdc_status_t a = trm_reduced_args(st, in_reduced, in_stride, out, out_stride);
    if (a != TDC_OK) {
        return a;
    }
    if (!st->have_full) {
        return TDC_ERR_STATE;
    }
    trm_reduced_open(st, in_reduced, in_stride, out, out_stride, 1);
    return tdc_trm_reduced_end(st);
}

tdc_status_t tdc_trm_reduced_begin(tdc_trm_t *st, const uint8_t *in_reduced, uint32_t in_stride, uint8_t *out,
                                   uint32_t out_stride, uint32_t seq)
{
    const tdc_status_t a = trm_reduced_args(st, in_reduced, in_stride, out, out_stride);
    if (a != TDC_OK) {
        return a;
    }
    const int paired = st->have_full && st->full_seq + 1u == seq;
    if (!paired) {
        st->stats.reduced_unpaired++;
        st->have_full = 0; /* whatever is kept is older than this frame: never use it again */
    }
    trm_reduced_open(st, in_reduced, in_stride, out, out_stride, paired);
    return TDC_OK;
}

tdc_status_t tdc_trm_reduced_seq(tdc_trm_t *st, const uint8_t *in_reduced, uint32_t in_stride, uint8_t *out,
                                 uint32_t out_stride, uint32_t seq)
{
    const tdc_status_t r = tdc_trm_reduced_begin(st, in_reduced, in_stride, out, out_stride, seq);
    return r != TDC_OK ? r : tdc_trm_reduced_end(st);
}

tdc_status_t tdc_trm_rowbuf_init(const tdc_trm_t *st, tdc_trm_rowbuf_t *b, void *mem, size_t bytes)
{
    tdc_arena_t arena;
    if (!st || !b || !tdc_arena_over(&arena, mem, bytes)) {
        return TDC_ERR_ARG;
    }
    if (bytes < TDC_TRM_ROWBUF_BYTES(st->cfg.width, st->rw)) {
        return TDC_ERR_SIZE;
    }
    TDC_TRM_ROWBUF(TDC_ROWBUF_CARVE, st->cfg.width, st->rw)
    return TDC_OK;
}

tdc_status_t tdc_trm_split(const tdc_trm_t *st, uint32_t *d_rows)
{
    if (!st || !d_rows || (st->inc.kind != 1u && st->inc.kind != 2u) || st->inc.y != 0u) {
        return TDC_ERR_STATE;
    }
    *d_rows = st->inc.kind == 1u && !st->passthrough ? st->rh : 0u;
    return st->inc.dy == 0u ? TDC_OK : TDC_ERR_STATE;
}

void tdc_trm_d_band(const tdc_trm_t *st, uint32_t j0, uint32_t j1, const tdc_trm_rowbuf_t *b)
{
    if (j0 >= j1) {
        return;
    }
    /* the ring starts empty below the first input row of D row j0 (rows
     * above the frame are row 0, clamped): from there each D row is what
     * trm_d_rows gives it in one pass over the frame */
    const int32_t k0 = st->dy_first[j0];
    int32_t loaded = (k0 < 0 ? 0 : k0) - 1;
    uint32_t jy = j0;
    trm_d_rows(st, b->ring, j1, st->inc.in, st->inc.in_stride, st->dprev, NULL, 0, st->cfg.height, &loaded, &jy);
}

void tdc_trm_band(const tdc_trm_t *st, uint32_t y0, uint32_t y1, const tdc_trm_rowbuf_t *b, uint64_t n[3])
{
    tdc_trm_rowctx_t k;
    trm_rowctx(st, &k);
    if (st->inc.kind == 2u && !st->inc.paired && y0 < y1) {
        trm_reduced_unpaired_rows(st, b);
    }
    for (uint32_t y = y0; y < y1; y++) {
        if (st->inc.kind == 1u) {
            trm_full_out_row(st, &k, y, b, n);
        } else {
            trm_reduced_out_row(st, &k, y, b, n);
        }
    }
}

void tdc_trm_join(tdc_trm_t *st, const uint64_t n[3])
{
    for (int i = 0; i < 3; i++) {
        st->inc.n[i] += n[i];
    }
    st->inc.y = st->cfg.height;
    if (st->inc.kind == 1u) {
        st->inc.dy = st->rh; /* D(I) done by the bands */
        st->inc.loaded = (int32_t)st->cfg.height - 1;
    }
}

tdc_status_t tdc_trm_downsample(tdc_trm_t *st, const uint8_t *in, uint32_t in_stride, uint8_t *out, uint32_t out_stride)
{
    if (!st || !in || !out || in_stride < 3u * st->cfg.width || out_stride < 3u * st->rw) {
        return TDC_ERR_ARG;
    }
    if (st->passthrough) {
        return TDC_ERR_STATE; /* no reduced frames in this configuration */
    }
    trm_apply_d(st, in, in_stride, NULL, out, out_stride);
    return TDC_OK;
}
