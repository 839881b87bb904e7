/*
 * tdc_main.c - the controller's frame loop (DESIGN §1):
 *
 *   transport bytes -> link decoder -> tile assembly | TRM | foveation -> LCD inverse -> panel
 *
 * One build per board/panel pair: every size comes from the panel's config
 * header (-include build/gen/tdc_panel_<panel>_config.h) and the enabled
 * stages (TDC_CFG_TRM, TDC_CFG_ASSEMBLE, TDC_CFG_FOV (+ TDC_CFG_FOV_TAA),
 * TDC_CFG_LCD, set by `make STAGES=`),
 * so every buffer is a static object and a pair that does not fit its board
 * fails at link time (see mk/boards.mk, docs/boards.md).
 *
 * Buffers (all eyes; W x H per eye, E eyes):
 *   frame buffer   E*W*H*3   RGB888 drive codes, eyes side by side; TRM
 *                            and the LCD inverse work on it in place
 *   link staging   W*H*(3 or 4) + 16   one payload, checked before anything
 *                            is unpacked; a FULL payload waits there until
 *                            the loop decides it updates its eye (defer_full)
 *   reduced        E * reduced frame (TRM, r <= TDC_CFG_R_NUM/TDC_CFG_R_DEN)
 *   subframe, sample motion, pattern bits   per eye (assembly)
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
 * A frame is shown when every eye has what its mode needs (TRM: the FULL or
 * REDUCED packet due; plain: FULL; foveated: FOVEATED or FULL, as a plain
 * stream's FULL; assembly: SUBFRAME and, if the stream sends them, its
 * sample motion vectors) or had that packet rejected for a
 * bad payload CRC or a refused foveation header (the eye keeps its last
 * image: rejected packets never touch the frame buffer, tdc_link.h).  If a packet of a later frame
 * arrives first, the unfinished frame is completed with what arrived and
 * shown.
 *
 * The frame buffer changes only for an eye the loop counts as updated for
 * the frame it shows next (a kept eye shows exactly its last shown image,
 * fuzz invariant 2 of tests/fuzz/fuzz_frameloop.c): the decoder leaves FULL
 * payloads in staging (defer_full) and the loop unpacks one only when it
 * processes that eye -- never a FULL packet no mode of the stream uses (an
 * assembly stream), never before the unfinished frame is shown.  This costs
 * no memory; before it (fuzz finding F1) the decoder unpacked every FULL
 * packet into the frame buffer on arrival.  What it does not give is an
 * atomic swap on scan-out hardware: the eye being updated is processed in
 * the buffer the LTDC reads (docs/boards.md, "Frame buffer and scan-out").
 *
 * With TDC_CFG_BANDS (rows in flight, issue 17 item 2): pictures arrive as
 * row bands (tdc_band_link.h), staging holds one band, each FULL band is
 * unpacked at its rows of the back buffer as it arrives, the last band
 * completes the eye; the frame buffer is a front/back pair and the swap
 * happens only when a frame is finished (eyes not updated copied from the
 * front first).  A picture with a bad or missing band is dropped whole by
 * the decoder (BAND_DROPPED): its eye keeps its last good image.
 */
#include <string.h>

#include "tdc_board.h"
#include "tdc_link.h"
#include "tdc_panel.h"
#include "tdc_text.h"

#ifndef TDC_PANEL_WIDTH
#error "the frame loop is built per panel: compile with -include tdc_panel_<panel>_config.h"
#endif
#ifndef TDC_CFG_TRM
#define TDC_CFG_TRM 0
#endif
#ifndef TDC_CFG_ASSEMBLE
#define TDC_CFG_ASSEMBLE 0
#endif
#ifndef TDC_CFG_LCD
#define TDC_CFG_LCD 0
#endif
/* Rows in flight (issue 17 item 2, docs/boards.md): FULL and REDUCED
 * pictures arrive as row bands of at most TDC_CFG_BAND_ROWS rows; staging
 * holds one band, the frame buffer is a front/back pair swapped only when a
 * frame is complete. */
#ifndef TDC_CFG_BANDS
#define TDC_CFG_BANDS 0
#endif
#ifndef TDC_CFG_BAND_ROWS
#define TDC_CFG_BAND_ROWS 16u
#endif
#if TDC_CFG_LCD && !TDC_PANEL_IS_LCD
#error "TDC_CFG_LCD on an OLED panel: the LCD inverse is compiled out of OLED builds"
#endif
#if TDC_CFG_TRM
#include "tdc_trm.h"
#endif
#if TDC_CFG_ASSEMBLE
#include "tdc_assemble.h"
#endif
#ifndef TDC_CFG_FOV
#define TDC_CFG_FOV 0
#endif
#if TDC_CFG_FOV
#include "tdc_fov.h"
#include "tdc_fov_lr.h"
/* Peripheral TAA (12 B/px of history per eye); without it a packet that
 * carries motion vectors is refused by the decoder (UNEXPECTED). */
#ifndef TDC_CFG_FOV_TAA
#define TDC_CFG_FOV_TAA 1
#endif
/* Largest buffer downscale delta (Q15) this build holds: the samples
 * buffer is sized for it, a larger delta is refused by the decoder
 * (LENGTH).  Default: 0.555 as senders quantise it (tdc_fov_link.h). */
#ifndef TDC_CFG_FOV_DELTA_Q15
#define TDC_CFG_FOV_DELTA_Q15 18187u
#endif
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
#if TDC_CFG_FOV_TRM
#include "tdc_fov_trm.h"
#endif
#if TDC_CFG_LCD
#include "tdc_lcd.h"
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
#endif

/* Largest TRM ratio r this build accepts (buffers are sized for it). */
#ifndef TDC_CFG_R_NUM
#define TDC_CFG_R_NUM 1
#define TDC_CFG_R_DEN 2
#endif

#define FW_W ((uint32_t)TDC_PANEL_WIDTH)
#define FW_H ((uint32_t)TDC_PANEL_HEIGHT)
#define FW_EYES ((uint32_t)TDC_PANEL_EYES)
#define FW_STRIDE (FW_EYES * FW_W * 3u)

extern const tdc_panel_t TDC_PANEL_SYMBOL;

/* ---- static buffers (sizes from the panel and the stages) ---- */
/* Staging holds the largest payload this build accepts: a full frame in
 * the widest compiled-in format (RGB30: 4 B/px; without it RGB888, 3 B/px),
 * or with bands one band (and the largest subframe-stream payload, 4 B per
 * tile, if assembly is in).  Per-pixel MOTION is never staged: no stage
 * here uses it (skip_motion). */
#define FW_FULL_BPP ((((unsigned)TDC_LINK_FORMAT_MASK >> TDC_PIXFMT_RGB30) & 1u) ? 4u : 3u)
#define FW_MAX2(a, b) ((a) > (b) ? (a) : (b))
#if TDC_CFG_FOV
/* Foveation (per eye): the samples buffer for TDC_CFG_FOV_DELTA_Q15
 * (tdc_fov_lp_size), the largest FOVEATED payload (header, every sample
 * with its vector, every pixel in the disk: disk fraction 1) and the
 * block carved from the eye's mode arena, in this order: stage arena,
 * disk frame, samples, vectors (the decoder's, at the same place in the
 * foveated TRM block), stage arena, log-rectilinear scratch. */
#define FW_LPW (((uint32_t)TDC_CFG_FOV_DELTA_Q15 * FW_W) >> 15)
#define FW_LPH (((uint32_t)TDC_CFG_FOV_DELTA_Q15 * FW_H) >> 15)
#define FW_LP_SAMPLES ((size_t)FW_LPW * FW_LPH)
#define FW_FOV_PAYLOAD \
    ((size_t)TDC_FOV_HDR_BYTES + FW_LP_SAMPLES * (3u + (TDC_CFG_FOV_TAA ? 4u : 0u)) + (size_t)FW_W * FW_H * 3u)
#define FW_FOV_STAGE_BYTES TDC_ARENA_ROUND(TDC_FOV_MEM_BYTES(FW_W, FW_H, TDC_CFG_FOV_TAA))
#define FW_FOV_LR_BYTES TDC_ARENA_ROUND(TDC_FOV_LR_MEM_BYTES(FW_W))
#define FW_FOV_DISK_BYTES TDC_ARENA_ROUND((size_t)FW_W * FW_H * 3u)
#define FW_FOV_LP_BYTES TDC_ARENA_ROUND(FW_LP_SAMPLES * 3u)
#define FW_FOV_MV_BYTES (TDC_CFG_FOV_TAA ? TDC_ARENA_ROUND(FW_LP_SAMPLES * 4u) : (size_t)0)
#define FW_FOV_DEC_BYTES (FW_FOV_DISK_BYTES + FW_FOV_LP_BYTES + FW_FOV_MV_BYTES)
#define FW_FOV_BYTES (FW_FOV_DEC_BYTES + FW_FOV_STAGE_BYTES + FW_FOV_LR_BYTES)
#else
#define FW_FOV_PAYLOAD ((size_t)0)
#define FW_FOV_BYTES ((size_t)0)
#endif
#if TDC_CFG_BANDS
/* front/back: the panel scans out g_fbs[g.front]; the stages write the other */
static uint8_t g_fbs[2][(size_t)FW_STRIDE * FW_H] TDC_EXTRAM;
#define FB_BACK (g_fbs[g.front ^ 1u])
#define FW_BAND_STAGING TDC_LINK_STAGING_BAND_BYTES(FW_W, TDC_CFG_BAND_ROWS, FW_FULL_BPP)
#if TDC_CFG_ASSEMBLE
#define FW_ASM_STAGING (TDC_TILE_COUNT(FW_W, FW_H) * 4u)
#else
#define FW_ASM_STAGING ((size_t)0)
#endif
#define FW_STAGING_BYTES FW_MAX2(FW_MAX2(FW_BAND_STAGING, FW_ASM_STAGING), FW_FOV_PAYLOAD)
#else
static uint8_t g_fb[(size_t)FW_STRIDE * FW_H] TDC_EXTRAM;
#define FB_BACK g_fb
#define FW_STAGING_BYTES FW_MAX2((size_t)FW_W * FW_H * FW_FULL_BPP + TDC_LINK_STREAM_HEADER_BYTES, FW_FOV_PAYLOAD)
#endif
static uint8_t g_staging[FW_STAGING_BYTES] TDC_EXTRAM;

#if TDC_CFG_TRM
#define FW_RW TDC_REDUCED_DIM(FW_W, TDC_CFG_R_NUM, TDC_CFG_R_DEN)
#define FW_RH TDC_REDUCED_DIM(FW_H, TDC_CFG_R_NUM, TDC_CFG_R_DEN)
static uint8_t g_reduced[FW_EYES][(size_t)FW_RW * FW_RH * 3u] TDC_EXTRAM;
#define FW_TRM_BYTES TDC_ARENA_ROUND(TDC_TRM_MEM_BYTES(FW_W, FW_H, TDC_CFG_R_NUM, TDC_CFG_R_DEN))
#else
#define FW_TRM_BYTES ((size_t)0)
#endif
#if TDC_CFG_FOV_TRM
/* decoder buffers, TRM's arena, both grids' stage arenas (no TAA) */
#define FW_FOVTRM_STAGE_BYTES TDC_ARENA_ROUND(TDC_FOV_TRM_MEM_BYTES(FW_W, FW_H, FW_RW, FW_RH))
#define FW_FOVTRM_BYTES (FW_FOV_DEC_BYTES + FW_TRM_BYTES + FW_FOVTRM_STAGE_BYTES)
#else
#define FW_FOVTRM_BYTES ((size_t)0)
#endif

#if TDC_CFG_ASSEMBLE
static uint8_t g_subframe[FW_EYES][TDC_LINK_SUBFRAME_BYTES(FW_W, FW_H)] TDC_EXTRAM;
static int16_t g_sample_mv[FW_EYES][TDC_LINK_SAMPLE_MOTION_COUNT(FW_W, FW_H)] TDC_EXTRAM;
static uint8_t g_pattern[FW_EYES][TDC_PATTERN_BYTES(FW_W, FW_H)] TDC_EXTRAM;
#define FW_ASM_BYTES TDC_ARENA_ROUND(TDC_ASM_MEM_BYTES(FW_W, FW_H))
#else
#define FW_ASM_BYTES ((size_t)0)
#endif

/* One arena per eye for the stream's mode.  The foveation block holds the
 * decoder's FOVEATED buffers too: the decoder writes them only for a
 * FOVEATED packet, which it accepts only in a stream flagged FOVEATED, and
 * in such a stream configure_stream runs no assembly, and TRM only in the
 * foveated TRM block, whose TRM arena starts after those buffers (it
 * refuses FOVEATED with SUBFRAMES, and with REDUCED without
 * TDC_CFG_FOV_TRM), so they never overlap a live TRM or assembly state; a
 * stage's init starts from nothing it finds there. */
#define FW_MODE_BYTES FW_MAX2(FW_MAX2(FW_MAX2(FW_TRM_BYTES, FW_ASM_BYTES), FW_FOV_BYTES), FW_FOVTRM_BYTES)
#if TDC_CFG_TRM || TDC_CFG_ASSEMBLE || TDC_CFG_FOV
static uint64_t g_mode_arena[FW_EYES][FW_MODE_BYTES / 8u] TDC_EXTRAM;
#endif
#if TDC_CFG_FOV
#define FOV_DISK(e) ((uint8_t *)g_mode_arena[e])
#define FOV_LP(e) (FOV_DISK(e) + FW_FOV_DISK_BYTES)
#define FOV_MV(e) ((int16_t *)(void *)(FOV_LP(e) + FW_FOV_LP_BYTES))
#define FOV_STAGE(e) (FOV_DISK(e) + FW_FOV_DEC_BYTES)
#define FOV_LR_MEM(e) (FOV_STAGE(e) + FW_FOV_STAGE_BYTES)
#endif
#if TDC_CFG_FOV_TRM
#define FOVTRM_TRM(e) (FOV_DISK(e) + FW_FOV_DEC_BYTES)
#define FOVTRM_STAGE(e) (FOVTRM_TRM(e) + FW_TRM_BYTES)
#endif

#if TDC_CFG_LCD
static uint64_t g_lcd_arena[FW_EYES][TDC_LCD_MEM_BYTES_MODE_BITS(FW_W, FW_H, TDC_CFG_LCD_MODE, TDC_CFG_LCD_PREV_BITS) /
                                     8u] TDC_EXTRAM;
#endif

/* Transport chunk: what one USB bulk transfer (or semihosting read) brings. */
static uint8_t g_rx[16384];

/* ---- loop state ---- */
typedef enum { MODE_NONE = 0, MODE_PLAIN, MODE_TRM, MODE_ASSEMBLE, MODE_FOV } fw_mode_t;

#define KIND_BIT(k) (1u << (k))
/* The kinds that carry one eye's whole picture (one slot per eye and
 * frame, tdc_link.c): processed on arrival, never left for finish_frame. */
#define PICTURE_KINDS (KIND_BIT(TDC_LINK_KIND_FULL) | KIND_BIT(TDC_LINK_KIND_FOVEATED))

static struct {
    tdc_link_decoder_t dec;
    uint8_t mode;         /* fw_mode_t of the active stream */
    uint8_t have_frame;   /* a frame is being collected */
    uint8_t eyes_done;    /* bit e: eye e processed (or tried) for `frame` */
    uint8_t eyes_updated; /* bit e: eye e's image changed for `frame` */
    uint8_t kinds[2];     /* KIND_BIT()s received per eye for `frame` */
    uint32_t frame;
    uint8_t have_last;     /* a frame of this stream was finished ... */
    uint32_t last_frame;   /* ... and this was its index */
    uint32_t late_packets; /* packets for a frame already finished (ignored) */
    uint32_t frames_shown;
    uint32_t eyes_incomplete; /* eyes that kept their last frame */
    uint32_t unused_full;     /* FULL packets no mode of the stream uses (left in staging, never unpacked) */
    uint32_t stage_errors;    /* a stage refused a frame (status != TDC_OK) */
    uint32_t unsupported;     /* streams this build cannot run */
    uint32_t stream_repeats;  /* identical stream headers (late-joiner copies): no-ops */
    uint32_t late_full;       /* FULL packets of a finished frame: processed, shown with the next frame */
    uint8_t pending_updated;  /* eyes a late FULL updated since the last show: updated in the next one */
    uint8_t have_rej;         /* a pixel packet of a frame not started yet was rejected ... */
    uint32_t rej_frame;       /* ... for this frame ... */
    uint8_t rej_kinds[2];     /* ... these kinds, per eye (applied only if a good packet starts it) */
    uint8_t have_stream;      /* the configured stream's header, to recognise a repeat */
    uint16_t stream_id;
    tdc_link_stream_info_t stream;
#if TDC_CFG_BANDS
    uint8_t front;          /* g_fbs[front] is on the panel */
    uint32_t bands;         /* row bands taken */
    uint32_t band_drops;    /* pictures dropped whole (a bad or missing band): the eye kept its image */
    uint32_t eye_copies;    /* kept eyes copied front -> back before a swap */
    uint8_t bopen[2];       /* eye's picture in flight has its stages open */
    uint32_t bfinal[2];     /* ... and this many output rows (from the top) final */
    uint32_t lcd_resets;    /* LCD history reset: a picture dropped after LCD rows ran */
    uint32_t held_max[2];   /* rows a band leaves not final (FULL, REDUCED: full-res rows) */
    uint64_t held_sum[2];
    uint32_t held_n[2];
#endif
#if TDC_CFG_TRM
    tdc_trm_t trm[FW_EYES];
#endif
#if TDC_CFG_FOV
    tdc_fov_t fov[FW_EYES];
    tdc_fov_lr_t fov_lr[FW_EYES];
    uint8_t fov_have;        /* bit e: fov_last[e] is eye e's last frame through the stage */
    uint32_t fov_last[2];
    uint32_t fov_dt_us;      /* frame time at the panel's rate (eq. 4.7) */
    uint32_t fov_frames;     /* foveated eye-frames composed */
    uint32_t fov_resets;     /* TAA histories forgotten: a gap in the eye's frames, a refusal or a FULL picture */
#endif
#if TDC_CFG_FOV_TRM
    tdc_fov_trm_t fovtrm[FW_EYES];
    uint8_t fovtrm_on;          /* MODE_TRM stream flagged FOVEATED: its slots may come foveated */
    uint32_t fovtrm_frames[2];  /* foveated pictures composed: full slot, reduced slot */
#endif
#if TDC_CFG_ASSEMBLE
    tdc_asm_t as[FW_EYES];
    uint32_t asm_skipped; /* frames behind assembly's counter */
    uint32_t asm_resyncs; /* joined mid-stream / too far ahead: assembly restarted at the frame */
#endif
#if TDC_CFG_LCD
    tdc_lcd_t lcd[FW_EYES];
    uint8_t lcd_ok;
#endif
} g;

/* ---- small text helpers for the log (no printf in firmware) ---- */
static void log_kv(const char *what, uint32_t v)
{
    char line[96];
    char *end = line + sizeof line - 1;
    char *o = tdc_text_str(line, end, what);
    o = tdc_text_u32(o, end, v);
    *o = 0;
    tdc_board_log(line);
}

static const char *reset_name(tdc_reset_cause_t c)
{
    static const char *const names[] = {"unknown", "power-on", "pin", "software", "watchdog", "brown-out", "low-power"};
    return (unsigned)c < sizeof names / sizeof names[0] ? names[c] : "unknown";
}

/* ---- stream configuration ---- */
#if TDC_CFG_TRM || TDC_CFG_LCD || TDC_CFG_FOV
/* The refresh rate the panel runs a stream at: the stream's if the panel
 * has that rate, else the panel's nominal one. */
static uint16_t panel_hz(const tdc_panel_t *panel, uint16_t stream_hz)
{
    uint16_t hz = panel->refresh_hz;
    for (unsigned i = 0; i < TDC_PANEL_MAX_RATES && panel->rates_hz[i]; i++) {
        if (panel->rates_hz[i] == stream_hz) {
            hz = stream_hz;
        }
    }
    return hz;
}
#endif

static void configure_stream(void)
{
    const tdc_link_stream_info_t *si = tdc_link_stream(&g.dec);
    const tdc_panel_t *panel = &TDC_PANEL_SYMBOL;
    (void)panel;
    g.mode = MODE_NONE;
#if TDC_CFG_FOV_TRM
    g.fovtrm_on = 0;
#endif
    g.have_frame = 0;
    g.have_last = 0;
    g.have_rej = 0;
    g.have_stream = 0;
    if (!si) {
        return;
    }
    g.stream = *si;
    g.stream_id = g.dec.stream_id;
    g.have_stream = 1;
    const int reduced = (si->flags & TDC_LINK_STREAM_REDUCED) != 0;
    const int subframes = (si->flags & TDC_LINK_STREAM_SUBFRAMES) != 0;
    const int bands = (si->flags & TDC_LINK_STREAM_BANDS) != 0;
    const int fov = (si->flags & TDC_LINK_STREAM_FOVEATED) != 0;
    if (bands != TDC_CFG_BANDS && (bands || (size_t)FW_W * FW_H * 3u + TDC_LINK_STREAM_HEADER_BYTES > sizeof g_staging)) {
        /* bands need the front/back pair (a single buffer would show a
         * dropped picture's first bands); a build staging one band cannot
         * take whole pictures */
        tdc_board_log(bands ? "stream sends row bands: this build has no back buffer (TDC_CFG_BANDS)"
                            : "stream sends whole pictures: this build stages one row band (TDC_CFG_BANDS)");
        g.unsupported++;
        return;
    }
    if ((reduced && subframes) || (fov && subframes) || (fov && reduced && !TDC_CFG_FOV_TRM)) {
        tdc_board_log(fov ? (subframes ? "stream foveates assembly frames: not supported by this build"
                                       : "stream foveates TRM frames: not in this build (TDC_CFG_FOV_TRM)")
                          : "stream uses TRM and tile assembly together: not supported by this build");
        g.unsupported++;
        return;
    }
    if (reduced) {
#if TDC_CFG_TRM
        /* foveated TRM: TRM's arena after the decoder's FOVEATED buffers,
         * the two grids' stage arenas after it (a plain TRM stream: TRM's
         * arena at the start of the mode arena, nothing else) */
        uint8_t *trm_mem[FW_EYES];
        size_t trm_bytes = sizeof g_mode_arena[0];
        int fovtrm = 0;
        for (uint32_t e = 0; e < FW_EYES; e++) {
            trm_mem[e] = (uint8_t *)g_mode_arena[e];
        }
#if TDC_CFG_FOV_TRM
        if (fov) {
            uint32_t rw = 0, rh = 0;
            tdc_link_reduced_size(&g.dec, &rw, &rh);
            const size_t need = tdc_fov_trm_get_size((uint16_t)FW_W, (uint16_t)FW_H, (uint16_t)rw, (uint16_t)rh);
            for (uint32_t e = 0; e < FW_EYES; e++) {
                if (need == 0 || need > FW_FOVTRM_STAGE_BYTES ||
                    tdc_fov_trm_init(&g.fovtrm[e], (uint16_t)FW_W, (uint16_t)FW_H, (uint16_t)rw, (uint16_t)rh,
                                     FOVTRM_STAGE(e), FW_FOVTRM_STAGE_BYTES) != TDC_OK) {
                    tdc_board_log("foveation stage refused the foveated TRM stream (size)");
                    g.unsupported++;
                    return;
                }
                trm_mem[e] = FOVTRM_TRM(e);
            }
            trm_bytes = FW_TRM_BYTES;
            fovtrm = 1;
        }
#endif
        for (uint32_t e = 0; e < FW_EYES; e++) {
            tdc_trm_config_t cfg;
            /* the rate the panel really runs: the stream's if the panel
             * has it, else the panel's own (a 60 Hz panel refuses TRM
             * whatever the stream claims) */
            tdc_trm_default_config(&cfg, (uint16_t)FW_W, (uint16_t)FW_H, panel_hz(panel, si->refresh_hz));
            cfg.r_num = si->r_num;
            cfg.r_den = si->r_den;
            cfg.reduced_in_stream = 1;
            cfg.keep_residual = 0; /* rho recomputed from the kept codes: 4.5 B/px, docs/boards.md */
            const size_t need = tdc_trm_get_size(&cfg);
            if (need == 0 || need > trm_bytes || tdc_trm_init(&g.trm[e], &cfg, panel, trm_mem[e], trm_bytes) != TDC_OK) {
                tdc_board_log("TRM refused the stream (ratio, refresh or size): frames keep the last image");
                g.unsupported++;
                return;
            }
        }
        g.mode = MODE_TRM;
#if TDC_CFG_FOV_TRM
        g.fovtrm_on = (uint8_t)fovtrm;
#endif
        (void)fovtrm;
#endif
    } else if (subframes) {
#if TDC_CFG_ASSEMBLE
        for (uint32_t e = 0; e < FW_EYES; e++) {
            const tdc_asm_config_t cfg = {(uint16_t)FW_W, (uint16_t)FW_H};
            const size_t need = tdc_asm_get_size(&cfg);
            if (need == 0 || need > sizeof g_mode_arena[e] ||
                tdc_asm_init(&g.as[e], &cfg, g_mode_arena[e], sizeof g_mode_arena[e]) != TDC_OK) {
                tdc_board_log("tile assembly refused the stream (size)");
                g.unsupported++;
                return;
            }
        }
        g.mode = MODE_ASSEMBLE;
#endif
    } else if (fov) {
#if TDC_CFG_FOV
        const tdc_fov_config_t cfg = {(uint16_t)FW_W, (uint16_t)FW_H, (uint8_t)TDC_CFG_FOV_TAA};
        for (uint32_t e = 0; e < FW_EYES; e++) {
            const size_t need = tdc_fov_get_size(&cfg);
            if (need == 0 || need > FW_FOV_STAGE_BYTES ||
                tdc_fov_init(&g.fov[e], &cfg, FOV_STAGE(e), FW_FOV_STAGE_BYTES) != TDC_OK ||
                tdc_fov_lr_init(&g.fov_lr[e], (uint16_t)FW_W, FOV_LR_MEM(e), FW_FOV_LR_BYTES) != TDC_OK ||
                tdc_fov_lr_attach(&g.fov[e], &g.fov_lr[e]) != TDC_OK) {
                tdc_board_log("foveation stage refused the panel (size)");
                g.unsupported++;
                return;
            }
        }
        const uint32_t hz = panel_hz(panel, si->refresh_hz);
        g.fov_dt_us = hz ? 1000000u / hz : 0u;
        g.fov_have = 0;
        g.mode = MODE_FOV;
#else
        /* (the decoder, which has no foveation buffers here, refused it already) */
        tdc_board_log("stream is foveated: this build has no foveation stage (STAGES=fov)");
        g.unsupported++;
        return;
#endif
    } else {
        g.mode = MODE_PLAIN;
    }
#if TDC_CFG_LCD
    /* The overdrive model is per refresh rate: the stream's if the panel
     * has it, else the panel's nominal one. */
    const uint16_t hz = panel_hz(panel, si->refresh_hz);
    g.lcd_ok = 1;
    for (uint32_t e = 0; e < FW_EYES; e++) {
        tdc_lcd_config_t cfg = {(uint16_t)FW_W, (uint16_t)FW_H, hz, TDC_CFG_LCD_MODE, (uint8_t)TDC_CFG_LCD_PREV_BITS};
        tdc_status_t st = tdc_lcd_init(&g.lcd[e], &cfg, panel, g_lcd_arena[e], sizeof g_lcd_arena[e]);
        if (st == TDC_ERR_PANEL && cfg.mode != TDC_LCD_MODE_EXACT) {
            cfg.mode = TDC_LCD_MODE_EXACT;
            st = tdc_lcd_init(&g.lcd[e], &cfg, panel, g_lcd_arena[e], sizeof g_lcd_arena[e]);
        }
        if (st != TDC_OK) {
            tdc_board_log("LCD inverse refused the panel profile: drive = wanted code");
            g.lcd_ok = 0;
        }
    }
#endif
}

/* ---- per-eye pipeline ---- */
static int fovtrm_on(void)
{
#if TDC_CFG_FOV_TRM
    return g.fovtrm_on;
#else
    return 0;
#endif
}

static uint32_t kinds_needed(uint32_t eye, uint32_t frame)
{
    switch (g.mode) {
    case MODE_TRM:
        /* the slot due; in a foveated TRM stream it may come FOVEATED (the
         * decoder checked that the packet's slot is the one due) */
        return KIND_BIT(tdc_link_trm_kind(frame, eye)) | (fovtrm_on() ? KIND_BIT(TDC_LINK_KIND_FOVEATED) : 0u);
    case MODE_ASSEMBLE: {
        const tdc_link_stream_info_t *si = tdc_link_stream(&g.dec);
        return KIND_BIT(TDC_LINK_KIND_SUBFRAME) |
               ((si && (si->flags & TDC_LINK_STREAM_SAMPLE_MV)) ? KIND_BIT(TDC_LINK_KIND_MOTION) : 0u);
    }
    case MODE_PLAIN: return KIND_BIT(TDC_LINK_KIND_FULL);
    case MODE_FOV: return PICTURE_KINDS; /* either fills the eye's picture slot */
    default: return 0u;
    }
}

#if TDC_CFG_ASSEMBLE
/* Assembly runs frames in order; frames without a subframe are assembled
 * from history (up to 64 behind, beyond that the frame is skipped). */
static int assemble_eye(uint32_t e, uint32_t frame, uint32_t kinds)
{
    tdc_asm_t *st = &g.as[e];
    if (frame < st->next_frame) {
        g.asm_skipped++;
        return 0;
    }
    if (frame - st->next_frame > 64u) {
        /* a late joiner (or a board reset mid-stream, or a long gap): the
         * history is gone either way; restart assembly at this frame */
        const tdc_asm_config_t cfg = {(uint16_t)FW_W, (uint16_t)FW_H};
        if (tdc_asm_init(st, &cfg, g_mode_arena[e], sizeof g_mode_arena[e]) != TDC_OK) {
            return 0;
        }
        tdc_asm_start_at(st, frame);
        g.asm_resyncs++;
    }
    while (st->next_frame < frame) {
        if (tdc_asm_assemble(st, st->next_frame) != TDC_OK) {
            return 0;
        }
    }
    if (kinds & KIND_BIT(TDC_LINK_KIND_SUBFRAME)) {
        const int16_t *mv = (kinds & KIND_BIT(TDC_LINK_KIND_MOTION)) ? g_sample_mv[e] : NULL;
        const uint8_t *bits = (kinds & KIND_BIT(TDC_LINK_KIND_PATTERN)) ? g_pattern[e] : NULL;
        if (tdc_asm_ingest(st, frame, g_subframe[e], mv, bits) != TDC_OK) {
            return 0;
        }
    }
    if (tdc_asm_assemble(st, frame) != TDC_OK) {
        return 0;
    }
    int stride = 0;
    const uint8_t *out = tdc_asm_output(st, &stride);
    for (uint32_t y = 0; y < FW_H; y++) {
        memcpy(FB_BACK + (size_t)y * FW_STRIDE + (size_t)e * FW_W * 3u, out + (size_t)y * (uint32_t)stride, FW_W * 3u);
    }
    return 1;
}
#endif

#if TDC_CFG_FOV
/* Forgets eye e's TAA history (its next foveated frame is taken as is). */
static void fov_forget(uint32_t e)
{
    if (g.fov_have & (1u << e)) {
        g.fov_resets++;
    }
    g.fov_have = (uint8_t)(g.fov_have & ~(1u << e));
    tdc_fov_reset(&g.fov[e]);
}

/* The FOVEATED packet tdc_link_feed() just returned for eye e of `frame`:
 * the samples and (TAA) vectors wait in the eye's foveation block, the
 * disk pixels in its disk frame; the stage remaps them into the eye's part
 * of the frame buffer (nothing written if it refuses).  Peripheral TAA
 * runs on packets that carry vectors (TDC_FOV_FLAG_MV), from a history
 * that is the eye's previous frame: after a lost, refused or late frame,
 * a FULL picture or a packet without vectors it is forgotten (the frame is
 * composed as the stage without TAA composes it), never applied later. */
static tdc_status_t fov_eye(uint32_t e, uint32_t frame, uint8_t *fb)
{
    const tdc_fov_hdr_t *h = tdc_link_fov(&g.dec, e);
    if (!h) {
        return TDC_ERR_STATE;
    }
    const int taa = (h->flags & TDC_FOV_FLAG_MV) != 0; /* the sender asks for TAA by sending vectors */
    if (!taa || !(g.fov_have & (1u << e)) || frame != g.fov_last[e] + 1u) {
        fov_forget(e);
    }
    const tdc_status_t st = tdc_fov_frame(&g.fov[e], &h->p, FOV_LP(e), (size_t)h->p.lp_w * 3u, taa ? FOV_MV(e) : NULL,
                                          (size_t)h->p.lp_w * 2u, FOV_DISK(e), (size_t)FW_W * 3u, g.fov_dt_us, fb,
                                          FW_STRIDE);
    if (st == TDC_OK && taa) {
        g.fov_have = (uint8_t)(g.fov_have | (1u << e));
        g.fov_last[e] = frame;
    } else if (st != TDC_OK) {
        fov_forget(e);
    }
    if (st == TDC_OK) {
        g.fov_frames++;
    }
    return st;
}
#endif

#if TDC_CFG_FOV_TRM
/* The FOVEATED packet tdc_link_feed() just returned for eye e of `frame` in
 * a foveated TRM stream: its slot is the one TRM's schedule has due (the
 * decoder refused any other).  tdc_fov_trm remaps the slot's picture in
 * place -- the full slot's disk frame (W x H) or the reduced slot's
 * picture g_reduced[e] (rW x rH), where the decoder left the disk pixels --
 * then TRM runs on it as on a FULL or REDUCED picture, writing the eye's
 * part of the frame buffer.  A refusal by the stage writes nothing there
 * (counted as a stage error); TRM's sequencing then shows the next reduced
 * frame without residual, as after a lost full frame. */
static tdc_status_t fovtrm_eye(uint32_t e, uint32_t frame, uint8_t *fb)
{
    const tdc_fov_hdr_t *h = tdc_link_fov(&g.dec, e);
    const int red = tdc_link_trm_kind(frame, e) == TDC_LINK_KIND_REDUCED;
    uint32_t rw = 0, rh = 0;
    tdc_link_reduced_size(&g.dec, &rw, &rh);
    if (!h) {
        return TDC_ERR_STATE;
    }
    uint8_t *pic = red ? g_reduced[e] : FOV_DISK(e);
    const uint32_t stride = red ? rw * 3u : FW_W * 3u;
    tdc_status_t st = tdc_fov_trm_frame(&g.fovtrm[e], h, red, FOV_LP(e), pic, stride);
    if (st != TDC_OK) {
        return st;
    }
    g.fov_frames++;
    g.fovtrm_frames[red]++;
    return red ? tdc_trm_reduced_seq(&g.trm[e], pic, stride, fb, FW_STRIDE, frame)
               : tdc_trm_full_seq(&g.trm[e], pic, stride, fb, FW_STRIDE, frame);
}
#endif

/* Runs the pipeline of eye e on what arrived; returns 1 if the eye's part of
 * the frame buffer was updated. */
static int process_eye_kinds(uint32_t e, uint32_t frame, uint32_t kinds)
{
    uint8_t *fb = FB_BACK + (size_t)e * FW_W * 3u;
    tdc_res_t *residual = NULL;
    tdc_status_t st = TDC_OK;
    (void)fb;
    (void)frame;
    switch (g.mode) {
    case MODE_PLAIN:
        if (!(kinds & KIND_BIT(TDC_LINK_KIND_FULL))) {
            return 0;
        }
        break;
#if TDC_CFG_TRM
    case MODE_TRM:
        /* The frame index ties a reduced frame to the full frame before it:
         * if that one was lost, rejected or out of order (or this is the
         * stream's start), the reduced frame is shown without residual,
         * never with stale state (tdc_trm_reduced_seq). */
        if (kinds & KIND_BIT(TDC_LINK_KIND_FOVEATED)) {
#if TDC_CFG_FOV_TRM
            st = fovtrm_eye(e, frame, fb);
#else
            return 0; /* (unreachable: needed only in a foveated TRM stream) */
#endif
        } else if (kinds & KIND_BIT(TDC_LINK_KIND_FULL)) {
            st = tdc_trm_full_seq(&g.trm[e], fb, FW_STRIDE, fb, FW_STRIDE, frame); /* in place: D(I) is taken first */
        } else if (kinds & KIND_BIT(TDC_LINK_KIND_REDUCED)) {
            uint32_t rw = 0, rh = 0;
            tdc_link_reduced_size(&g.dec, &rw, &rh);
            st = tdc_trm_reduced_seq(&g.trm[e], g_reduced[e], rw * 3u, fb, FW_STRIDE, frame);
        } else {
            return 0;
        }
        /* NULL (rho is recomputed, not stored): the LCD inverse drops the
         * light it cannot reach and counts it (tdc_lcd_stats_t) */
        residual = tdc_trm_residual(&g.trm[e]);
        break;
#endif
#if TDC_CFG_FOV
    case MODE_FOV:
        if (kinds & KIND_BIT(TDC_LINK_KIND_FOVEATED)) {
            st = fov_eye(e, frame, fb);
        } else if (kinds & KIND_BIT(TDC_LINK_KIND_FULL)) {
            fov_forget(e); /* a whole picture: shown as it is, the history no longer matches it */
        } else {
            return 0;
        }
        break;
#endif
#if TDC_CFG_ASSEMBLE
    case MODE_ASSEMBLE:
        if (!assemble_eye(e, frame, kinds)) {
            g.stage_errors++;
            return 0;
        }
        break;
#endif
    default: return 0;
    }
    if (st != TDC_OK) {
        g.stage_errors++;
        return 0;
    }
#if TDC_CFG_LCD
    if (g.lcd_ok && tdc_lcd_frame(&g.lcd[e], fb, FW_STRIDE, fb, FW_STRIDE, residual) != TDC_OK) {
        g.stage_errors++;
    }
#endif
    (void)residual;
    return 1;
}

/* The FULL packet tdc_link_feed() just returned, for eye e: unpacked from
 * staging into the eye's part of the frame buffer, then processed.  Returns
 * 1 if the frame buffer changed (a stage error after the unpack is counted
 * by process_eye_kinds and still leaves the eye changed). */
static int process_full(uint32_t e, uint32_t frame)
{
    if (tdc_link_unpack_full(&g.dec, FB_BACK + (size_t)e * FW_W * 3u, FW_STRIDE) != TDC_OK) {
        g.stage_errors++;
        return 0;
    }
    (void)process_eye_kinds(e, frame, KIND_BIT(TDC_LINK_KIND_FULL));
    return 1;
}

/* The picture packet (FULL or FOVEATED) tdc_link_feed() just returned, for
 * eye e: returns 1 if the frame buffer changed.  A FOVEATED frame the stage
 * refuses leaves the eye's image as it was (the stage writes nothing; the
 * refusal is counted in stage_errors and 0 returned). */
static int process_picture(uint32_t e, uint32_t frame, uint32_t kind)
{
    if (kind == TDC_LINK_KIND_FULL) {
        return process_full(e, frame);
    }
    return process_eye_kinds(e, frame, KIND_BIT(kind));
}

static int process_eye(uint32_t e, uint32_t frame)
{
    return process_eye_kinds(e, frame, g.kinds[e]);
}

static void show_frame(void)
{
#if TDC_CFG_BANDS
    /* an eye not updated keeps its last shown image: the front's, copied
     * into the back before the swap (the back may hold a dropped picture) */
    for (uint32_t e = 0; e < FW_EYES; e++) {
        if (!(g.eyes_updated & (1u << e))) {
            const size_t off = (size_t)e * FW_W * 3u;
            for (uint32_t y = 0; y < FW_H; y++) {
                memcpy(FB_BACK + (size_t)y * FW_STRIDE + off, g_fbs[g.front] + (size_t)y * FW_STRIDE + off, FW_W * 3u);
            }
            g.eye_copies++;
        }
    }
    g.front ^= 1u;
    (void)tdc_board_panel_show(g_fbs[g.front], FW_STRIDE, FW_EYES * FW_W, FW_H, g.frame);
#else
    (void)tdc_board_panel_show(g_fb, FW_STRIDE, FW_EYES * FW_W, FW_H, g.frame);
#endif
    tdc_board_vsync_wait();
    g.frames_shown++;
}

/* Ends the frame being collected: eyes still missing something are
 * processed with what arrived (or keep their last image); the frame is shown
 * if any eye changed.  A FULL packet is processed on arrival (its payload
 * is in staging only until the next feed), so only assembly eyes are left
 * here. */
static void finish_frame(void)
{
    if (!g.have_frame) {
        return;
    }
    g.have_frame = 0;
    g.have_last = 1;
    g.last_frame = g.frame;
    for (uint32_t e = 0; e < FW_EYES; e++) {
        if (!(g.eyes_done & (1u << e)) && (g.kinds[e] & ~PICTURE_KINDS) && process_eye(e, g.frame)) {
            g.eyes_updated = (uint8_t)(g.eyes_updated | (1u << e));
        }
        if (!(g.eyes_updated & (1u << e))) {
            g.eyes_incomplete++;
        }
    }
    if (g.eyes_updated) {
        show_frame();
    }
}

static void start_frame(uint32_t frame)
{
    finish_frame();
    g.have_frame = 1;
    g.frame = frame;
    g.eyes_done = 0;
    g.eyes_updated = g.pending_updated; /* a late FULL's eye: changed since the last show */
    g.pending_updated = 0;
    g.kinds[0] = g.kinds[1] = 0;
    if (g.have_rej && g.rej_frame == frame) {
        /* rejected earlier for this frame: those eyes keep their image */
        for (uint32_t e = 0; e < FW_EYES; e++) {
            if (g.rej_kinds[e] & kinds_needed(e, frame)) {
                g.eyes_done = (uint8_t)(g.eyes_done | (1u << e));
            }
        }
    }
    if (g.have_rej && g.rej_frame <= frame) {
        g.have_rej = 0;
    }
}

static void eye_done(uint32_t e)
{
    g.eyes_done = (uint8_t)(g.eyes_done | (1u << e));
    if (g.eyes_done == (1u << FW_EYES) - 1u) {
        finish_frame(); /* every eye had what it needs (or lost it): show now */
    }
}

#if TDC_CFG_BANDS
/* Eye e's picture in flight was dropped: rows the LCD inverse already ran
 * hold that picture's history, so the eye's LCD starts again without
 * history (never from a mixed one); TRM's kept state was invalidated when
 * the full frame began (tdc_trm_full_begin), a reduced frame keeps none. */
static void band_abandon(uint32_t e)
{
    if (e >= FW_EYES || !g.bopen[e]) {
        return;
    }
    g.bopen[e] = 0;
#if TDC_CFG_LCD
    if (g.lcd_ok && g.bfinal[e] > 0u) {
        tdc_lcd_reset(&g.lcd[e]);
        g.lcd_resets++;
    }
#endif
}

/* The stages a band lets run, in the eye's part of the back buffer: TRM's
 * full-res path (D rows as its kernel rows arrive, then the output rows
 * whose U rows are done) or reduced path (output rows whose reduced rows
 * are there), then the LCD inverse on the rows that became final.  The
 * last band closes the frame of each stage and completes the eye. */
static void band_stages(uint32_t e, uint32_t kind, const tdc_band_hdr_t *bh)
{
    uint8_t *fb = FB_BACK + (size_t)e * FW_W * 3u;
    (void)fb; /* a build without TRM and LCD only unpacks */
    const int last = bh->index + 1u == bh->count;
    const uint32_t avail = (uint32_t)bh->first_row + bh->rows;
    uint32_t done = avail, covered = avail; /* output rows final; output rows the arrived rows cover */
    tdc_status_t st = TDC_OK;
    tdc_res_t *residual = NULL;
    if (bh->index == 0u) {
        g.bopen[e] = 1;
        g.bfinal[e] = 0;
    }
    switch (g.mode) {
    case MODE_PLAIN:
        break;
#if TDC_CFG_FOV
    case MODE_FOV: /* a FULL picture in a foveated stream: shown as it is */
        if (bh->index == 0u) {
            fov_forget(e);
        }
        break;
#endif
#if TDC_CFG_TRM
    case MODE_TRM: {
        tdc_trm_t *t = &g.trm[e];
        if (kind == TDC_LINK_KIND_FULL) {
            if (bh->index == 0u) {
                st = tdc_trm_full_begin(t, fb, FW_STRIDE, fb, FW_STRIDE); /* in place: D reads a row before it is written */
            }
            if (st == TDC_OK) {
                st = last ? tdc_trm_full_end(t, g.frame) : tdc_trm_full_rows(t, avail, &done);
            }
        } else {
            uint32_t rw = 0, rh = 0;
            tdc_link_reduced_size(&g.dec, &rw, &rh);
            if (bh->index == 0u) {
                st = tdc_trm_reduced_begin(t, g_reduced[e], rw * 3u, fb, FW_STRIDE, g.frame);
            }
            if (st == TDC_OK) {
                st = last ? tdc_trm_reduced_end(t) : tdc_trm_reduced_rows(t, avail, &done);
            }
            covered = rh ? (uint32_t)(((uint64_t)avail * FW_H) / rh) : FW_H;
        }
        residual = tdc_trm_residual(t);
        break;
    }
#endif
    default: st = TDC_ERR_STATE; break;
    }
    if (last) {
        done = covered = FW_H;
    }
    if (st != TDC_OK) {
        g.stage_errors++;
        band_abandon(e);
        eye_done(e);
        return;
    }
#if TDC_CFG_LCD
    if (g.lcd_ok && done > g.bfinal[e] &&
        tdc_lcd_rows(&g.lcd[e], fb, FW_STRIDE, fb, FW_STRIDE, residual, g.bfinal[e], done) != TDC_OK) {
        g.stage_errors++;
    }
#endif
    (void)residual;
    g.bfinal[e] = done;
    const uint32_t k = kind == TDC_LINK_KIND_FULL ? 0u : 1u, held = covered > done ? covered - done : 0u;
    g.held_max[k] = held > g.held_max[k] ? held : g.held_max[k];
    g.held_sum[k] += held;
    g.held_n[k]++;
    if (last) {
#if TDC_CFG_LCD
        if (g.lcd_ok) {
            tdc_lcd_frame_done(&g.lcd[e]);
        }
#endif
        g.bopen[e] = 0;
        g.eyes_updated = (uint8_t)(g.eyes_updated | (1u << e));
        eye_done(e);
    }
}
#endif

/* A pixel packet of the current or a later frame failed its payload CRC:
 * that eye keeps its image for this frame.  A rejected packet never moves
 * the loop's notion of time (its frame index is not trusted: only the
 * header CRC vouched for it): for the current frame the eye is done; for a
 * later one this is remembered and applied only if an accepted packet
 * starts that frame. */
static void on_rejected(const tdc_link_event_t *ev)
{
    /* a band's CRC error: the decoder reports the drop of the picture it
     * names (BAND_DROPPED), which is what counts here */
    /* (a foveation header refused after its payload CRC matched: the frame
     * index is vouched for, the picture lost the same way) */
    const int lost = (ev->error == TDC_LINK_ERR_CRC && !(ev->flags & TDC_LINK_PKT_BAND)) ||
                     ev->error == TDC_LINK_ERR_BAND_DROPPED || ev->error == TDC_LINK_ERR_FOVEATION;
    if (ev->error == TDC_LINK_ERR_STREAM_HEADER) {
        /* a stream header the decoder refused after its CRC matched: a
         * stage the stream needs is not in this build (no buffer for it),
         * or the header is invalid; nothing of that stream is shown */
        tdc_board_log("stream header refused by the decoder: a stage it needs is not in this build, or invalid");
        g.unsupported++;
        return;
    }
#if TDC_CFG_BANDS
    if (ev->error == TDC_LINK_ERR_BAND_DROPPED) {
        g.band_drops++;
        band_abandon(ev->eye);
    }
#endif
    if (g.mode == MODE_NONE || !lost || ev->eye >= FW_EYES ||
        (g.have_frame && ev->frame_index < g.frame) || (g.have_last && ev->frame_index <= g.last_frame)) {
        return;
    }
    if (g.have_frame && ev->frame_index == g.frame) {
        const uint32_t need = kinds_needed(ev->eye, g.frame);
        if ((need & KIND_BIT(ev->kind)) && !(g.eyes_done & (1u << ev->eye))) {
            eye_done(ev->eye);
        }
        return;
    }
    if (!g.have_rej || g.rej_frame != ev->frame_index) {
        /* one frame ahead is all a real loss needs; a newer claim replaces
         * an older one (both unverified) */
        g.have_rej = 1;
        g.rej_frame = ev->frame_index;
        g.rej_kinds[0] = g.rej_kinds[1] = 0;
    }
    if (ev->kind <= 7u) {
        g.rej_kinds[ev->eye] = (uint8_t)(g.rej_kinds[ev->eye] | KIND_BIT(ev->kind));
    }
}

/* A FULL (or FOVEATED) packet the decoder accepted for an eye of the frame
 * the loop finished last (rejected first, then resent intact): processed
 * now, so TRM pairs the next reduced frame with it, and shown with the next
 * frame, in which that eye counts as updated (pending_updated). */
static void late_full(uint32_t e, uint32_t frame, uint32_t kind)
{
    g.late_full++;
    if ((kinds_needed(e, frame) & KIND_BIT(kind)) && process_picture(e, frame, kind)) {
        g.pending_updated = (uint8_t)(g.pending_updated | (1u << e));
    }
}

/* A row band of the current frame (FULL or REDUCED, due for its eye): a
 * FULL band is unpacked at its rows of the eye's part of the back buffer
 * (the decoder wrote a REDUCED band into g_reduced itself), then the
 * stages run on what it completes (band_stages). */
#if TDC_CFG_BANDS
static void band_work(const tdc_link_event_t *ev)
{
    const uint32_t e = ev->eye;
    const tdc_band_hdr_t *bh = tdc_link_band(&g.dec, e);
    g.bands++;
    if (!bh || (g.eyes_done & (1u << e)) || (bh->index > 0u && !g.bopen[e])) {
        return;
    }
    if (ev->kind == TDC_LINK_KIND_FULL && tdc_link_unpack_full(&g.dec, FB_BACK + (size_t)e * FW_W * 3u, FW_STRIDE) != TDC_OK) {
        g.stage_errors++;
        return;
    }
    /* (g.kinds stays clear: finish_frame must never run an eye's stages
     * on a picture whose bands did not all come) */
    band_stages(e, ev->kind, bh);
}
/* What a band's event costs, from the decoder's event to its pixels being
 * final, by kind: separate functions so an instruction count can take
 * them apart (host: valgrind --toggle-collect, docs/boards.md). */
void tdc_fw_band_full(const tdc_link_event_t *ev);
void tdc_fw_band_reduced(const tdc_link_event_t *ev);
__attribute__((noinline)) void tdc_fw_band_full(const tdc_link_event_t *ev)
{
    band_work(ev);
}
__attribute__((noinline)) void tdc_fw_band_reduced(const tdc_link_event_t *ev)
{
    band_work(ev);
}
#endif

static void on_band(const tdc_link_event_t *ev)
{
#if TDC_CFG_BANDS
    if (ev->kind == TDC_LINK_KIND_FULL) {
        tdc_fw_band_full(ev);
    } else {
        tdc_fw_band_reduced(ev);
    }
#else
    (void)ev; /* configure_stream refuses band streams without a back buffer */
#endif
}

static int same_stream(const tdc_link_event_t *ev)
{
    const tdc_link_stream_info_t *si = tdc_link_stream(&g.dec);
    return g.have_stream && si && ev->stream_id == g.stream_id && g.stream.flags == si->flags &&
           g.stream.r_num == si->r_num && g.stream.r_den == si->r_den && g.stream.width == si->width &&
           g.stream.height == si->height && g.stream.eyes == si->eyes && g.stream.refresh_hz == si->refresh_hz;
}

static void on_packet(const tdc_link_event_t *ev)
{
    if (ev->kind == TDC_LINK_KIND_STREAM) {
        if (g.mode != MODE_NONE && same_stream(ev)) {
            g.stream_repeats++; /* the late joiners' copy: nothing changes */
            return;
        }
        finish_frame();
        configure_stream();
        return;
    }
    if (g.mode == MODE_NONE || ev->eye >= FW_EYES) {
        return;
    }
    const int band = (ev->flags & TDC_LINK_PKT_BAND) != 0;
    if (!g.have_frame && g.have_last && ev->frame_index <= g.last_frame) {
        /* (a band of a finished frame: its picture is not whole; ignored) */
        /* (a late foveated reduced slot is ignored as a late REDUCED is) */
        const int fov_reduced = ev->kind == TDC_LINK_KIND_FOVEATED && (ev->flags & TDC_LINK_PKT_FOV_REDUCED);
        if ((KIND_BIT(ev->kind) & PICTURE_KINDS) && ev->frame_index == g.last_frame && !band && !fov_reduced) {
            late_full(ev->eye, ev->frame_index, ev->kind);
        } else {
            g.late_packets++; /* its frame was shown already (or dropped) */
        }
        return;
    }
    const uint32_t e = ev->eye;
    if ((KIND_BIT(ev->kind) & PICTURE_KINDS) && !(kinds_needed(e, ev->frame_index) & KIND_BIT(ev->kind))) {
        g.unused_full++; /* e.g. in an assembly stream: left in staging, time not moved */
        return;
    }
    if (!g.have_frame || ev->frame_index != g.frame) {
        start_frame(ev->frame_index);
    }
    if (band) {
        on_band(ev);
        return;
    }
    g.kinds[e] = (uint8_t)(g.kinds[e] | KIND_BIT(ev->kind));
    if (KIND_BIT(ev->kind) & PICTURE_KINDS) {
        /* the eye's whole need (plain, TRM's full slot, foveated); also
         * when it was rejected first and resent intact before the frame
         * finished */
        if (process_picture(e, g.frame, ev->kind)) {
            g.eyes_updated = (uint8_t)(g.eyes_updated | (1u << e));
        }
        if (!(g.eyes_done & (1u << e))) {
            eye_done(e);
        }
        return;
    }
    /* assembly needs every kind it names; TRM one of its slot's (REDUCED,
     * or FOVEATED: a picture kind, processed above) */
    const uint32_t need = kinds_needed(e, g.frame) & ~PICTURE_KINDS;
    if (!(g.eyes_done & (1u << e)) && need && (g.kinds[e] & need) == need) {
        if (process_eye(e, g.frame)) {
            g.eyes_updated = (uint8_t)(g.eyes_updated | (1u << e));
        }
        eye_done(e);
    }
}

static void decoder_init(void)
{
    tdc_link_config_t cfg = {(uint16_t)FW_W, (uint16_t)FW_H, (uint8_t)FW_EYES};
    tdc_link_buffers_t b = {0};
    b.staging = g_staging;
    b.staging_bytes = sizeof g_staging;
    b.skip_motion = 1; /* per-pixel motion: sent by the renderer, used by no stage here */
    b.defer_full = 1;  /* FULL payloads unpacked by process_full(), only for an eye being updated */
    for (uint32_t e = 0; e < FW_EYES; e++) {
#if TDC_CFG_TRM
        b.reduced[e] = g_reduced[e];
#endif
#if TDC_CFG_FOV
        b.full[e] = FOV_DISK(e); /* FOVEATED disk pixels only: FULL payloads stay deferred */
        b.fov_lp[e] = FOV_LP(e);
        b.fov_mv[e] = TDC_CFG_FOV_TAA ? FOV_MV(e) : NULL;
#endif
#if TDC_CFG_ASSEMBLE
        b.subframe[e] = g_subframe[e];
        b.sample_motion[e] = g_sample_mv[e];
        b.pattern[e] = g_pattern[e];
#endif
    }
#if TDC_CFG_TRM
    b.reduced_bytes = sizeof g_reduced[0];
#endif
#if TDC_CFG_FOV
    b.full_stride = FW_W * 3u;
    b.fov_lp_bytes = FW_LP_SAMPLES * 3u;
    b.fov_mv_count = TDC_CFG_FOV_TAA ? FW_LP_SAMPLES * 2u : 0u;
#endif
    if (tdc_link_decoder_init(&g.dec, &cfg, &b) != TDC_OK) {
        tdc_board_log("link decoder: panel larger than the compiled maximum");
    }
}

int tdc_fw_run(void)
{
    if (tdc_board_init() != TDC_BOARD_OK) {
        tdc_board_log("board init failed");
        return 1;
    }
    tdc_board_log(reset_name(tdc_board_reset_cause()));
    decoder_init();
    const uint32_t t0 = tdc_board_time_us();
    int status = 0;
    for (;;) {
        uint32_t got = 0;
        const tdc_board_status_t rs = tdc_board_transport_read(g_rx, sizeof g_rx, &got);
        if (rs == TDC_BOARD_END) {
            break;
        }
        if (rs != TDC_BOARD_OK) {
            tdc_board_log("transport failed");
            status = 1;
            break;
        }
        const uint8_t *p = g_rx;
        while (got) {
            tdc_link_event_t ev;
            const size_t used = tdc_link_feed(&g.dec, p, got, &ev);
            p += used;
            got -= (uint32_t)used;
            if (ev.type == TDC_LINK_EV_PACKET) {
                on_packet(&ev);
            } else if (ev.type == TDC_LINK_EV_ERROR) {
                on_rejected(&ev);
            }
        }
    }
    /* Queued events, then the last frame. */
    for (;;) {
        tdc_link_event_t ev;
        (void)tdc_link_feed(&g.dec, g_rx, 0, &ev);
        if (ev.type == TDC_LINK_EV_NONE) {
            break;
        }
        if (ev.type == TDC_LINK_EV_PACKET) {
            on_packet(&ev);
        } else if (ev.type == TDC_LINK_EV_ERROR) {
            on_rejected(&ev);
        }
    }
    finish_frame();
    const tdc_link_counters_t *c = tdc_link_counters(&g.dec);
    uint32_t errors = 0;
    for (unsigned i = 1; i < TDC_LINK_ERR_COUNT; i++) {
        errors += c->errors[i];
    }
    log_kv("packets accepted: ", c->packets_ok);
    log_kv("packets/bytes rejected: ", errors);
    log_kv("frames shown: ", g.frames_shown);
    log_kv("eyes kept (incomplete): ", g.eyes_incomplete);
    log_kv("full packets unused (never unpacked): ", g.unused_full);
    log_kv("late packets (ignored): ", g.late_packets);
    log_kv("stage errors: ", g.stage_errors);
    log_kv("unsupported streams: ", g.unsupported);
    log_kv("repeated stream headers (no-op): ", g.stream_repeats);
    log_kv("late full packets processed: ", g.late_full);
    log_kv("packets skipped (unused kind): ", c->packets_skipped);
#if TDC_CFG_BANDS
    log_kv("row bands: ", g.bands);
    log_kv("pictures dropped (bad or missing band): ", g.band_drops);
    log_kv("kept eyes copied before a swap: ", g.eye_copies);
    log_kv("LCD history resets (picture dropped after its first LCD rows): ", g.lcd_resets);
    log_kv("rows a FULL band leaves not final, max: ", g.held_max[0]);
    log_kv("rows a FULL band leaves not final, mean x100: ",
           g.held_n[0] ? (uint32_t)(g.held_sum[0] * 100u / g.held_n[0]) : 0u);
    log_kv("rows a REDUCED band leaves not final, max: ", g.held_max[1]);
    log_kv("rows a REDUCED band leaves not final, mean x100: ",
           g.held_n[1] ? (uint32_t)(g.held_sum[1] * 100u / g.held_n[1]) : 0u);
#endif
#if TDC_CFG_TRM
    if (g.mode == MODE_TRM) {
        uint32_t unpaired = 0;
        for (uint32_t e = 0; e < FW_EYES; e++) {
            unpaired += g.trm[e].stats.reduced_unpaired;
        }
        log_kv("reduced frames without their full frame (no residual): ", unpaired);
    }
#endif
#if TDC_CFG_ASSEMBLE
    log_kv("assembly restarts (joined mid-stream): ", g.asm_resyncs);
#endif
#if TDC_CFG_FOV
    {
        uint32_t refused = 0;
        for (unsigned i = 1; i < TDC_FOV_HDR_COUNT; i++) {
            refused += c->fov_refused[i];
        }
        log_kv("foveated frames composed: ", g.fov_frames);
        log_kv("foveation headers refused: ", refused);
        log_kv("foveated TAA histories forgotten (gap, refusal or full frame): ", g.fov_resets);
    }
#endif
#if TDC_CFG_FOV_TRM
    if (g.fovtrm_on) {
        log_kv("foveated TRM pictures composed, full slot: ", g.fovtrm_frames[0]);
        log_kv("foveated TRM pictures composed, reduced slot: ", g.fovtrm_frames[1]);
    }
#endif
#if TDC_CFG_LCD
    {
        uint64_t dropped = 0;
        for (uint32_t e = 0; e < FW_EYES; e++) {
            dropped += g.lcd[e].stats.residual_dropped;
        }
        log_kv("LCD unreached light dropped (pixel-channels): ",
               (uint32_t)(dropped > 0xffffffffu ? 0xffffffffu : dropped));
    }
#endif
    log_kv("time us: ", tdc_board_time_us() - t0);
    return status || g.stage_errors || g.unsupported ? 1 : 0;
}

#ifndef TDC_FW_NO_MAIN
int main(void);
int main(void)
{
    return tdc_fw_run();
}
#endif
