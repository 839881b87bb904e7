/*
 * tdc_fw_bands.c - rows in flight, a property of the transport (stream flag
 * BANDS, TDC_CFG_BANDS; docs/boards.md "Rows in flight"): pictures arrive
 * as row bands (tdc_band_link.h), staging holds one band, each FULL band is
 * unpacked at its rows of the back buffer as it arrives and the family and
 * the LCD inverse run on the rows it makes final; the last band completes
 * the eye.  The frame buffer is a front/back pair and the swap happens only
 * when a frame is finished (eyes not updated copied from the front first).
 * A picture with a bad or missing band is dropped whole by the decoder
 * (BAND_DROPPED): its eye keeps its last good image.
 */
#include <string.h>

#include "tdc_fw_family.h"

#if TDC_CFG_BANDS
static struct {
    uint32_t bands;       /* row bands taken */
    uint32_t band_drops;  /* pictures dropped whole (a bad or missing band): the eye kept its image */
    uint32_t eye_copies;  /* kept eyes copied front -> back before a swap */
    uint8_t open[2];      /* eye's picture in flight has its stages open */
    uint32_t final[2];    /* ... and this many output rows (from the top) final */
    uint32_t lcd_resets;  /* LCD history reset: a picture dropped after LCD rows ran */
    uint32_t held_max[2]; /* rows a band leaves not final (FULL, REDUCED: full-res rows) */
    uint64_t held_sum[2];
    uint32_t held_n[2];
} b;

/* Eye e's picture in flight was dropped: rows the LCD inverse already ran
 * hold that picture's history, so the eye's LCD starts again without
 * history; TRM's kept state was invalidated when the full frame began
 * (tdc_trm_full_begin), a reduced frame keeps none. */
static void band_abandon(uint32_t e)
{
    if (e >= FW_EYES || !b.open[e]) {
        return;
    }
    b.open[e] = 0;
    if (b.final[e] > 0u && tdc_fw_lcd_reset(e)) {
        b.lcd_resets++;
    }
}

void tdc_fw_band_dropped(uint32_t e)
{
    b.band_drops++;
    band_abandon(e);
}

/* The stages a band lets run, in the eye's part of the back buffer: the
 * family's rows (tdc_fw_family_t.band), then the LCD inverse on the rows
 * that became final.  The last band closes the frame of each stage and
 * completes the eye. */
static void band_stages(uint32_t e, uint32_t kind, const tdc_band_hdr_t *bh)
{
    uint8_t *fb = tdc_fw_back_eye(e);
    const int last = bh->index + 1u == bh->count;
    const uint32_t avail = (uint32_t)bh->first_row + bh->rows;
    uint32_t done = avail, covered = avail; /* output rows final; output rows the arrived rows cover */
    tdc_res_t *residual = NULL;
    if (bh->index == 0u) {
        b.open[e] = 1;
        b.final[e] = 0;
    }
    const tdc_fw_family_t *fam = tdc_fw.fam;
    tdc_status_t st = fam->band ? fam->band(e, tdc_fw.frame, kind, bh, fb, &done, &covered, &residual) : TDC_ERR_STATE;
    if (last) {
        done = covered = FW_H;
    }
    if (st != TDC_OK) {
        tdc_fw.stage_errors++;
        band_abandon(e);
        tdc_fw_eye_done(e);
        return;
    }
    if (done > b.final[e] && tdc_fw_lcd_rows(e, fb, residual, b.final[e], done) != 0) {
        tdc_fw.stage_errors++;
    }
    b.final[e] = done;
    const uint32_t k = kind == TDC_LINK_KIND_FULL ? 0u : 1u, held = covered > done ? covered - done : 0u;
    b.held_max[k] = held > b.held_max[k] ? held : b.held_max[k];
    b.held_sum[k] += held;
    b.held_n[k]++;
    if (last) {
        tdc_fw_lcd_frame_done(e);
        b.open[e] = 0;
        tdc_fw.eyes_updated = (uint8_t)(tdc_fw.eyes_updated | (1u << e));
        tdc_fw_eye_done(e);
    }
}

/* A row band of the current frame (FULL or REDUCED, due for its eye): a
 * FULL band is unpacked at its rows of the eye's part of the back buffer
 * (the decoder wrote a REDUCED band into the reduced picture itself), then
 * the stages run on what it completes. */
static void band_work(const tdc_link_event_t *ev)
{
    const uint32_t e = ev->eye;
    const tdc_band_hdr_t *bh = tdc_link_band(&tdc_fw.dec, e);
    b.bands++;
    if (!bh || (tdc_fw.eyes_done & (1u << e)) || (bh->index > 0u && !b.open[e])) {
        return;
    }
    if (ev->kind == TDC_LINK_KIND_FULL && tdc_link_unpack_full(&tdc_fw.dec, tdc_fw_back_eye(e), FW_STRIDE) != TDC_OK) {
        tdc_fw.stage_errors++;
        return;
    }
    /* (tdc_fw.kinds stays clear: finish_frame must never run an eye's
     * stages on a picture whose bands did not all come) */
    band_stages(e, ev->kind, bh);
}

/* What a band's event costs, from the decoder's event to its pixels being
 * final, by kind: separate functions so an instruction count can take them
 * apart (host: valgrind --toggle-collect, docs/boards.md). */
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

void tdc_fw_band(const tdc_link_event_t *ev)
{
    if (ev->kind == TDC_LINK_KIND_FULL) {
        tdc_fw_band_full(ev);
    } else {
        tdc_fw_band_reduced(ev);
    }
}

/* An eye not updated keeps its last shown image: the front's, copied into
 * the back before the swap (the back may hold a dropped picture). */
void tdc_fw_bands_keep_eyes(void)
{
    const uint8_t *front = tdc_fw_fb[tdc_fw.front];
    for (uint32_t e = 0; e < FW_EYES; e++) {
        if (!(tdc_fw.eyes_updated & (1u << e))) {
            const size_t off = (size_t)e * FW_W * 3u;
            uint8_t *back = tdc_fw_back_eye(e);
            for (uint32_t y = 0; y < FW_H; y++) {
                memcpy(back + (size_t)y * FW_STRIDE, front + off + (size_t)y * FW_STRIDE, FW_W * 3u);
            }
            b.eye_copies++;
        }
    }
    tdc_fw.front ^= 1u;
}

void tdc_fw_bands_log(void)
{
    tdc_fw_log_kv("row bands: ", b.bands);
    tdc_fw_log_kv("pictures dropped (bad or missing band): ", b.band_drops);
    tdc_fw_log_kv("kept eyes copied before a swap: ", b.eye_copies);
    tdc_fw_log_kv("LCD history resets (picture dropped after its first LCD rows): ", b.lcd_resets);
    tdc_fw_log_kv("rows a FULL band leaves not final, max: ", b.held_max[0]);
    tdc_fw_log_kv("rows a FULL band leaves not final, mean x100: ",
                  b.held_n[0] ? (uint32_t)(b.held_sum[0] * 100u / b.held_n[0]) : 0u);
    tdc_fw_log_kv("rows a REDUCED band leaves not final, max: ", b.held_max[1]);
    tdc_fw_log_kv("rows a REDUCED band leaves not final, mean x100: ",
                  b.held_n[1] ? (uint32_t)(b.held_sum[1] * 100u / b.held_n[1]) : 0u);
}
#else
typedef int tdc_fw_bands_unused_t; /* whole pictures only in this build: an empty object */
#endif
