/*
 * tdc_fw_memmap.h - the frame loop's static memory map: every buffer's size
 * from the panel and the stages of the build (tdc_fw_config.h), and where
 * each stream family finds its part of the mode arena.
 *
 * Buffers (all eyes; W x H per eye, E eyes):
 *   frame buffer   E*W*H*3   RGB888 drive codes, eyes side by side; TRM
 *                            and the LCD inverse work on it in place; with
 *                            bands a front/back pair (tdc_fw_bands.c)
 *   link staging   W*H*(3 or 4) + 16   one payload, checked before anything
 *                            is unpacked; a FULL payload waits there until
 *                            the loop decides it updates its eye (defer_full)
 *   reduced        E * reduced frame (TRM, r <= TDC_CFG_R_NUM/TDC_CFG_R_DEN)
 *   subframe, sample motion, pattern bits   per eye (assembly)
 *   layer planes   per eye, every layer type's values and vectors and the
 *                  falloff (layered assembly, TDC_CFG_LAYERS)
 *   mode arena     per eye max(TRM arena, assembly arena, foveation block,
 *                  foveated TRM block): a stream uses TRM (reduced frames),
 *                  assembly (subframes), foveation (FOVEATED packets) or
 *                  foveated TRM (both), never another combination
 *   foveation block (TDC_CFG_FOV, in the mode arena) first the decoder's
 *                  FOVEATED buffers: the disk frame W*H*3 (the decoder's
 *                  full[]: disk pixels land there, never in the frame
 *                  buffer), the log-polar / log-rectilinear samples and
 *                  (TAA) their vectors, for deltas up to
 *                  TDC_CFG_FOV_DELTA_Q15; then the stage's arena (radial
 *                  table, row scratch; with TDC_CFG_FOV_TAA the two history
 *                  frames, 12 B/px) and the log-rectilinear scratch
 *   foveated TRM block (TDC_CFG_FOV_TRM, in the mode arena) the same
 *                  decoder buffers at the same place, then TRM's arena and
 *                  tdc_fov_trm's (two stage arenas without TAA, W x H and
 *                  rW x rH): a plain TRM stream keeps TRM's arena at the
 *                  start of the mode arena as without foveation
 *   LCD arena      per eye (LCD panels only)
 *
 * The mode arena is shared by the families: the decoder writes the
 * FOVEATED buffers only for a FOVEATED packet, which it accepts only in a
 * stream flagged FOVEATED, and such a stream runs no assembly, and TRM only
 * in the foveated TRM block, whose TRM arena starts after those buffers;
 * so they never overlap a live TRM or assembly state, and a stage's init
 * starts from nothing it finds there.
 */
#ifndef TDC_FW_MEMMAP_H
#define TDC_FW_MEMMAP_H

#include <stddef.h>
#include <stdint.h>

#include "tdc_arena.h"
#include "tdc_board.h"
#include "tdc_fw_config.h"
#include "tdc_link.h"

#define FW_MAX2(a, b) ((a) > (b) ? (a) : (b))

/* Staging holds the largest payload this build accepts: a full frame in
 * the widest compiled-in format (RGB30: 4 B/px; without it RGB888, 3 B/px),
 * or with bands one band (and the largest subframe-stream payload, 4 B per
 * tile, if assembly is in).  Per-pixel MOTION is never staged: no stage
 * here uses it (skip_motion). */
#define FW_FULL_BPP ((((unsigned)TDC_LINK_FORMAT_MASK >> TDC_PIXFMT_RGB30) & 1u) ? 4u : 3u)

/* ---- TRM ---- */
#if TDC_CFG_TRM
#include "tdc_trm.h"
#define FW_RW TDC_REDUCED_DIM(FW_W, TDC_CFG_R_NUM, TDC_CFG_R_DEN)
#define FW_RH TDC_REDUCED_DIM(FW_H, TDC_CFG_R_NUM, TDC_CFG_R_DEN)
#define FW_TRM_BYTES TDC_ARENA_ROUND(TDC_TRM_MEM_BYTES(FW_W, FW_H, TDC_CFG_R_NUM, TDC_CFG_R_DEN))
/* the reduced picture the decoder writes (tdc_fw_trm.c) */
extern uint8_t tdc_fw_reduced[FW_EYES][(size_t)FW_RW * FW_RH * 3u];
#else
#define FW_TRM_BYTES ((size_t)0)
#endif

/* ---- tile assembly ---- */
#if TDC_CFG_ASSEMBLE
#include "tdc_assemble.h"
#define FW_ASM_BYTES TDC_ARENA_ROUND(TDC_ASM_MEM_BYTES(FW_W, FW_H))
#define FW_ASM_STAGING (TDC_TILE_COUNT(FW_W, FW_H) * 4u)
#else
#define FW_ASM_BYTES ((size_t)0)
#define FW_ASM_STAGING ((size_t)0)
#endif

/* ---- layered tile assembly: its arena with history (the bound); the
 * largest LAYERS payload (every layer and the falloff plane, 28 B a tile) ---- */
#if TDC_CFG_LAYERS
#include "tdc_layers.h"
#define FW_LASM_BYTES TDC_ARENA_ROUND(TDC_LASM_MEM_BYTES_HIST(FW_W, FW_H))
#define FW_LASM_STAGING TDC_LINK_STAGING_LAYERS_BYTES(FW_W, FW_H)
#else
#define FW_LASM_BYTES ((size_t)0)
#define FW_LASM_STAGING ((size_t)0)
#endif

/* ---- foveation: the samples buffer for TDC_CFG_FOV_DELTA_Q15
 * (tdc_fov_lp_size), the largest FOVEATED payload (header, every sample
 * with its vector, every pixel in the disk: disk fraction 1) and the block
 * carved from the eye's mode arena, in this order: disk frame, samples,
 * vectors (the decoder's, at the same place in the foveated TRM block),
 * stage arena, log-rectilinear scratch. ---- */
#if TDC_CFG_FOV
#include "tdc_fov.h"
#include "tdc_fov_lr.h"
#define FW_LPW (((uint32_t)TDC_CFG_FOV_DELTA_Q15 * FW_W) >> 15)
#define FW_LPH (((uint32_t)TDC_CFG_FOV_DELTA_Q15 * FW_H) >> 15)
#define FW_LP_SAMPLES ((size_t)FW_LPW * FW_LPH)
#define FW_FOV_PAYLOAD \
    ((size_t)TDC_FOV_HDR_BYTES + FW_LP_SAMPLES * (3u + (TDC_CFG_FOV_TAA ? 4u : 0u)) + (size_t)FW_W * FW_H * 3u)
#define FW_FOV_STAGE_BYTES TDC_ARENA_ROUND(TDC_FOV_MEM_BYTES(FW_W, FW_H, TDC_CFG_FOV_TAA))
#define FW_FOV_LR_BYTES TDC_ARENA_ROUND(TDC_FOV_LR_MEM_BYTES(FW_W))
#define FW_FOV_DISK_BYTES TDC_ARENA_ROUND((size_t)FW_W *FW_H * 3u)
#define FW_FOV_LP_BYTES TDC_ARENA_ROUND(FW_LP_SAMPLES * 3u)
#define FW_FOV_MV_BYTES (TDC_CFG_FOV_TAA ? TDC_ARENA_ROUND(FW_LP_SAMPLES * 4u) : (size_t)0)
#define FW_FOV_DEC_BYTES (FW_FOV_DISK_BYTES + FW_FOV_LP_BYTES + FW_FOV_MV_BYTES)
#define FW_FOV_BYTES (FW_FOV_DEC_BYTES + FW_FOV_STAGE_BYTES + FW_FOV_LR_BYTES)
#define FOV_DISK(e) ((uint8_t *)tdc_fw_mode_arena[e])
#define FOV_LP(e) (FOV_DISK(e) + FW_FOV_DISK_BYTES)
#define FOV_MV(e) ((int16_t *)(void *)(FOV_LP(e) + FW_FOV_LP_BYTES))
#define FOV_STAGE(e) (FOV_DISK(e) + FW_FOV_DEC_BYTES)
#define FOV_LR_MEM(e) (FOV_STAGE(e) + FW_FOV_STAGE_BYTES)
#else
#define FW_FOV_PAYLOAD ((size_t)0)
#define FW_FOV_BYTES ((size_t)0)
#endif

/* ---- foveated TRM: decoder buffers, TRM's arena, both grids' stage
 * arenas (no TAA) ---- */
#if TDC_CFG_FOV_TRM
#include "tdc_fov_trm.h"
#define FW_FOVTRM_STAGE_BYTES TDC_ARENA_ROUND(TDC_FOV_TRM_MEM_BYTES(FW_W, FW_H, FW_RW, FW_RH))
#define FW_FOVTRM_BYTES (FW_FOV_DEC_BYTES + FW_TRM_BYTES + FW_FOVTRM_STAGE_BYTES)
#define FOVTRM_TRM(e) (FOV_DISK(e) + FW_FOV_DEC_BYTES)
#define FOVTRM_STAGE(e) (FOVTRM_TRM(e) + FW_TRM_BYTES)
#else
#define FW_FOVTRM_BYTES ((size_t)0)
#endif

/* ---- what every build has ---- */
#define FW_FB_BYTES ((size_t)FW_STRIDE * FW_H)
#define FW_FB_COUNT (TDC_CFG_BANDS ? 2u : 1u) /* bands: front/back */
#define FW_STAGING_WHOLE ((size_t)FW_W * FW_H * FW_FULL_BPP + TDC_LINK_STREAM_HEADER_BYTES)
/* a whole RGB888 picture: what a build staging one band must hold to take
 * whole-picture streams too */
#define FW_STAGING_RGB888 ((size_t)FW_W * FW_H * 3u + TDC_LINK_STREAM_HEADER_BYTES)
#define FW_STAGING_BANDS FW_MAX2(TDC_LINK_STAGING_BAND_BYTES(FW_W, TDC_CFG_BAND_ROWS, FW_FULL_BPP), FW_ASM_STAGING)
#define FW_STAGING_BYTES \
    FW_MAX2(FW_MAX2(TDC_CFG_BANDS ? FW_STAGING_BANDS : FW_STAGING_WHOLE, FW_FOV_PAYLOAD), FW_LASM_STAGING)
#define FW_MODE_BYTES \
    FW_MAX2(FW_MAX2(FW_MAX2(FW_MAX2(FW_TRM_BYTES, FW_ASM_BYTES), FW_FOV_BYTES), FW_FOVTRM_BYTES), FW_LASM_BYTES)
/* (a build with no stream family but plain still has one word) */
#define FW_MODE_WORDS FW_MAX2(FW_MODE_BYTES / 8u, (size_t)1)

/* The panel scans out tdc_fw_fb[tdc_fw.front]; the stages write the back
 * one (the same one without bands). */
extern uint8_t tdc_fw_fb[FW_FB_COUNT][FW_FB_BYTES];
extern uint8_t tdc_fw_staging[FW_STAGING_BYTES];
extern uint64_t tdc_fw_mode_arena[FW_EYES][FW_MODE_WORDS];

#endif
