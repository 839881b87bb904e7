/*
 * tdc_assemble.c - tile-ordered frame assembly (DESIGN §4.3); see
 * tdc_assemble.h for the algorithm and formats.
 */
#include "tdc_assemble.h"

#include <string.h>

#include "tdc_math.h"

#define TDC_ASM_ALIGN(n) (((n) + 7u) & ~(size_t)7u)

static int tdc_asm_cfg_ok(const tdc_asm_config_t *cfg)
{
    return cfg && cfg->width >= 1 && cfg->height >= 1 && cfg->width <= TDC_ASM_MAX_DIM &&
           cfg->height <= TDC_ASM_MAX_DIM;
}

size_t tdc_asm_get_size(const tdc_asm_config_t *cfg)
{
    if (!tdc_asm_cfg_ok(cfg)) return 0;
    size_t px = (size_t)cfg->width * cfg->height;
    size_t bm = (size_t)TDC_ORDERING_BITMAP_BYTES(cfg->width, cfg->height);
    return TDC_ASM_ALIGN(px * 3u) * 2u + TDC_ASM_ALIGN(px * 12u) + TDC_ASM_ALIGN(px) + TDC_ASM_ALIGN(px * 4u) +
           TDC_ASM_ALIGN((size_t)cfg->width * 3u * sizeof(tdc_asm_mvmax_t)) + TDC_ASM_ALIGN(bm) * 2u;
}

tdc_status_t tdc_asm_init(tdc_asm_t *st, const tdc_asm_config_t *cfg, void *arena, size_t n)
{
    if (!st || !arena || !tdc_asm_cfg_ok(cfg)) return TDC_ERR_ARG;
    if (((uintptr_t)arena & 7u) != 0) return TDC_ERR_ARG;
    if (n < tdc_asm_get_size(cfg)) return TDC_ERR_SIZE;
    memset(st, 0, sizeof(*st));
    st->cfg = *cfg;
    st->tiles_x = TDC_ORDERING_TILES_X((uint32_t)cfg->width);
    st->tiles_y = TDC_ORDERING_TILES_Y((uint32_t)cfg->height);
    size_t px = (size_t)cfg->width * cfg->height;
    size_t bm = (size_t)TDC_ORDERING_BITMAP_BYTES(cfg->width, cfg->height);
    uint8_t *p = (uint8_t *)arena;
    st->frame[0] = p, p += TDC_ASM_ALIGN(px * 3u);
    st->frame[1] = p, p += TDC_ASM_ALIGN(px * 3u);
    st->samples = p, p += TDC_ASM_ALIGN(px * 12u);
    st->window = p, p += TDC_ASM_ALIGN(px);
    st->mv = (int16_t *)(void *)p, p += TDC_ASM_ALIGN(px * 4u);
    st->ring = (tdc_asm_mvmax_t *)(void *)p, p += TDC_ASM_ALIGN((size_t)cfg->width * 3u * sizeof(tdc_asm_mvmax_t));
    st->pattern = p, p += TDC_ASM_ALIGN(bm);
    st->pattern_next = p;
    memset(arena, 0, tdc_asm_get_size(cfg));
    return TDC_OK;
}

const uint8_t *tdc_asm_output(const tdc_asm_t *st, int *stride_bytes)
{
    if (!st) return NULL;
    if (stride_bytes) *stride_bytes = (int)st->cfg.width * 3;
    return st->frame[st->cur];
}

const uint8_t *tdc_asm_pattern(const tdc_asm_t *st)
{
    return st ? st->pattern : NULL;
}

/* ------------------------------------------------------------------------
 * Ingest.
 * ---------------------------------------------------------------------- */
tdc_status_t tdc_asm_ingest(tdc_asm_t *st, uint32_t frame, const uint8_t *samples, const int16_t *mvs,
                            const uint8_t *pattern_bits)
{
    if (!st || !samples) return TDC_ERR_ARG;
    if (frame != st->next_frame || st->have_subframe) return (tdc_status_t)TDC_ASM_ERR_FRAME;
    const uint32_t w = st->cfg.width, h = st->cfg.height, k = frame & 3u;
    const uint32_t slot = (frame >> 2) & 3u;
    if (pattern_bits) {
        /* Compare the stream's orderings with ours; on the first subframe
         * of a cycle adopt the stream's (the renderer traced with them). */
        uint32_t nt = st->tiles_x * st->tiles_y, diff = 0;
        for (uint32_t i = 0; i < nt; i++) diff += tdc_ordering_get(pattern_bits, i) != tdc_ordering_get(st->pattern, i);
        st->stats.pattern_checks += nt;
        st->stats.pattern_disagreements += diff;
        if (k == 0 && diff) memcpy(st->pattern, pattern_bits, (size_t)TDC_ORDERING_BITMAP_BYTES(w, h));
    }
    const unsigned pos_h = tdc_ordering_pixel(TDC_ORDER_HOURGLASS, k);
    const unsigned pos_b = tdc_ordering_pixel(TDC_ORDER_BOWTIE, k);
    for (uint32_t ty = 0; ty < st->tiles_y; ty++) {
        for (uint32_t tx = 0; tx < st->tiles_x; tx++) {
            uint32_t ti = ty * st->tiles_x + tx;
            unsigned pos = tdc_ordering_get(st->pattern, ti) == TDC_ORDER_BOWTIE ? pos_b : pos_h;
            uint32_t x = 2u * tx + (pos & 1u), y = 2u * ty + (pos >> 1);
            if (x >= w || y >= h) continue; /* partial tile: no such pixel */
            size_t p = (size_t)y * w + x;
            uint8_t *s = st->samples + p * 12u + slot * 3u;
            s[0] = samples[ti * 3u];
            s[1] = samples[ti * 3u + 1u];
            s[2] = samples[ti * 3u + 2u];
            int16_t dx = mvs ? mvs[ti * 2u] : 0, dy = mvs ? mvs[ti * 2u + 1u] : 0;
            int was = (st->mv[p * 2u] | st->mv[p * 2u + 1u]) != 0, is = (dx | dy) != 0;
            st->mv_nonzero = st->mv_nonzero + (uint32_t)is - (uint32_t)was;
            st->mv[p * 2u] = dx;
            st->mv[p * 2u + 1u] = dy;
        }
    }
    st->have_subframe = 1;
    st->stats.subframes++;
    return TDC_OK;
}

/* ------------------------------------------------------------------------
 * Helpers of assembly.
 * ---------------------------------------------------------------------- */

/* Mean of the samples in the window mask (1..4 slots), rounded half up.
 * Scaling and overflow: sum <= 4 * 255; round(sum / n) =
 * floor((2 sum + n) / (2 n)) = ((2 sum + n) * ceil(2^16 / 2n)) >> 16, exact
 * for sum <= 1020 (tests/test_assemble.c checks all sums and n). */
static const uint16_t tdc_asm_half_recip_q16[5] = {0, 32768, 16384, 10923, 8192};

uint8_t tdc_asm_mean_u8(uint32_t sum, unsigned n)
{
    if (n < 1u || n > 4u) return 0;
    return (uint8_t)(((2u * sum + n) * tdc_asm_half_recip_q16[n]) >> 16);
}

static void tdc_asm_window_mean(const uint8_t *s12, unsigned mask, uint8_t *out)
{
    unsigned n = 0, r = 0, g = 0, b = 0;
    for (unsigned i = 0; i < 4; i++) {
        if (mask & (1u << i)) {
            n++;
            r += s12[i * 3u];
            g += s12[i * 3u + 1u];
            b += s12[i * 3u + 2u];
        }
    }
    out[0] = tdc_asm_mean_u8(r, n);
    out[1] = tdc_asm_mean_u8(g, n);
    out[2] = tdc_asm_mean_u8(b, n);
}

/* floor(sqrt(x)) for 32-bit x, digit by digit (16 steps), exact. */
static uint32_t tdc_isqrt32(uint32_t x)
{
    uint32_t r = 0, bit = 1u << 30;
    while (bit > x) bit >>= 2;
    while (bit) {
        if (x >= r + bit) {
            x -= r + bit;
            r = (r >> 1) + bit;
        } else {
            r >>= 1;
        }
        bit >>= 2;
    }
    return r;
}

/* Horizontal 3-maximum (longest MV, first on ties) of motion row y. */
static int tdc_asm_hmax_row(const tdc_asm_t *st, uint32_t y, tdc_asm_mvmax_t *out)
{
    const uint32_t w = st->cfg.width;
    const int16_t *mv = st->mv + (size_t)y * w * 2u;
    uint32_t any = 0;
    uint32_t l_prev = 0, l_cur, l_next;
    int32_t cdx = mv[0], cdy = mv[1];
    l_cur = (uint32_t)(cdx * cdx) + (uint32_t)(cdy * cdy);
    for (uint32_t x = 0; x < w; x++) {
        int32_t ndx = 0, ndy = 0;
        l_next = 0;
        if (x + 1u < w) {
            ndx = mv[2u * x + 2u];
            ndy = mv[2u * x + 3u];
            l_next = (uint32_t)(ndx * ndx) + (uint32_t)(ndy * ndy);
        }
        /* Candidates in order left, centre, right; strict > keeps the first. */
        uint32_t best = 0;
        int32_t bx = 0, by = 0;
        if (x > 0 && l_prev > best) best = l_prev, bx = mv[2u * x - 2u], by = mv[2u * x - 1u];
        if (l_cur > best) best = l_cur, bx = cdx, by = cdy;
        if (l_next > best) best = l_next, bx = ndx, by = ndy;
        out[x].l2 = best;
        out[x].dx = (int16_t)bx;
        out[x].dy = (int16_t)by;
        any |= best;
        l_prev = l_cur;
        l_cur = l_next;
        cdx = ndx;
        cdy = ndy;
    }
    return any != 0;
}

/* Is pixel (x, y) traced by the current subframe? */
static inline int tdc_asm_is_new(const tdc_asm_t *st, uint32_t x, uint32_t y, unsigned pos_h, unsigned pos_b)
{
    uint32_t ti = (y >> 1) * st->tiles_x + (x >> 1);
    unsigned pos = ((y & 1u) << 1) | (x & 1u);
    return pos == (tdc_ordering_get(st->pattern, ti) == TDC_ORDER_BOWTIE ? pos_b : pos_h);
}

/* Bilinear sample of frame `src` at (x + dx/16, y + dy/16), position
 * clamped to the frame; result in code Q8 per channel (weights Q4 x Q4 =
 * Q8, sum 256: max 255 * 256, exact).  Returns 1 if the position was
 * clamped. */
static int tdc_asm_bilinear_q8(const tdc_asm_t *st, const uint8_t *src, uint32_t x, uint32_t y, int32_t dx,
                               int32_t dy, int32_t out_q8[3])
{
    const int32_t w = st->cfg.width, h = st->cfg.height;
    int32_t sx = (int32_t)x * 16 + dx, sy = (int32_t)y * 16 + dy;
    int clamped = 0;
    if (sx < 0) sx = 0, clamped = 1;
    if (sy < 0) sy = 0, clamped = 1;
    if (sx > (w - 1) * 16) sx = (w - 1) * 16, clamped = 1;
    if (sy > (h - 1) * 16) sy = (h - 1) * 16, clamped = 1;
    int32_t x0 = sx >> 4, y0 = sy >> 4, fx = sx & 15, fy = sy & 15; /* sx, sy >= 0 */
    int32_t x1 = x0 + (fx != 0), y1 = y0 + (fy != 0);
    const uint8_t *r0 = src + ((size_t)y0 * (size_t)w) * 3u, *r1 = src + ((size_t)y1 * (size_t)w) * 3u;
    int32_t w00 = (16 - fx) * (16 - fy), w01 = fx * (16 - fy), w10 = (16 - fx) * fy, w11 = fx * fy;
    for (int c = 0; c < 3; c++)
        out_q8[c] = w00 * r0[x0 * 3 + c] + w01 * r0[x1 * 3 + c] + w10 * r1[x0 * 3 + c] + w11 * r1[x1 * 3 + c];
    return clamped;
}

/* Old dynamic pixel: reproject and clamp to the newest neighbours' box. */
static void tdc_asm_reproject_pixel(tdc_asm_t *st, const uint8_t *prev, uint32_t x, uint32_t y, int32_t dx,
                                    int32_t dy, unsigned slot, unsigned pos_h, unsigned pos_b, int have_new,
                                    uint8_t *out)
{
    const uint32_t w = st->cfg.width, h = st->cfg.height;
    int32_t v[3];
    st->stats.reproject_edge += (uint64_t)tdc_asm_bilinear_q8(st, prev, x, y, dx, dy, v);
    st->stats.reprojected++;

    /* Variance sampling over the immediate neighbours in the newest
     * subframe.  S1 <= 8*255, S2 <= 8*255^2: int32. */
    int32_t n = 0, s1[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
    if (have_new) {
        for (int oy = -1; oy <= 1; oy++) {
            int32_t ny = (int32_t)y + oy;
            if (ny < 0 || ny >= (int32_t)h) continue;
            for (int ox = -1; ox <= 1; ox++) {
                int32_t nx = (int32_t)x + ox;
                if ((ox | oy) == 0 || nx < 0 || nx >= (int32_t)w) continue;
                if (!tdc_asm_is_new(st, (uint32_t)nx, (uint32_t)ny, pos_h, pos_b)) continue;
                const uint8_t *s = st->samples + ((size_t)ny * w + (size_t)nx) * 12u + slot * 3u;
                for (int c = 0; c < 3; c++) {
                    s1[c] += s[c];
                    s2[c] += (int32_t)s[c] * s[c];
                }
                n++;
            }
        }
    }
    if (n == 0) {
        st->stats.clamp_no_neighbour++;
        for (int c = 0; c < 3; c++) out[c] = (uint8_t)((v[c] + 128) >> 8);
        return;
    }
    st->stats.clamp_boxes++;
    for (int c = 0; c < 3; c++) {
        /* n^2 var = n S2 - S1^2 in [0, 64 * 255^2 / 4] < 2^20; << 12 < 2^32.
         * r = n sigma in Q6 (floor); the box [S1*256 -+ 4r] / n in Q8. */
        uint32_t d = (uint32_t)(n * s2[c] - s1[c] * s1[c]);
        uint32_t r4 = tdc_isqrt32(d << 12) * 4u;
        int32_t lo_num = s1[c] * 256 - (int32_t)r4;
        int32_t lo = lo_num > 0 ? lo_num / n : 0;
        int32_t hi = (s1[c] * 256 + (int32_t)r4) / n;
        int32_t val = v[c];
        if (val < lo) val = lo, st->stats.clamp_changed++;
        else if (val > hi) val = hi, st->stats.clamp_changed++;
        out[c] = (uint8_t)((val + 128) >> 8);
    }
}

/* Static pixel: new sample joins the window (mean), otherwise keep. */
static inline void tdc_asm_static_pixel(tdc_asm_t *st, size_t p, int is_new, unsigned slot, const uint8_t *prev,
                                        uint8_t *out)
{
    if (is_new) {
        st->window[p] = (uint8_t)(st->window[p] | (1u << slot));
        tdc_asm_window_mean(st->samples + p * 12u, st->window[p], out);
        st->stats.static_averaged++;
    } else if (out != prev) {
        out[0] = prev[0];
        out[1] = prev[1];
        out[2] = prev[2];
        st->stats.static_kept++;
    } else {
        st->stats.static_kept++;
    }
}

/* Static frame: only the new samples change; update in place. */
static void tdc_asm_static_frame(tdc_asm_t *st, uint32_t frame)
{
    const uint32_t w = st->cfg.width, h = st->cfg.height, k = frame & 3u, slot = (frame >> 2) & 3u;
    uint8_t *img = st->frame[st->cur];
    st->stats.static_frames++;
    if (!st->have_subframe) {
        st->stats.static_kept += (uint64_t)w * h;
        return;
    }
    const unsigned pos_h = tdc_ordering_pixel(TDC_ORDER_HOURGLASS, k);
    const unsigned pos_b = tdc_ordering_pixel(TDC_ORDER_BOWTIE, k);
    uint64_t averaged = 0;
    for (uint32_t ty = 0; ty < st->tiles_y; ty++) {
        for (uint32_t tx = 0; tx < st->tiles_x; tx++) {
            unsigned pos = tdc_ordering_get(st->pattern, ty * st->tiles_x + tx) == TDC_ORDER_BOWTIE ? pos_b : pos_h;
            uint32_t x = 2u * tx + (pos & 1u), y = 2u * ty + (pos >> 1);
            if (x >= w || y >= h) continue;
            size_t p = (size_t)y * w + x;
            st->window[p] = (uint8_t)(st->window[p] | (1u << slot));
            tdc_asm_window_mean(st->samples + p * 12u, st->window[p], img + p * 3u);
            averaged++;
        }
    }
    st->stats.static_averaged += averaged;
    st->stats.static_kept += (uint64_t)w * h - averaged;
}

/* Frame with motion somewhere: full pass into the other frame buffer. */
static void tdc_asm_dynamic_frame(tdc_asm_t *st, uint32_t frame)
{
    const uint32_t w = st->cfg.width, h = st->cfg.height, k = frame & 3u, slot = (frame >> 2) & 3u;
    const unsigned pos_h = tdc_ordering_pixel(TDC_ORDER_HOURGLASS, k);
    const unsigned pos_b = tdc_ordering_pixel(TDC_ORDER_BOWTIE, k);
    const int have_new = st->have_subframe;
    const uint8_t *prev = st->frame[st->cur];
    uint8_t *dst = st->frame[st->cur ^ 1];
    int row_any[3] = {0, 0, 0};

    row_any[0] = tdc_asm_hmax_row(st, 0, st->ring);
    for (uint32_t y = 0; y < h; y++) {
        if (y + 1u < h) row_any[(y + 1u) % 3u] = tdc_asm_hmax_row(st, y + 1u, st->ring + (size_t)((y + 1u) % 3u) * w);
        const int top = y > 0, bot = y + 1u < h;
        const tdc_asm_mvmax_t *rt = st->ring + (size_t)((y + 2u) % 3u) * w;
        const tdc_asm_mvmax_t *rm = st->ring + (size_t)(y % 3u) * w;
        const tdc_asm_mvmax_t *rb = st->ring + (size_t)((y + 1u) % 3u) * w;
        const uint8_t *prow = prev + (size_t)y * w * 3u;
        uint8_t *drow = dst + (size_t)y * w * 3u;
        int any = row_any[y % 3u] || (top && row_any[(y + 2u) % 3u]) || (bot && row_any[(y + 1u) % 3u]);
        if (!any) {
            /* Static row: copy, then average the new samples. */
            memcpy(drow, prow, (size_t)w * 3u);
            st->stats.static_rows++;
            for (uint32_t x = 0; x < w; x++) {
                size_t p = (size_t)y * w + x;
                int is_new = have_new && tdc_asm_is_new(st, x, y, pos_h, pos_b);
                tdc_asm_static_pixel(st, p, is_new, slot, drow + x * 3u, drow + x * 3u);
            }
            continue;
        }
        for (uint32_t x = 0; x < w; x++) {
            /* Vertical maximum in order top, middle, bottom (first on ties). */
            tdc_asm_mvmax_t m = {0, 0, 0};
            if (top && rt[x].l2 > m.l2) m = rt[x];
            if (rm[x].l2 > m.l2) m = rm[x];
            if (bot && rb[x].l2 > m.l2) m = rb[x];
            size_t p = (size_t)y * w + x;
            int is_new = have_new && tdc_asm_is_new(st, x, y, pos_h, pos_b);
            if (m.l2 == 0) {
                tdc_asm_static_pixel(st, p, is_new, slot, prow + x * 3u, drow + x * 3u);
                continue;
            }
            if (st->window[p]) {
                st->window[p] = 0;
                st->stats.window_resets++;
            }
            if (is_new) {
                const uint8_t *s = st->samples + p * 12u + slot * 3u;
                drow[x * 3u] = s[0];
                drow[x * 3u + 1u] = s[1];
                drow[x * 3u + 2u] = s[2];
                st->stats.new_dynamic++;
            } else {
                tdc_asm_reproject_pixel(st, prev, x, y, m.dx, m.dy, slot, pos_h, pos_b, have_new, drow + x * 3u);
            }
        }
    }
    st->cur ^= 1;
}

tdc_status_t tdc_asm_assemble(tdc_asm_t *st, uint32_t frame)
{
    if (!st) return TDC_ERR_ARG;
    if (frame != st->next_frame) return (tdc_status_t)TDC_ASM_ERR_FRAME;
    if (!st->have_subframe) st->stats.subframes_missing++;
    if (st->mv_nonzero == 0)
        tdc_asm_static_frame(st, frame);
    else
        tdc_asm_dynamic_frame(st, frame);
    st->stats.frames++;
    if ((frame & 3u) == 3u) {
        /* Decide the orderings of the next cycle from the motion buffer. */
        size_t bm = (size_t)TDC_ORDERING_BITMAP_BYTES(st->cfg.width, st->cfg.height);
        if (st->mv_nonzero != 0) {
            memcpy(st->pattern_next, st->pattern, bm);
            tdc_ordering_update(st->mv, st->cfg.width, st->cfg.height, st->pattern_next, frame + 1u);
            memcpy(st->pattern, st->pattern_next, bm);
        } /* all motion zero: every tile keeps its ordering, nothing to do */
    }
    st->have_subframe = 0;
    st->next_frame = frame + 1u;
    return TDC_OK;
}
