/*
 * tdc_fov.c - foveated remap to Cartesian with the radial blur, the disk
 * composite and peripheral TAA.  The equations and formats are in
 * tdc_fov.h; the double-precision reference is ref/ref_fov.c.
 *
 * Scaling and overflow (every product is checked here once):
 *   display coordinates Q8, |x'| < 3 * 8192 * 256 < 2^23, so |x'|^2 (Q16) < 2^47
 *   in uint64; log2 values Q24 with |value| < 64, so < 2^30; the u coordinate
 *   Q16 < 8192 * 2^16 = 2^29 (past R at most 2^30: the table's last node);
 *   radial table interpolation: u (a (2^16 - f) + b f) < 2^46 in uint64, sigma
 *   Q14 and 1/sigma^2 Q12 <= 2^15, so their sums <= 2^31 + 2^15 in uint32;
 *   the angle's ratio (n << clz(m)) * inv < 2^64; colours Q8 codes <= 255 * 256
 *   < 2^16; kernel weights Q15 normalised to sum 2^15 exactly (the remainder
 *   on the largest), so a weighted sum of 8-bit samples < 255 * 2^15 + 64 <
 *   2^23 (uint32; tdc_fov_kernels.h for the two-tap kernel); the >2-tap path's
 *   normalisation: raw sum >= G(1) 2^15 = 17859, so 2^30 / sum < 2^16 and
 *   weight * reciprocal < 2^31;
 *   TAA blend a (Q15) * colour (Q8) < 2^31 in uint32.
 * Rounding: half up at every shift; tables interpolated linearly.
 *
 * Per-pixel work (docs/foveation.md "Remap speed"): eq. 2.2's radial part
 * and eq. 4.4's sigma come from the per-frame radial table (tdc_fov.h),
 * interpolated on |x'|^2 (no square root, no logarithm or power per pixel;
 * exact within 4 px of the gaze), rebuilt only when R, alpha or lp_w change;
 * the angle's atan ratio uses per-column and per-row reciprocals (no divide
 * per pixel).  At sigma = 1/2 (most pixels at alpha 4) the two taps' weights
 * come pre-normalised from tdc_fov_tent_tab.
 *
 * Separability: eq. 2.2 is radial/angular, so it does not separate into
 * rows and columns.  Each display row takes three passes over a row of
 * scratch: geometry (the blend weight, u, v, sigma: a tap descriptor per
 * pixel, or the >2-tap colour itself), the tap kernel (tdc_fov_kernels.h:
 * C, AVX2, Helium), the composite (+ TAA).  TAA is one pass over rows with
 * 2 rows of composed colour and 3 rows of |s - h| scratch (the 3x3 box of
 * eq. 4.9 finishes row y - 1 while row y is composed).
 */
#include "tdc_fov.h"

#include "tdc_fov_lr.h"
#include "tdc_fov_tables.h"
#include "tdc_math.h"

#define Q24 (1 << 24)
#define ONE_Q15 32768u

/* 2^(-g) for g in [0, 1] (Q24, g <= 2^24), Q30 in [2^29, 2^30].
 * Error <= 9.2e-7 relative (interpolation) + 0.5 LSB. */
static uint32_t exp2_frac_q30(uint32_t g)
{
    const uint32_t idx = g >> 16, fr = g & 0xFFFFu;
    const uint32_t a = tdc_fov_exp2_tab[idx];
    const uint32_t b = idx < 256u ? tdc_fov_exp2_tab[idx + 1u] : a;
    return a - (uint32_t)tdc_urshr64((uint64_t)(a - b) * fr, 16);
}

/* 2^(-n) for n >= 0 (Q24), Q30. */
static uint32_t exp2neg_q30(uint32_t n)
{
    const uint32_t ip = n >> 24;
    if (ip >= 31u) {
        return 0;
    }
    const uint32_t v = exp2_frac_q30(n & 0xFFFFFFu);
    return ip ? tdc_urshr32(v, ip) : v;
}

/* 2^s, s in Q24 (any sign), Q16, saturating at INT32_MAX for s >= 14. */
int32_t tdc_fov_exp2_q16(int32_t s)
{
    const int32_t k = tdc_asr32(s, 24);                  /* floor(s) */
    const uint32_t f = (uint32_t)(s - TDC_SHL32(k, 24)); /* [0, 2^24) */
    /* 2^s = 2^(k+1) * 2^-(1 - f); the Q30 value shifts right by 13 - k */
    const uint32_t v = exp2_frac_q30((uint32_t)Q24 - f);
    const int32_t sh = 13 - k;
    if (sh > 31) {
        return 0;
    }
    if (sh > 0) {
        return (int32_t)tdc_urshr32(v, (unsigned)sh);
    }
    return sh == 0 ? (int32_t)v : INT32_MAX;
}

/* atan2(dy, dx) mod 2 pi in Q32 turns (eq. 2.2's arctan + 1[y' < 0] 2 pi).
 * One octant from the table (error < 2e-7 turns), the rest by symmetry. */
uint32_t tdc_fov_turns_q32(int32_t dx, int32_t dy)
{
    const uint32_t ax = (uint32_t)tdc_abs32(dx), ay = (uint32_t)tdc_abs32(dy);
    if ((ax | ay) == 0u) {
        return 0;
    }
    const uint32_t mx = ax > ay ? ax : ay, mn = ax > ay ? ay : ax;
    return tdc_fov_turns_from_ratio(tdc_fov_atan_tab, (uint32_t)tdc_div_q30(mn, mx), ax, ay, dx, dy); /* [0, 2^30] */
}

/* The division-free ratio of the pixel loop: for m > 0, inv = floor((2^63 - 1)
 * / (m << clz(m))) in (2^31, 2^32); then n / m in Q30 = ((n << clz(m)) * inv)
 * >> 33 for n <= m (n << clz(m) < 2^32: the product < 2^64), at most 1 LSB
 * below tdc_div_q30's value.  One 64/32 divide per display column and per row
 * and frame instead of one per pixel. */
static uint32_t recip_norm(uint32_t m)
{
    return m ? tdc_udiv64_32(~(uint64_t)0 >> 1, m << tdc_clz32(m)) : 0u;
}

/* eq. 2.2 radial part for |x'|^2 in Q16, with the intermediates the blur
 * needs.  ln|x'| / L = log2(|x'|^2) / log2(R^2) = rho; u/w = 2^(log2(rho)/alpha). */
typedef struct {
    uint32_t u_q16;
    int32_t l1;    /* log2(|x'|^2), Q24 (0 when |x'| <= 1) */
    int32_t lg_l1; /* log2 of the Q24 integer l1 */
    int32_t nq;    /* -log2(u/w), Q24 (negative past R when not clipped) */
} fov_radial_t;

/* clip: u = lp_w from R on (eq. 2.2); else the same formula continued past R
 * (the radial table's last node: no kink inside the last interpolated segment;
 * the table's user clips).  Past R, |x'|^2 <= 2 R^2, so -nq <= 1/alpha * log2(1 + 1 /
 * log2(R^2)) < 1 (Q24) and 2^-nq = 2 * 2^-(1 + nq), Q31 < 2^32. */
static void radial(const tdc_fov_geom_t *g, uint64_t r2_q16, fov_radial_t *o, int clip)
{
    o->u_q16 = 0;
    o->l1 = 0;
    o->lg_l1 = 0;
    o->nq = 31 * Q24;
    if (r2_q16 <= 65536u) {
        return; /* |x'| <= 1: ln |x'| <= 0, K^-1 undefined below 0: u = 0 */
    }
    const int32_t l1 = tdc_log2_q24(r2_q16) - 16 * Q24;
    if (l1 <= 0) {
        return;
    }
    o->l1 = l1;
    if (l1 >= g->log2_r2max_q24 && clip) {
        o->lg_l1 = g->lg_lr_q24;
        o->nq = 0;
        o->u_q16 = (uint32_t)g->lp_w << 16;
        return;
    }
    o->lg_l1 = tdc_log2_q24((uint64_t)l1);
    const int32_t neg = g->lg_lr_q24 - o->lg_l1;
    if (neg >= 0) {
        o->nq = (int32_t)(((uint64_t)(uint32_t)neg * g->inv_alpha_q24 + (1u << 23)) >> 24);
        o->u_q16 = (uint32_t)(((uint64_t)g->lp_w * exp2neg_q30((uint32_t)o->nq) + (1u << 13)) >> 14);
    } else {
        const uint32_t pos = (uint32_t)(((uint64_t)(uint32_t)(-neg) * g->inv_alpha_q24 + (1u << 23)) >> 24);
        o->nq = -(int32_t)pos;
        const uint64_t v31 = 2u * (uint64_t)exp2_frac_q30((uint32_t)Q24 - (pos < (uint32_t)Q24 ? pos : (uint32_t)Q24));
        o->u_q16 = (uint32_t)(((uint64_t)g->lp_w * v31 + (1u << 14)) >> 15);
    }
}

void tdc_fov_to_lp(const tdc_fov_geom_t *g, int32_t x_q8, int32_t y_q8, uint32_t *u_q16, uint32_t *v_q16)
{
    const int32_t dx = x_q8 - g->cx_q8, dy = y_q8 - g->cy_q8;
    fov_radial_t rr;
    radial(g, (uint64_t)((int64_t)dx * dx + (int64_t)dy * dy), &rr, 1);
    *u_q16 = rr.u_q16;
    *v_q16 = (uint32_t)(((uint64_t)tdc_fov_turns_q32(dx, dy) * g->lp_h) >> 16);
}

/* R^2 in Q16 (the farthest screen corner from the gaze, eq. 2.4's L = ln R). */
static uint64_t r2max_q16(int32_t cx_q8, int32_t cy_q8, uint32_t width, uint32_t height)
{
    const int64_t w8 = (int64_t)width * 256, h8 = (int64_t)height * 256;
    const int64_t ex = cx_q8 > w8 - cx_q8 ? cx_q8 : w8 - cx_q8;
    const int64_t ey = cy_q8 > h8 - cy_q8 ? cy_q8 : h8 - cy_q8;
    return (uint64_t)(ex * ex + ey * ey);
}

tdc_status_t tdc_fov_geom(tdc_fov_geom_t *g, uint16_t width, uint16_t height, const tdc_fov_params_t *p)
{
    if (!g || !p || width < TDC_FOV_MIN_SIZE || height < TDC_FOV_MIN_SIZE || width > TDC_FOV_MAX_SIZE ||
        height > TDC_FOV_MAX_SIZE || p->lp_w < TDC_FOV_MIN_SIZE || p->lp_h < TDC_FOV_MIN_SIZE ||
        p->alpha_q8 < TDC_FOV_ALPHA_MIN_Q8 || p->alpha_q8 > TDC_FOV_ALPHA_MAX_Q8 || p->disk_q15 > ONE_Q15) {
        return TDC_ERR_ARG;
    }
    const int32_t w8 = (int32_t)width * 256, h8 = (int32_t)height * 256;
    if (p->gaze_x_q8 < -w8 || p->gaze_x_q8 > 2 * w8 || p->gaze_y_q8 < -h8 || p->gaze_y_q8 > 2 * h8) {
        return TDC_ERR_ARG;
    }
    if (p->lp_w > width || p->lp_h > height) {
        return TDC_ERR_SIZE;
    }
    g->width = width;
    g->height = height;
    g->lp_w = p->lp_w;
    g->lp_h = p->lp_h;
    g->cx_q8 = p->gaze_x_q8;
    g->cy_q8 = p->gaze_y_q8;
    const uint64_t r2max = r2max_q16(p->gaze_x_q8, p->gaze_y_q8, width, height); /* >= 8 px^2 */
    g->log2_r2max_q24 = tdc_log2_q24(r2max) - 16 * Q24;
    g->lg_lr_q24 = tdc_log2_q24((uint64_t)g->log2_r2max_q24);
    g->log2_w_q24 = tdc_log2_q24(p->lp_w);
    g->log2_alpha_q24 = tdc_log2_q24(p->alpha_q8) - 8 * Q24;
    g->inv_alpha_q24 = tdc_udiv64_32(((uint64_t)1 << 32) + p->alpha_q8 / 2u, p->alpha_q8);
    g->r_max_q8 = tdc_isqrt64(r2max);
    g->r_disk_q8 = (uint32_t)tdc_urshr64((uint64_t)p->disk_q15 * g->r_max_q8, 15);
    g->r_disk2_q16 = (uint64_t)g->r_disk_q8 * g->r_disk_q8;
    fov_radial_t rr;
    radial(g, g->r_disk2_q16, &rr, 1);
    uint32_t l = (rr.u_q16 + 65535u) >> 16; /* eq. 4.5: ceil */
    g->l = (uint16_t)(l > p->lp_w ? p->lp_w : l);
    uint32_t u0 = 0;
    if (g->r_disk_q8 > (uint32_t)TDC_FOV_BLEND_Q8) {
        const uint64_t rb = g->r_disk_q8 - (uint32_t)TDC_FOV_BLEND_Q8;
        radial(g, rb * rb, &rr, 1);
        const uint32_t fu = rr.u_q16 >> 16;
        u0 = fu > (uint32_t)TDC_FOV_REACH ? fu - (uint32_t)TDC_FOV_REACH : 0u;
    }
    g->u0 = (uint16_t)(u0 > g->l ? g->l : u0);
    g->transform = (uint8_t)p->transform;
    if (p->transform != TDC_FOV_KERNEL_LOG_POLAR) { /* log-rectilinear: the whole buffer (tdc_fov_lr.h) */
        g->l = 0;
        g->u0 = 0;
        return tdc_fov_lr_params_ok(p) ? TDC_OK : TDC_ERR_ARG;
    }
    return TDC_OK;
}

int tdc_fov_in_disk(const tdc_fov_geom_t *g, int32_t i, int32_t j)
{
    const int64_t dx = (int64_t)i * 256 + 128 - g->cx_q8, dy = (int64_t)j * 256 + 128 - g->cy_q8;
    return (uint64_t)(dx * dx + dy * dy) <= g->r_disk2_q16;
}

uint32_t tdc_fov_disk_span(const tdc_fov_geom_t *g, int32_t j, int32_t *x0)
{
    *x0 = 0;
    const int64_t dy = (int64_t)j * 256 + 128 - g->cy_q8;
    const uint64_t dy2 = (uint64_t)(dy * dy);
    if (j < 0 || j >= (int32_t)g->height || dy2 > g->r_disk2_q16) {
        return 0;
    }
    /* |dx| <= s = floor(sqrt(r_d^2 - dy^2)) (Q8); centres i*256+128 */
    const int64_t s = tdc_isqrt64(g->r_disk2_q16 - dy2);
    int64_t lo = tdc_asr64(g->cx_q8 - s - 128 + 255, 8); /* ceil((cx - s - 128) / 256) */
    int64_t hi = tdc_asr64(g->cx_q8 + s - 128, 8);       /* floor */
    lo = lo < 0 ? 0 : lo;
    hi = hi >= g->width ? g->width - 1 : hi;
    if (hi < lo) {
        return 0;
    }
    *x0 = (int32_t)lo;
    return (uint32_t)(hi - lo + 1);
}

uint32_t tdc_fov_disk_pixels(const tdc_fov_geom_t *g)
{
    uint32_t n = 0;
    for (int32_t j = 0; j < (int32_t)g->height; j++) {
        int32_t x0;
        n += tdc_fov_disk_span(g, j, &x0);
    }
    return n;
}

/* ---------------------------------------------------------------------
 * eq. 4.4's sigma_u = eta/4 du/dr, du/dr = u / (alpha ln(r) r), eta = 1.4 +
 * 16 r/R, all in log2: log2 sigma = log2 eta + log2 u - 2 - log2 alpha -
 * log2 ln r - log2 r.  Returns log2 sigma clamped to [-1, 1] (Q24).
 * ------------------------------------------------------------------- */
static int32_t log2_sigma(const tdc_fov_geom_t *g, const fov_radial_t *rr, int32_t leta_max)
{
    if (rr->l1 <= 0) {
        return Q24; /* sigma = 2 where r <= 1 */
    }
    const int64_t lnr = (int64_t)rr->lg_l1 - 24 * Q24 + TDC_FOV_LOG2_LN2_Q24 - Q24;
    const int64_t s0 = (int64_t)g->log2_w_q24 - (int64_t)rr->nq - 2 * Q24 - g->log2_alpha_q24 - lnr - (rr->l1 / 2);
    if (s0 + leta_max <= -Q24) {
        return -Q24; /* clamped whatever eta is (the common case at alpha 4): no eta */
    }
    const int32_t x_q16 = tdc_fov_exp2_q16(tdc_asr32(rr->l1 - g->log2_r2max_q24, 1));
    const int32_t leta = tdc_log2_q24((uint64_t)(91750 + 16 * (int64_t)x_q16)) - 16 * Q24;
    const int64_t s64 = s0 + leta;
    return (int32_t)(s64 < -Q24 ? -Q24 : (s64 > Q24 ? Q24 : s64));
}

/* u, sigma (Q14, [2^13, 2^15]) and 1/sigma^2 (Q12, [2^10, 2^14]) at |x'|^2:
 * a node of the radial table, or a pixel closer than 4 px to the gaze. */
void tdc_fov_node_fill(const tdc_fov_geom_t *g, uint64_t r2_q16, int clip, int32_t leta_max, tdc_fov_node_t *nd)
{
    fov_radial_t rr;
    radial(g, r2_q16, &rr, clip);
    const int32_t ls = log2_sigma(g, &rr, leta_max);
    nd->u_q16 = rr.u_q16;
    nd->sig_q14 = (uint16_t)tdc_urshr32((uint32_t)tdc_fov_exp2_q16(ls), 2);
    nd->inv2_q12 = (uint16_t)tdc_urshr32((uint32_t)tdc_fov_exp2_q16(-2 * ls), 4);
}

/* Nodes the frame needs: up to the one past the octave of R^2 (<= the
 * arena's TDC_FOV_RAD_NODES: R^2 <= 4 (W^2 + H^2) px^2). */
static uint32_t rad_nodes_for(uint64_t r2max)
{
    if (r2max < ((uint64_t)1 << TDC_FOV_NODE_E0)) {
        return 0;
    }
    const uint32_t e = 63u - tdc_clz64(r2max);
    return ((e - TDC_FOV_NODE_E0 + 1u) << TDC_FOV_NODE_BITS) + 1u;
}

/* The composite of pixel i after the kernel ran: Q8 colour c, returns b. */
static inline uint32_t px_colour(const tdc_fov_t *st, const uint8_t *drow, int32_t i, uint16_t c[3])
{
    const uint32_t bf = st->t_b[i], b = bf & 511u;
    uint32_t lpc[3];
    if (bf & TDC_FOV_GEN_FLAG) {
        const uint16_t *gp = st->t_gen + (size_t)i * 3u;
        lpc[0] = gp[0], lpc[1] = gp[1], lpc[2] = gp[2];
    } else if (!b) {
        lpc[0] = lpc[1] = lpc[2] = 0; /* the disk only; the tap kernel may not have run (log-rectilinear rows) */
    } else {
        const uint16_t *kp = st->t_out + i;
        const size_t w = st->cfg.width;
        lpc[0] = kp[0], lpc[1] = kp[w], lpc[2] = kp[2u * w];
    }
    if (b < 256u) {
        const uint8_t *dp = drow + (size_t)i * 3u;
        c[0] = (uint16_t)tdc_urshr32((256u - b) * dp[0] * 256u + b * lpc[0], 8);
        c[1] = (uint16_t)tdc_urshr32((256u - b) * dp[1] * 256u + b * lpc[1], 8);
        c[2] = (uint16_t)tdc_urshr32((256u - b) * dp[2] * 256u + b * lpc[2], 8);
    } else {
        c[0] = (uint16_t)lpc[0], c[1] = (uint16_t)lpc[1], c[2] = (uint16_t)lpc[2];
    }
    return b;
}

/* ---------------------------------------------------------------------
 * Stage state.
 * ------------------------------------------------------------------- */
static int fov_config_valid(const tdc_fov_config_t *cfg)
{
    return cfg && cfg->width >= TDC_FOV_MIN_SIZE && cfg->height >= TDC_FOV_MIN_SIZE && cfg->width <= TDC_FOV_MAX_SIZE &&
           cfg->height <= TDC_FOV_MAX_SIZE && cfg->taa <= 1u;
}

/* The one layout (tdc_fov.h TDC_FOV_ARENA); NULL views in a dry run. */
static void fov_carve(tdc_fov_t *st, const tdc_fov_config_t *cfg,
                      tdc_arena_t *arena){TDC_FOV_ARENA(TDC_ARENA_CARVE, cfg->width, cfg->height, cfg->taa)}

size_t tdc_fov_get_size(const tdc_fov_config_t *cfg)
{
    if (!fov_config_valid(cfg)) {
        return 0;
    }
    tdc_fov_t dry;
    tdc_arena_t arena;
    tdc_arena_dry(&arena);
    fov_carve(&dry, cfg, &arena);
    return tdc_arena_size(&arena);
}

tdc_status_t tdc_fov_init(tdc_fov_t *st, const tdc_fov_config_t *cfg, void *mem, size_t mem_bytes)
{
    tdc_arena_t arena;
    if (!st || !fov_config_valid(cfg) || !tdc_arena_over(&arena, mem, mem_bytes)) {
        return TDC_ERR_ARG; /* null, bad size, mem not aligned to TDC_ARENA_ALIGN */
    }
    if (mem_bytes < tdc_fov_get_size(cfg)) { /* the same carve, dry: nothing is touched on error */
        return TDC_ERR_SIZE;
    }
    fov_carve(st, cfg, &arena);
    st->cfg = *cfg;
    st->lr = 0;
    st->frames = 0;
    st->rejected_frames = 0;
    st->rad_builds = 0;
    st->rad_valid = 0;
    st->rad_half_lo = 1;
    st->rad_half_hi = 0;
    st->colinv_valid = 0;
    st->rad_nodes = 0;
    tdc_fov_set_simd(st, 1);
    tdc_fov_reset(st);
    return TDC_OK;
}

void tdc_fov_set_simd(tdc_fov_t *st, int enable)
{
    const int avx2 = enable && tdc_fov_avx2_available();
    st->tap2 = avx2 ? tdc_fov_tap2_row_avx2 : TDC_FOV_TAP2_BOARD;
    st->geom = avx2 ? tdc_fov_geom_row_avx2 : tdc_fov_geom_row_c;
}

void tdc_fov_reset(tdc_fov_t *st)
{
    st->cur = 0;
    st->have_hist = 0;
    st->dt_prev_us = 0;
    st->gaze_prev_x_q8 = 0;
    st->gaze_prev_y_q8 = 0;
}

/* Row scratch layout (uint16): slot k (row y & 1) of 8 values per pixel
 * {s0, s1, s2, h0, h1, h2, H, b}, then 3 rows of |s - h| (slot y % 3). */
#define ROW_VALS 8u

typedef struct {
    uint16_t *slot[2];
    uint16_t *dif[3];
} fov_rows_t;

/* eq. 2.5 for one channel: s + (1 - a)(h - s), (1 - a) in Q15 (k), the
 * product rounded toward zero (see finish_row). */
static inline uint32_t taa_blend(uint32_t s, uint32_t h, uint32_t k)
{
    const int32_t dlt = (int32_t)h - (int32_t)s;
    const int32_t m = (int32_t)((k * (uint32_t)tdc_abs32(dlt)) >> 15);
    return (uint32_t)((int32_t)s + (dlt < 0 ? -m : m));
}

/* History at a Q4 position: bilinear in Q4, Q8 codes out (<= 255 * 256). */
static inline uint32_t hist_bilinear(const uint16_t *h00, const uint16_t *h01, const uint16_t *h10, const uint16_t *h11,
                                     uint32_t fx, uint32_t fy)
{
    const uint32_t top = *h00 * (16u - fx) + *h01 * fx;
    const uint32_t bot = *h10 * (16u - fx) + *h11 * fx;
    return (top * (16u - fy) + bot * fy + 128u) >> 8;
}

/* eq. 4.9 box, eq. 4.10 and eq. 2.5 for row y; writes history and output. */
static void finish_row(const tdc_fov_t *st, const fov_rows_t *rw, int32_t y, uint16_t *hist_new, uint8_t *orow)
{
    const int32_t W = st->cfg.width, H = st->cfg.height;
    const uint16_t *sl = rw->slot[y & 1];
    /* the 3x3 box as a sliding sum of column sums over the rows y - 1..y + 1 on the screen */
    const uint16_t *d0 = y > 0 ? rw->dif[(y - 1) % 3] : 0, *d1 = rw->dif[y % 3], *d2 = y + 1 < H ? rw->dif[(y + 1) % 3] : 0;
    const uint32_t nrows = 1u + (d0 != 0) + (d2 != 0);
#define COLSUM(xx) ((uint32_t)d1[xx] + (d0 ? d0[xx] : 0u) + (d2 ? d2[xx] : 0u))
    uint32_t cs_l = 0, cs_c = COLSUM(0), cs_r = COLSUM(1); /* W >= 4 */
    for (int32_t x = 0; x < W; x++) {
        const uint16_t *e = sl + (size_t)x * ROW_VALS;
        uint16_t *hn = hist_new + ((size_t)y * W + (size_t)x) * 3u;
        uint32_t f[3] = {e[0], e[1], e[2]};
        if (e[6] != 0xFFFFu) { /* history valid */
            const uint32_t sum = cs_l + cs_c + cs_r, cnt = nrows * (3u - (x == 0) - (x == W - 1));
            const uint32_t eps = cnt == 9u ? (sum + 4u) / 9u : (sum + cnt / 2u) / cnt; /* Q8 codes */
            uint32_t amin = (eps * ONE_Q15 + 32640u) / 65280u;
            amin = amin < 3277u ? 3277u : (amin > ONE_Q15 ? ONE_Q15 : amin);
            const uint32_t a = amin + tdc_urshr32((ONE_Q15 - amin) * e[6], 15);
            const uint32_t aeff = ONE_Q15 - tdc_urshr32(e[7] * (ONE_Q15 - a), 8);
            /* f = s + (1 - a)(h - s), the product rounded toward zero: |f - s|
             * shrinks every frame, so a static field converges to exactly s
             * (rounding half up stalls at h - s = 5/256 of a code with a = 0.1) */
            f[0] = taa_blend(e[0], e[3], ONE_Q15 - aeff);
            f[1] = taa_blend(e[1], e[4], ONE_Q15 - aeff);
            f[2] = taa_blend(e[2], e[5], ONE_Q15 - aeff);
        }
        hn[0] = (uint16_t)f[0], hn[1] = (uint16_t)f[1], hn[2] = (uint16_t)f[2];
        orow[(size_t)x * 3u] = (uint8_t)((f[0] + 128u) >> 8);
        orow[(size_t)x * 3u + 1u] = (uint8_t)((f[1] + 128u) >> 8);
        orow[(size_t)x * 3u + 2u] = (uint8_t)((f[2] + 128u) >> 8);
        cs_l = cs_c;
        cs_c = cs_r;
        cs_r = x + 2 < W ? COLSUM(x + 2) : 0u;
    }
#undef COLSUM
}

/* log2 of eq. 4.4's largest eta (x = 1: 1.4 + 16 = 91750 / 2^16 + 16), Q24: eta is at most this. */
static int32_t leta_max_q24(void)
{
    return tdc_log2_q24(91750u + 16u * 65536u) - 16 * Q24;
}

/* The frame's tables: the radial table, rebuilt only when R (the gaze), alpha or lp_w changed (a
 * log-rectilinear frame does not read it: geom_px takes its periphery from tdc_fov_lr.c; kept for
 * the next log-polar one), with its longest run of nodes with sigma = 1/2, [half_lo, half_hi] (a
 * pixel between two of them takes the two-tap path: the SIMD geometry tests that on the node index
 * alone); the columns' reciprocals, rebuilt when the gaze's x changed. */
static void frame_tables(tdc_fov_t *st, const tdc_fov_geom_t *g, const tdc_fov_params_t *p)
{
    const int32_t leta_max = leta_max_q24();
    const int lr = g->transform == TDC_FOV_LOG_RECT;
    const uint32_t nodes = lr ? st->rad_nodes : rad_nodes_for(r2max_q16(g->cx_q8, g->cy_q8, g->width, g->height));
    if (!lr && (!st->rad_valid || st->rad_key_r2 != g->log2_r2max_q24 || st->rad_key_lpw != g->lp_w ||
                st->rad_key_alpha != p->alpha_q8 || st->rad_nodes != nodes)) {
        uint32_t run = 0, best = 0;
        st->rad_half_lo = 1;
        st->rad_half_hi = 0;
        for (uint32_t n = 0; n < nodes; n++) {
            const uint32_t e = TDC_FOV_NODE_E0 + (n >> TDC_FOV_NODE_BITS), m = n & 127u;
            tdc_fov_node_fill(g, ((uint64_t)1 << e) + ((uint64_t)m << (e - 7u)), 0, leta_max, &st->rad[n]);
            run = st->rad[n].sig_q14 == 8192u ? run + 1u : 0u;
            if (run > best) {
                best = run;
                st->rad_half_lo = n + 1u - run;
                st->rad_half_hi = n;
            }
        }
        st->rad_valid = 1;
        st->rad_key_r2 = g->log2_r2max_q24;
        st->rad_key_lpw = g->lp_w;
        st->rad_key_alpha = p->alpha_q8;
        st->rad_nodes = nodes;
        st->rad_builds++;
    }
    if (!st->colinv_valid || st->colinv_cx != g->cx_q8) {
        for (int32_t x = 0; x < g->width; x++) {
            st->colinv[x] = recip_norm((uint32_t)tdc_abs32(x * 256 + 128 - g->cx_q8));
        }
        st->colinv_valid = 1;
        st->colinv_cx = g->cx_q8;
    }
}

/* The geometry pass's arguments for a frame (the stage's tables and row
 * buffers; the radial table's node count once it is built) and a row. */
static void geom_args_frame(const tdc_fov_t *st, const tdc_fov_geom_t *g, const uint8_t *lp, size_t lp_stride,
                            tdc_fov_geom_args_t *a)
{
    const tdc_fov_geom_args_t z = {0};
    *a = z;
    a->g = g;
    a->lp = lp;
    a->lp_stride = lp_stride;
    a->rad = st->rad;
    a->rad_nodes = st->rad_nodes;
    a->half_lo = st->rad_half_lo;
    a->half_hi = st->rad_half_hi;
    a->colinv = st->colinv;
    a->atan_tab = tdc_fov_atan_tab;
    a->tent_tab = tdc_fov_tent_tab;
    a->rb_q8 = (int32_t)g->r_disk_q8 - TDC_FOV_BLEND_Q8;
    a->rb2_q16 = a->rb_q8 > 0 ? (uint64_t)a->rb_q8 * (uint64_t)a->rb_q8 : 0u;
    a->leta_max = leta_max_q24();
    a->off_dummy = (uint32_t)g->u0 * 3u;
    a->taa = st->cfg.taa;
    a->lr = g->transform == TDC_FOV_LOG_RECT ? st->lr : 0;
    a->off0 = st->t_off0;
    a->off1 = st->t_off1;
    a->wf = st->t_wf;
    a->ij = st->t_ij;
    a->gen = st->t_gen;
    a->b = st->t_b;
}

static void geom_args_row(tdc_fov_geom_args_t *a, int32_t y)
{
    a->dy = y * 256 + 128 - a->g->cy_q8;
    a->dy2 = (uint64_t)((int64_t)a->dy * a->dy);
    a->ay = (uint32_t)tdc_abs32(a->dy);
    a->inv_y = recip_norm(a->ay);
}

tdc_status_t tdc_fov_geom_args(tdc_fov_t *st, const tdc_fov_params_t *p, const uint8_t *lp, size_t lp_stride,
                               int32_t y, tdc_fov_geom_t *g, tdc_fov_geom_args_t *a)
{
    if (!st || !p || !lp || !g || !a) {
        return TDC_ERR_ARG;
    }
    const tdc_status_t s = tdc_fov_geom(g, st->cfg.width, st->cfg.height, p);
    if (s != TDC_OK || g->transform != TDC_FOV_KERNEL_LOG_POLAR || y < 0 || y >= (int32_t)g->height) {
        return s != TDC_OK ? s : TDC_ERR_ARG;
    }
    frame_tables(st, g, p);
    geom_args_frame(st, g, lp, lp_stride, a);
    geom_args_row(a, y);
    return TDC_OK;
}

tdc_status_t tdc_fov_frame(tdc_fov_t *st, const tdc_fov_params_t *p, const uint8_t *lp, size_t lp_stride,
                           const int16_t *mv, size_t mv_stride, const uint8_t *disk, size_t disk_stride, uint32_t dt_us,
                           uint8_t *out, size_t out_stride)
{
    if (!st || !p || !lp || !disk || !out) {
        return TDC_ERR_ARG;
    }
    tdc_fov_geom_t g;
    const tdc_status_t s = tdc_fov_geom(&g, st->cfg.width, st->cfg.height, p);
    if (s != TDC_OK) {
        return s;
    }
    if (lp_stride < (size_t)p->lp_w * 3u || disk_stride < (size_t)g.width * 3u || out_stride < (size_t)g.width * 3u ||
        (mv && mv_stride < (size_t)p->lp_w * 2u)) {
        return TDC_ERR_ARG;
    }
    /* tap descriptors hold byte offsets below 2^31 (tdc_fov_kernels.h) */
    const uint64_t lp_bytes64 = (uint64_t)(p->lp_h - 1u) * (uint64_t)lp_stride + (uint64_t)p->lp_w * 3u; /* no wrap */
    if (lp_bytes64 >= ((uint64_t)1 << 31)) {
        return TDC_ERR_ARG;
    }
    const size_t lp_bytes = (size_t)lp_bytes64;
    const int32_t W = g.width, H = g.height;
    const tdc_fov_tap2_args_t ka = {lp, lp_bytes, st->t_off0, st->t_off1, st->t_wf,
                                    {st->t_out, st->t_out + W, st->t_out + 2 * W}};
    if (g.transform == TDC_FOV_LOG_RECT) { /* the second kind: needs its scratch attached */
        if (!st->lr) {
            return TDC_ERR_ARG;
        }
        const tdc_status_t ls = tdc_fov_lr_begin(st->lr, &g, p, lp, lp_stride);
        if (ls != TDC_OK) {
            return ls;
        }
    }
    frame_tables(st, &g, p);
    tdc_fov_geom_args_t src;
    geom_args_frame(st, &g, lp, lp_stride, &src);

    /* TAA set-up: eq. 4.7 rate, 60 / R_n (Q16); saccade rejection */
    int reject_all = 1;
    uint32_t r60_q16 = 0;
    int32_t log2_diag2 = 0;
    if (st->cfg.taa) {
        const uint32_t dt = dt_us ? (dt_us < 100u ? 100u : dt_us) : (st->dt_prev_us ? st->dt_prev_us : 11111u);
        const uint32_t dtp = st->dt_prev_us ? st->dt_prev_us : dt;
        const uint32_t rn = (256000000u + dt / 2u) / dt, rp = (256000000u + dtp / 2u) / dtp; /* Hz Q8 */
        const uint32_t rate = (rn + 9u * rp + 5u) / 10u;
        r60_q16 = (1006632960u + rate / 2u) / rate; /* 60 * 2^24 / rate */
        st->dt_prev_us = dt;
        const uint64_t diag2 = (uint64_t)W * W + (uint64_t)H * H;
        log2_diag2 = tdc_log2_q24(diag2);
        const int64_t gx = (int64_t)p->gaze_x_q8 - st->gaze_prev_x_q8, gy = (int64_t)p->gaze_y_q8 - st->gaze_prev_y_q8;
        const int saccade = (uint64_t)(gx * gx + gy * gy) > diag2 * 1024u; /* > diag / 8, Q8 */
        reject_all = !st->have_hist || saccade;
        st->rejected_frames += (uint32_t)(st->have_hist && saccade);
        st->gaze_prev_x_q8 = p->gaze_x_q8;
        st->gaze_prev_y_q8 = p->gaze_y_q8;
    }

    uint32_t h_m2 = 0, h_hq = 0; /* eq. 4.8's H of the last vector (H(0) = 0) */
    fov_rows_t rw = {{0, 0}, {0, 0, 0}};
    uint16_t *hist_old = 0, *hist_new = 0;
    if (st->cfg.taa) {
        rw.slot[0] = st->rows;
        rw.slot[1] = st->rows + (size_t)W * ROW_VALS;
        for (int k = 0; k < 3; k++) {
            rw.dif[k] = st->rows + (size_t)W * (2u * ROW_VALS + (size_t)k);
        }
        hist_old = st->hist[st->cur];
        hist_new = st->hist[st->cur ^ 1u];
    }

    for (int32_t y = 0; y < H; y++) {
        const uint8_t *drow = disk + (size_t)y * disk_stride;
        geom_args_row(&src, y);
        uint8_t *orow = out + (size_t)y * out_stride;
        uint16_t *sl = st->cfg.taa ? rw.slot[y & 1] : 0, *dif_row = st->cfg.taa ? rw.dif[y % 3] : 0;
        if (src.lr) {
            tdc_fov_lr_row(st->lr, y);
        }
        st->geom(&src, 0, W);
        if (!src.lr) { /* a log-rectilinear row has every periphery colour in gen already */
            st->tap2(&ka, (uint32_t)W);
        }
        if (!st->cfg.taa) {
            /* b = 256 from the kernel (most pixels): Q8 -> 8 bits; the rest through px_colour */
            const uint16_t *kr = st->t_out, *kg = kr + W, *kb = kg + W;
            for (int32_t x = 0; x < W; x++) {
                uint8_t *o = orow + (size_t)x * 3u;
                if (st->t_b[x] == 256u) {
                    o[0] = (uint8_t)((kr[x] + 128u) >> 8);
                    o[1] = (uint8_t)((kg[x] + 128u) >> 8);
                    o[2] = (uint8_t)((kb[x] + 128u) >> 8);
                } else {
                    uint16_t c[3];
                    (void)px_colour(st, drow, x, c);
                    for (int ch = 0; ch < 3; ch++) {
                        o[ch] = (uint8_t)((c[ch] + 128u) >> 8);
                    }
                }
            }
            continue;
        }
        for (int32_t x = 0; x < W; x++) {
            uint16_t c[3];
            const uint32_t b = px_colour(st, drow, x, c);
            const uint32_t iu = st->t_ij[x] & 0xFFFFu, jv = st->t_ij[x] >> 16;
            uint16_t *e = sl + (size_t)x * ROW_VALS;
            e[0] = c[0];
            e[1] = c[1];
            e[2] = c[2];
            e[6] = 0xFFFFu; /* no history */
            e[7] = (uint16_t)b;
            uint32_t dsum = 3u * 65280u;
            if (!reject_all && b) {
                int32_t mx = 0, my = 0;
                if (mv) {
                    const int16_t *m = mv + (size_t)jv * mv_stride + (size_t)iu * 2u;
                    mx = m[0];
                    my = m[1];
                }
                /* reprojection pi(p) of eq. 2.5 = p + mv (backward MVs, the link's
                 * common interface; the thesis's eq. 4.6 m = p - f(W[p]) is -mv) */
                int32_t px = x * 16 + mx, py = y * 16 + my;
                if (px >= -8 && px <= (W - 1) * 16 + 8 && py >= -8 && py <= (H - 1) * 16 + 8) {
                    px = tdc_clamp32(px, 0, (W - 1) * 16);
                    py = tdc_clamp32(py, 0, (H - 1) * 16);
                    const int32_t x0 = px >> 4, y0 = py >> 4;
                    const uint32_t fx = (uint32_t)px & 15u, fy = (uint32_t)py & 15u;
                    const int32_t x1 = x0 + 1 < W ? x0 + 1 : x0, y1 = y0 + 1 < H ? y0 + 1 : y0;
                    const uint16_t *h00 = hist_old + ((size_t)y0 * W + (size_t)x0) * 3u;
                    const uint16_t *h01 = h00 + (size_t)(x1 - x0) * 3u;
                    const uint16_t *h10 = h00 + (size_t)(y1 - y0) * (size_t)W * 3u, *h11 = h10 + (size_t)(x1 - x0) * 3u;
                    const uint32_t hv0 = hist_bilinear(h00, h01, h10, h11, fx, fy);
                    const uint32_t hv1 = hist_bilinear(h00 + 1, h01 + 1, h10 + 1, h11 + 1, fx, fy);
                    const uint32_t hv2 = hist_bilinear(h00 + 2, h01 + 2, h10 + 2, h11 + 2, fx, fy);
                    e[3] = (uint16_t)hv0, e[4] = (uint16_t)hv1, e[5] = (uint16_t)hv2;
                    dsum = (uint32_t)tdc_abs32((int32_t)c[0] - (int32_t)hv0) +
                           (uint32_t)tdc_abs32((int32_t)c[1] - (int32_t)hv1) +
                           (uint32_t)tdc_abs32((int32_t)c[2] - (int32_t)hv2);
                    /* eq. 4.8: H = (|m| / |(W, H)|)^(1/4) * 60 / R_n, Q15, capped at 1 (eq. 4.10's min) */
                    const uint32_t m2 = (uint32_t)(mx * mx) + (uint32_t)(my * my);
                    uint32_t hq = 0;
                    if (m2 == h_m2) {
                        hq = h_hq; /* neighbours mostly share one sample's vector */
                    } else if (m2) {
                        const int32_t lg = tdc_log2_q24(m2) - 8 * Q24 - log2_diag2;
                        const uint64_t e16 = (uint64_t)tdc_fov_exp2_q16(tdc_asr32(lg, 3));
                        const uint64_t hh = (e16 * r60_q16 + (1u << 16)) >> 17;
                        hq = hh > ONE_Q15 ? ONE_Q15 : (uint32_t)hh;
                        h_m2 = m2;
                        h_hq = hq;
                    }
                    e[6] = (uint16_t)hq;
                }
            }
            dif_row[x] = (uint16_t)((dsum + 1u) / 3u);
        }
        if (st->cfg.taa && y > 0) {
            finish_row(st, &rw, y - 1, hist_new, out + (size_t)(y - 1) * out_stride);
        }
    }
    if (st->cfg.taa) {
        finish_row(st, &rw, H - 1, hist_new, out + (size_t)(H - 1) * out_stride);
        st->cur ^= 1u;
        st->have_hist = 1;
    }
    st->frames++;
    return TDC_OK;
}
