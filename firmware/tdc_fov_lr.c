/*
 * tdc_fov_lr.c - log-rectilinear foveation: the separable warp and the
 * periphery sample of the stage (equations, Q formats and the scaling and
 * overflow note in tdc_fov_lr.h; double-precision reference
 * ref/ref_fov_lr.c).  The disk composite and the peripheral TAA are
 * tdc_fov.c's: tdc_fov_frame calls tdc_fov_lr_begin / _row / _sample in
 * place of the kernel log-polar sampling when the frame's transform says so.
 * Rounding: half up at every shift and division.
 */
#include "tdc_fov_lr.h"

#include "tdc_math.h"

#define Q24 (1 << 24)

/* the parameters compare bytewise (parsed headers): no padding */
_Static_assert(sizeof(tdc_fov_params_t) == 24u, "tdc_fov_params_t has padding");

int tdc_fov_lr_params_ok(const tdc_fov_params_t *p)
{
    return p->transform == TDC_FOV_LOG_RECT && p->alpha_q8 == 256u && p->lr_k_q4[0] >= TDC_FOV_LR_K_MIN_Q4 &&
           p->lr_k_q4[1] >= TDC_FOV_LR_K_MIN_Q4;
}

int32_t tdc_fov_lr_warp_q24(const tdc_fov_lr_axis_t *a, int32_t d_q8)
{
    const uint32_t ad = (uint32_t)tdc_abs32(d_q8);
    const int32_t s = tdc_log2_q24((uint64_t)a->k_q8 + ad) - a->lk_q24; /* >= 0: log2 is monotone */
    return d_q8 < 0 ? -s : s;
}

void tdc_fov_lr_axis(tdc_fov_lr_axis_t *a, int32_t c_q8, uint16_t k_q4, uint16_t N, uint16_t n)
{
    a->c_q8 = c_q8;
    a->k_q8 = (uint32_t)k_q4 * 16u;
    a->lk_q24 = tdc_log2_q24(a->k_q8);
    a->N = N;
    a->n = n;
    a->s0_q24 = tdc_fov_lr_warp_q24(a, -c_q8);
    const int32_t s1 = tdc_fov_lr_warp_q24(a, (int32_t)N * 256 - c_q8);
    /* s is strictly increasing and N >= 4 px apart: S >= log2(1 + 4 / 4096)
     * ~ 2^-10 in exact terms, ~ 23500 Q24 steps, far above the table error */
    a->S_q24 = (uint32_t)(s1 - a->s0_q24);
    if (a->S_q24 == 0u) { /* not reachable in range (see above); keeps the divisions defined */
        a->S_q24 = 1u;
    }
}

uint32_t tdc_fov_lr_fwd_q16(const tdc_fov_lr_axis_t *a, int32_t x_q8)
{
    const int32_t x = tdc_clamp32(x_q8, 0, (int32_t)a->N * 256);
    int32_t ds = tdc_fov_lr_warp_q24(a, x - a->c_q8) - a->s0_q24;
    ds = tdc_clamp32(ds, 0, (int32_t)a->S_q24); /* the ends exactly: same table values */
    const uint64_t num = ((uint64_t)(uint32_t)ds * a->n << 16) + (a->S_q24 >> 1);
    return tdc_udiv64_32(num, a->S_q24);
}

/* The one layout (TDC_FOV_LR_ARENA); NULL views in a dry run. */
static void lr_carve(tdc_fov_lr_t *st, uint16_t width, tdc_arena_t *arena)
{
    TDC_FOV_LR_ARENA(TDC_ARENA_CARVE, width)
}

size_t tdc_fov_lr_get_size(uint16_t width)
{
    if (width < TDC_FOV_MIN_SIZE || width > TDC_FOV_MAX_SIZE) {
        return 0;
    }
    tdc_fov_lr_t dry;
    tdc_arena_t arena;
    tdc_arena_dry(&arena);
    lr_carve(&dry, width, &arena);
    return tdc_arena_size(&arena);
}

tdc_status_t tdc_fov_lr_init(tdc_fov_lr_t *lr, uint16_t width, void *mem, size_t mem_bytes)
{
    tdc_arena_t arena;
    const size_t need = tdc_fov_lr_get_size(width);
    if (!lr || !need || !tdc_arena_over(&arena, mem, mem_bytes)) {
        return TDC_ERR_ARG;
    }
    if (mem_bytes < need) { /* the same carve, dry: nothing touched on error */
        return TDC_ERR_SIZE;
    }
    lr_carve(lr, width, &arena);
    lr->width = width;
    lr->jv = 0;
    lr->lp = 0;
    lr->lp_stride = 0;
    lr->frames = 0;
    return TDC_OK;
}

/* u - 1/2 (the texel centres) clamped to [0, n - 1], Q16 */
static uint32_t texel_pos(const tdc_fov_lr_axis_t *a, int32_t i)
{
    const int32_t u = (int32_t)tdc_fov_lr_fwd_q16(a, i * 256 + 128) - 32768;
    return (uint32_t)tdc_clamp32(u, 0, ((int32_t)a->n - 1) * 65536);
}

tdc_status_t tdc_fov_lr_begin(tdc_fov_lr_t *lr, const tdc_fov_geom_t *g, const tdc_fov_params_t *p,
                              const uint8_t *lp, size_t lp_stride)
{
    if (!tdc_fov_lr_params_ok(p)) {
        return TDC_ERR_ARG;
    }
    if (g->width > lr->width) {
        return TDC_ERR_SIZE;
    }
    tdc_fov_lr_axis(&lr->ax, g->cx_q8, p->lr_k_q4[0], g->width, g->lp_w);
    tdc_fov_lr_axis(&lr->ay, g->cy_q8, p->lr_k_q4[1], g->height, g->lp_h);
    for (int32_t i = 0; i < (int32_t)g->width; i++) {
        lr->col[i] = texel_pos(&lr->ax, i);
    }
    lr->lp = lp;
    lr->lp_stride = lp_stride;
    lr->frames++;
    return TDC_OK;
}

/* Nearest texel of a clamped position: round(u - 1/2) = floor(u). */
static uint32_t nearest(uint32_t t_q16, uint16_t n)
{
    const uint32_t m = (t_q16 + 32768u) >> 16;
    return m < n ? m : n - 1u;
}

void tdc_fov_lr_row(tdc_fov_lr_t *lr, int32_t y)
{
    const uint32_t t = texel_pos(&lr->ay, y);
    const uint32_t j0 = t >> 16, fv = t & 0xFFFFu;
    const uint32_t j1 = j0 + 1u < lr->ay.n ? j0 + 1u : j0;
    const uint8_t *r0 = lr->lp + (size_t)j0 * lr->lp_stride, *r1 = lr->lp + (size_t)j1 * lr->lp_stride;
    const size_t n3 = (size_t)lr->ax.n * 3u;
    for (size_t k = 0; k < n3; k++) { /* Q16 codes < 2^24, half up to Q8 */
        lr->row[k] = (uint16_t)((r0[k] * (65536u - fv) + r1[k] * fv + 128u) >> 8);
    }
    lr->jv = nearest(t, lr->ay.n);
}

void tdc_fov_lr_sample(const tdc_fov_lr_t *lr, int32_t x, uint32_t c[3], uint32_t *iu, uint32_t *jv)
{
    const uint32_t t = lr->col[x];
    const uint32_t m0 = t >> 16, fu = t & 0xFFFFu;
    const uint32_t m1 = m0 + 1u < lr->ax.n ? m0 + 1u : m0;
    const uint16_t *a = lr->row + (size_t)m0 * 3u, *b = lr->row + (size_t)m1 * 3u;
    for (int ch = 0; ch < 3; ch++) {
        c[ch] = (a[ch] * (65536u - fu) + b[ch] * fu + 32768u) >> 16;
    }
    *iu = nearest(t, lr->ax.n);
    *jv = lr->jv;
}
