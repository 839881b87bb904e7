/*
 * tdc_fw_config.h - the frame loop's build configuration: which stages are
 * in (TDC_CFG_*, set by `make STAGES=` and the board's board.mk, mk/boards.mk)
 * and their defaults, checked once here.
 *
 * One build per board/panel pair: every size comes from the panel's config
 * header (-include build/gen/tdc_panel_<panel>_config.h), so every buffer
 * of the loop is a static object (tdc_fw_memmap.h) and a pair that does not
 * fit its board fails at link time (docs/boards.md).
 */
#ifndef TDC_FW_CONFIG_H
#define TDC_FW_CONFIG_H

#include <stdint.h>

#include "tdc_panel.h"

#ifndef TDC_PANEL_WIDTH
#error "the frame loop is built per panel: compile with -include tdc_panel_<panel>_config.h"
#endif

/* TRM (REDUCED streams, tdc_trm.h). */
#ifndef TDC_CFG_TRM
#define TDC_CFG_TRM 0
#endif
/* Largest TRM ratio r this build accepts (buffers are sized for it). */
#ifndef TDC_CFG_R_NUM
#define TDC_CFG_R_NUM 1
#define TDC_CFG_R_DEN 2
#endif

/* Tile assembly (SUBFRAME streams, tdc_assemble.h). */
#ifndef TDC_CFG_ASSEMBLE
#define TDC_CFG_ASSEMBLE 0
#endif

/* Layered tile assembly (SUBFRAMES | LAYERS streams, tdc_layers.h) with
 * the per-layer history a stream may switch on (stream flag LAYER_HIST):
 * every layer type kept, 148 B/px of arena per eye (not in any board's
 * default stages: STAGES=layers). */
#ifndef TDC_CFG_LAYERS
#define TDC_CFG_LAYERS 0
#endif

/* Foveation (FOVEATED streams, tdc_fov.h). */
#ifndef TDC_CFG_FOV
#define TDC_CFG_FOV 0
#endif
/* Peripheral TAA (12 B/px of history per eye); without it a packet that
 * carries motion vectors is refused by the decoder (UNEXPECTED). */
#ifndef TDC_CFG_FOV_TAA
#define TDC_CFG_FOV_TAA TDC_CFG_FOV
#endif
/* Largest buffer downscale delta (Q15) this build holds: the samples
 * buffer is sized for it, a larger delta is refused by the decoder
 * (LENGTH).  Default: 0.555 as senders quantise it (tdc_fov_link.h). */
#ifndef TDC_CFG_FOV_DELTA_Q15
#define TDC_CFG_FOV_DELTA_Q15 18187u
#endif

/* Foveated TRM (stream flags REDUCED | FOVEATED, docs/foveation.md
 * "Foveated TRM"): with TRM and the foveation stage both in, the loop plays
 * it through tdc_fov_trm, whose two instances and the decoder's FOVEATED
 * buffers sit beside TRM's arena (not in it: both are live at once).  A
 * board short of memory sets 0: the mode arena is then as without it and
 * such a stream is refused by name. */
#ifndef TDC_CFG_FOV_TRM
#define TDC_CFG_FOV_TRM (TDC_CFG_TRM && TDC_CFG_FOV)
#endif
#if TDC_CFG_FOV_TRM && !(TDC_CFG_TRM && TDC_CFG_FOV)
#error "TDC_CFG_FOV_TRM needs TDC_CFG_TRM and TDC_CFG_FOV"
#endif

/* The LCD inverse (an output stage after every family, LCD panels only). */
#ifndef TDC_CFG_LCD
#define TDC_CFG_LCD 0
#endif
#if TDC_CFG_LCD && !TDC_PANEL_IS_LCD
#error "TDC_CFG_LCD on an OLED panel: the LCD inverse is compiled out of OLED builds"
#endif
/* Overdrive table (what monitor scalers use; ~4.5x fewer instructions per
 * pixel than the exact solve on Cortex-M7, docs/boards.md); profiles
 * without that table fall back to the exact solve. */
#ifndef TDC_CFG_LCD_MODE
#define TDC_CFG_LCD_MODE TDC_LCD_MODE_TABLE33
#endif
/* Bits per sample of the LCD history (previous drive and light): 8 is
 * exact; a board short of memory configures fewer (boards/<b>/board.mk). */
#ifndef TDC_CFG_LCD_PREV_BITS
#define TDC_CFG_LCD_PREV_BITS 8u
#endif

/* Row workers: the most bands of a frame's output rows the loop runs at
 * once (TRM, tdc_fw_trm.c), each band but the first with its own static
 * row buffers (TDC_TRM_ROWBUF_BYTES, ~30 KB at 1080 pixels); the board says
 * how many it has (tdc_board_workers).  1 (no threads): the Cortex-M
 * boards; the Linux board's loop is built with 4. */
#ifndef TDC_CFG_ROW_WORKERS
#define TDC_CFG_ROW_WORKERS 1
#endif

/* Rows in flight (docs/boards.md): FULL and REDUCED pictures arrive as row
 * bands of at most TDC_CFG_BAND_ROWS rows; staging holds one band, the
 * frame buffer is a front/back pair swapped only when a frame is complete. */
#ifndef TDC_CFG_BANDS
#define TDC_CFG_BANDS 0
#endif
#ifndef TDC_CFG_BAND_ROWS
#define TDC_CFG_BAND_ROWS 16u
#endif

#define FW_W ((uint32_t)TDC_PANEL_WIDTH)
#define FW_H ((uint32_t)TDC_PANEL_HEIGHT)
#define FW_EYES ((uint32_t)TDC_PANEL_EYES)
#define FW_STRIDE (FW_EYES * FW_W * 3u) /* eyes side by side, RGB888 */

extern const tdc_panel_t TDC_PANEL_SYMBOL;

#endif
