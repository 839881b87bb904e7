/*
 * tdc_fov_rows.c - the foveation stage's portable C row kernels (as TRM's
 * are in tdc_trm_rows.c): the geometry pass over a display row
 * (tdc_fov_geom_row_c: per pixel the blend weight, eq. 2.2's u and v,
 * eq. 4.4's sigma, the tap descriptor or the blurred colour itself) and the
 * two-tap kernel over a row (tdc_fov_tap2_row_c).  They are the reference
 * and what boards run; tdc_fov_avx2.c and tdc_fov_mve.c must produce the
 * same bytes (tests/checkasm/checkasm_fov.c) and fall back to these where
 * they have no vector path.  The per-frame tables they read (radial nodes,
 * column reciprocals) are built by the stage, tdc_fov.c.
 */
#include "tdc_fov.h"
#include "tdc_fov_kernels.h"
#include "tdc_fov_lr.h"
#include "tdc_fov_tables.h" /* tdc_fov_gauss_tab */
#include "tdc_math.h"

/* Out of line where a rare path would crowd the hot one's registers (GNU C
 * compilers; plain elsewhere).  Same code and results either way. */
#if defined(__GNUC__) || defined(__clang__)
#define FOV_COLD __attribute__((noinline, cold))
#else
#define FOV_COLD
#endif

/* The division-free ratio n / m in Q30 from inv = the stage's per-column /
 * per-row reciprocal of m (recip_norm, tdc_fov.c). */
static inline uint32_t ratio_q30(uint32_t n, uint32_t m, uint32_t inv)
{
    return (uint32_t)(((uint64_t)(n << tdc_clz32(m)) * inv) >> 33);
}

/* ---------------------------------------------------------------------
 * The geometry pass, one display pixel: the blend weight b (Q8, 0 = disk
 * only), eq. 2.2's u and v, eq. 4.4's sigma; at sigma = 1/2 (most pixels)
 * the tap descriptor for the kernel (tdc_fov_kernels.h), else the blurred
 * colour itself (3 to 9 taps).  b[i] = b | 512 for a pixel with its
 * colour in gen; ij[i] = iu | jv << 16 (the nearest sample).
 * ------------------------------------------------------------------- */
/* The pass's inputs and outputs: tdc_fov_geom_args_t (tdc_fov.h). */
typedef tdc_fov_geom_args_t fov_src_t;

#define TAPS_MAX 9 /* sigma <= 2: |t - u| <= 2 sigma = 4 */

/* Linear interpolation between nodes, f in Q16: (a (2^16 - f) + b f + 2^15) >> 16.
 * u < 2^30: 64-bit sum; sigma, 1/sigma^2 <= 2^15: the sum <= 2^31 + 2^15 fits 32 bits. */
static inline uint32_t lerp_u(uint32_t a, uint32_t b, uint32_t f)
{
    return (uint32_t)tdc_urshr64((uint64_t)a * (65536u - f) + (uint64_t)b * f, 16);
}

static inline uint32_t lerp_s(uint32_t a, uint32_t b, uint32_t f)
{
    return tdc_urshr32(a * (65536u - f) + b * f, 16);
}

static void geom_general(const fov_src_t *s, int32_t i, uint32_t b, int32_t u, int32_t sig, int32_t inv2, uint32_t j0,
                         uint32_t j1, uint32_t fv);

static void geom_px(const fov_src_t *s, int32_t i, int32_t dx, uint64_t r2)
{
    const int32_t dy = s->dy;
    const tdc_fov_geom_t *g = s->g;
    uint32_t b = 256;
    if (r2 < g->r_disk2_q16) {
        if (r2 <= s->rb2_q16) {
            b = 0;
        } else {
            const int32_t x = (int32_t)tdc_isqrt64(r2) - s->rb_q8;
            b = (uint32_t)tdc_clamp32(x, 0, TDC_FOV_BLEND_Q8) >> 2;
        }
    }
    s->b[i] = (uint16_t)b;
    if (!b || s->lr) {
        if (!s->lr) {                                  /* the tap kernel runs over log-polar rows only */
            s->off0[i] = s->off_dummy | TDC_FOV_STEP0; /* a harmless descriptor: sample (u0, 0), weight 1 */
            s->off1[i] = s->off_dummy;
            s->wf[i] = 32768u;
        }
        if (b) { /* log-rectilinear: the periphery sample (Q8) is the pixel's colour, as geom_general's */
            uint32_t c[3], iu = 0, jv = 0;
            tdc_fov_lr_sample(s->lr, i, c, &iu, &jv);
            uint16_t *gp = s->gen + (size_t)i * 3u;
            gp[0] = (uint16_t)c[0], gp[1] = (uint16_t)c[1], gp[2] = (uint16_t)c[2]; /* <= 255 * 256 */
            s->ij[i] = iu | jv << 16;
            s->b[i] = (uint16_t)(b | TDC_FOV_GEN_FLAG);
        }
        return;
    }
    /* eq. 2.2 radial part and eq. 4.4's sigma: the radial table, interpolated on |x'|^2 */
    int32_t u;
    const uint32_t e = r2 >= ((uint64_t)1 << TDC_FOV_NODE_E0) ? 63u - tdc_clz64(r2) : 0u;
    /* the top 24 bits of |x'|^2: the leading 1, 7 bits of node, 16 of fraction */
    const uint32_t m24 = e >= 23u ? (uint32_t)(r2 >> (e - 23u)) : (uint32_t)r2 << (23u - e);
    const uint32_t n = e ? ((e - TDC_FOV_NODE_E0) << TDC_FOV_NODE_BITS) | ((m24 >> 16) & 127u) : 0u;
    const tdc_fov_node_t *na, *nb;
    tdc_fov_node_t nd;
    uint32_t f;
    if (e && n + 1u < s->rad_nodes) {
        f = m24 & 0xFFFFu; /* Q16 in the node */
        na = s->rad + n;
        nb = na + 1;
        const uint32_t uu = lerp_u(na->u_q16, nb->u_q16, f);
        u = (int32_t)(uu > (uint32_t)g->lp_w << 16 ? (uint32_t)g->lp_w << 16 : uu);
    } else {
        tdc_fov_node_fill(g, r2, 1, s->leta_max, &nd); /* within 4 px of the gaze: exact */
        na = nb = &nd;
        f = 0;
        u = (int32_t)nd.u_q16;
    }
    const int32_t sig = (int32_t)lerp_s(na->sig_q14, nb->sig_q14, f);
    /* eq. 2.2 angle: atan of the octant ratio, the divide by a per-column / per-row reciprocal */
    const uint32_t ax = (uint32_t)tdc_abs32(dx), ay = s->ay;
    uint32_t turns = 0;
    if (ax | ay) {
        const uint32_t t = ax > ay ? ratio_q30(ay, ax, s->colinv[i]) : ratio_q30(ax, ay, s->inv_y);
        turns = tdc_fov_turns_from_ratio(s->atan_tab, t, ax, ay, dx, dy);
    }
    const uint32_t v = (uint32_t)(((uint64_t)turns * g->lp_h) >> 16);
    const uint32_t j0 = v >> 16, fv = (v & 0xFFFFu) >> 1; /* Q15 */
    const uint32_t j1 = j0 + 1u == g->lp_h ? 0u : j0 + 1u;
    const int32_t cmin = g->u0, cmax = (int32_t)g->lp_w - 1;
    if (s->taa) { /* the nearest sample: its motion vector */
        const uint32_t ui = tdc_urshr32((uint32_t)u, 16), vi = tdc_urshr32(v, 16);
        s->ij[i] = (uint32_t)tdc_clamp32((int32_t)ui, cmin, cmax) | (vi >= g->lp_h ? 0u : vi) << 16;
    }
    if (sig == 8192) { /* sigma = 1/2: two taps, floor(u) and floor(u) + 1, from the tent table */
        const uint32_t fu = (uint32_t)u & 0xFFFFu, k = fu >> 8, fr = fu & 255u;
        const uint32_t ta = s->tent_tab[k], tb = s->tent_tab[k + 1u];
        const int32_t c0 = tdc_clamp32(u >> 16, cmin, cmax), c1 = tdc_clamp32((u >> 16) + 1, cmin, cmax);
        s->off0[i] = (uint32_t)(j0 * s->lp_stride + (size_t)c0 * 3u) | (c1 == c0 ? TDC_FOV_STEP0 : 0u);
        s->off1[i] = (uint32_t)(j1 * s->lp_stride + (size_t)c0 * 3u);
        s->wf[i] = (ta - tdc_urshr32((ta - tb) * fr, 8)) | fv << 16;
        return;
    }
    geom_general(s, i, b, u, sig, (int32_t)lerp_s(na->inv2_q12, nb->inv2_q12, f), j0, j1, fv);
}

/* sigma > 1/2 (few pixels at alpha 4): up to 9 taps, computed here, not by the
 * kernel.  Out of line: the common two-tap path above keeps its registers. */
static FOV_COLD void geom_general(const fov_src_t *s, int32_t i, uint32_t b, int32_t u, int32_t sig, int32_t inv2,
                                  uint32_t j0, uint32_t j1, uint32_t fv)
{
    const int32_t cmin = s->g->u0, cmax = (int32_t)s->g->lp_w - 1;
    /* sigma > 1/2: up to 9 taps, weights from the cut Gaussian normalised to 2^15 */
    const int32_t lo = tdc_asr32(u - 8 * sig + 65535, 16), hi = tdc_asr32(u + 8 * sig, 16);
    const int32_t u12 = (u + 8) >> 4;
    int32_t col[TAPS_MAX];
    uint32_t wt[TAPS_MAX], sum = 0;
    int32_t nt = 0;
    for (int32_t t = lo; t <= hi && nt < TAPS_MAX; t++) {
        const int32_t d = TDC_SHL32(t, 12) - u12;       /* Q12, |d| <= 4.01 */
        const uint32_t d2 = (uint32_t)(d * d) >> 12;    /* Q12 < 2^17 */
        const uint32_t t2 = (d2 * (uint32_t)inv2) >> 8; /* (d / sigma)^2, Q16 */
        const uint32_t k = t2 >> 10, fr = t2 & 1023u;
        if (k >= 256u) {
            continue;
        }
        const uint32_t ga = tdc_fov_gauss_tab[k], gb = tdc_fov_gauss_tab[k + 1u];
        wt[nt] = ga - tdc_urshr32((ga - gb) * fr, 10);
        col[nt] = tdc_clamp32(t, cmin, cmax);
        sum += wt[nt];
        nt++;
    }
    /* sum >= G(1) 2^15 = 17859 (some tap has |d| <= 1/2 <= sigma): recip < 2^16, wt * recip < 2^31.
     * The rounding remainder goes to the largest weight, so the weights sum to 2^15 exactly. */
    const uint32_t recip = ((1u << 30) + sum / 2u) / sum;
    uint32_t nsum = 0;
    int32_t kmax = 0;
    for (int32_t k = 0; k < nt; k++) {
        kmax = wt[k] > wt[kmax] ? k : kmax;
        wt[k] = tdc_urshr32(wt[k] * recip, 15);
        nsum += wt[k];
    }
    wt[kmax] += 32768u - nsum;                 /* |32768 - nsum| <= nt / 2 + 1, wt[kmax] >= 2^15 / nt */
    s->off0[i] = s->off_dummy | TDC_FOV_STEP0; /* the kernel's value is not used */
    s->off1[i] = s->off_dummy;
    s->wf[i] = 32768u;
    /* the kernel's arithmetic per tap: rows j0, j1 weighted (w - a, a), a = (w fv + 2^14) >> 15 */
    const uint8_t *r0 = s->lp + (size_t)j0 * s->lp_stride, *r1 = s->lp + (size_t)j1 * s->lp_stride;
    uint32_t acc[3] = {64u, 64u, 64u};
    for (int32_t k = 0; k < nt; k++) {
        const uint32_t wa = tdc_urshr32(wt[k] * fv, 15), wb = wt[k] - wa;
        const uint8_t *p0 = r0 + (size_t)col[k] * 3u, *p1 = r1 + (size_t)col[k] * 3u;
        for (int ch = 0; ch < 3; ch++) {
            acc[ch] += wb * p0[ch] + wa * p1[ch]; /* weights sum to 2^15: < 255 * 2^15 + 64 */
        }
    }
    for (int ch = 0; ch < 3; ch++) {
        s->gen[(size_t)i * 3u + (size_t)ch] = (uint16_t)(acc[ch] >> 7); /* Q8 */
    }
    s->b[i] = (uint16_t)(b | TDC_FOV_GEN_FLAG);
}

/* The geometry pass over pixels [x0, x1) of one row (the C kernel of
 * tdc_fov_geom_row_fn).  The arguments and the geometry are copied to
 * locals first: the descriptor stores cannot alias them, so the compiler
 * keeps them in registers instead of reloading them after every store. */
void tdc_fov_geom_row_c(const tdc_fov_geom_args_t *a, int32_t x0, int32_t x1)
{
    const tdc_fov_geom_t g = *a->g;
    fov_src_t s = *a;
    s.g = &g;
    for (int32_t x = x0; x < x1; x++) {
        const int32_t dx = x * 256 + 128 - g.cx_q8;
        geom_px(&s, x, dx, (uint64_t)((int64_t)dx * dx) + s.dy2);
    }
}

/* The C tap kernel (tdc_fov_kernels.h). */
void tdc_fov_tap2_row_c(const tdc_fov_tap2_args_t *a, uint32_t n)
{
    const tdc_fov_tap2_args_t l = *a; /* locals: the stores below cannot move the pointers */
    for (uint32_t k = 0; k < n; k++) {
        tdc_fov_tap2_px(&l, k);
    }
}

tdc_status_t tdc_fov_lr_attach(tdc_fov_t *st, tdc_fov_lr_t *lr)
{
    if (!st) {
        return TDC_ERR_ARG;
    }
    if (lr && lr->width < st->cfg.width) {
        return TDC_ERR_SIZE;
    }
    st->lr = lr;
    return TDC_OK;
}
