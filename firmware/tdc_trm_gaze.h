/*
 * tdc_trm_gaze.h - gaze-aware TRM (beyond the paper): a
 * compensation strength that falls where the image moves on the retina.
 *
 * TRM's compensation (beta = 2 I - U D I, and the residual) cancels on the
 * retina only where the eye tracks the content (TRM §4.1).  A headset with
 * an eye tracker knows the gaze velocity g; the renderer's motion vectors m
 * say how the content moves; u = m - g is the retinal motion.  Where |u| is
 * large the sharpened frame and the reduced frame land on different retinal
 * positions and the compensation becomes a pattern of its own, so the full
 * frame is sharpened with strength k(u) in [kmin, 1]:
 *     beta_k = I + k (I - U D I)        (linear light; k = 1: TRM's beta)
 *     rho    = beta_k - clamp(beta_k)   (k = 0: beta = I, rho = 0: the
 *                                        reduced frame is U(i) alone)
 *     k(u)   = 1                                  |u|^2 <= u0^2
 *            = 1 - (1 - kmin) (|u|^2 - u0^2) / (u1^2 - u0^2)   between
 *            = kmin                               |u|^2 >= u1^2
 * (a ramp in squared speed: no square root per tile).  k is one value per
 * tile of `tile` x `tile` pixels, from one motion vector per tile.
 *
 * Use: tdc_trm_gaze_init() on a caller-owned arena (get_size()), then
 * tdc_trm_set_gaze(&trm, &gaze); before every full-resolution frame
 * tdc_trm_gaze_update() with that frame's tile motion vectors (the link's
 * MOTION payload format: int16 (dx, dy) pairs, Q4 px per frame) and the eye
 * tracker's gaze velocity (Q4 px per frame).  The map stays with the full
 * frame: its reduced frame recomputes rho with the same k.  Not attached
 * (the default) the stage's bytes are today's: no call of this file runs.
 *
 * Formats: k Q15 (32768 = 1); u in Q4, |u|^2 in Q8 (uint64 before the
 * clamp); the ramp fraction Q30 by tdc_div_q30 (num < den < 2^32).
 * Scaling and overflow (the row): d = I - U D I in [-2^24, 2^24] (Q24), k d
 * in Q39 < 2^40 in int64, rounded back to Q24: beta in [-2^24, 2^25], as
 * TRM's own beta range [-1, 2].
 */
#ifndef TDC_TRM_GAZE_H
#define TDC_TRM_GAZE_H

#include "tdc_arena.h"
#include "tdc_status.h"
#include "tdc_trm.h"

#define TDC_TRM_GAZE_MIN_TILE 4u
#define TDC_TRM_GAZE_MAX_TILE 256u
/* tiles of a W x H eye at tile size T */
#define TDC_TRM_GAZE_TILES_X(W, T) (((uint32_t)(W) + (T)-1u) / (T))
#define TDC_TRM_GAZE_TILES_Y(H, T) (((uint32_t)(H) + (T)-1u) / (T))

typedef struct {
    uint16_t width, height; /* the TRM stage's eye */
    uint16_t tile;          /* tile edge in pixels, TDC_TRM_GAZE_MIN_TILE..MAX_TILE */
    uint16_t u0_q4;         /* retinal speed (px/frame, Q4) up to which k = 1 */
    uint16_t u1_q4;         /* speed from which k = kmin (> u0_q4) */
    uint16_t kmin_q15;      /* strength at and beyond u1, 0..32768 */
} tdc_trm_gaze_config_t;

/* The arena: X(member, type, count) for TX x TY tiles. */
#define TDC_TRM_GAZE_ARENA(X, TX, TY)                                       \
    X(k_q15, uint16_t, (size_t)(TX) * (TY)) /* strength per tile, Q15 */    \
    X(row_active, uint8_t, (size_t)(TY))    /* a tile of the row has k < 1 */
#define TDC_TRM_GAZE_MEM_BYTES(W, H, T)                                                                 \
    ((size_t)0 TDC_TRM_GAZE_ARENA(TDC_ARENA_BLOCK_BYTES, TDC_TRM_GAZE_TILES_X(W, T), TDC_TRM_GAZE_TILES_Y(H, T)))

struct tdc_trm_gaze {
    tdc_trm_gaze_config_t cfg;
    uint32_t tx, ty; /* tiles */
    uint16_t *k_q15; /* tx * ty */
    uint8_t *row_active;
    uint32_t updates, rejected; /* maps computed, updates refused (kept the last) */
};

/* Default: 16-pixel tiles, k = 1 up to 0.5 px/frame of retinal motion,
 * falling to kmin = 0 at 2 px/frame. */
void tdc_trm_gaze_default_config(tdc_trm_gaze_config_t *cfg, uint16_t width, uint16_t height);
/* Arena bytes, or 0 for an invalid configuration. */
size_t tdc_trm_gaze_get_size(const tdc_trm_gaze_config_t *cfg);
/* TDC_ERR_ARG: null, invalid configuration or unaligned arena; TDC_ERR_SIZE:
 * arena too small.  Starts with k = 1 everywhere (plain TRM). */
TDC_MUST_CHECK
tdc_status_t tdc_trm_gaze_init(tdc_trm_gaze_t *g, const tdc_trm_gaze_config_t *cfg, void *mem, size_t mem_bytes);

/* k of one tile's retinal motion (u = m - g, Q4 px/frame), Q15. */
uint16_t tdc_trm_gaze_strength_q15(const tdc_trm_gaze_config_t *cfg, int32_t udx_q4, int32_t udy_q4);

/* The map for the next full frame: mv = tx * ty (dx, dy) Q4 pairs (row-major
 * tiles), n_pairs = their count; gaze velocity (gdx, gdy) Q4.  A wrong
 * count, a NULL mv or a motion component of -32768 is refused with
 * TDC_ERR_ARG and the last good map is kept (counted in rejected). */
TDC_MUST_CHECK
tdc_status_t tdc_trm_gaze_update(tdc_trm_gaze_t *g, const int16_t *mv, uint32_t n_pairs, int16_t gdx_q4,
                                 int16_t gdy_q4);

/* Attaches the map to a TRM stage (NULL detaches: plain TRM).  TDC_ERR_SIZE
 * when the map's eye is not the stage's. */
TDC_MUST_CHECK
tdc_status_t tdc_trm_set_gaze(tdc_trm_t *st, const tdc_trm_gaze_t *g);

#endif
