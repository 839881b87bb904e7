/*
 * bench_arm_main.c - instructions per output pixel of each firmware stage
 * on the emulated Cortex-M boards.  Run under QEMU with the counting plugin
 * (tests/arm/tdc_insn_plugin.c): each measurement is bracketed by two calls
 * of tdc_bench_mark(), whose executions the plugin records with the number
 * of guest instructions executed so far; the guest writes one line
 * "label pixels" per measurement to stdout (semihosting), and
 * tests/arm/bench_arm.sh divides.  Inputs are prepared outside the marks.
 *
 * Frame: BENCH_W x BENCH_H (one eye), two frames per measurement, contents
 * from tests/golden/tdc_content.h (moving text = typical, noise = worst
 * case for the motion test).  Panels: HTC Vive gamma for TRM; the first
 * LCD profile for the LCD inverse.
 */
#include <stdint.h>
#include <string.h>

#include "board.h"
#include "tdc_assemble.h"
#include "tdc_content.h"
#include "tdc_crt0.h"
#include "tdc_fov.h"
#include "tdc_fov_lr.h"
#include "tdc_layer_content.h"
#include "tdc_layer_hist.h"
#include "tdc_lhist_content.h"
#include "tdc_layers.h"
#include "tdc_lcd.h"
#include "tdc_link.h"
#include "tdc_link_encode.h"
#include "tdc_panels.h"
#include "tdc_semihost.h"
#include "tdc_text.h"
#include "tdc_trm.h"

#define BENCH_W 640u
#define BENCH_H 360u
#define BENCH_PX (BENCH_W * BENCH_H)
#define BENCH_FRAMES 2u
#define RW ((BENCH_W + 1u) / 2u)
#define RH ((BENCH_H + 1u) / 2u)

void tdc_bench_mark(void);
__attribute__((noinline, used)) void tdc_bench_mark(void)
{
    __asm__ volatile("" ::: "memory");
}

static uint8_t g_in[BENCH_FRAMES][BENCH_PX * 3u] TDC_EXTRAM;
static uint8_t g_red[BENCH_FRAMES][RW * RH * 3u] TDC_EXTRAM;
static uint8_t g_out[BENCH_PX * 3u] TDC_EXTRAM;
static uint8_t g_pkt[BENCH_FRAMES][BENCH_PX * 4u + 64u] TDC_EXTRAM;
static uint32_t g_pkt_len[BENCH_FRAMES];
static uint8_t g_staging[TDC_LINK_STAGING_BYTES(BENCH_W, BENCH_H)] TDC_EXTRAM;
static uint64_t g_arena[(TDC_ASM_MEM_BYTES(BENCH_W, BENCH_H) > TDC_TRM_MEM_BYTES(BENCH_W, BENCH_H, 1, 2)
                             ? TDC_ASM_MEM_BYTES(BENCH_W, BENCH_H)
                             : TDC_TRM_MEM_BYTES(BENCH_W, BENCH_H, 1, 2)) /
                            8u +
                        1u] TDC_EXTRAM;
static uint64_t g_lcd_arena[TDC_LCD_MEM_BYTES(BENCH_W, BENCH_H) / 8u] TDC_EXTRAM;
static uint8_t g_samples[RW * RH * 3u] TDC_EXTRAM;
/* foveated remap: log-polar buffer 0.555 W x 0.555 H, its motion vectors, TAA arena */
#define FOV_LW ((BENCH_W * 555u) / 1000u)
#define FOV_LH ((BENCH_H * 555u) / 1000u)
static uint8_t g_fov_lp[FOV_LW * FOV_LH * 3u] TDC_EXTRAM;
static int16_t g_fov_mv[FOV_LW * FOV_LH * 2u] TDC_EXTRAM;
static uint64_t g_fov_arena[TDC_FOV_MEM_BYTES(BENCH_W, BENCH_H, 1) / 8u] TDC_EXTRAM;
static tdc_fov_t g_fov;
static uint64_t g_fov_lr_arena[TDC_FOV_LR_MEM_BYTES(BENCH_W) / 8u];
static tdc_fov_lr_t g_fov_lr;
static int16_t g_mv[RW * RH * 2u] TDC_EXTRAM;

static tdc_link_decoder_t g_dec;
static tdc_trm_t g_trm;
static tdc_asm_t g_asm;
static tdc_lcd_t g_lcd;

static const tdc_panel_t *const k_panels[] = {
#define PANEL_PTR(sym) &sym,
    TDC_PANEL_LIST(PANEL_PTR)};

static void report(const char *label, uint32_t pixels)
{
    char num[13];
    char *o = tdc_text_u32(tdc_text_str(num, NULL, " "), NULL, pixels);
    *o++ = '\n';
    *o = 0;
    tdc_semihost_puts(1, label);
    tdc_semihost_puts(1, num);
}

static void fail(const char *what)
{
    tdc_semihost_puts(2, "[" TDC_BOARD_NAME "] bench: ");
    tdc_semihost_puts(2, what);
    tdc_semihost_puts(2, "\n");
    tdc_semihost_exit(1);
}

static void make_inputs(tdc_content_t c)
{
    for (uint32_t f = 0; f < BENCH_FRAMES; f++) {
        tdc_content_frame(c, f, 5u, g_in[f], (int)BENCH_W, (int)BENCH_H, (int)(BENCH_W * 3u));
        tdc_content_frame(c, f, 5u, g_out, (int)RW, (int)RH, (int)(RW * 3u)); /* reduced content, own frame */
        memcpy(g_red[f], g_out, RW * RH * 3u);
    }
}

static void bench_memcpy(void)
{
    tdc_bench_mark();
    for (uint32_t f = 0; f < BENCH_FRAMES; f++) {
        memcpy(g_out, g_in[f], BENCH_PX * 3u);
    }
    tdc_bench_mark();
    report("memcpy RGB888 frame (reference)", BENCH_FRAMES * BENCH_PX);
}

static void bench_link(tdc_pixfmt_t fmt, const char *label)
{
    tdc_link_stream_info_t info = {0, 1, 1, (uint16_t)BENCH_W, (uint16_t)BENCH_H, 1, 0, 120};
    tdc_link_encoder_t enc;
    tdc_link_encoder_init(&enc, 3, &info);
    uint8_t hdr[64];
    const size_t hn = tdc_link_encode_stream(&enc, hdr, sizeof hdr);
    for (uint32_t f = 0; f < BENCH_FRAMES; f++) {
        g_pkt_len[f] = (uint32_t)tdc_link_encode_frame(&enc, g_pkt[f], sizeof g_pkt[f], TDC_LINK_KIND_FULL, 0, f, fmt,
                                                       g_in[f], BENCH_W, BENCH_H, BENCH_W * 3u);
        if (!g_pkt_len[f]) {
            fail("link encode");
        }
    }
    const tdc_link_config_t cfg = {(uint16_t)BENCH_W, (uint16_t)BENCH_H, 1};
    tdc_link_buffers_t b;
    memset(&b, 0, sizeof b);
    b.staging = g_staging;
    b.staging_bytes = sizeof g_staging;
    b.full[0] = g_out;
    b.full_stride = BENCH_W * 3u;
    if (tdc_link_decoder_init(&g_dec, &cfg, &b) != TDC_OK) {
        fail("link decoder init");
    }
    tdc_link_event_t ev;
    const uint8_t *p = hdr;
    size_t n = hn;
    while (n) {
        const size_t used = tdc_link_feed(&g_dec, p, n, &ev);
        p += used;
        n -= used;
    }
    uint32_t ok = 0;
    tdc_bench_mark();
    for (uint32_t f = 0; f < BENCH_FRAMES; f++) {
        p = g_pkt[f];
        n = g_pkt_len[f];
        while (n) {
            const size_t used = tdc_link_feed(&g_dec, p, n, &ev);
            p += used;
            n -= used;
            ok += ev.type == TDC_LINK_EV_PACKET;
        }
    }
    tdc_bench_mark();
    if (ok != BENCH_FRAMES) {
        fail("link decode rejected a frame");
    }
    report(label, BENCH_FRAMES * BENCH_PX);
}

/* g_trm for a stream of reduced frames at 90 Hz, HTC Vive gamma. */
static void trm_init_stream(void)
{
    tdc_trm_config_t cfg;
    tdc_trm_default_config(&cfg, (uint16_t)BENCH_W, (uint16_t)BENCH_H, 90);
    cfg.reduced_in_stream = 1;
    if (tdc_trm_init(&g_trm, &cfg, &tdc_panel_htc_vive, g_arena, sizeof g_arena) != TDC_OK) {
        fail("TRM init");
    }
}

static void bench_trm(tdc_content_t c, const char *full_label, const char *reduced_label)
{
    make_inputs(c);
    trm_init_stream();
    /* Full and reduced alternate, as in a stream; each kind is bracketed. */
    uint64_t dummy = 0;
    for (uint32_t f = 0; f < BENCH_FRAMES; f++) {
        tdc_bench_mark();
        if (tdc_trm_full(&g_trm, g_in[f], BENCH_W * 3u, g_out, BENCH_W * 3u) != TDC_OK) {
            fail("TRM full");
        }
        tdc_bench_mark();
        report(full_label, BENCH_PX);
        tdc_bench_mark();
        if (tdc_trm_reduced(&g_trm, g_red[f], RW * 3u, g_out, BENCH_W * 3u) != TDC_OK) {
            fail("TRM reduced");
        }
        tdc_bench_mark();
        report(reduced_label, BENCH_PX);
        dummy += g_out[f];
    }
    (void)dummy;
}

/* Static pair: the reduced frame is TRM's own prefilter of the full frame,
 * so the motion test finds c = 0 and skips the weights. */
static void bench_trm_static(void)
{
    make_inputs(TDC_CONTENT_TEXT);
    tdc_trm_config_t cfg;
    tdc_trm_default_config(&cfg, (uint16_t)BENCH_W, (uint16_t)BENCH_H, 90);
    cfg.reduced_in_stream = 1;
    if (tdc_trm_init(&g_trm, &cfg, &tdc_panel_htc_vive, g_arena, sizeof g_arena) != TDC_OK ||
        tdc_trm_downsample(&g_trm, g_in[0], BENCH_W * 3u, g_red[0], RW * 3u) != TDC_OK) {
        fail("TRM static init");
    }
    for (uint32_t f = 0; f < BENCH_FRAMES; f++) {
        if (tdc_trm_full(&g_trm, g_in[0], BENCH_W * 3u, g_out, BENCH_W * 3u) != TDC_OK) {
            fail("TRM full");
        }
        tdc_bench_mark();
        if (tdc_trm_reduced(&g_trm, g_red[0], RW * 3u, g_out, BENCH_W * 3u) != TDC_OK) {
            fail("TRM reduced");
        }
        tdc_bench_mark();
        report("TRM reduced frame r=1/2 (static pair)", BENCH_PX);
    }
}

static void bench_assemble(int moving, const char *label)
{
    const tdc_asm_config_t cfg = {(uint16_t)BENCH_W, (uint16_t)BENCH_H};
    if (tdc_asm_init(&g_asm, &cfg, g_arena, sizeof g_arena) != TDC_OK) {
        fail("assembly init");
    }
    /* 8 frames (two cycles) warm the history; the next 4 are measured. */
    for (uint32_t f = 0; f < 12u; f++) {
        tdc_content_frame(TDC_CONTENT_TEXT, moving ? f : 0u, 5u, g_samples, (int)RW, (int)RH, (int)(RW * 3u));
        for (uint32_t i = 0; i < RW * RH; i++) {
            g_mv[2u * i] = (int16_t)(moving ? -2 * 16 : 0);
            g_mv[2u * i + 1u] = (int16_t)(moving ? 16 : 0);
        }
        if (f >= 8u) {
            tdc_bench_mark();
        }
        if (tdc_asm_ingest(&g_asm, f, g_samples, g_mv, NULL) != TDC_OK || tdc_asm_assemble(&g_asm, f) != TDC_OK) {
            fail("assembly");
        }
        if (f >= 8u) {
            tdc_bench_mark();
            report(label, BENCH_PX);
        }
    }
}

/* The first LCD profile (TDC_PANEL_LIST order) whose tables mode needs;
 * g_lcd is left initialised in that mode.  NULL if none. */
static const tdc_panel_t *first_lcd_panel(uint8_t mode)
{
    for (unsigned i = 0; i < sizeof k_panels / sizeof k_panels[0]; i++) {
        const tdc_lcd_config_t cfg = {(uint16_t)BENCH_W, (uint16_t)BENCH_H, k_panels[i]->refresh_hz, mode, 8u};
        if (k_panels[i]->type == TDC_PANEL_LCD &&
            tdc_lcd_init(&g_lcd, &cfg, k_panels[i], g_lcd_arena, sizeof g_lcd_arena) == TDC_OK) {
            return k_panels[i];
        }
    }
    return NULL;
}

static void bench_lcd(void)
{
    static const struct {
        uint8_t mode;
        const char *label;
    } modes[] = {{TDC_LCD_MODE_EXACT, "LCD inverse, exact solve (moving text)"},
                 {TDC_LCD_MODE_TABLE17, "LCD inverse, 17x17 table (moving text)"},
                 {TDC_LCD_MODE_TABLE33, "LCD inverse, 33x33 table (moving text)"},
                 {TDC_LCD_MODE_STATEFUL, "LCD inverse, stateful tables (moving text)"},
                 {TDC_LCD_MODE_STATEFUL_PAIR, "LCD inverse, stateful pair-fused, mean of a pair (moving text)"}};
    /* Every mode on one profile: the first LCD profile (TDC_PANEL_LIST
     * order) with the transition tables, i.e. every mode's tables (pg279q;
     * disco-dsi, first in the list, has neither those nor 33x33). */
    const tdc_panel_t *lcd = first_lcd_panel(TDC_LCD_MODE_STATEFUL_PAIR);
    if (!lcd) {
        return;
    }
    make_inputs(TDC_CONTENT_TEXT);
    for (unsigned m = 0; m < sizeof modes / sizeof modes[0]; m++) {
        const tdc_lcd_config_t cfg = {(uint16_t)BENCH_W, (uint16_t)BENCH_H, lcd->refresh_hz, modes[m].mode, 8u};
        if (tdc_lcd_init(&g_lcd, &cfg, lcd, g_lcd_arena, sizeof g_lcd_arena) != TDC_OK) {
            continue; /* the profile has no table of this size */
        }
        /* Frame 0 has no history (steady-state solve); measure frame 1. */
        if (tdc_lcd_frame(&g_lcd, g_in[0], BENCH_W * 3u, g_out, BENCH_W * 3u, NULL) != TDC_OK) {
            fail("LCD frame");
        }
        /* The pair mode differs between a pair's first and second refresh:
         * measure both (frames 1 and 2 from the owe/pay phases) and report
         * the mean per pixel. */
        const unsigned nf = modes[m].mode == TDC_LCD_MODE_STATEFUL_PAIR ? 2u : 1u;
        tdc_bench_mark();
        for (unsigned f = 0; f < nf; f++) {
            if (tdc_lcd_frame(&g_lcd, g_in[1u - f % 2u], BENCH_W * 3u, g_out, BENCH_W * 3u, NULL) != TDC_OK) {
                fail("LCD frame");
            }
        }
        tdc_bench_mark();
        report(modes[m].label, nf * BENCH_PX);
    }
}

/* Rows in flight (issue 17 item 2): a TRM stream in row bands of 16 rows
 * through the decoder (one band staged), each band's rows through TRM and
 * the LCD inverse (33x33 table) as it arrives, as the board loop does
 * (firmware/board/tdc_main.c, band_stages).  Measured per band: from
 * feeding its last byte (the decoder's checks and event) to its rows being
 * final (unpack, TRM rows, LCD rows).  Frames 0 and 1 fill the history;
 * frames 2 (FULL) and 3 (REDUCED) are measured. */
#define BAND_ROWS 16u
static void bench_bands(void)
{
    make_inputs(TDC_CONTENT_TEXT);
    trm_init_stream();
    if (!first_lcd_panel(TDC_LCD_MODE_TABLE33)) {
        fail("no LCD profile with a 33x33 table");
    }
    const tdc_link_stream_info_t info = {TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_BANDS, 1, 2, (uint16_t)BENCH_W,
                                         (uint16_t)BENCH_H, 1, 0, 90};
    tdc_link_encoder_t enc;
    tdc_link_encoder_init(&enc, 5, &info);
    const tdc_link_config_t dcfg = {(uint16_t)BENCH_W, (uint16_t)BENCH_H, 1};
    tdc_link_buffers_t b;
    memset(&b, 0, sizeof b);
    b.staging = g_staging;
    b.staging_bytes = TDC_LINK_STAGING_BAND_BYTES(BENCH_W, BAND_ROWS, 4u); /* one band, as a banded board */
    b.defer_full = 1;
    b.reduced[0] = g_samples;
    b.reduced_bytes = sizeof g_samples;
    if (tdc_link_decoder_init(&g_dec, &dcfg, &b) != TDC_OK) {
        fail("link decoder init");
    }
    tdc_link_event_t ev;
    size_t n = tdc_link_encode_stream(&enc, g_pkt[0], sizeof g_pkt[0]);
    for (size_t used = 0; used < n;) {
        used += tdc_link_feed(&g_dec, g_pkt[0] + used, n - used, &ev);
    }
    for (uint32_t f = 0; f < 4u; f++) {
        const int full = (f & 1u) == 0u;
        const uint32_t h = full ? BENCH_H : RH, nb = tdc_band_count(h, BAND_ROWS);
        uint32_t final_rows = 0;
        for (uint32_t i = 0; i < nb; i++) {
            n = full ? tdc_link_encode_band(&enc, g_pkt[0], sizeof g_pkt[0], TDC_LINK_KIND_FULL, 0, f, TDC_PIXFMT_RGB888,
                                            g_in[f & 1u], BENCH_W, BENCH_H, BENCH_W * 3u, BAND_ROWS, i)
                     : tdc_link_encode_band(&enc, g_pkt[0], sizeof g_pkt[0], TDC_LINK_KIND_REDUCED, 0, f,
                                            TDC_PIXFMT_RGB888, g_red[f & 1u], RW, RH, RW * 3u, BAND_ROWS, i);
            size_t used = 0;
            while (used + 1u < n) {
                used += tdc_link_feed(&g_dec, g_pkt[0] + used, n - 1u - used, &ev);
            }
            if (f >= 2u) {
                tdc_bench_mark();
            }
            ev.type = TDC_LINK_EV_NONE;
            while (ev.type != TDC_LINK_EV_PACKET) {
                const size_t k = tdc_link_feed(&g_dec, g_pkt[0] + used, n - used, &ev);
                used += k;
                if (ev.type == TDC_LINK_EV_NONE || ev.type == TDC_LINK_EV_ERROR) {
                    fail("band refused");
                }
            }
            const tdc_band_hdr_t *bh = tdc_link_band(&g_dec, 0);
            const int last = i + 1u == nb;
            const uint32_t avail = (uint32_t)bh->first_row + bh->rows;
            uint32_t done = 0;
            tdc_status_t st = TDC_OK;
            if (full) {
                st = tdc_link_unpack_full(&g_dec, g_out, BENCH_W * 3u);
                if (st == TDC_OK && i == 0u) {
                    st = tdc_trm_full_begin(&g_trm, g_out, BENCH_W * 3u, g_out, BENCH_W * 3u);
                }
                if (st == TDC_OK) {
                    st = last ? tdc_trm_full_end(&g_trm, f) : tdc_trm_full_rows(&g_trm, avail, &done);
                }
            } else {
                if (i == 0u) {
                    st = tdc_trm_reduced_begin(&g_trm, g_samples, RW * 3u, g_out, BENCH_W * 3u, f);
                }
                if (st == TDC_OK) {
                    st = last ? tdc_trm_reduced_end(&g_trm) : tdc_trm_reduced_rows(&g_trm, avail, &done);
                }
            }
            done = last ? BENCH_H : done;
            if (st != TDC_OK ||
                tdc_lcd_rows(&g_lcd, g_out, BENCH_W * 3u, g_out, BENCH_W * 3u, NULL, final_rows, done) != TDC_OK) {
                fail("band stages");
            }
            final_rows = done;
            if (last) {
                tdc_lcd_frame_done(&g_lcd);
            }
            if (f >= 2u) {
                tdc_bench_mark();
                report(full ? "band latency: FULL band of 16 rows, last byte to final pixels (TRM + LCD 33x33), per band"
                            : "band latency: REDUCED band of 16 rows, last byte to final pixels (TRM + LCD 33x33), per band",
                       1u);
            }
        }
    }
}

/* Foveated remap at alpha = 4, delta = 0.555, 12.443 % disk, gaze off-centre;
 * frame 0 fills the history, frame 1 is measured: with the same gaze (the
 * radial table and the column reciprocals kept), or with the gaze moved by
 * (1, 1) px (both rebuilt, as every frame of a moving gaze does).  lr: the
 * log-rectilinear kind at the same gaze, its foveal scales from the sender's
 * default rule (ref_fov_lr_k: 165.75 and 91.875 px at 640 x 360). */
static void bench_fov(uint8_t taa, uint8_t lr, int move, const char *label)
{
    const tdc_fov_config_t cfg = {(uint16_t)BENCH_W, (uint16_t)BENCH_H, taa};
    if (tdc_fov_init(&g_fov, &cfg, g_fov_arena, sizeof g_fov_arena) != TDC_OK ||
        tdc_fov_lr_init(&g_fov_lr, (uint16_t)BENCH_W, g_fov_lr_arena, sizeof g_fov_lr_arena) != TDC_OK ||
        tdc_fov_lr_attach(&g_fov, &g_fov_lr) != TDC_OK) {
        fail("fov init");
    }
    const tdc_fov_params_t p = {(int32_t)(BENCH_W * 110u),
                                (int32_t)(BENCH_H * 140u),
                                lr ? 256u : 1024u,
                                4077u,
                                (uint16_t)FOV_LW,
                                (uint16_t)FOV_LH,
                                {lr ? 2652u : 0u, lr ? 1470u : 0u},
                                lr ? TDC_FOV_LOG_RECT : TDC_FOV_KERNEL_LOG_POLAR,
                                0};
    tdc_content_frame(TDC_CONTENT_TEXT, 0u, 1u, g_fov_lp, (int)FOV_LW, (int)FOV_LH, (int)(FOV_LW * 3u));
    for (uint32_t k = 0; k < FOV_LW * FOV_LH; k++) {
        g_fov_mv[2u * k] = -24; /* a 1.5 px pan: backward MV */
        g_fov_mv[2u * k + 1u] = 0;
    }
    if (tdc_fov_frame(&g_fov, &p, g_fov_lp, FOV_LW * 3u, g_fov_mv, FOV_LW * 2u, g_in[0], BENCH_W * 3u, 11111u, g_out,
                      BENCH_W * 3u) != TDC_OK) {
        fail("fov frame");
    }
    tdc_fov_params_t p1 = p;
    p1.gaze_x_q8 += move ? 256 : 0;
    p1.gaze_y_q8 += move ? 256 : 0;
    tdc_bench_mark();
    if (tdc_fov_frame(&g_fov, &p1, g_fov_lp, FOV_LW * 3u, g_fov_mv, FOV_LW * 2u, g_in[1], BENCH_W * 3u, 11111u, g_out,
                      BENCH_W * 3u) != TDC_OK) {
        fail("fov frame");
    }
    tdc_bench_mark();
    report(label, BENCH_PX);
}

/* Layered tile assembly (tdc_layers.h) at LAYER_W x LAYER_H in the arena the
 * TRM and assembly benchmarks use (its 94 B/px with every layer would not
 * fit the boards' external RAM at 640 x 360), on the layered test stream:
 * 8 frames warm the history, the next 4 are measured. */
#define LAYER_W 320u
#define LAYER_H 160u
#define LAYER_T ((LAYER_W / 2u) * (LAYER_H / 2u))
#define g_lasm_arena g_arena
_Static_assert(TDC_LASM_MEM_BYTES(LAYER_W, LAYER_H) <= sizeof g_arena, "layered arena in the shared bench arena");
/* the layered samples (383 KiB) in external RAM: in the DTCM they overflowed
 * the M55's 512 KiB (mps3-an547 bench image did not link) */
static uint8_t g_lval[TDC_LAYER_MAX][LAYER_T * 3u] TDC_EXTRAM;
static int16_t g_lmv[TDC_LAYER_MAX][LAYER_T * 2u] TDC_EXTRAM;
static uint16_t g_lw[LAYER_T] TDC_EXTRAM;
static uint8_t g_lpat[TDC_PATTERN_BYTES(LAYER_W, LAYER_H)];
static tdc_lasm_t g_lasm;

/* With history (148 B/px) at LHIST_W x LHIST_H: the pair of rows with and
 * without it at that size gives the history's own cost per pixel. */
#define LHIST_W 160u
#define LHIST_H 80u
_Static_assert(TDC_LASM_MEM_BYTES_HIST(LHIST_W, LHIST_H) <= sizeof g_arena, "layered arena with history");

static void bench_layers_at(uint32_t w, uint32_t h, uint8_t history, uint16_t layers, uint8_t k, uint8_t cleanup,
                            uint8_t splat, int16_t sh_v, const char *label)
{
    const tdc_lasm_config_t cfg = {(uint16_t)w, (uint16_t)h, (uint16_t)(layers & TDC_LAYER_PKT_TYPES),
                                   k, cleanup, splat, history, 3277, &tdc_panel_htc_vive};
    if (tdc_lasm_init(&g_lasm, &cfg, g_lasm_arena, sizeof g_lasm_arena) != TDC_OK) {
        fail("layered assembly init");
    }
    const tdc_lcontent_t c = {(uint16_t)w, (uint16_t)h, layers, sh_v, 8, 18, -30, 10, 1, 0, 1u};
    tdc_layer_frame_t lf;
    TDC_LAYER_FRAME_WIRE(lf, g_lval, g_lmv, g_lw);
    for (uint32_t f = 0; f < 12u; f++) {
        tdc_layer_content_subframe(&c, f, g_lpat, &lf);
        if (f >= 8u) {
            tdc_bench_mark();
        }
        if (tdc_lasm_ingest(&g_lasm, f, &lf, g_lpat) != TDC_OK || tdc_lasm_assemble(&g_lasm, f) != TDC_OK) {
            fail("layered assembly");
        }
        if (f >= 8u) {
            tdc_bench_mark();
            report(label, w * h);
        }
    }
}

static void bench_layers(uint16_t layers, uint8_t k, uint8_t cleanup, uint8_t splat, int16_t sh_v, const char *label)
{
    bench_layers_at(LAYER_W, LAYER_H, 0, layers, k, cleanup, splat, sh_v, label);
}

/* Per-layer history (tdc_layer_hist.h, Zeng eq. 2/4) at HIST_W x HIST_H
 * (its inputs at LAYER_W x LAYER_H overflowed the AN500's PSRAM by 125 KiB)
 * in the same arena, on the noisy panning layer of tdc_lhist_content.h:
 * 4 frames warm it, the next 2 are measured. */
#define HIST_W 160u
#define HIST_H 80u
_Static_assert(TDC_LHIST_MEM_BYTES(HIST_W, HIST_H) <= sizeof g_arena, "history arena in the shared bench arena");
static uint8_t g_hx[HIST_W * HIST_H * 3u] TDC_EXTRAM;
static int16_t g_hmv[HIST_W * HIST_H * 2u] TDC_EXTRAM;
static uint16_t g_hg[HIST_W * HIST_H] TDC_EXTRAM;
static tdc_lhist_t g_lhist;

static void bench_lhist(uint8_t ch, uint8_t k, uint8_t falloff, const char *label)
{
    const tdc_lhist_config_t cfg = {(uint16_t)HIST_W, (uint16_t)HIST_H, ch, k, 3277};
    const tdc_lhist_content_t c = {(uint16_t)HIST_W, (uint16_t)HIST_H, ch, 30, 20, -6, 0, falloff, 1u};
    if (tdc_lhist_init(&g_lhist, &cfg, g_arena, sizeof g_arena) != TDC_OK) {
        fail("layer history init");
    }
    for (uint32_t f = 0; f < 6u; f++) {
        tdc_lhist_content(&c, f, g_hx, g_hmv, g_hg);
        if (f >= 4u) {
            tdc_bench_mark();
        }
        if (tdc_lhist_step(&g_lhist, g_hx, g_hmv, falloff ? g_hg : NULL) != TDC_OK) {
            fail("layer history");
        }
        if (f >= 4u) {
            tdc_bench_mark();
            report(label, HIST_W * HIST_H);
        }
    }
}

/* Group from QEMU's -append (last word): link, trm, assemble, lcd, fov, layers; anything
 * else runs all (make profile-arm runs one group under the profiler). */
static int want(const char *group)
{
    static char cmd[256];
    static const char *word;
    if (!word) {
        word = "";
        if (tdc_semihost_cmdline(cmd, sizeof cmd) >= 0) {
            word = cmd;
            for (const char *p = cmd; *p; p++) {
                if (*p == ' ') {
                    word = p + 1;
                }
            }
        }
    }
    static const char *const groups[] = {"link", "trm", "assemble", "lcd", "fov", "layers", "bands"};
    int known = 0;
    for (unsigned i = 0; i < sizeof groups / sizeof groups[0]; i++) {
        known |= !strcmp(word, groups[i]);
    }
    return !known || !strcmp(word, group);
}

int main(void)
{
    tdc_bench_mark();
    tdc_bench_mark();
    report("(mark overhead)", 1u);
    make_inputs(TDC_CONTENT_TEXT);
    if (want("link")) {
        bench_memcpy();
        bench_link(TDC_PIXFMT_RGB888, "link decode, full frame RGB888");
        bench_link(TDC_PIXFMT_RGB565, "link decode, full frame RGB565");
        bench_link(TDC_PIXFMT_YCBCR420, "link decode, full frame YCbCr 4:2:0");
    }
    if (want("trm")) {
        bench_trm(TDC_CONTENT_TEXT, "TRM full-res frame (moving text)", "TRM reduced frame r=1/2 (moving text)");
        bench_trm(TDC_CONTENT_NOISE, "TRM full-res frame (noise)", "TRM reduced frame r=1/2 (noise)");
        bench_trm_static();
    }
    if (want("assemble")) {
        bench_assemble(0, "tile assembly, static (4x SSAA window)");
        bench_assemble(1, "tile assembly, dynamic (reprojection + clamp)");
    }
    if (want("layers")) {
        const uint16_t sh = TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING), vi = TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY);
        const uint16_t all = 0xFu | TDC_LAYER_PKT_FALLOFF;
        bench_layers(sh, 1, 0, 0, 24, "layered assembly, one layer (pan)");
        bench_layers(sh | vi | TDC_LAYER_PKT_FALLOFF, 3, 0, 2, 0, "layered assembly, fence (shadow MVs, splat)");
        bench_layers(sh | vi | TDC_LAYER_PKT_FALLOFF, 3, 1, 2, 0, "layered assembly, fence + clean-up");
        bench_layers(all, 3, 1, 2, 24, "layered assembly, all 4 layers + clean-up");
        bench_layers_at(LHIST_W, LHIST_H, 0, all, 3, 1, 2, 24, "layered assembly, all 4 layers + clean-up, 160x80");
        bench_layers_at(LHIST_W, LHIST_H, 1, all, 3, 1, 2, 24, "layered assembly, all 4 layers + clean-up + history, 160x80");
        bench_lhist(3, 3, 0, "layer history, colour layer (eq. 2, 3 sigma)");
        bench_lhist(1, 3, 1, "layer history, visibility (eq. 2 + eq. 4 falloff, 3 sigma)");
    }
    if (want("lcd")) {
        bench_lcd();
    }
    if (want("bands")) {
        bench_bands();
    }
    if (want("fov")) {
        bench_fov(0, 0, 0, "foveated remap (alpha 4, 12.4 % disk)");
        bench_fov(1, 0, 0, "foveated remap + peripheral TAA");
        bench_fov(0, 0, 1, "foveated remap, gaze moved (tables rebuilt)");
        bench_fov(0, 1, 0, "foveated remap, log-rectilinear");
        bench_fov(1, 1, 0, "foveated remap, log-rectilinear + TAA");
    }
    return 0;
}
