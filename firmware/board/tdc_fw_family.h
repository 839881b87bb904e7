/*
 * tdc_fw_family.h - what a stream family implements for the board frame
 * loop (internal to firmware/board), and the loop state the families share.
 *
 * A family (plain, TRM, tile assembly, layered assembly, foveation,
 * foveated TRM) is one
 * file, tdc_fw_<family>.c, compiled in every build; unless its stage is
 * (TDC_CFG_*) it holds only a descriptor that matches no stream, so a
 * family not built is not linked.  The loop
 * (tdc_main.c) owns what every stream shares - the decoder, the frame being
 * collected, which eye is done or updated, the frame buffer and the counters
 * - and picks the family whose stream flags the stream header carries:
 *
 *     wire       (once)        the family's decoder buffers
 *     configure  (per stream)  the stages of every eye; non-zero: refused
 *                              (the family logs why), nothing is shown
 *     needs      (per eye)     the packet kinds that complete an eye's frame
 *     eye        (per eye)     run the stages on what arrived into the eye's
 *                              part of the back buffer
 *     band       (per band)    the same for one row band (rows in flight)
 *     log        (at the end)  the family's counters
 *
 * The LCD inverse is an output stage after every family (tdc_fw_lcd.c), row
 * bands a property of the transport (tdc_fw_bands.c).
 *
 * Adding a family: a new tdc_fw_<family>.c with its tdc_fw_family_t, listed
 * once in TDC_FW_FAMILIES below (mk/boards.mk builds every tdc_fw_*.c).
 */
#ifndef TDC_FW_FAMILY_H
#define TDC_FW_FAMILY_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "tdc_band_link.h"
#include "tdc_fw_memmap.h"
#include "tdc_link.h"
#include "tdc_status.h"

#define KIND_BIT(k) (1u << (k))
/* The kinds that carry one eye's whole picture (one slot per eye and
 * frame, tdc_link.c): processed on arrival, never left for finish_frame. */
#define PICTURE_KINDS (KIND_BIT(TDC_LINK_KIND_FULL) | KIND_BIT(TDC_LINK_KIND_FOVEATED))
/* The stream flags that choose a family. */
#define FW_FAMILY_FLAGS \
    (TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_SUBFRAMES | TDC_LINK_STREAM_FOVEATED | TDC_LINK_STREAM_LAYERS)

/* What eye() did. */
enum { FW_EYE_REFUSED = -1, FW_EYE_NOTHING = 0, FW_EYE_UPDATED = 1 };

/* Per-stage timing (tdc_fw_log.c): what the loop's cycles go to. */
enum {
    FW_STAGE_DECODE, /* link decoder, FULL unpack */
    FW_STAGE_FAMILY, /* the stream family's stages: TRM, assembly, foveated remap */
    FW_STAGE_LCD,    /* the LCD inverse */
    FW_STAGE_SHOW,   /* scan-out flip and the vsync wait */
    FW_STAGE_COUNT
};
/* One timing line every 2^FW_TIMING_LOG2 frames shown (64: about 1 s at
 * 60 Hz; a power of two, so the mean is a shift). */
#define FW_TIMING_LOG2 6u

typedef struct tdc_fw_family tdc_fw_family_t;
struct tdc_fw_family {
    const char *name;
    uint32_t flags; /* FW_FAMILY_FLAGS of the streams it plays */
    void (*wire)(tdc_link_buffers_t *b);
    /* hz: the rate the panel runs the stream at (tdc_fw_panel_hz) */
    int (*configure)(const tdc_link_stream_info_t *si, uint16_t hz);
    uint32_t (*needs)(uint32_t e, uint32_t frame);
    /* kinds: what arrived for the eye; fb: the eye's part of the back
     * buffer; *residual: what TRM could not reach, for the LCD inverse */
    int (*eye)(uint32_t e, uint32_t frame, uint32_t kinds, uint8_t *fb, tdc_res_t **residual);
    /* one row band of `kind` (a FULL band already unpacked at its rows):
     * *done output rows are final, *covered are covered by arrived rows;
     * NULL: the family takes no bands (TDC_ERR_STATE) */
    tdc_status_t (*band)(uint32_t e, uint32_t frame, uint32_t kind, const tdc_band_hdr_t *bh, uint8_t *fb,
                         uint32_t *done, uint32_t *covered, tdc_res_t **residual);
    void (*log)(const tdc_link_counters_t *c);
};

/* The families, in the order their counters are logged.  A family whose
 * stage is not in the build is a descriptor that matches no stream
 * (FW_FAMILY_OFF): none of its code is linked. */
#define FW_FAMILY_OFF 0xffffffffu
#define TDC_FW_FAMILY_NOT_BUILT(fam) \
    const tdc_fw_family_t tdc_fw_family_##fam = {#fam, FW_FAMILY_OFF, NULL, NULL, NULL, NULL, NULL, NULL}
extern const tdc_fw_family_t tdc_fw_family_trm, tdc_fw_family_assemble, tdc_fw_family_layers, tdc_fw_family_fov,
    tdc_fw_family_fov_trm, tdc_fw_family_plain;
#define TDC_FW_FAMILIES                                                                                         \
    &tdc_fw_family_trm, &tdc_fw_family_assemble, &tdc_fw_family_layers, &tdc_fw_family_fov, &tdc_fw_family_fov_trm, \
        &tdc_fw_family_plain

/* ---- stream set-up (tdc_fw_stream.c) ---- */
extern const tdc_fw_family_t *const tdc_fw_families[];
extern const size_t tdc_fw_family_count;


/* The loop state every family sees (tdc_main.c). */
typedef struct {
    tdc_link_decoder_t dec;
    const tdc_fw_family_t *fam; /* the active stream's family; NULL: none */
    uint8_t front;              /* tdc_fw_fb[front] is on the panel */
    uint8_t have_frame;         /* a frame is being collected */
    uint8_t eyes_done;          /* bit e: eye e processed (or tried) for `frame` */
    uint8_t eyes_updated;       /* bit e: eye e's image changed for `frame` */
    uint16_t kinds[2];          /* KIND_BIT()s received per eye for `frame` (LAYERS is bit 8) */
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
    uint32_t fov_composed;    /* foveated eye-frames composed (foveation and foveated TRM) */
    uint8_t pending_updated;  /* eyes a late FULL updated since the last show: updated in the next one */
    uint8_t have_rej;         /* a pixel packet of a frame not started yet was rejected ... */
    uint32_t rej_frame;       /* ... for this frame ... */
    uint16_t rej_kinds[2];    /* ... these kinds, per eye (applied only if a good packet starts it) */
    uint8_t have_stream;      /* the configured stream's header, to recognise a repeat */
    uint16_t stream_id;
    tdc_link_stream_info_t stream;
    uint64_t stage_cycles[FW_STAGE_COUNT]; /* tdc_board_cycles() spent per stage since the last timing line */
    uint32_t timed_frames;                 /* frames shown since then */
} tdc_fw_loop_t;

extern tdc_fw_loop_t tdc_fw;

/* The eye's part of the buffer the stages write. */
static inline uint8_t *tdc_fw_back_eye(uint32_t e)
{
    return tdc_fw_fb[(tdc_fw.front ^ 1u) % FW_FB_COUNT] + (size_t)e * FW_W * 3u;
}

/* A stage's W x H RGB888 output (rows `stride` bytes apart) into the eye's
 * part of the frame buffer. */
static inline void tdc_fw_put_eye(uint8_t *fb, const uint8_t *out, int stride)
{
    for (uint32_t y = 0; y < FW_H; y++) {
        memcpy(fb + (size_t)y * FW_STRIDE, out + (size_t)y * (uint32_t)stride, FW_W * 3u);
    }
}

/* ---- the log (tdc_fw_log.c) ---- */
/* one "what: value" line */
void tdc_fw_log_kv(const char *what, uint32_t v);
const char *tdc_fw_reset_name(tdc_reset_cause_t c);
/* the loop's own counters (each family logs its own) */
void tdc_fw_log_loop(const tdc_link_counters_t *c);
/* adds tdc_board_cycles() - since to the stage; returns the counter now */
uint32_t tdc_fw_time_stage(unsigned stage, uint32_t since);
/* a frame was shown: every 2^FW_TIMING_LOG2 frames one line of the mean
 * cycles per frame of each stage (none when the board counts no cycles) */
void tdc_fw_time_frame(void);

/* ---- the LCD inverse after every family (tdc_fw_lcd.c) ---- */
#if TDC_CFG_LCD
void tdc_fw_lcd_configure(uint16_t hz);
/* 0, or the failure of a stage that ran */
int tdc_fw_lcd_frame(uint32_t e, uint8_t *fb, tdc_res_t *residual);
int tdc_fw_lcd_rows(uint32_t e, uint8_t *fb, tdc_res_t *residual, uint32_t y0, uint32_t y1);
void tdc_fw_lcd_frame_done(uint32_t e);
int tdc_fw_lcd_reset(uint32_t e); /* 1 if the eye had history to forget */
void tdc_fw_lcd_log(void);
#else
static inline void tdc_fw_lcd_configure(uint16_t hz)
{
    (void)hz;
}
static inline int tdc_fw_lcd_frame(uint32_t e, uint8_t *fb, tdc_res_t *residual)
{
    (void)e, (void)fb, (void)residual;
    return 0;
}
static inline int tdc_fw_lcd_rows(uint32_t e, uint8_t *fb, tdc_res_t *residual, uint32_t y0, uint32_t y1)
{
    (void)e, (void)fb, (void)residual, (void)y0, (void)y1;
    return 0;
}
static inline void tdc_fw_lcd_frame_done(uint32_t e)
{
    (void)e;
}
static inline int tdc_fw_lcd_reset(uint32_t e)
{
    (void)e;
    return 0;
}
static inline void tdc_fw_lcd_log(void)
{
}
#endif

/* ---- row bands (tdc_fw_bands.c): the loop's side of a banded transport ---- */
#if TDC_CFG_BANDS
/* a band of the current frame, due for its eye */
void tdc_fw_band(const tdc_link_event_t *ev);
/* the decoder dropped eye e's picture in flight (a bad or missing band) */
void tdc_fw_band_dropped(uint32_t e);
/* before the swap: eyes not updated get the front's image */
void tdc_fw_bands_keep_eyes(void);
void tdc_fw_bands_log(void);
#else
static inline void tdc_fw_band(const tdc_link_event_t *ev)
{
    (void)ev; /* configure refuses band streams without a back buffer */
}
static inline void tdc_fw_band_dropped(uint32_t e)
{
    (void)e;
}
static inline void tdc_fw_bands_keep_eyes(void)
{
}
static inline void tdc_fw_bands_log(void)
{
}
#endif

/* The stream header the decoder just accepted: its family, set up, or NULL
 * (refused: logged and counted in tdc_fw.unsupported). */
const tdc_fw_family_t *tdc_fw_stream_start(void);
/* 1 if it repeats the configured stream's header (a copy for late joiners) */
int tdc_fw_stream_repeat(const tdc_link_event_t *ev);

/* eye e is done for the frame (tdc_main.c): the frame is shown when all are */
void tdc_fw_eye_done(uint32_t e);

#endif
