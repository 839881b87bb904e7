/*
 * tdc_assemble.h - tile-ordered frame assembly for 240 Hz streams
 * (docs/design.md §4.3, TDRT paper §3.2).
 *
 * Every refresh the renderer traces one pixel per 2x2 tile (a subframe):
 * subframe k = frame mod 4 holds, for each tile, the pixel at position
 * tdc_ordering_pixel(ordering of the tile, k).  The stage keeps full-res
 * buffers and builds a full RGB888 frame each refresh:
 *
 *   m(p) = longest motion vector of p's 3x3 pixel neighbourhood (clipped),
 *          taken from the motion buffer (each pixel: MV of its latest sample);
 *   static  (m = 0): output = mean of the pixel's last up to 4 samples
 *          (moving window, one sample per 4-frame cycle, slot = cycle mod 4 =
 *          the jitter index), round half up; pixels without a new sample keep
 *          their previous output;
 *   dynamic (m != 0): the window is reset (averaging drops at once);
 *          new sample (traced this frame) -> stored directly;
 *          old -> bilinear sample of the previous output frame at p + m
 *          (backward Q4 MV, position clamped to the frame edge), in code Q8,
 *          then clamped per channel to [mean - sigma, mean + sigma] of the
 *          pixel's 8 immediate neighbours that belong to the newest subframe
 *          (population sigma); no clamp when no neighbour is new (dropped
 *          subframe); rounded half up to 8 bits.  No exponential history.
 *
 * Orderings: the stage decides the orderings of the next cycle at the end of
 * the last frame of a cycle (tdc_ordering_update over its motion buffer, with
 * frame = first frame of the new cycle).  A stream that carries pattern bits
 * with the first subframe of a cycle overrides them (the renderer traced with
 * those); every tile where they differ is counted in
 * stats.pattern_disagreements.
 *
 * Stage elision: while the motion buffer holds no non-zero vector the frame
 * is static: the new samples are averaged in place into the current output
 * and nothing else is read or written (no 3x3 search, no copy, no
 * reprojection, no clamp).  In a frame with motion, rows whose 3x3
 * neighbourhood has no motion take the static path (copy + averages).
 *
 * Memory: one caller-owned arena (libopus style):
 *     size_t n = tdc_asm_get_size(&cfg);   // <= TDC_ASM_MEM_BYTES(W, H)
 *     tdc_asm_init(&st, &cfg, arena, n);
 * Per frame:  tdc_asm_ingest(&st, f, samples, mvs, bits)  (skip when dropped)
 *             tdc_asm_assemble(&st, f);  out = tdc_asm_output(&st, &stride);
 * Frames must be assembled in order f = 0, 1, 2, ...
 *
 * From the link decoder (firmware/tdc_link.h) for eye e: samples =
 * buffers.subframe[e], mvs = buffers.sample_motion[e] (streams with
 * per-sample motion) and pattern_bits = buffers.pattern[e] on the first
 * subframe of a cycle; per-pixel motion (buffers.motion[e]) goes through
 * tdc_asm_set_motion().  The layouts are the same by construction.
 */
#ifndef TDC_ASSEMBLE_H
#define TDC_ASSEMBLE_H

#include "tdc_arena.h"
#include "tdc_fixed.h"
#include "tdc_ordering.h"

#define TDC_ASM_MAX_DIM 4096

/* Bytes per pixel of the arena: 2 output frames (6), window mask (1),
 * motion buffer (4); plus 48 per tile: 4 slots x 4 positions of RGB888;
 * plus 75 per column of row rings. */
#define TDC_ASM_BYTES_PER_PIXEL 11u

/*
 * The arena (tdc_arena.h), one line per block: X(member of tdc_asm_t,
 * element type, count) for a W x H frame of TILES 2x2 tiles and BM bytes of
 * ordering bits.  Init carves it, get_size() is the same carve as a dry
 * run, TDC_ASM_MEM_BYTES the same list at the build's size.
 */
#define TDC_ASM_ARENA(X, W, H, TILES, BM)                                                  \
    X(frame[0], uint8_t, (size_t)(W) * (H)*3u) /* output frames, RGB888 */                 \
    X(frame[1], uint8_t, (size_t)(W) * (H)*3u)                                             \
    X(samples, uint8_t, (size_t)(TILES)*48u) /* 4 slots x 4 positions x RGB888 per tile */ \
    X(window, uint8_t, (size_t)(W) * (H))    /* averaging window mask */                   \
    X(mv, int16_t, (size_t)(W) * (H)*2u)     /* motion buffer, (dx, dy) Q4 */              \
    X(ring, tdc_asm_mvmax_t, (size_t)(W)*3u) /* 3 rows of horizontal 3-maxima */           \
    X(newring, uint8_t, (size_t)(W)*3u)                                                    \
    X(boxring, uint64_t, (size_t)(W)*3u * 2u) /* 3 rows of box sums and sums of squares */ \
    X(pattern, uint8_t, (size_t)(BM))         /* orderings of the cycle */                 \
    X(pattern_next, uint8_t, (size_t)(BM))

#define TDC_ASM_MEM_BYTES(W, H) \
    ((size_t)0 TDC_ASM_ARENA(TDC_ARENA_BLOCK_BYTES, W, H, (size_t)TDC_TILES(W) * TDC_TILES(H), TDC_PATTERN_BYTES(W, H)))

typedef struct {
    uint16_t width; /* full-res frame size, 1 .. TDC_ASM_MAX_DIM */
    uint16_t height;
} tdc_asm_config_t;

/* Counters: what ran and what was elided. */
typedef struct {
    uint32_t frames;                /* frames assembled */
    uint32_t subframes;             /* subframes ingested */
    uint32_t subframes_missing;     /* frames assembled without their subframe */
    uint32_t static_frames;         /* frames done by the in-place static path */
    uint32_t pattern_checks;        /* tiles whose stream bit was compared */
    uint32_t pattern_disagreements; /* ... and differed from the firmware's decision */
    uint64_t new_dynamic;           /* dynamic pixels stored from the new subframe */
    uint64_t reprojected;           /* old dynamic pixels reprojected (bilinear) */
    uint64_t reproject_edge;        /* ... of which the MV pointed outside (clamped) */
    uint64_t clamp_boxes;           /* mean +- sigma boxes computed */
    uint64_t clamp_changed;         /* pixel-channels moved by the clamp */
    uint64_t clamp_no_neighbour;    /* old dynamic pixels with no new neighbour */
    uint64_t static_averaged;       /* new static samples averaged */
    uint64_t static_kept;           /* old static pixels copied from the last frame */
    uint64_t window_resets;         /* pixels whose averaging window was reset */
    uint64_t static_rows;           /* rows of dynamic frames done by the static path */
} tdc_asm_stats_t;

typedef struct {
    uint32_t l2;    /* squared length, Q8 px^2 */
    int16_t dx, dy; /* Q4 */
} tdc_asm_mvmax_t;

typedef struct {
    tdc_asm_config_t cfg;
    uint32_t tiles_x, tiles_y;
    uint8_t *frame[2];     /* output frames, RGB888, stride width*3 */
    int cur;               /* index of the last output frame */
    uint8_t *samples;      /* 16 planes (slot * 4 + tile position) of tiles RGB888:
                               last samples, slot = cycle mod 4 */
    uint8_t *window;       /* per pixel: bit s = slot s holds a sample of the window */
    int16_t *mv;           /* per pixel (dx, dy) Q4 of its latest sample */
    tdc_asm_mvmax_t *ring; /* 3 rows of horizontal 3-maxima */
    uint8_t *newring;      /* 3 rows: 1 where the pixel is in the newest subframe */
    uint64_t *boxring;     /* 3 rows x W x 2: horizontal 3-sums of the newest samples
                               and their count, R | G << 16 | B << 32 | count << 48,
                               and of their squares, R | G << 21 | B << 42 */
    uint8_t *pattern;      /* orderings of the current cycle */
    uint8_t *pattern_next; /* scratch for the next decision */
    uint32_t mv_nonzero;   /* pixels whose motion-buffer entry is non-zero */
    uint32_t next_frame;   /* frame index the next assemble must have */
    int have_subframe;     /* a subframe was ingested for next_frame */
    tdc_asm_stats_t stats;
} tdc_asm_t;

/* Arena bytes for cfg (0 if cfg is invalid). */
size_t tdc_asm_get_size(const tdc_asm_config_t *cfg);

/* Initialises st over arena (aligned to TDC_ARENA_ALIGN, n >= get_size;
 * else TDC_ERR_ARG / TDC_ERR_SIZE and nothing is touched).  Output starts
 * black, motion zero, all tiles hourglass. */
TDC_MUST_CHECK
tdc_status_t tdc_asm_init(tdc_asm_t *st, const tdc_asm_config_t *cfg, void *arena, size_t n);

/*
 * Ingests the subframe of `frame` (must equal the next frame to assemble).
 *   samples: tiles_x * tiles_y RGB888, tile rows packed (tiles_x*3 bytes);
 *   mvs: tiles_x * tiles_y (dx, dy) Q4 pairs, or NULL for no motion;
 *   pattern_bits: the stream's orderings (only read when frame % 4 == 0),
 *                 or NULL: the stage uses its own decision.
 * Samples of partial tiles that fall outside the frame are ignored.
 * Errors: TDC_ERR_ARG (null st/samples), TDC_ERR_FRAME (out of sequence,
 * or a second subframe for the same frame); nothing is changed on error.
 */
TDC_MUST_CHECK
tdc_status_t tdc_asm_ingest(tdc_asm_t *st, uint32_t frame, const uint8_t *samples, const int16_t *mvs,
                            const uint8_t *pattern_bits);

/*
 * Streams that send per-pixel motion (a full w x h field of (dx, dy) Q4
 * pairs, e.g. the link's MOTION packets without the per-sample flag):
 * replaces the whole motion buffer for `frame` (call after tdc_asm_ingest,
 * or alone when the subframe was lost, before tdc_asm_assemble).
 * Errors: TDC_ERR_ARG, TDC_ERR_FRAME (not the next frame).
 */
TDC_MUST_CHECK
tdc_status_t tdc_asm_set_motion(tdc_asm_t *st, uint32_t frame, const int16_t *mv);

/* Right after tdc_asm_init: the stream starts (or was joined late, e.g.
 * after a board reset mid-stream) at `frame` instead of 0. */
void tdc_asm_start_at(tdc_asm_t *st, uint32_t frame);

/* Assembles output frame `frame` (= the next frame; missing subframe allowed). */
TDC_MUST_CHECK
tdc_status_t tdc_asm_assemble(tdc_asm_t *st, uint32_t frame);

/* The last assembled frame, RGB888, *stride_bytes = width * 3. */
const uint8_t *tdc_asm_output(const tdc_asm_t *st, int *stride_bytes);

/* Orderings the stage will use for the current/next cycle (bitmap). */
const uint8_t *tdc_asm_pattern(const tdc_asm_t *st);

/* The stage's generic arithmetic (window mean, division by 1..8, table
 * square root, the random-band hash) is in tdc_math.h. */

#endif /* TDC_ASSEMBLE_H */
