/*
 * tdc_trm.h - temporal resolution multiplexing (docs/design.md §4.1, TRM paper §4).
 *
 * Per colour channel, for one eye:
 *   full-res frame t:  beta = 2 I - lin(U(D(I)))      (linear light)
 *                      shown clamp(beta, 0, 1); rho = beta - clamp(beta)
 *   reduced frame t+1: alpha = lin(U(i))
 *                      c = |A - B| / (A + B), A = lin(U(D(I_t))), B = alpha
 *                      w = exp(-s c); shown clamp(alpha + w rho, 0, 1)
 * D = separable Gaussian (sigma in full-res pixels) evaluated at the reduced
 * sample centres; U = bilinear.  Both act on gamma-compressed values (code
 * Q8, U output Q16); compensation and residual live in linear light (Q24).
 * The contrast c is Michelson contrast of linear light, as in eq. 5.
 *
 * Frames are RGB888 interleaved, rows `stride` bytes apart (so one eye of a
 * side-by-side stereo frame is just a pointer and the panel's stride).
 *
 * Memory: all state lives in one caller-owned arena (libopus style, layout
 * and alignment rule in tdc_arena.h: 8-byte aligned):
 *     size_t n = tdc_trm_get_size(&cfg);      // <= TDC_TRM_MEM_BYTES(...)
 *     tdc_trm_init(&trm, &cfg, panel, arena, n);
 * TDC_TRM_MEM_BYTES gives a compile-time upper bound for static arenas.
 */
#ifndef TDC_TRM_H
#define TDC_TRM_H

#include "tdc_arena.h"
#include "tdc_fixed.h"
#include "tdc_geom.h"
#include "tdc_panel.h"
#include "tdc_trm_kernels.h" /* the row kernels below the stage; TDC_TRM_WEXP_ENTRIES */

/* Largest Gaussian support: taps within 3 sigma, sigma <= 3.5 px. */
#define TDC_TRM_MAX_TAPS 24
#define TDC_TRM_MAX_SIGMA_Q8 (7 * 128) /* 3.5 px */
/* Taps of D for sigma (Q8): integer k with |k - x| <= 3 sigma number at
 * most floor(6 sigma) + 1 (22 at the largest sigma, 16 at 2.5 px). */
#define TDC_TRM_TAPS(sigma_q8)                                                                 \
    ((((6u * (uint32_t)(sigma_q8)) >> 8) + 1u) > TDC_TRM_MAX_TAPS ? (uint32_t)TDC_TRM_MAX_TAPS \
                                                                  : (((6u * (uint32_t)(sigma_q8)) >> 8) + 1u))

/* Reduced size for ratio num/den: round(n * num / den), at least 1. */
/* The AVX2 row kernels' one-step encode index (TDC_TRM_ENC_COMB,
 * tdc_trm_kernels.h): 3 channels x TDC_TRM_ENC_COMB entries + 4 bytes of
 * gather padding, on x86-64 hosts only; boards reserve nothing for it. */
#if defined(__x86_64__) && !defined(TDC_NO_SIMD)
#define TDC_TRM_SIMD_BYTES (3u * TDC_TRM_ENC_COMB + 8u)
#else
#define TDC_TRM_SIMD_BYTES 0u
#endif

/* The reduced size of ratio r_num / r_den: TDC_REDUCED_DIM (tdc_geom.h),
 * the rule the link and the host use too. */

/*
 * The arena (tdc_arena.h), one line per block: X(member of tdc_trm_t,
 * element type, count) for a W x H eye, reduced RW x RH, TAPS taps per D
 * kernel, KEEP = keep_residual.  Init carves it with the configuration's
 * geometry, get_size() is the same carve as a dry run, TDC_TRM_MEM_BYTES
 * the same list summed at the largest geometry.  A pass-through
 * configuration carves nothing; a block of 0 elements is NULL (rho is
 * stored only with KEEP, the full frame's codes and the rho/code row only
 * without).  Per display pixel at r = 1/2 without KEEP: 3 B of codes +
 * 1.5 B of D(I) + a few rows (docs/boards.md).  Order matters for one
 * block: the AVX2 horizontal D pass may read 2 bytes past dx_w (dy_w
 * follows it).
 */
#define TDC_TRM_ARENA(X, W, H, RW, RH, TAPS, KEEP)                                                     \
    X(residual, tdc_res_t, (KEEP) ? (size_t)(W) * (H)*3u : 0u) /* rho, Q24 linear light (KEEP) */      \
    X(icodes, uint8_t, (KEEP) ? 0u : (size_t)(W) * (H)*3u)     /* codes of the last full frame */      \
    X(rrow, tdc_res_t, (KEEP) ? 0u : (size_t)(W)*3u)           /* one row of rho, recomputed */        \
    X(crow, uint8_t, (KEEP) ? 0u : (size_t)(W)*3u)             /* one row of codes, discarded */       \
    X(dprev, tdc_gval_t, (size_t)(RW) * (RH)*3u)               /* D(I_t), code Q8 */                   \
    X(ring, tdc_gval_t, (size_t)(TAPS) * (RW)*3u)              /* horizontal D pass, a ring of rows */ \
    X(urow, uint32_t, (size_t)2u * ((RW) + 1u) * 3u)           /* two U rows, code Q22 */              \
    X(dx_first, int16_t, (size_t)(RW))                         /* D kernels */                         \
    X(dy_first, int16_t, (size_t)(RH))                                                                 \
    X(dx_w, uint16_t, (size_t)(RW) * (TAPS))                                                           \
    X(dy_w, uint16_t, (size_t)(RH) * (TAPS))                                                           \
    X(ux_i, uint16_t, (size_t)(W)*2u) /* U tables (index, fraction) */                                 \
    X(uy_i, uint16_t, (size_t)(H)*2u)                                                                  \
    X(enc_comb, uint8_t, (size_t)TDC_TRM_SIMD_BYTES) /* AVX2 encode index (0 on boards) */

/*
 * Compile-time arena bound for a W x H eye at reduction ratios up to
 * RNUM/RDEN (the board's largest r < 1) and any sigma: the list above at
 * that geometry with the taps of the largest sigma (every block grows with
 * r and taps, so no smaller configuration needs more), default layout
 * (keep_residual = 0); _KEEP with rho stored.
 */
#define TDC_TRM_MEM_BYTES(W, H, RNUM, RDEN)                                               \
    ((size_t)0 TDC_TRM_ARENA(TDC_ARENA_BLOCK_BYTES, W, H, TDC_REDUCED_DIM(W, RNUM, RDEN), \
                             TDC_REDUCED_DIM(H, RNUM, RDEN), TDC_TRM_TAPS(TDC_TRM_MAX_SIGMA_Q8), 0))
#define TDC_TRM_MEM_BYTES_KEEP(W, H, RNUM, RDEN)                                          \
    ((size_t)0 TDC_TRM_ARENA(TDC_ARENA_BLOCK_BYTES, W, H, TDC_REDUCED_DIM(W, RNUM, RDEN), \
                             TDC_REDUCED_DIM(H, RNUM, RDEN), TDC_TRM_TAPS(TDC_TRM_MAX_SIGMA_Q8), 1))

typedef struct {
    uint16_t width; /* full-res eye size in pixels */
    uint16_t height;
    uint16_t r_num; /* reduction ratio r = r_num / r_den, 1/4 <= r <= 1 */
    uint16_t r_den;
    uint16_t sigma_q8;         /* Gaussian sigma of D in full-res pixels, Q8 (2.5 = 640) */
    uint16_t refresh_hz;       /* refresh the stream runs at */
    uint16_t min_refresh_hz;   /* TRM refused below this (paper §9: 90 Hz) */
    uint32_t s_q8;             /* motion sensitivity s of w = exp(-s c), Q8 */
    uint8_t reduced_in_stream; /* 0: stream has no reduced frames -> pass-through */
    /* 0 (default): keep the full frame's codes I_t and D(I_t) and recompute
     * rho = beta - clamp(beta) row by row when the reduced frame arrives
     * (beta is a deterministic function of I_t and D(I_t): same bytes,
     * 4.5 B/px at r = 1/2 instead of 13.5).  1: store rho (W*H*3 Q24), which
     * tdc_trm_residual() exposes so the LCD inverse can add its unreached
     * light to it (the simulator does; boards drop that light, counted). */
    uint8_t keep_residual;
} tdc_trm_config_t;

/* Per-stage counters: show what ran and what was elided. */
typedef struct {
    uint32_t full_frames;        /* beta computed */
    uint32_t reduced_frames;     /* alpha' computed */
    uint32_t passthrough_frames; /* r = 1 or no reduced frames: no TRM work */
    uint64_t weight_computed;    /* pixel-channels where exp(-s c) ran */
    uint64_t weight_skipped;     /* pixel-channels with c = 0 known (A == B) */
    uint64_t residual_skipped;   /* pixel-channels with rho = 0: no weight needed */
    uint64_t clamped_high;       /* pixel-channels where beta > 1 */
    uint64_t clamped_low;        /* pixel-channels where beta < 0 */
    uint32_t reduced_unpaired;   /* reduced frames shown without residual: their full
                                    frame (sequence number - 1) was lost or out of order */
} tdc_trm_stats_t;

/* Gaze-aware compensation strength (tdc_trm_gaze.h); NULL: plain TRM. */
typedef struct tdc_trm_gaze tdc_trm_gaze_t;

typedef struct {
    /* configuration, validated */
    tdc_trm_config_t cfg;
    const tdc_panel_t *panel;
    uint16_t rw, rh;     /* reduced size */
    uint16_t dtaps;      /* taps per D kernel */
    uint8_t passthrough; /* r == 1 or no reduced frames in the stream */
    uint8_t have_full;   /* a full frame's D(I) and rho are valid */
    uint32_t full_seq;   /* sequence number of that full frame (tdc_trm_full_seq) */
    uint8_t simd;        /* row kernels: 1 = AVX2 (host), 0 = portable C */
    /* views into the arena */
    tdc_res_t *residual;  /* keep_residual: W*H*3, Q24 linear light; else NULL */
    uint8_t *icodes;      /* keep_residual = 0: W*H*3 codes of the last full frame */
    tdc_res_t *rrow;      /* keep_residual = 0: one row of rho (W*3, Q24) */
    uint8_t *crow;        /* keep_residual = 0: one row of codes (W*3), discarded */
    tdc_gval_t *dprev;    /* rw*rh*3, D(I_t), code Q8 */
    tdc_gval_t *ring;     /* dtaps rows of rw*3: horizontal D pass */
    uint32_t *urow;       /* 2 rows of (rw+1)*3: vertically interpolated U rows, code Q22 */
    int16_t *dx_first;    /* rw: first full-res column of each D kernel */
    int16_t *dy_first;    /* rh */
    uint16_t *dx_w;       /* rw*dtaps: kernel weights Q15, each sums to 32768 */
    uint16_t *dy_w;       /* rh*dtaps */
    uint16_t *ux_i;       /* W: left reduced column of U */
    uint16_t *ux_f;       /* W: bilinear fraction Q14 */
    uint16_t *uy_i;       /* H */
    uint16_t *uy_f;       /* H */
    const uint32_t *wexp; /* tdc_trm_wexp_q30: exp(-k/256) in Q30, const (generated) */
    uint8_t *enc_comb;    /* TDC_TRM_SIMD_BYTES: AVX2 encode index (NULL without) */
    uint8_t enc_one_step; /* enc_comb needs at most one threshold step */
    const tdc_trm_gaze_t *gaze; /* tdc_trm_set_gaze(); NULL (init's default): today's bytes */
    tdc_trm_stats_t stats;
    /* the frame in progress (every frame runs through it: whole frames
     * with all rows at once, row bands as they arrive) */
    struct {
        const uint8_t *in;
        uint8_t *out;
        uint32_t in_stride, out_stride;
        int32_t loaded;  /* full: highest input row through D's horizontal pass (-1: none) */
        uint32_t dy;     /* full: rows of D(I) done */
        uint32_t y;      /* output rows final */
        uint64_t n[3];   /* full: clamped high, low; reduced: computed, skipped, no residual */
        uint8_t kind;    /* 0 none, 1 full, 2 reduced */
        uint8_t paired;  /* reduced: with the kept state */
    } inc;
} tdc_trm_t;

/* Validates cfg (ratio, sigma, sizes) and returns the arena size in bytes
 * (a dry run of init's layout), or 0 when cfg is invalid.  Pass-through
 * (r = 1 or no reduced frames in the stream) keeps no state and needs only
 * TDC_ARENA_ALIGN bytes. */
size_t tdc_trm_get_size(const tdc_trm_config_t *cfg);

/* Default configuration: r = 1/2, sigma 2.5 px, s = 10, 90 Hz minimum. */
void tdc_trm_default_config(tdc_trm_config_t *cfg, uint16_t width, uint16_t height, uint16_t refresh_hz);

/*
 * Initialises the stage.  Errors: TDC_ERR_ARG (null), TDC_ERR_RATIO (r
 * outside [1/4, 1]), TDC_ERR_REFRESH_LOW (r < 1 and refresh below the
 * minimum: TRM is refused, paper §9), TDC_ERR_SIZE (arena too small or eye
 * larger than the kernel tables allow), TDC_ERR_PANEL (panel not 8-bit),
 * TDC_ERR_ARG also for mem not aligned to TDC_ARENA_ALIGN.  Nothing is
 * written (st or mem) on error.
 */
TDC_MUST_CHECK
tdc_status_t tdc_trm_init(tdc_trm_t *st, const tdc_trm_config_t *cfg, const tdc_panel_t *panel, void *mem,
                          size_t mem_bytes);

/* Forget history (stream reset): the next reduced frame needs a full one first. */
void tdc_trm_reset(tdc_trm_t *st);

/*
 * Full-resolution frame: in (W x H) -> out (W x H) drive codes, updates rho
 * and D(I).  In pass-through mode out = in and nothing else runs.
 */
TDC_MUST_CHECK
tdc_status_t tdc_trm_full(tdc_trm_t *st, const uint8_t *in, uint32_t in_stride, uint8_t *out, uint32_t out_stride);

/*
 * Reduced frame: in (rw x rh) -> out (W x H) drive codes.
 * TDC_ERR_STATE if no full frame preceded it since init/reset (out is left
 * untouched: the panel keeps the last good frame).
 */
TDC_MUST_CHECK
tdc_status_t tdc_trm_reduced(tdc_trm_t *st, const uint8_t *in_reduced, uint32_t in_stride, uint8_t *out,
                             uint32_t out_stride);

/*
 * The renderer-side prefilter with this stage's D: full-res in -> reduced
 * codes (rounded).  For tests, tdc-run --auto-reduce and the demo; a real
 * renderer supersamples instead (TRM §4.3).
 */
TDC_MUST_CHECK
tdc_status_t tdc_trm_downsample(tdc_trm_t *st, const uint8_t *in, uint32_t in_stride, uint8_t *out,
                                uint32_t out_stride);

/* The motion weight w = exp(-x), x in Q16, as the reduced path computes it
 * (table interpolation; exposed for the accuracy test). */
int32_t tdc_trm_weight(const tdc_trm_t *st, uint32_t x_q16);

/*
 * Frames tied by sequence number (the link's frame index).  tdc_trm_full_seq
 * is tdc_trm_full and records seq; tdc_trm_reduced_seq uses the kept state
 * only if it belongs to the full frame seq - 1 of this eye (the frame just
 * before: TRM alternates per eye).  Otherwise -- the full frame was lost,
 * rejected or came out of order, or no full frame at all since init/reset --
 * the reduced frame is shown as alpha = lin(U(i)) alone, without residual
 * (never with stale state), counted in stats.reduced_unpaired, and TDC_OK.
 */
TDC_MUST_CHECK
tdc_status_t tdc_trm_full_seq(tdc_trm_t *st, const uint8_t *in, uint32_t in_stride, uint8_t *out, uint32_t out_stride,
                              uint32_t seq);
TDC_MUST_CHECK
tdc_status_t tdc_trm_reduced_seq(tdc_trm_t *st, const uint8_t *in_reduced, uint32_t in_stride, uint8_t *out,
                                 uint32_t out_stride, uint32_t seq);

/*
 * Rows in flight (docs/boards.md): the same frames, fed
 * as their rows arrive, top to bottom.  _begin takes the frame's buffers
 * (in may be out, as for the whole frame); _rows says that the first
 * `avail` rows of the input are there (full: input rows; reduced: reduced
 * rows; not decreasing) and runs what they allow -- full: D(I) rows whose
 * kernel is covered, then the output rows whose U(D(I)) rows are done; an
 * output row is written only when D no longer needs that input row --
 * and returns in *done how many output rows (from the top) are final;
 * _end runs the rest and closes the frame.  The output bytes are those of
 * tdc_trm_full_seq / tdc_trm_reduced_seq (which run through these).  From
 * _begin of a full frame until its _end the kept state is being replaced:
 * a reduced frame in between (a full frame dropped mid-way) is unpaired.
 * TDC_ERR_STATE: _rows/_end without the matching _begin.
 */
TDC_MUST_CHECK
tdc_status_t tdc_trm_full_begin(tdc_trm_t *st, const uint8_t *in, uint32_t in_stride, uint8_t *out,
                                uint32_t out_stride);
TDC_MUST_CHECK
tdc_status_t tdc_trm_full_rows(tdc_trm_t *st, uint32_t avail, uint32_t *done);
TDC_MUST_CHECK
tdc_status_t tdc_trm_full_end(tdc_trm_t *st, uint32_t seq);
TDC_MUST_CHECK
tdc_status_t tdc_trm_reduced_begin(tdc_trm_t *st, const uint8_t *in_reduced, uint32_t in_stride, uint8_t *out,
                                   uint32_t out_stride, uint32_t seq);
TDC_MUST_CHECK
tdc_status_t tdc_trm_reduced_rows(tdc_trm_t *st, uint32_t avail, uint32_t *done);
TDC_MUST_CHECK
tdc_status_t tdc_trm_reduced_end(tdc_trm_t *st);

/*
 * Whole frames on several cores (a board with row workers, docs/boards.md
 * "Real time"): with every input row there, D(I)'s rows are independent
 * given their input rows, and a frame's output rows are independent once
 * D(I) is done, so both run as bands, each band with its own buffers.
 * After _begin, with every input row there:
 *   tdc_trm_split   checks the state (no row done yet) and gives *d_rows,
 *                   D(I)'s rows to run (a full frame; 0 otherwise);
 *   tdc_trm_d_band  D(I) rows [j0, j1) with b's ring (bands of disjoint
 *                   rows with distinct b at the same time; each reloads
 *                   the few input rows its first kernel reaches back);
 *   tdc_trm_band    after every D band: output rows [y0, y1) with b,
 *                   counters added to n[3]; bands of disjoint rows with
 *                   distinct b at the same time (st is only read; the
 *                   output rows, their kept codes and b written);
 *   tdc_trm_join    after every band [0, H): their counters (summed), the
 *                   rows done; then _end closes the frame.
 * The bytes are those of _rows/_end whatever the bands (tested with 1, 2
 * and 3: tests/linux/test_board_threads.sh).  The stage's own buffers are
 * one worker's (tdc_trm_rowbuf_own); each further worker carves its own
 * with tdc_trm_rowbuf_init from TDC_TRM_ROWBUF_BYTES(W, RW) bytes aligned
 * to TDC_ARENA_ALIGN (TDC_ERR_SIZE if fewer, TDC_ERR_ARG if misaligned).
 */
typedef struct {
    uint32_t *urow;   /* 2 rows of (rw+1)*3: U rows, code Q22 */
    tdc_res_t *rrow;  /* W*3: rho recomputed (NULL with keep_residual) */
    uint8_t *crow;    /* W*3: the recompute's codes, discarded */
    tdc_gval_t *ring; /* taps rows of rw*3: D's horizontal pass */
} tdc_trm_rowbuf_t;
#define TDC_TRM_ROWBUF(X, W, RW)                                                                        \
    X(urow, uint32_t, (size_t)2u * ((RW) + 1u) * 3u)                                                    \
    X(rrow, tdc_res_t, (size_t)(W)*3u)                                                                  \
    X(crow, uint8_t, (size_t)(W)*3u)                                                                    \
    X(ring, tdc_gval_t, (size_t)TDC_TRM_TAPS(TDC_TRM_MAX_SIGMA_Q8) * (RW)*3u)
#define TDC_TRM_ROWBUF_BYTES(W, RW) ((size_t)0 TDC_TRM_ROWBUF(TDC_ARENA_BLOCK_BYTES, W, RW))
TDC_MUST_CHECK
tdc_status_t tdc_trm_rowbuf_init(const tdc_trm_t *st, tdc_trm_rowbuf_t *b, void *mem, size_t bytes);
static inline tdc_trm_rowbuf_t tdc_trm_rowbuf_own(const tdc_trm_t *st)
{
    const tdc_trm_rowbuf_t b = {st->urow, st->rrow, st->crow, st->ring};
    return b;
}
TDC_MUST_CHECK
tdc_status_t tdc_trm_split(const tdc_trm_t *st, uint32_t *d_rows);
void tdc_trm_d_band(const tdc_trm_t *st, uint32_t j0, uint32_t j1, const tdc_trm_rowbuf_t *b);
void tdc_trm_band(const tdc_trm_t *st, uint32_t y0, uint32_t y1, const tdc_trm_rowbuf_t *b, uint64_t n[3]);
void tdc_trm_join(tdc_trm_t *st, const uint64_t n[3]);

/* Forget the kept full frame (it is no longer what the next reduced frame
 * pairs with), keeping the tables: e.g. when a newer full frame of this
 * eye was lost. */
void tdc_trm_invalidate(tdc_trm_t *st);

/*
 * rho of row y (W*3 Q24) of the last full frame, as the reduced frame uses
 * it: recomputed from the kept codes (or copied when keep_residual).
 * TDC_ERR_STATE without a full frame.  For tests and golden vectors.
 */
TDC_MUST_CHECK
tdc_status_t tdc_trm_residual_row(tdc_trm_t *st, uint32_t y, tdc_res_t *out);

/* Row kernels: AVX2 (enable = 1, the default when the host CPU has it) or
 * portable C (0).  Both give the same bytes (tests/checkasm/checkasm_trm.c); boards
 * and CPUs without AVX2 always run C. */
void tdc_trm_set_simd(tdc_trm_t *st, int enable);

/* Residual buffer rho (W*H*3, Q24 linear light, interleaved like the frame),
 * for the LCD stage, which adds the light the panel could not reach; NULL
 * unless keep_residual (rho is then recomputed, never stored). */
static inline tdc_res_t *tdc_trm_residual(tdc_trm_t *st)
{
    return st->residual;
}

/* Stereo (paper §7.2): eye 0 gets full-res frames on even frame indices,
 * eye 1 on odd ones; each eye has its own tdc_trm_t. */
static inline int tdc_trm_stereo_eye_is_full(uint32_t frame_index, int eye)
{
    return (int)((frame_index + (uint32_t)eye) & 1u) == 0;
}

#endif /* TDC_TRM_H */
