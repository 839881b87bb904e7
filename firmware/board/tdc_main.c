/*
 * tdc_main.c - the controller's frame loop (docs/design.md §1):
 *
 *   transport bytes -> link decoder -> stream family -> LCD inverse -> panel
 *
 * The loop reads the transport, feeds the link decoder and dispatches its
 * events: a stream header picks the stream family (tdc_fw_family.h: plain
 * here, TRM, tile assembly, foveation, foveated TRM in their own files), a
 * packet completes an eye of the frame being collected, a rejected packet
 * leaves its eye as it was.  The build's configuration is tdc_fw_config.h,
 * its static memory map tdc_fw_memmap.h.
 *
 * A frame is shown when every eye has what its family needs (TRM: the FULL
 * or REDUCED packet due; plain: FULL; foveated: FOVEATED or FULL, as a plain
 * stream's FULL; assembly: SUBFRAME and, if the stream sends them, its
 * sample motion vectors) or had that packet rejected for a bad payload CRC
 * or a refused foveation header (the eye keeps its last image: rejected
 * packets never touch the frame buffer, tdc_link.h).  If a packet of a
 * later frame arrives first, the unfinished frame is completed with what
 * arrived and shown.
 *
 * The frame buffer changes only for an eye the loop counts as updated for
 * the frame it shows next (a kept eye shows exactly its last shown image,
 * invariant 2 of tests/fuzz/fuzz_frameloop.c): the decoder leaves FULL
 * payloads in staging (defer_full) and the loop unpacks one only when it
 * processes that eye -- never a FULL packet no family of the stream uses
 * (an assembly stream), never before the unfinished frame is shown.  This
 * costs no memory; a decoder that unpacked every FULL packet on arrival
 * would show new pixels in a kept eye (tests/fuzz/findings/frameloop-kept-
 * eye-overwritten*).  What it does not give is an atomic swap on scan-out
 * hardware: the eye being updated is processed in the buffer the LTDC reads
 * (docs/boards.md, "Frame buffer and scan-out"); row bands (tdc_fw_bands.c)
 * give a front/back pair.
 */
#include <string.h>

#include "tdc_board.h"
#include "tdc_fw_family.h"

/* ---- the static memory map (sizes: tdc_fw_memmap.h) ---- */
uint8_t tdc_fw_fb[FW_FB_COUNT][FW_FB_BYTES] TDC_EXTRAM;
uint8_t tdc_fw_staging[FW_STAGING_BYTES] TDC_EXTRAM;
uint64_t tdc_fw_mode_arena[FW_EYES][FW_MODE_WORDS] TDC_EXTRAM;
/* Transport chunk: what one USB bulk transfer (or semihosting read) brings. */
static uint8_t g_rx[16384];

tdc_fw_loop_t tdc_fw;

/* A stream header the decoder accepted: a new stream starts (its family
 * chosen and set up by tdc_fw_stream.c, NULL if refused). */
static void configure_stream(void)
{
    tdc_fw.fam = NULL;
    tdc_fw.have_frame = 0;
    tdc_fw.have_last = 0;
    tdc_fw.have_rej = 0;
    tdc_fw.fam = tdc_fw_stream_start();
}

/* A row band: packet flag BAND on a FULL or REDUCED packet (packet flags
 * are per kind: a LAYERS packet's bit 1 says a visibility layer follows). */
static int is_band(const tdc_link_event_t *ev)
{
    return (ev->kind == TDC_LINK_KIND_FULL || ev->kind == TDC_LINK_KIND_REDUCED) && (ev->flags & TDC_LINK_PKT_BAND);
}

static uint32_t kinds_needed(uint32_t e, uint32_t frame)
{
    return tdc_fw.fam ? tdc_fw.fam->needs(e, frame) : 0u;
}

/* Runs the family of eye e on what arrived, then the LCD inverse; returns 1
 * if the eye's part of the frame buffer was updated. */
static int process_eye_kinds(uint32_t e, uint32_t frame, uint32_t kinds)
{
    uint8_t *fb = tdc_fw_back_eye(e);
    tdc_res_t *residual = NULL;
    uint32_t t = tdc_board_cycles();
    const int r = tdc_fw.fam ? tdc_fw.fam->eye(e, frame, kinds, fb, &residual) : FW_EYE_NOTHING;
    t = tdc_fw_time_stage(FW_STAGE_FAMILY, t);
    if (r != FW_EYE_UPDATED) {
        tdc_fw.stage_errors += r == FW_EYE_REFUSED;
        return 0;
    }
    if (tdc_fw_lcd_frame(e, fb, residual) != 0) {
        tdc_fw.stage_errors++;
    }
    (void)tdc_fw_time_stage(FW_STAGE_LCD, t);
    return 1;
}

/* The picture packet (FULL or FOVEATED) tdc_link_feed() just returned, for
 * eye e: returns 1 if the frame buffer changed.  A FULL payload is unpacked
 * from staging into the eye's part of the frame buffer first (a stage error
 * after the unpack is counted and still leaves the eye changed).  A FOVEATED
 * frame the stage refuses leaves the eye's image as it was (the stage
 * writes nothing; the refusal is counted in stage_errors and 0 returned). */
static int process_picture(uint32_t e, uint32_t frame, uint32_t kind)
{
    if (kind != TDC_LINK_KIND_FULL) {
        return process_eye_kinds(e, frame, KIND_BIT(kind));
    }
    const uint32_t t = tdc_board_cycles();
    const tdc_status_t st = tdc_link_unpack_full(&tdc_fw.dec, tdc_fw_back_eye(e), FW_STRIDE);
    (void)tdc_fw_time_stage(FW_STAGE_DECODE, t);
    if (st != TDC_OK) {
        tdc_fw.stage_errors++;
        return 0;
    }
    (void)process_eye_kinds(e, frame, KIND_BIT(TDC_LINK_KIND_FULL));
    return 1;
}

static void mark_updated(uint32_t e, int updated)
{
    tdc_fw.eyes_updated = (uint8_t)(tdc_fw.eyes_updated | ((updated ? 1u : 0u) << e));
}

static void show_frame(void)
{
    const uint32_t t = tdc_board_cycles();
    tdc_fw_bands_keep_eyes(); /* bands: kept eyes from the front, then the swap */
    (void)tdc_board_panel_show(tdc_fw_fb[tdc_fw.front], FW_STRIDE, FW_EYES * FW_W, FW_H, tdc_fw.frame);
    tdc_board_vsync_wait();
    (void)tdc_fw_time_stage(FW_STAGE_SHOW, t);
    tdc_fw.frames_shown++;
    tdc_fw_time_frame();
}

/* Ends the frame being collected: eyes still missing something are
 * processed with what arrived (or keep their last image); the frame is shown
 * if any eye changed.  A FULL packet is processed on arrival (its payload
 * is in staging only until the next feed), so only assembly eyes are left
 * here. */
static void finish_frame(void)
{
    if (!tdc_fw.have_frame) {
        return;
    }
    tdc_fw.have_frame = 0;
    tdc_fw.have_last = 1;
    tdc_fw.last_frame = tdc_fw.frame;
    for (uint32_t e = 0; e < FW_EYES; e++) {
        if (!(tdc_fw.eyes_done & (1u << e)) && (tdc_fw.kinds[e] & ~PICTURE_KINDS)) {
            mark_updated(e, process_eye_kinds(e, tdc_fw.frame, tdc_fw.kinds[e]));
        }
        tdc_fw.eyes_incomplete += !(tdc_fw.eyes_updated & (1u << e));
    }
    if (tdc_fw.eyes_updated) {
        show_frame();
    }
}

static void start_frame(uint32_t frame)
{
    finish_frame();
    tdc_fw.have_frame = 1;
    tdc_fw.frame = frame;
    tdc_fw.eyes_done = 0;
    tdc_fw.eyes_updated = tdc_fw.pending_updated; /* a late FULL's eye: changed since the last show */
    tdc_fw.pending_updated = 0;
    tdc_fw.kinds[0] = tdc_fw.kinds[1] = 0;
    for (uint32_t e = 0; e < FW_EYES && tdc_fw.have_rej && tdc_fw.rej_frame == frame; e++) {
        /* rejected earlier for this frame: those eyes keep their image */
        tdc_fw.eyes_done =
            (uint8_t)(tdc_fw.eyes_done | ((tdc_fw.rej_kinds[e] & kinds_needed(e, frame)) ? 1u << e : 0u));
    }
    tdc_fw.have_rej = (uint8_t)(tdc_fw.have_rej && tdc_fw.rej_frame > frame);
}

void tdc_fw_eye_done(uint32_t e)
{
    tdc_fw.eyes_done = (uint8_t)(tdc_fw.eyes_done | (1u << e));
    if (tdc_fw.eyes_done == (1u << FW_EYES) - 1u) {
        finish_frame(); /* every eye had what it needs (or lost it): show now */
    }
}

/* A pixel packet of the current or a later frame failed its payload CRC:
 * that eye keeps its image for this frame.  A rejected packet never moves
 * the loop's notion of time (its frame index is not trusted: only the
 * header CRC vouched for it): for the current frame the eye is done; for a
 * later one this is remembered and applied only if an accepted packet
 * starts that frame. */
static void on_rejected(const tdc_link_event_t *ev)
{
    /* a band's CRC error: the decoder reports the drop of the picture it
     * names (BAND_DROPPED), which is what counts here; a foveation header
     * refused after its payload CRC matched: the frame index is vouched
     * for, the picture lost the same way */
    const int lost = (ev->error == TDC_LINK_ERR_CRC && !is_band(ev)) ||
                     ev->error == TDC_LINK_ERR_BAND_DROPPED || ev->error == TDC_LINK_ERR_FOVEATION;
    if (ev->error == TDC_LINK_ERR_STREAM_HEADER) {
        /* a stream header the decoder refused after its CRC matched: a
         * stage the stream needs is not in this build (no buffer for it),
         * or the header is invalid; nothing of that stream is shown */
        tdc_board_log("stream header refused by the decoder: a stage it needs is not in this build, or invalid");
        tdc_fw.unsupported++;
        return;
    }
    if (ev->error == TDC_LINK_ERR_BAND_DROPPED) {
        tdc_fw_band_dropped(ev->eye);
    }
    if (!tdc_fw.fam || !lost || ev->eye >= FW_EYES || (tdc_fw.have_frame && ev->frame_index < tdc_fw.frame) ||
        (tdc_fw.have_last && ev->frame_index <= tdc_fw.last_frame)) {
        return;
    }
    if (tdc_fw.have_frame && ev->frame_index == tdc_fw.frame) {
        if ((kinds_needed(ev->eye, tdc_fw.frame) & KIND_BIT(ev->kind)) && !(tdc_fw.eyes_done & (1u << ev->eye))) {
            tdc_fw_eye_done(ev->eye);
        }
        return;
    }
    if (!tdc_fw.have_rej || tdc_fw.rej_frame != ev->frame_index) {
        /* one frame ahead is all a real loss needs; a newer claim replaces
         * an older one (both unverified) */
        tdc_fw.have_rej = 1;
        tdc_fw.rej_frame = ev->frame_index;
        tdc_fw.rej_kinds[0] = tdc_fw.rej_kinds[1] = 0;
    }
    if (ev->kind <= TDC_LINK_KIND_LAST) {
        tdc_fw.rej_kinds[ev->eye] = (uint16_t)(tdc_fw.rej_kinds[ev->eye] | KIND_BIT(ev->kind));
    }
}

static void on_packet(const tdc_link_event_t *ev)
{
    if (ev->kind == TDC_LINK_KIND_STREAM) {
        if (tdc_fw.fam && tdc_fw_stream_repeat(ev)) {
            tdc_fw.stream_repeats++; /* the late joiners' copy: nothing changes */
            return;
        }
        finish_frame();
        configure_stream();
        return;
    }
    if (!tdc_fw.fam || ev->eye >= FW_EYES) {
        return;
    }
    const uint32_t e = ev->eye, bit = KIND_BIT(ev->kind);
    const int band = is_band(ev);
    if (!tdc_fw.have_frame && tdc_fw.have_last && ev->frame_index <= tdc_fw.last_frame) {
        /* A FULL (or FOVEATED) packet of the frame finished last (rejected
         * first, then resent intact): processed now, so TRM pairs the next
         * reduced frame with it, and shown with the next frame.  A band of
         * a finished frame (its picture is not whole) and a late foveated
         * reduced slot are ignored as a late REDUCED is. */
        const int fov_reduced = ev->kind == TDC_LINK_KIND_FOVEATED && (ev->flags & TDC_LINK_PKT_FOV_REDUCED);
        if ((bit & PICTURE_KINDS) && ev->frame_index == tdc_fw.last_frame && !band && !fov_reduced) {
            tdc_fw.late_full++;
            if ((kinds_needed(e, ev->frame_index) & bit) && process_picture(e, ev->frame_index, ev->kind)) {
                tdc_fw.pending_updated = (uint8_t)(tdc_fw.pending_updated | (1u << e));
            }
        } else {
            tdc_fw.late_packets++; /* its frame was shown already (or dropped) */
        }
        return;
    }
    if ((bit & PICTURE_KINDS) && !(kinds_needed(e, ev->frame_index) & bit)) {
        tdc_fw.unused_full++; /* e.tdc_fw. in an assembly stream: left in staging, time not moved */
        return;
    }
    if (!tdc_fw.have_frame || ev->frame_index != tdc_fw.frame) {
        start_frame(ev->frame_index);
    }
    if (band) {
        tdc_fw_band(ev);
        return;
    }
    tdc_fw.kinds[e] = (uint16_t)(tdc_fw.kinds[e] | bit);
    if (bit & PICTURE_KINDS) {
        /* the eye's whole need (plain, TRM's full slot, foveated); also
         * when it was rejected first and resent intact before the frame
         * finished */
        mark_updated(e, process_picture(e, tdc_fw.frame, ev->kind));
        if (!(tdc_fw.eyes_done & (1u << e))) {
            tdc_fw_eye_done(e);
        }
        return;
    }
    /* assembly needs every kind it names; TRM one of its slot's (REDUCED,
     * or FOVEATED: a picture kind, processed above) */
    const uint32_t need = kinds_needed(e, tdc_fw.frame) & ~PICTURE_KINDS;
    if (!(tdc_fw.eyes_done & (1u << e)) && need && (tdc_fw.kinds[e] & need) == need) {
        mark_updated(e, process_eye_kinds(e, tdc_fw.frame, tdc_fw.kinds[e]));
        tdc_fw_eye_done(e);
    }
}

static void decoder_init(void)
{
    tdc_link_config_t cfg = {(uint16_t)FW_W, (uint16_t)FW_H, (uint8_t)FW_EYES};
    tdc_link_buffers_t b = {0};
    b.staging = tdc_fw_staging;
    b.staging_bytes = sizeof tdc_fw_staging;
    b.skip_motion = 1; /* per-pixel motion: sent by the renderer, used by no stage here */
    b.defer_full = 1;  /* FULL payloads unpacked by process_picture(), only for an eye being updated */
    for (size_t i = 0; i < tdc_fw_family_count; i++) {
        if (tdc_fw_families[i]->wire) {
            tdc_fw_families[i]->wire(&b);
        }
    }
    if (tdc_link_decoder_init(&tdc_fw.dec, &cfg, &b) != TDC_OK) {
        tdc_board_log("link decoder: panel larger than the compiled maximum");
    }
}

/* Hands every event tdc_link_feed() has to the loop; 0 when there was none. */
static int dispatch(const uint8_t *p, uint32_t n, size_t *used)
{
    tdc_link_event_t ev;
    const uint32_t t = tdc_board_cycles();
    *used = tdc_link_feed(&tdc_fw.dec, p, n, &ev);
    (void)tdc_fw_time_stage(FW_STAGE_DECODE, t);
    if (ev.type == TDC_LINK_EV_PACKET) {
        on_packet(&ev);
    } else if (ev.type == TDC_LINK_EV_ERROR) {
        on_rejected(&ev);
    }
    return ev.type != TDC_LINK_EV_NONE;
}

static void log_counters(void)
{
    const tdc_link_counters_t *c = tdc_link_counters(&tdc_fw.dec);
    tdc_fw_log_loop(c);
    tdc_fw_bands_log();
    for (size_t i = 0; i < tdc_fw_family_count; i++) {
        if (tdc_fw_families[i]->log) {
            tdc_fw_families[i]->log(c);
        }
    }
    tdc_fw_lcd_log();
}

int tdc_fw_run(void)
{
    if (tdc_board_init() != TDC_BOARD_OK) {
        tdc_board_log("board init failed");
        return 1;
    }
    tdc_board_log(tdc_fw_reset_name(tdc_board_reset_cause()));
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
        for (const uint8_t *p = g_rx; got;) {
            size_t used = 0;
            (void)dispatch(p, got, &used);
            p += used;
            got -= (uint32_t)used;
        }
    }
    /* Queued events, then the last frame. */
    for (size_t used = 0; dispatch(g_rx, 0, &used);) {
    }
    finish_frame();
    log_counters();
    tdc_fw_log_kv("time us: ", tdc_board_time_us() - t0);
    return status || tdc_fw.stage_errors || tdc_fw.unsupported ? 1 : 0;
}

#ifndef TDC_FW_NO_MAIN
int main(void);
int main(void)
{
    return tdc_fw_run();
}
#endif
