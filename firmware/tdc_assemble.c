/*
 * tdc_assemble.c - tile-ordered frame assembly (docs/design.md §4.3); see
 * tdc_assemble.h for the algorithm and formats.
 */
#include "tdc_assemble.h"

#include <stddef.h>
#include <string.h>

#include "tdc_math.h"

/* The clamp is inlined into the span loops on x86-64 hosts (measured: pan
 * and lines ~5-9 % faster); on Cortex-M the call is kept (inlining it cost
 * instructions per pixel on the M7, docs/tile-assembly.md).  Same code and
 * results either way. */
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define TDC_ASM_HOT_INLINE __attribute__((always_inline)) inline
#else
#define TDC_ASM_HOT_INLINE inline
#endif
/* Forced inlining where a body is instantiated twice on purpose (GNU C
 * compilers: gcc, clang, arm-none-eabi-gcc; plain inline elsewhere). */
#if defined(__GNUC__) || defined(__clang__)
#define TDC_ASM_ALWAYS_INLINE __attribute__((always_inline)) inline
#else
#define TDC_ASM_ALWAYS_INLINE inline
#endif

static int tdc_asm_cfg_ok(const tdc_asm_config_t *cfg)
{
    return cfg && cfg->width >= 1 && cfg->height >= 1 && cfg->width <= TDC_ASM_MAX_DIM &&
           cfg->height <= TDC_ASM_MAX_DIM;
}

/* The one layout (tdc_assemble.h TDC_ASM_ARENA); NULL views in a dry run. */
static void tdc_asm_carve(tdc_asm_t *st, const tdc_asm_config_t *cfg, tdc_arena_t *arena){
    TDC_ASM_ARENA(TDC_ARENA_CARVE, cfg->width, cfg->height,
                  (size_t)TDC_TILES((uint32_t)cfg->width) * TDC_TILES((uint32_t)cfg->height),
                  TDC_PATTERN_BYTES(cfg->width, cfg->height))}

size_t tdc_asm_get_size(const tdc_asm_config_t *cfg)
{
    if (!tdc_asm_cfg_ok(cfg)) return 0;
    tdc_asm_t dry;
    tdc_arena_t arena;
    tdc_arena_dry(&arena);
    tdc_asm_carve(&dry, cfg, &arena);
    return tdc_arena_size(&arena);
}

tdc_status_t tdc_asm_init(tdc_asm_t *st, const tdc_asm_config_t *cfg, void *arena, size_t n)
{
    tdc_arena_t a;
    if (!st || !tdc_asm_cfg_ok(cfg) || !tdc_arena_over(&a, arena, n)) return TDC_ERR_ARG;
    const size_t need = tdc_asm_get_size(cfg); /* the same carve, dry: nothing is touched on error */
    if (n < need) return TDC_ERR_SIZE;
    memset(st, 0, sizeof(*st));
    st->cfg = *cfg;
    st->tiles_x = TDC_TILES((uint32_t)cfg->width);
    st->tiles_y = TDC_TILES((uint32_t)cfg->height);
    tdc_asm_carve(st, cfg, &a);
    memset(arena, 0, need);
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

/* Ordering of tile row [ti0, ti0 + n) of `bits` if every tile has the
 * same one (0 hourglass, 1 bowtie), -1 if they differ (n >= 1). */
static int tdc_asm_bits_uniform(const uint8_t *bits, uint32_t ti0, uint32_t n)
{
    const unsigned first = (unsigned)tdc_ordering_get(bits, ti0);
    const uint8_t all = first ? 0xFFu : 0x00u;
    uint32_t i = ti0, end = ti0 + n;
    for (; i < end && (i & 7u); i++)
        if ((unsigned)tdc_ordering_get(bits, i) != first) return -1;
    for (; i + 8u <= end; i += 8u)
        if (bits[i >> 3] != all) return -1;
    for (; i < end; i++)
        if ((unsigned)tdc_ordering_get(bits, i) != first) return -1;
    return (int)first;
}

/* ------------------------------------------------------------------------
 * Ingest.
 * ---------------------------------------------------------------------- */
/* Tile row ty of a subframe whose tiles trace pixel position pos_h
 * (hourglass ordering) or pos_b (bowtie): when every tile of the row traces
 * the same position (subframes 0 and 3, or one ordering for the whole tile
 * row), its samples are one dense row of pixels: 1 with that position, its
 * pixel row y, column parity q and the tiles n that have the pixel; 0 when
 * that pixel row is past the frame (a partial tile row); -1 when the row
 * mixes orderings (then per tile).  The walk of ingest and of the static
 * frame. */
typedef struct {
    unsigned pos;
    int bowtie;
    uint32_t y, q, n;
} tdc_asm_tile_row_t;

static inline int tdc_asm_tile_row(const tdc_asm_t *st, uint32_t ty, unsigned pos_h, unsigned pos_b,
                                   tdc_asm_tile_row_t *r)
{
    const uint32_t tx_n = st->tiles_x;
    const int row_order = pos_h == pos_b ? 0 : tdc_asm_bits_uniform(st->pattern, ty * tx_n, tx_n);
    if (row_order < 0) return -1;
    r->bowtie = row_order;
    r->pos = row_order ? pos_b : pos_h;
    r->y = 2u * ty + (r->pos >> 1);
    r->q = r->pos & 1u;
    r->n = tx_n - (r->q && (st->cfg.width & 1u) ? 1u : 0u);
    return r->y < st->cfg.height;
}

void tdc_asm_start_at(tdc_asm_t *st, uint32_t frame)
{
    if (st) {
        st->next_frame = frame;
        st->have_subframe = 0;
    }
}

tdc_status_t tdc_asm_ingest(tdc_asm_t *st, uint32_t frame, const uint8_t *samples, const int16_t *mvs,
                            const uint8_t *pattern_bits)
{
    if (!st || !samples) return TDC_ERR_ARG;
    if (frame != st->next_frame || st->have_subframe) return TDC_ERR_FRAME;
    const uint32_t w = st->cfg.width, h = st->cfg.height, k = frame & 3u;
    const uint32_t slot = (frame >> 2) & 3u;
    if (pattern_bits) {
        /* Compare the stream's orderings with ours; on the first subframe
         * of a cycle adopt the stream's (the renderer traced with them). */
        uint32_t nt = st->tiles_x * st->tiles_y, diff = 0;
        for (uint32_t i = 0; i < nt; i++) diff += tdc_ordering_get(pattern_bits, i) != tdc_ordering_get(st->pattern, i);
        st->stats.pattern_checks += nt;
        st->stats.pattern_disagreements += diff;
        if (k == 0 && diff) memcpy(st->pattern, pattern_bits, (size_t)TDC_PATTERN_BYTES(w, h));
    }
    const unsigned pos_h = tdc_ordering_pixel(TDC_ORDER_HOURGLASS, k);
    const unsigned pos_b = tdc_ordering_pixel(TDC_ORDER_BOWTIE, k);
    const uint32_t tx_n = st->tiles_x;
    const size_t tiles = (size_t)tx_n * st->tiles_y;
    uint8_t *const plane_h = st->samples + (size_t)(slot * 4u + pos_h) * tiles * 3u;
    uint8_t *const plane_b = st->samples + (size_t)(slot * 4u + pos_b) * tiles * 3u;
    int32_t nz = 0; /* change of the count of non-zero motion entries */
    for (uint32_t ty = 0; ty < st->tiles_y; ty++) {
        const uint32_t ti0 = ty * tx_n;
        tdc_asm_tile_row_t r;
        const int dense = tdc_asm_tile_row(st, ty, pos_h, pos_b, &r);
        if (dense == 0) continue; /* partial tile row: no such pixels */
        if (dense > 0) {
            /* the row of samples: one dense copy into one plane */
            memcpy((r.bowtie ? plane_b : plane_h) + (size_t)ti0 * 3u, samples + (size_t)ti0 * 3u, (size_t)r.n * 3u);
            int16_t *m = st->mv + ((size_t)r.y * w + r.q) * 2u;
            for (uint32_t tx = 0; tx < r.n; tx++, m += 4) {
                uint32_t was = tdc_mv_word(m), is = 0;
                if (mvs) memcpy(&is, mvs + (size_t)(ti0 + tx) * 2u, sizeof(is));
                if (is != was) memcpy(m, &is, sizeof(is)); /* unchanged: keep the line clean */
                nz += (int32_t)(is != 0) - (int32_t)(was != 0);
            }
            continue;
        }
        for (uint32_t tx = 0; tx < tx_n; tx++) {
            const uint32_t ti = ti0 + tx;
            const int bowtie = tdc_ordering_get(st->pattern, ti) == TDC_ORDER_BOWTIE;
            const unsigned pos = bowtie ? pos_b : pos_h;
            uint32_t x = 2u * tx + (pos & 1u), y = 2u * ty + (pos >> 1);
            if (x >= w || y >= h) continue; /* partial tile: no such pixel */
            uint8_t *d = (bowtie ? plane_b : plane_h) + (size_t)ti * 3u;
            d[0] = samples[ti * 3u];
            d[1] = samples[ti * 3u + 1u];
            d[2] = samples[ti * 3u + 2u];
            int16_t *m = st->mv + ((size_t)y * w + x) * 2u;
            uint32_t was = tdc_mv_word(m), is = 0;
            if (mvs) memcpy(&is, mvs + (size_t)ti * 2u, sizeof(is));
            if (is != was) memcpy(m, &is, sizeof(is));
            nz += (int32_t)(is != 0) - (int32_t)(was != 0);
        }
    }
    st->mv_nonzero = (uint32_t)((int32_t)st->mv_nonzero + nz);
    st->have_subframe = 1;
    st->stats.subframes++;
    return TDC_OK;
}

tdc_status_t tdc_asm_set_motion(tdc_asm_t *st, uint32_t frame, const int16_t *mv)
{
    if (!st || !mv) return TDC_ERR_ARG;
    if (frame != st->next_frame) return TDC_ERR_FRAME;
    const size_t n = (size_t)st->cfg.width * st->cfg.height;
    uint32_t nz = 0;
    for (size_t i = 0; i < n; i++) {
        int16_t dx = mv[2u * i], dy = mv[2u * i + 1u];
        st->mv[2u * i] = dx;
        st->mv[2u * i + 1u] = dy;
        nz += (uint32_t)((dx | dy) != 0);
    }
    st->mv_nonzero = nz;
    return TDC_OK;
}

/* ------------------------------------------------------------------------
 * Helpers of assembly.
 * ---------------------------------------------------------------------- */

/* Sample storage: 16 planes of tiles RGB888, plane (slot * 4 + position);
 * a subframe is written densely into (at most two of) the planes of its slot,
 * and a pixel's 4 window samples are at the same offset of 4 planes.
 * Returns the start of row y's samples for pixels with x & 1 = q in `slot`:
 * pixel x is at + (x >> 1) * 3. */
static inline const uint8_t *tdc_asm_sample_row(const tdc_asm_t *st, uint32_t y, unsigned q, uint32_t slot)
{
    const size_t tiles = (size_t)st->tiles_x * st->tiles_y;
    unsigned pos = ((y & 1u) << 1) | q;
    return st->samples + ((size_t)(slot * 4u + pos) * tiles + (size_t)(y >> 1) * st->tiles_x) * 3u;
}

/* Mean of a partial window (mask != 0xF): the first frames after a reset.
 * Branch-free: each slot's sample times its mask bit (0 or 1). */
static void tdc_asm_window_mean_part(const uint8_t *s0, size_t stride, unsigned mask, uint8_t *out)
{
    static const uint8_t popcount4[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};
    const uint8_t *a = s0, *b1 = s0 + stride, *c = s0 + 2u * stride, *d = s0 + 3u * stride;
    const unsigned m0 = mask & 1u, m1 = (mask >> 1) & 1u, m2 = (mask >> 2) & 1u, m3 = (mask >> 3) & 1u;
    const unsigned n = popcount4[mask & 15u];
    out[0] = tdc_mean_u8(a[0] * m0 + b1[0] * m1 + c[0] * m2 + d[0] * m3, n);
    out[1] = tdc_mean_u8(a[1] * m0 + b1[1] * m1 + c[1] * m2 + d[1] * m3, n);
    out[2] = tdc_mean_u8(a[2] * m0 + b1[2] * m1 + c[2] * m2 + d[2] * m3, n);
}

/* s0: the pixel's sample in slot 0; slot i is at s0 + i * stride. */
static inline void tdc_asm_window_mean(const uint8_t *s0, size_t stride, unsigned mask, uint8_t *out)
{
    if (mask != 0xFu) {
        tdc_asm_window_mean_part(s0, stride, mask, out);
        return;
    }
    /* Full window (the steady state of a static pixel): plain mean of 4. */
    const uint8_t *a = s0, *b1 = s0 + stride, *c = s0 + 2u * stride, *d = s0 + 3u * stride;
    out[0] = (uint8_t)((a[0] + b1[0] + c[0] + d[0] + 2u) >> 2);
    out[1] = (uint8_t)((a[1] + b1[1] + c[1] + d[1] + 2u) >> 2);
    out[2] = (uint8_t)((a[2] + b1[2] + c[2] + d[2] + 2u) >> 2);
}

/* Summary of motion row y (tdc_mv_row_scan, tdc_ordering.h): lets a frame
 * skip the per-pixel 3x3 search where three consecutive rows hold one and
 * the same vector. */
static unsigned tdc_asm_row_scan(const tdc_asm_t *st, uint32_t y, uint32_t *value)
{
    return tdc_mv_row_scan(st->mv + (size_t)y * st->cfg.width * 2u, st->cfg.width, value);
}

/* Horizontal 3-maximum (longest MV, first on ties) of motion row y. */
static void tdc_asm_hmax_row(const tdc_asm_t *st, uint32_t y, tdc_asm_mvmax_t *out)
{
    const uint32_t w = st->cfg.width;
    const int16_t *mv = st->mv + (size_t)y * w * 2u;
    uint32_t l_prev = 0, l_cur, l_next;
    int32_t pdx = 0, pdy = 0, cdx = mv[0], cdy = mv[1];
    l_cur = (uint32_t)(cdx * cdx) + (uint32_t)(cdy * cdy);
    for (uint32_t x = 0; x < w; x++) {
        int32_t ndx = 0, ndy = 0;
        l_next = 0;
        if (x + 1u < w && tdc_mv_word(mv + 2u * x + 2u) != 0) { /* zero: l = 0, no multiply */
            ndx = mv[2u * x + 2u];
            ndy = mv[2u * x + 3u];
            l_next = (uint32_t)(ndx * ndx) + (uint32_t)(ndy * ndy);
        }
        /* Candidates in order left, centre, right; strict > keeps the first
         * (l_prev = 0 at x = 0). */
        uint32_t best = l_prev;
        int32_t bx = pdx, by = pdy;
        if (l_cur > best) best = l_cur, bx = cdx, by = cdy;
        if (l_next > best) best = l_next, bx = ndx, by = ndy;
        out[x].l2 = best;
        out[x].dx = (int16_t)bx;
        out[x].dy = (int16_t)by;
        l_prev = l_cur, pdx = cdx, pdy = cdy;
        l_cur = l_next, cdx = ndx, cdy = ndy;
    }
}

/* Newness of row y: out[x] = 1 if pixel (x, y) is in the newest subframe.
 * Returns 0 if no pixel of the row is new, TDC_ASM_NEW_EVEN / _ODD if the
 * new pixels are exactly the even / odd columns, TDC_ASM_NEW_MIXED else. */
#define TDC_ASM_NEW_EVEN 1
#define TDC_ASM_NEW_ODD 2
#define TDC_ASM_NEW_MIXED 3

static int tdc_asm_new_row(const tdc_asm_t *st, uint32_t y, unsigned pos_h, unsigned pos_b, int have_new, uint8_t *out)
{
    const uint32_t w = st->cfg.width;
    const unsigned py = (y & 1u) << 1;
    if (!have_new || ((pos_h & 2u) != py && (pos_b & 2u) != py)) {
        memset(out, 0, w);
        return 0;
    }
    const uint32_t ti0 = (y >> 1) * st->tiles_x;
    const int row_order = pos_h == pos_b ? 0 : tdc_asm_bits_uniform(st->pattern, ti0, st->tiles_x);
    if (row_order >= 0) {
        /* One position for every tile (subframes 0 and 3, or one ordering
         * for the tile row): new pixels in row parity pos >> 1, column
         * parity pos & 1. */
        const unsigned pos = row_order ? pos_b : pos_h;
        if ((pos & 2u) != py) {
            memset(out, 0, w);
            return 0;
        }
        const uint8_t q = (uint8_t)(pos & 1u);
        for (uint32_t x = 0; x < w; x++) out[x] = (uint8_t)((x & 1u) == q);
        return q ? TDC_ASM_NEW_ODD : TDC_ASM_NEW_EVEN;
    }
    int any = 0;
    for (uint32_t tx = 0; tx < st->tiles_x; tx++) {
        unsigned pos = tdc_ordering_get(st->pattern, ti0 + tx) == TDC_ORDER_BOWTIE ? pos_b : pos_h;
        uint32_t x = 2u * tx;
        out[x] = (uint8_t)(pos == py);
        any |= pos == py;
        if (x + 1u < w) {
            out[x + 1u] = (uint8_t)(pos == (py | 1u));
            any |= pos == (py | 1u);
        }
    }
    return any ? TDC_ASM_NEW_MIXED : 0;
}

/*
 * Box sums of row y for the clamp: per pixel the sums over x-1..x+1 of the
 * newest samples (0 where a pixel is not new) and their count, packed as
 * R | G << 16 | B << 32 | count << 48 (box[2x]), and of their squares as
 * R | G << 21 | B << 42 (box[2x+1]).  Summing rows y-1, y, y+1 gives an old
 * pixel's sums over its 8 neighbours in the newest subframe (the pixel
 * itself is not new), with no branch per neighbour.  Scaling: a final sum
 * <= 8 * 255 = 2040 < 2^16, a count <= 8, a sum of squares <= 8 * 255^2 =
 * 520200 < 2^21, so lanes never carry.
 */
#define TDC_ASM_BOX_ONE ((uint64_t)1 << 48) /* count lane of box[2x] */

static inline uint64_t tdc_asm_box_sum_lanes(const uint8_t *q)
{
    return (uint64_t)q[0] | (uint64_t)q[1] << 16 | (uint64_t)q[2] << 32 | TDC_ASM_BOX_ONE;
}

static inline uint64_t tdc_asm_box_sq_lanes(const uint8_t *q)
{
    return (uint64_t)(q[0] * q[0]) | (uint64_t)(q[1] * q[1]) << 21 | (uint64_t)(q[2] * q[2]) << 42;
}

static void tdc_asm_box_row(const tdc_asm_t *st, uint32_t y, uint32_t slot, const uint8_t *newrow, int kind,
                            uint64_t *box)
{
    const uint32_t w = st->cfg.width;
    if (kind == TDC_ASM_NEW_EVEN || kind == TDC_ASM_NEW_ODD) {
        /* New pixels exactly in column parity q: a new pixel's sums are its
         * own sample (its neighbours are old), an old pixel's are those of
         * its left and right neighbours.  Each sample is packed once. */
        const uint32_t q = kind == TDC_ASM_NEW_ODD ? 1u : 0u;
        const uint8_t *s = tdc_asm_sample_row(st, y, q, slot);
        uint64_t l1 = 0, l2 = 0; /* the last new pixel's lanes (0 before the first) */
        for (uint32_t x = 0; x < w; x++) {
            if ((x & 1u) != q) {
                box[2u * x] = l1; /* left neighbour; the right one is added next */
                box[2u * x + 1u] = l2;
                continue;
            }
            const uint8_t *p = s + (size_t)(x >> 1) * 3u;
            l1 = tdc_asm_box_sum_lanes(p);
            l2 = tdc_asm_box_sq_lanes(p);
            box[2u * x] = l1;
            box[2u * x + 1u] = l2;
            if (x > 0) {
                box[2u * x - 2u] += l1;
                box[2u * x - 1u] += l2;
            }
        }
        return;
    }
    const uint8_t *base[2] = {tdc_asm_sample_row(st, y, 0, slot), tdc_asm_sample_row(st, y, 1, slot)};
    uint64_t p1 = 0, p2 = 0, c1 = 0, c2 = 0;
    if (newrow[0]) {
        c1 = tdc_asm_box_sum_lanes(base[0]);
        c2 = tdc_asm_box_sq_lanes(base[0]);
    }
    for (uint32_t x = 0; x < w; x++) {
        uint64_t n1 = 0, n2 = 0;
        if (x + 1u < w && newrow[x + 1u]) {
            const uint8_t *q = base[(x + 1u) & 1u] + (size_t)((x + 1u) >> 1) * 3u;
            n1 = tdc_asm_box_sum_lanes(q);
            n2 = tdc_asm_box_sq_lanes(q);
        }
        box[2u * x] = p1 + c1 + n1;
        box[2u * x + 1u] = p2 + c2 + n2;
        p1 = c1, p2 = c2;
        c1 = n1, c2 = n2;
    }
}

/* Local counters of one dynamic frame (kept out of the stage struct in the
 * inner loops so byte stores do not force reloads). */
typedef struct {
    uint64_t reprojected, edge, boxes, changed, no_neighbour, new_dynamic, resets;
} tdc_asm_dyn_count_t;

/* RGB888 pixel -> R | G << 16 | B << 32. */
static inline uint64_t tdc_asm_lanes(const uint8_t *p)
{
    return (uint64_t)p[0] | (uint64_t)p[1] << 16 | (uint64_t)p[2] << 32;
}

/* Bilinear sample of frame `src` at (x + dx/16, y + dy/16), position
 * clamped to the frame; result in code Q8 per channel, packed in 16-bit
 * lanes R | G << 16 | B << 32 (weights Q4 x Q4 = Q8, sum 256: a lane's sum
 * <= 255 * 256 < 2^16, so lanes never carry into each other).  *clamped =
 * 1 if the position was clamped. */
static uint64_t tdc_asm_bilinear_q8(const tdc_asm_t *st, const uint8_t *src, uint32_t x, uint32_t y, int32_t dx,
                                    int32_t dy, uint64_t *clamped)
{
    const int32_t w = st->cfg.width, h = st->cfg.height;
    int32_t sx = (int32_t)x * 16 + dx, sy = (int32_t)y * 16 + dy;
    int c = 0;
    if (sx < 0) sx = 0, c = 1;
    if (sy < 0) sy = 0, c = 1;
    if (sx > (w - 1) * 16) sx = (w - 1) * 16, c = 1;
    if (sy > (h - 1) * 16) sy = (h - 1) * 16, c = 1;
    *clamped += (uint64_t)c;
    int32_t x0 = sx >> 4, y0 = sy >> 4, fx = sx & 15, fy = sy & 15; /* sx, sy >= 0 */
    int32_t x1 = x0 + (fx != 0), y1 = y0 + (fy != 0);
    const uint8_t *r0 = src + ((size_t)y0 * (size_t)w) * 3u, *r1 = src + ((size_t)y1 * (size_t)w) * 3u;
    uint64_t w00 = (uint64_t)((16 - fx) * (16 - fy)), w01 = (uint64_t)(fx * (16 - fy));
    uint64_t w10 = (uint64_t)((16 - fx) * fy), w11 = (uint64_t)(fx * fy);
    return w00 * tdc_asm_lanes(r0 + x0 * 3) + w01 * tdc_asm_lanes(r0 + x1 * 3) + w10 * tdc_asm_lanes(r1 + x0 * 3) +
           w11 * tdc_asm_lanes(r1 + x1 * 3);
}

/*
 * Clamp of one channel to the mean +- sigma box of n samples with sums S1,
 * S2 (code units); v in code Q8.  Scaling and overflow: d = n S2 - S1^2 =
 * n^2 var in [0, 64 * 255^2 / 4] < 2^20.  The box test is exact:
 * |n v - 256 S1| > 256 sqrt(d)  <=>  (n v - 256 S1)^2 > 65536 d (int64:
 * < 2^39 and < 2^36); tdc_asm_box_out() says whether it fails.  Only then
 * is the edge computed (tdc_asm_box_edge_u8): R = tdc_sqrt_q8(d) =
 * n sigma in Q8 (within 0.02 code), edge = (256 S1 -+ R) / n, floor, lower
 * edge >= 0, rounded half up to 8 bits.
 */
static inline int tdc_asm_box_out(int32_t v, int32_t n, int32_t s1, int32_t s2)
{
    /* n v <= 8 * 65280 and 256 S1 <= 256 * 2040: dev fits int32; only the
     * square needs 64 bits. */
    const uint32_t d = (uint32_t)(n * s2 - s1 * s1);
    const int32_t dev = n * v - 256 * s1;
    return (uint64_t)((int64_t)dev * dev) > ((uint64_t)d << 16);
}

static uint8_t tdc_asm_box_edge_u8(int32_t v, int32_t n, int32_t s1, int32_t s2)
{
    uint32_t d = (uint32_t)(n * s2 - s1 * s1);
    int32_t r = (int32_t)tdc_sqrt_q8(d);
    int32_t e;
    if (n * v < 256 * s1) { /* both < 2^20 */
        int32_t lo_num = s1 * 256 - r;
        e = lo_num > 0 ? (int32_t)tdc_div_small((uint32_t)lo_num, (uint32_t)n) : 0;
    } else {
        e = (int32_t)tdc_div_small((uint32_t)(s1 * 256 + r), (uint32_t)n);
    }
    return (uint8_t)((e + 128) >> 8);
}

/* One channel: v (code Q8) clamped to its box, as an 8-bit code. */
static inline uint8_t tdc_asm_clamp_box_u8(int32_t v, int32_t n, int32_t s1, int32_t s2, uint64_t *changed)
{
    if (!tdc_asm_box_out(v, n, s1, s2)) return (uint8_t)((v + 128) >> 8);
    (*changed)++;
    return tdc_asm_box_edge_u8(v, n, s1, s2);
}

/* Old dynamic pixel, after the bilinear sample v (16-bit lanes, code Q8):
 * clamp to the box of the newest neighbours and store.  bx[0 .. nbx-1]: the
 * box-sum rows among rows y-1, y, y+1 that exist and hold a new pixel
 * (none when no subframe arrived). */
static TDC_ASM_HOT_INLINE void tdc_asm_clamp_store(uint64_t v, uint32_t x, const uint64_t *const bx[3], int nbx,
                                                   tdc_asm_dyn_count_t *cnt, uint8_t *out)
{
    const int32_t v0 = (int32_t)(v & 0xFFFFu), v1 = (int32_t)((v >> 16) & 0xFFFFu), v2 = (int32_t)((v >> 32) & 0xFFFFu);
    cnt->reprojected++;
    /* Variance sampling over the immediate neighbours in the newest
     * subframe: S1 <= 8*255 (16-bit lanes, count in the top lane),
     * S2 <= 8*255^2 (21-bit lanes). */
    uint64_t l1 = 0, l2 = 0;
    for (int j = 0; j < nbx; j++) {
        l1 += bx[j][2u * x];
        l2 += bx[j][2u * x + 1u];
    }
    const int32_t n = (int32_t)(l1 >> 48);
    if (n == 0) {
        cnt->no_neighbour++;
        out[0] = (uint8_t)((v0 + 128) >> 8);
        out[1] = (uint8_t)((v1 + 128) >> 8);
        out[2] = (uint8_t)((v2 + 128) >> 8);
        return;
    }
    cnt->boxes++;
    const uint64_t m21 = (1u << 21) - 1u;
    const int32_t a1 = (int32_t)(l1 & 0xFFFFu), a2 = (int32_t)(l2 & m21);
    const int32_t b1 = (int32_t)((l1 >> 16) & 0xFFFFu), b2 = (int32_t)((l2 >> 21) & m21);
    const int32_t c1 = (int32_t)((l1 >> 32) & 0xFFFFu), c2 = (int32_t)((l2 >> 42) & m21);
    out[0] = tdc_asm_clamp_box_u8(v0, n, a1, a2, &cnt->changed);
    out[1] = tdc_asm_clamp_box_u8(v1, n, b1, b2, &cnt->changed);
    out[2] = tdc_asm_clamp_box_u8(v2, n, c1, c2, &cnt->changed);
}

/* Everything one row of a dynamic frame needs. */
typedef struct {
    uint32_t y;
    const uint8_t *prev;   /* previous output frame */
    const uint8_t *prow;   /* its row y */
    uint8_t *drow;         /* output row y */
    uint8_t *win;          /* window masks of row y */
    const uint8_t *newrow; /* newness of row y */
    int has_new;           /* tdc_asm_new_row's result for row y (0: no new pixel) */
    const uint8_t *rec[2]; /* slot-0 sample rows of row y for even / odd x */
    const uint64_t *bx[3]; /* box-sum rows among y-1, y, y+1 that hold a new pixel */
    int nbx;               /* ... how many */
} tdc_asm_row_t;

/* (dx, dy) of an MV maximum as one 32-bit word (memory order, so that
 * memcpy back to an int16_t pair gives dx, dy; 0 iff the vector is zero). */
static inline uint32_t tdc_asm_mvmax_word(const tdc_asm_mvmax_t *m)
{
    uint32_t v;
    memcpy(&v, (const uint8_t *)m + offsetof(tdc_asm_mvmax_t, dx), sizeof(v));
    return v;
}

/* Vertical 3-maximum of pixel x from the horizontal maxima of rows y-1, y,
 * y+1, in that order, first on ties (the longest MV of the 3x3
 * neighbourhood), as a word.  Selects instead of branches: the outcome
 * follows the content and would mispredict at every motion edge. */
static inline uint32_t tdc_asm_vmax_word(const tdc_asm_mvmax_t *t, const tdc_asm_mvmax_t *m, const tdc_asm_mvmax_t *b,
                                         uint32_t x)
{
    uint32_t l2 = t[x].l2, wd = tdc_asm_mvmax_word(&t[x]);
    const uint32_t lm = m[x].l2, wm = tdc_asm_mvmax_word(&m[x]);
    const uint32_t lb = b[x].l2, wb = tdc_asm_mvmax_word(&b[x]);
    const int cm = lm > l2;
    l2 = cm ? lm : l2;
    wd = cm ? wm : wd;
    return lb > l2 ? wb : wd;
}

/* Window reset of pixels [xs, xe) (all dynamic): one OR scan of the masks,
 * written (and counted) only when some mask is set (rare: the first dynamic
 * frames after a static spell), so clean lines stay clean. */
static void tdc_asm_window_reset(uint8_t *win, uint32_t xs, uint32_t xe, tdc_asm_dyn_count_t *cnt)
{
    uint64_t any = 0;
    uint32_t x = xs;
    for (; x + 8u <= xe; x += 8u) {
        uint64_t v8;
        memcpy(&v8, win + x, sizeof(v8));
        any |= v8;
    }
    for (; x < xe; x++) any |= win[x];
    if (!any) return;
    uint64_t resets = 0;
    for (x = xs; x < xe; x++) resets += win[x] != 0;
    memset(win + xs, 0, xe - xs);
    cnt->resets += resets;
}

/*
 * Span [xs, xe) of row y whose pixels all have the 3x3 maximum (dx, dy) != 0
 * (a whole row in a pan, a run of equal maxima in a general row): window
 * reset, then new pixels stored and old ones reprojected and clamped, as
 * defined in tdc_assemble.h.  The bilinear position p + (dx, dy) has the
 * same fractional weights and row pair for every pixel of the span, so the
 * pixels whose position stays inside the frame horizontally take a loop with
 * span-constant weights and no clamping tests; the others take the general
 * (clamping) bilinear.  Same integers as the per-pixel definition.
 */
static TDC_ASM_ALWAYS_INLINE void tdc_asm_dyn_span_body(const tdc_asm_t *st, const tdc_asm_row_t *r, uint32_t xs,
                                                        uint32_t xe, int32_t dx, int32_t dy, size_t slot_off,
                                                        tdc_asm_dyn_count_t *cnt)
{
    const uint32_t w = st->cfg.width;
    const int32_t h = st->cfg.height;
    tdc_asm_window_reset(r->win, xs, xe, cnt);

    /* Vertical position: the same for the whole row. */
    int32_t sy = (int32_t)r->y * 16 + dy;
    uint64_t yc = 0;
    if (sy < 0) sy = 0, yc = 1;
    if (sy > (h - 1) * 16) sy = (h - 1) * 16, yc = 1;
    const int32_t y0 = sy >> 4, fy = sy & 15, y1 = y0 + (fy != 0);
    const uint8_t *r0 = r->prev + (size_t)y0 * w * 3u, *r1 = r->prev + (size_t)y1 * w * 3u;
    /* Horizontal: 0 <= 16 x + dx <= 16 (w - 1) for x in [xa, xb). */
    const int32_t wi = (int32_t)w;
    int32_t xa = dx >= 0 ? 0 : (-dx + 15) / 16;
    int32_t xb = 16 * (wi - 1) - dx < 0 ? 0 : (16 * (wi - 1) - dx) / 16 + 1;
    if (xa < (int32_t)xs) xa = (int32_t)xs;
    if (xb > (int32_t)xe) xb = (int32_t)xe;
    if (xa > (int32_t)xe) xa = (int32_t)xe;
    if (xb < xa) xb = xa;
    const int32_t fx = (int32_t)((uint32_t)dx & 15u), step = fx != 0;
    const uint64_t w00 = (uint64_t)((16 - fx) * (16 - fy)), w01 = (uint64_t)(fx * (16 - fy));
    const uint64_t w10 = (uint64_t)((16 - fx) * fy), w11 = (uint64_t)(fx * fy);
    uint64_t new_dynamic = 0;
    if (!r->has_new && xa < xb) {
        /* No new pixel in the row: every pixel is old, and consecutive
         * pixels share a tap column.  Vertical blend per column once,
         * colv(c) = (16 - fy) L(r0, c) + fy L(r1, c) (lanes <= 16 * 255),
         * then v = (16 - fx) colv(x0) + fx colv(x1) (lanes <= 65280): the
         * same integer as the four-tap sum, regrouped. */
        const uint64_t wy0 = (uint64_t)(16 - fy), wy1 = (uint64_t)fy, wx0 = (uint64_t)(16 - fx), wx1 = (uint64_t)fx;
        int32_t c = (xa * 16 + dx) >> 4; /* x0 of pixel xa (>= 0) */
        uint64_t col0 = wy0 * tdc_asm_lanes(r0 + c * 3) + wy1 * tdc_asm_lanes(r1 + c * 3);
        for (int32_t x = xa; x < xb; x++, c++) {
            /* col0 = colv(x0).  step = 1: x1 = x0 + 1 is the next pixel's
             * x0 (one new column per pixel); step = 0: x1 = x0, wx1 = 0. */
            uint64_t col1 = col0;
            if (step) col1 = wy0 * tdc_asm_lanes(r0 + (c + 1) * 3) + wy1 * tdc_asm_lanes(r1 + (c + 1) * 3);
            tdc_asm_clamp_store(wx0 * col0 + wx1 * col1, (uint32_t)x, r->bx, r->nbx, cnt, r->drow + (size_t)x * 3u);
            if (step)
                col0 = col1;
            else if (x + 1 < xb)
                col0 = wy0 * tdc_asm_lanes(r0 + (c + 1) * 3) + wy1 * tdc_asm_lanes(r1 + (c + 1) * 3);
        }
        cnt->edge += yc * (uint64_t)(xb - xa);
        for (uint32_t x = xs; x < xe; x++) {
            if ((int32_t)x == xa) x = (uint32_t)xb;
            if (x >= xe) break;
            uint64_t v = tdc_asm_bilinear_q8(st, r->prev, x, r->y, dx, dy, &cnt->edge);
            tdc_asm_clamp_store(v, x, r->bx, r->nbx, cnt, r->drow + x * 3u);
        }
        return;
    }
    /* New pixels exactly in one column parity q (the common case): the
     * old ones and the new ones each with a stride of 2, no test per pixel;
     * otherwise one loop testing the newness. */
    const int regular = r->has_new == TDC_ASM_NEW_EVEN || r->has_new == TDC_ASM_NEW_ODD;
    const uint32_t q = r->has_new == TDC_ASM_NEW_ODD ? 1u : 0u;
    const uint32_t xq = xs + ((xs & 1u) != q), xo = xs + ((xs & 1u) == q); /* first new / old x */
    if (regular) {
        const uint8_t *s = r->rec[q] + slot_off + (size_t)(xq >> 1) * 3u;
        for (uint32_t x = xq; x < xe; x += 2u, s += 3) {
            uint8_t *o = r->drow + x * 3u;
            o[0] = s[0], o[1] = s[1], o[2] = s[2];
            new_dynamic++;
        }
    }
    for (uint32_t x = regular ? xo : xs; x < xe; x += regular ? 2u : 1u) {
        uint8_t *o = r->drow + x * 3u;
        if (!regular && r->newrow[x]) {
            const uint8_t *s = r->rec[x & 1u] + (size_t)(x >> 1) * 3u + slot_off;
            o[0] = s[0], o[1] = s[1], o[2] = s[2];
            new_dynamic++;
            continue;
        }
        uint64_t v;
        if ((int32_t)x >= xa && (int32_t)x < xb) {
            const int32_t x0 = ((int32_t)x * 16 + dx) >> 4, x1 = x0 + step; /* 16 x + dx >= 0 */
            v = w00 * tdc_asm_lanes(r0 + x0 * 3) + w01 * tdc_asm_lanes(r0 + x1 * 3) + w10 * tdc_asm_lanes(r1 + x0 * 3) +
                w11 * tdc_asm_lanes(r1 + x1 * 3);
            cnt->edge += yc;
        } else {
            v = tdc_asm_bilinear_q8(st, r->prev, x, r->y, dx, dy, &cnt->edge);
        }
        tdc_asm_clamp_store(v, x, r->bx, r->nbx, cnt, o);
    }
    cnt->new_dynamic += new_dynamic;
}

/* A span of a general row (a run of equal maxima). */
static void tdc_asm_dyn_span(const tdc_asm_t *st, const tdc_asm_row_t *r, uint32_t xs, uint32_t xe, int32_t dx,
                             int32_t dy, size_t slot_off, tdc_asm_dyn_count_t *cnt)
{
    tdc_asm_dyn_span_body(st, r, xs, xe, dx, dy, slot_off, cnt);
}

/* A whole uniform row (a pan): the same body with the span [0, w), its
 * bounds constant (a copy of its own, so the row loops keep the registers
 * they had before spans existed: fewer instructions per pixel on the M7). */
static void tdc_asm_uniform_row(const tdc_asm_t *st, const tdc_asm_row_t *r, int32_t dx, int32_t dy, size_t slot_off,
                                tdc_asm_dyn_count_t *cnt)
{
    tdc_asm_dyn_span_body(st, r, 0, st->cfg.width, dx, dy, slot_off, cnt);
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
    const uint32_t tx_n = st->tiles_x;
    const size_t tiles = (size_t)tx_n * st->tiles_y, stride = tiles * 12u;
    const uint8_t bit = (uint8_t)(1u << slot);
    for (uint32_t ty = 0; ty < st->tiles_y; ty++) {
        const uint32_t ti0 = ty * tx_n;
        tdc_asm_tile_row_t r;
        const int dense = tdc_asm_tile_row(st, ty, pos_h, pos_b, &r);
        if (dense == 0) continue;
        if (dense > 0) {
            const uint8_t *s0 = st->samples + ((size_t)r.pos * tiles + ti0) * 3u;
            uint8_t *win = st->window + (size_t)r.y * w + r.q, *o = img + ((size_t)r.y * w + r.q) * 3u;
            for (uint32_t tx = 0; tx < r.n; tx++, win += 2, o += 6, s0 += 3) {
                *win = (uint8_t)(*win | bit);
                tdc_asm_window_mean(s0, stride, *win, o);
            }
            averaged += r.n;
            continue;
        }
        for (uint32_t tx = 0; tx < tx_n; tx++) {
            uint32_t ti = ti0 + tx;
            unsigned pos = tdc_ordering_get(st->pattern, ti) == TDC_ORDER_BOWTIE ? pos_b : pos_h;
            uint32_t x = 2u * tx + (pos & 1u), y = 2u * ty + (pos >> 1);
            if (x >= w || y >= h) continue;
            size_t p = (size_t)y * w + x;
            st->window[p] = (uint8_t)(st->window[p] | bit);
            tdc_asm_window_mean(st->samples + ((size_t)pos * tiles + ti) * 3u, stride, st->window[p], img + p * 3u);
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
    tdc_asm_dyn_count_t cnt = {0, 0, 0, 0, 0, 0, 0};
    const size_t stride = (size_t)st->tiles_x * st->tiles_y * 12u; /* bytes between slots */
    const size_t slot_off = slot * stride;
    uint64_t averaged = 0, kept = 0, static_rows = 0;
    const size_t bw = (size_t)w * 2u;
    /* Ring slot s = r % 3 holds row r's summaries; hmax_of[s] = the row whose
     * horizontal maxima are in st->ring slot s (computed only when a row
     * needs the per-pixel search), UINT32_MAX = none. */
    unsigned rinfo[3] = {0, 0, 0};
    uint32_t rval[3] = {0, 0, 0}, hmax_of[3] = {UINT32_MAX, UINT32_MAX, UINT32_MAX};
    int has_new[3] = {0, 0, 0};

    for (uint32_t r = 0; r < 2u && r < h; r++) {
        rinfo[r] = tdc_asm_row_scan(st, r, &rval[r]);
        has_new[r] = tdc_asm_new_row(st, r, pos_h, pos_b, have_new, st->newring + (size_t)r * w);
        if (has_new[r])
            tdc_asm_box_row(st, r, slot, st->newring + (size_t)r * w, has_new[r], st->boxring + (size_t)r * bw);
    }
    for (uint32_t y = 0; y < h; y++) {
        if (y >= 1u && y + 1u < h) {
            const uint32_t s = (y + 1u) % 3u;
            rinfo[s] = tdc_asm_row_scan(st, y + 1u, &rval[s]);
            has_new[s] = tdc_asm_new_row(st, y + 1u, pos_h, pos_b, have_new, st->newring + (size_t)s * w);
            if (has_new[s])
                tdc_asm_box_row(st, y + 1u, slot, st->newring + (size_t)s * w, has_new[s],
                                st->boxring + (size_t)s * bw);
        }
        const int top = y > 0, bot = y + 1u < h;
        const uint32_t ri[3] = {(y + 2u) % 3u, y % 3u, (y + 1u) % 3u};
        const int in[3] = {top, 1, bot};
        tdc_asm_row_t row;
        row.y = y;
        row.prev = prev;
        row.prow = prev + (size_t)y * w * 3u;
        row.drow = dst + (size_t)y * w * 3u;
        row.win = st->window + (size_t)y * w;
        row.newrow = st->newring + (size_t)ri[1] * w;
        row.has_new = has_new[ri[1]];
        row.nbx = 0;
        row.bx[0] = row.bx[1] = row.bx[2] = NULL;
        /* slot-0 sample rows of row y for even / odd x; slot i at + i * stride */
        row.rec[0] = tdc_asm_sample_row(st, y, 0, 0);
        row.rec[1] = tdc_asm_sample_row(st, y, 1, 0);
        unsigned any = 0, uniform = TDC_MV_ROW_UNIFORM;
        for (int j = 0; j < 3; j++) {
            const int use = in[j] && has_new[ri[j]];
            if (use) row.bx[row.nbx++] = st->boxring + (size_t)ri[j] * bw;
            if (!in[j]) continue;
            any |= rinfo[ri[j]] & TDC_MV_ROW_ANY;
            uniform &= rinfo[ri[j]];
            if (rval[ri[j]] != rval[ri[1]]) uniform = 0;
        }
        uint8_t *win = row.win, *drow = row.drow;
        const uint8_t *nr1 = row.newrow, *prow = row.prow;
        if (!any) {
            /* Static row: copy, then average the new samples. */
            memcpy(drow, prow, (size_t)w * 3u);
            static_rows++;
            for (uint32_t x = 0; x < w; x++) {
                if (nr1[x]) {
                    win[x] = (uint8_t)(win[x] | (1u << slot));
                    tdc_asm_window_mean(row.rec[x & 1u] + (size_t)(x >> 1) * 3u, stride, win[x], drow + x * 3u);
                    averaged++;
                } else {
                    kept++;
                }
            }
            continue;
        }
        if (uniform) {
            /* Rows y-1..y+1 hold one non-zero vector everywhere. */
            const int16_t *m = st->mv + (size_t)y * w * 2u;
            tdc_asm_uniform_row(st, &row, m[0], m[1], slot_off, &cnt);
            continue;
        }
        /* General row: per-pixel 3x3 maximum from the horizontal maxima. */
        for (int j = 0; j < 3; j++) {
            const uint32_t r = y + (uint32_t)j - 1u;
            if (in[j] && hmax_of[ri[j]] != r) {
                tdc_asm_hmax_row(st, r, st->ring + (size_t)ri[j] * w);
                hmax_of[ri[j]] = r;
            }
        }
        /* Absent rows (frame edge) read the middle row again: a repeated
         * candidate never wins over itself (strict >), the same as none. */
        const tdc_asm_mvmax_t *rm = st->ring + (size_t)ri[1] * w;
        const tdc_asm_mvmax_t *rt = top ? st->ring + (size_t)ri[0] * w : rm;
        const tdc_asm_mvmax_t *rb = bot ? st->ring + (size_t)ri[2] * w : rm;
        /* Runs of pixels with one and the same maximum: a zero run takes the
         * static path, a non-zero one the span path (span-constant bilinear
         * weights), the same integers as pixel by pixel. */
        uint32_t xs = 0, run = tdc_asm_vmax_word(rt, rm, rb, 0); /* current run [xs, x) and its vector */
        for (uint32_t x = 1; x <= w; x++) {
            const uint32_t word = x < w ? tdc_asm_vmax_word(rt, rm, rb, x) : ~run; /* x = w ends the last run */
            if (word == run) continue;
            if (run != 0) {
                int16_t m[2];
                memcpy(m, &run, sizeof(m));
                tdc_asm_dyn_span(st, &row, xs, x, m[0], m[1], slot_off, &cnt);
            } else {
                for (uint32_t xx = xs; xx < x; xx++) {
                    if (nr1[xx]) {
                        win[xx] = (uint8_t)(win[xx] | (1u << slot));
                        tdc_asm_window_mean(row.rec[xx & 1u] + (size_t)(xx >> 1) * 3u, stride, win[xx], drow + xx * 3u);
                        averaged++;
                    } else {
                        uint8_t *o = drow + xx * 3u;
                        o[0] = prow[xx * 3u], o[1] = prow[xx * 3u + 1u], o[2] = prow[xx * 3u + 2u];
                        kept++;
                    }
                }
            }
            xs = x, run = word;
        }
    }
    st->cur ^= 1;
    st->stats.reprojected += cnt.reprojected;
    st->stats.reproject_edge += cnt.edge;
    st->stats.clamp_boxes += cnt.boxes;
    st->stats.clamp_changed += cnt.changed;
    st->stats.clamp_no_neighbour += cnt.no_neighbour;
    st->stats.new_dynamic += cnt.new_dynamic;
    st->stats.window_resets += cnt.resets;
    st->stats.static_averaged += averaged;
    st->stats.static_kept += kept;
    st->stats.static_rows += static_rows;
}

tdc_status_t tdc_asm_assemble(tdc_asm_t *st, uint32_t frame)
{
    if (!st) return TDC_ERR_ARG;
    if (frame != st->next_frame) return TDC_ERR_FRAME;
    if (!st->have_subframe) st->stats.subframes_missing++;
    if (st->mv_nonzero == 0)
        tdc_asm_static_frame(st, frame);
    else
        tdc_asm_dynamic_frame(st, frame);
    st->stats.frames++;
    if ((frame & 3u) == 3u) {
        /* Decide the orderings of the next cycle from the motion buffer. */
        size_t bm = (size_t)TDC_PATTERN_BYTES(st->cfg.width, st->cfg.height);
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
