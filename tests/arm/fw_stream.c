/*
 * fw_stream.c - writes the link streams the firmware frame loop is tested
 * with (on the host double and on the emulated boards), through the host
 * link encoder (firmware/tdc_link_encode.h).
 *
 * Usage: fw_stream MODE WIDTH HEIGHT EYES FRAMES OUT.tdcs [EXPECTED]
 *   plain      full RGB888 frames every refresh; frame 1 of eye 0 arrives
 *              with a corrupted payload byte (must be rejected: the eye
 *              keeps frame 0), frame 2 of the last eye in RGB565, frame 3
 *              of eye 0 is lost on the way (never sent: the loop learns it
 *              only from frame 4's FULL packet; frame 3 is shown with eye 0
 *              keeping frame 2, since a FULL packet is unpacked only when
 *              its eye is updated, never into the frame still collected)
 *   trm        TRM stream, r = 1/2 at 90 Hz: per frame one eye full, the
 *              other reduced (2x2 box prefilter), swapped every frame
 *   subframes  240 Hz tile-ordered subframes: hourglass pattern bits on the
 *              first frame of every cycle, one sample per 2x2 tile, and a
 *              motion vector per sample (content panning 3 px per frame)
 * Crafted variants (issue 17: the loop must show what the plain stream
 * shows; tests/arm/test_fw_loop.sh compares them):
 *   trm-motion      the renderer's TRM stream: also per-pixel MOTION
 *                   packets (stream flag MOTION), which no stage uses
 *   trm-future      after frame 0, the packets of both eyes with a valid
 *                   header CRC, frame index 0x7FFFFFF0 and a bad payload CRC
 *   trm-rehdr       the identical stream header again after every frame
 *   trm-resend      frame 2: eye 0's FULL corrupted, then resent intact
 *                   after eye 1's packet; frame 3: eye 0's REDUCED corrupted
 *   trm-resend-ref  frame 2 intact, frame 3 eye 0's REDUCED corrupted
 *   subframes-late  the subframe stream with frame indices from 1000
 *   trm-drop        frame 2: eye 0's FULL corrupted (rejected, eye kept)
 *   trm-fov         foveated TRM (stream flags REDUCED | FOVEATED, as the
 *                   foveated streams below, no vectors): each slot as a
 *                   FOVEATED packet, the reduced one on the rW x rH grid
 *                   (tdc_link_encode_foveated_slot) from the 2x2 box
 *                   reduced picture; frame 1 of eye 0 (a reduced slot) with a
 *                   corrupted payload byte (CRC: kept), frame 4 of eye 0 (a
 *                   full slot) with a foveation header the decoder refuses
 *                   (alpha 9.0: kept, and frame 5's reduced slot of that eye
 *                   shown without residual), frame 6 every eye's slot as a
 *                   plain FULL or REDUCED picture; trm-fov-clean: without
 *                   those three (make bench-arm's loop row)
 * Rows in flight (issue 17 item 2; tests/arm/test_fw_bands.sh): the TRM
 * stream with stream flag BANDS, every picture as bands of 16 rows:
 *   trm-bands          clean: must show what trm shows through the loop
 *                      without bands
 *   trm-bands-crc      frame 2, eye 0's FULL: band 3 with a bad payload CRC
 *   trm-bands-order    ... bands 3 and 4 swapped
 *   trm-bands-missing  ... its last band never sent
 *   trm-bands-size     ... band 3 in bands of 8 rows (the frame changes size)
 *                      (these four must show what trm-drop shows)
 *   trm-bands-other    ... band 5 of frame 4 between its bands 2 and 3 (a
 *                      band for another frame: refused alone, as trm)
 * Foveated streams (issue 14; stream flag FOVEATED, tdc_link_encode_foveated),
 * alpha 4, delta 0.555 (18187), disk 12.443 %, the gaze moving every frame:
 *   fov        kernel log-polar samples (the picture's pixel at each
 *              sample's display position, ref_fov_lp_samples: the sender's
 *              placement), no vectors
 *   fov-taa    the same with a vector per sample (peripheral TAA)
 *   fovlr      log-rectilinear: area averages of the picture (the sender's
 *              summed-area table, ref/ref_fov_lr.c), no vectors
 *   in each (9 frames: mono panels too keep runs of consecutive TAA frames):
 *   frame 1 of eye 0 with a corrupted payload byte (CRC: eye 0 keeps
 *   frame 0, and under TAA its next frame starts a new history), frame 4
 *   of the last eye with a foveation header the decoder refuses (fov,
 *   fov-taa: alpha 9.0; fovlr: the gaze two screens outside; both CRCs
 *   recomputed, so only the foveation check can refuse it: kept), and
 *   frame 6 of the last eye a FULL picture (shown as it is; TAA starts
 *   again after it).  fov-clean, fov-taa-clean, fovlr-clean: the same
 *   streams without those three (make bench-arm's frame-loop rows).
 * Layered streams (stream flags SUBFRAMES | LAYERS; tests/arm/fw_stream.c
 * layers_stream): the four layers of tests/golden/tdc_layer_content.h
 * (shading panning, visibility with shadow vectors and falloff, glossy,
 * indirect), a hash ordering per cycle (PATTERN on frame 0 mod 4):
 *   layers       the layered assembly without history
 *   layers-hist  stream flag LAYER_HIST: with the per-layer history
 *   EXPECTED: every frame as tdc_layers itself assembles the packets sent,
 *   with the configuration the loop's layered family uses (PANEL: the
 *   panel's gamma for the recombination).
 * Contents: tests/golden/tdc_content.h (edge on eye 0, text on eye 1).
 *
 * EXPECTED (plain and foveated modes, for panels that show the decoded
 * codes, i.e. not LCD; trm-fov with PANEL, the panel's name, for TRM's
 * profile, and only if TRM accepts the panel's rate): the "frame N
 * fnv1a64" lines the panel must show,
 * computed here independently of the firmware loop: each eye's packet
 * payload unpacked into a side-by-side frame buffer (a foveated one through
 * the stage, tdc_fov_frame, of this program's own per eye: TAA only on
 * packets with vectors, from the eye's previous frame's history, at the
 * stream's frame time), a refused packet's eye keeping its previous image,
 * a frame with no accepted packet not shown at all.  trm-fov: each slot's
 * picture through this program's own stage instance of that slot's grid
 * (tdc_fov_frame into a separate picture), then the slot's TRM step
 * (tdc_trm_full_seq / tdc_trm_reduced_seq, configured as the board
 * configures it) into the frame buffer.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <math.h>

#include "ref_fov.h"
#include "ref_fov_lr.h"
#include "tdc_content.h"
#include "tdc_crc32.h"
#include "tdc_fov_lr.h"
#include "tdc_layer_content.h"
#include "tdc_layers.h"
#include "tdc_math.h"
#include "tdc_link_encode.h"
#include "tdc_ordering.h"
#include "tdc_pixfmt.h"
#include "tdc_trm.h"
#include "tdc_panels.h"

static uint8_t *g_pkt;
static size_t g_cap;
static FILE *g_out;

static void put(size_t n, const char *what)
{
    if (n == 0 || fwrite(g_pkt, 1, n, g_out) != n) {
        fprintf(stderr, "fw_stream: cannot encode/write %s\n", what);
        exit(1);
    }
}

/* Row bands of 16 rows of a picture; frame 2, eye 0 damaged per `how`. */
static void put_bands(const tdc_link_encoder_t *enc, tdc_link_kind_t kind, uint32_t e, uint32_t f, const uint8_t *rgb,
                      uint32_t w, uint32_t h, const char *how)
{
    const uint32_t br = 16, n = tdc_band_count(h, br);
    const int bad = f == 2 && e == 0 && kind == TDC_LINK_KIND_FULL && *how;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t idx = i, rows = br, fr = f;
        if (bad && !strcmp(how, "order") && (i == 3 || i == 4)) {
            idx = 7 - i;
        }
        if (bad && !strcmp(how, "missing") && i + 1 == n) {
            break;
        }
        if (bad && !strcmp(how, "size") && i == 3) {
            idx = 6;
            rows = 8;
        }
        size_t k = tdc_link_encode_band(enc, g_pkt, g_cap, kind, e, fr, TDC_PIXFMT_RGB888, rgb, w, h, w * 3u, rows, idx);
        if (bad && !strcmp(how, "crc") && i == 3) {
            g_pkt[TDC_LINK_HEADER_BYTES + TDC_BAND_HDR_BYTES + 5u] ^= 0x20u;
        }
        put(k, "band");
        if (bad && !strcmp(how, "other") && i == 2) {
            put(tdc_link_encode_band(enc, g_pkt, g_cap, kind, e, f + 2u, TDC_PIXFMT_RGB888, rgb, w, h, w * 3u, br, 5),
                "band of another frame");
        }
    }
}

static tdc_content_t eye_content(uint32_t eye)
{
    return eye ? TDC_CONTENT_TEXT : TDC_CONTENT_EDGE;
}

/* ---- foveated streams ---- */
#define FOV_DELTA_Q15 18187u
typedef struct {
    tdc_fov_t st;
    tdc_fov_lr_t lr;
    void *arena, *lr_arena;
    uint8_t *lp, *disk;
    int16_t *mv;
    int have;      /* last: the eye's last frame through the stage */
    uint32_t last;
} fov_ref_t;

/* The reference stage of one eye (EXPECTED), TAA as the board builds it. */
static void fov_ref_init(fov_ref_t *r, uint32_t w, uint32_t h, int taa)
{
    const tdc_fov_config_t cfg = {(uint16_t)w, (uint16_t)h, (uint8_t)taa};
    const size_t n = (tdc_fov_get_size(&cfg) + 7u) & ~(size_t)7u, ln = (tdc_fov_lr_get_size((uint16_t)w) + 7u) & ~(size_t)7u;
    const size_t lp = (size_t)tdc_fov_lp_size(FOV_DELTA_Q15, (uint16_t)w) * tdc_fov_lp_size(FOV_DELTA_Q15, (uint16_t)h);
    r->arena = aligned_alloc(8, n);
    r->lr_arena = aligned_alloc(8, ln);
    r->lp = malloc(lp * 3u);
    r->mv = malloc(lp * 4u);
    r->disk = malloc((size_t)w * h * 3u);
    r->have = 0;
    if (!r->arena || !r->lr_arena || !r->lp || !r->mv || !r->disk || tdc_fov_init(&r->st, &cfg, r->arena, n) != TDC_OK ||
        tdc_fov_lr_init(&r->lr, (uint16_t)w, r->lr_arena, ln) != TDC_OK || tdc_fov_lr_attach(&r->st, &r->lr) != TDC_OK) {
        fprintf(stderr, "fw_stream: foveation reference init failed\n");
        exit(1);
    }
}

static void fov_ref_free(fov_ref_t *r)
{
    free(r->arena);
    free(r->lr_arena);
    free(r->lp);
    free(r->mv);
    free(r->disk);
}

/* The packet pkt (accepted by the decoder) through the reference stage
 * into out; returns 1 if out changed. */
static int fov_ref_frame(fov_ref_t *r, const uint8_t *pkt, uint32_t frame, uint32_t w, uint32_t h, uint32_t dt_us,
                         uint8_t *out, size_t out_stride)
{
    tdc_fov_hdr_t fh;
    if (tdc_fov_hdr_parse(pkt + TDC_LINK_HEADER_BYTES, (uint16_t)w, (uint16_t)h, &fh) != TDC_FOV_HDR_OK) {
        return 0;
    }
    tdc_fov_unpack(&fh, pkt + TDC_LINK_HEADER_BYTES + TDC_FOV_HDR_BYTES, r->lp, (size_t)fh.p.lp_w * 3u, r->mv,
                   (size_t)fh.p.lp_w * 2u, r->disk, (size_t)w * 3u);
    const int taa = (fh.flags & TDC_FOV_FLAG_MV) != 0;
    if (!taa || !r->have || frame != r->last + 1u) {
        tdc_fov_reset(&r->st);
    }
    if (tdc_fov_frame(&r->st, &fh.p, r->lp, (size_t)fh.p.lp_w * 3u, taa ? r->mv : NULL, (size_t)fh.p.lp_w * 2u,
                      r->disk, (size_t)w * 3u, dt_us, out, out_stride) != TDC_OK) {
        r->have = 0;
        return 0;
    }
    r->have = taa;
    r->last = frame;
    return 1;
}

/* ---- foveated TRM (trm-fov) ---- */
/* The 2x2 box prefilter of the TRM streams' reduced frames (rounded; edge
 * pixels replicated). */
static void box_reduce(const uint8_t *rgb, uint32_t w, uint32_t h, uint8_t *red, uint32_t rw, uint32_t rh)
{
    for (uint32_t y = 0; y < rh; y++) {
        for (uint32_t x = 0; x < rw; x++) {
            for (uint32_t c = 0; c < 3; c++) {
                uint32_t s = 0;
                for (uint32_t k = 0; k < 4; k++) {
                    uint32_t xx = 2 * x + (k & 1), yy = 2 * y + (k >> 1);
                    xx = xx < w ? xx : w - 1;
                    yy = yy < h ? yy : h - 1;
                    s += rgb[((size_t)yy * w + xx) * 3 + c];
                }
                red[((size_t)y * rw + x) * 3 + c] = (uint8_t)((s + 2) / 4);
            }
        }
    }
}

typedef struct {
    fov_ref_t full, red; /* one stage instance per slot grid */
    tdc_trm_t trm;
    void *arena;
    uint8_t *pic; /* the slot's picture after the remap (or unpacked) */
    uint32_t rw, rh;
} fovtrm_ref_t;

/* Eye reference of a foveated TRM stream (EXPECTED): TRM configured as the
 * board's loop configures it (the stream's rate if the panel has it, else
 * the panel's own; r = 1/2, reduced frames in the stream, rho not kept).
 * Returns 0 if TRM refuses the panel (the loop refuses the stream then). */
static int fovtrm_ref_init(fovtrm_ref_t *r, const tdc_panel_t *panel, uint32_t w, uint32_t h, uint16_t stream_hz)
{
    uint16_t hz = panel->refresh_hz;
    for (unsigned i = 0; i < TDC_PANEL_MAX_RATES && panel->rates_hz[i]; i++) {
        hz = panel->rates_hz[i] == stream_hz ? stream_hz : hz;
    }
    tdc_trm_config_t cfg;
    tdc_trm_default_config(&cfg, (uint16_t)w, (uint16_t)h, hz);
    cfg.r_num = 1;
    cfg.r_den = 2;
    cfg.reduced_in_stream = 1;
    cfg.keep_residual = 0;
    const size_t n = (tdc_trm_get_size(&cfg) + 7u) & ~(size_t)7u;
    r->arena = n ? aligned_alloc(8, n) : NULL;
    if (!r->arena || tdc_trm_init(&r->trm, &cfg, panel, r->arena, n) != TDC_OK) {
        free(r->arena);
        return 0;
    }
    r->rw = TDC_REDUCED_DIM(w, 1u, 2u);
    r->rh = TDC_REDUCED_DIM(h, 1u, 2u);
    fov_ref_init(&r->full, w, h, 0);
    fov_ref_init(&r->red, r->rw, r->rh, 0);
    r->pic = malloc((size_t)w * h * 3u);
    if (!r->pic) {
        fprintf(stderr, "fw_stream: out of memory\n");
        exit(1);
    }
    return 1;
}

static void fovtrm_ref_free(fovtrm_ref_t *r)
{
    fov_ref_free(&r->full);
    fov_ref_free(&r->red);
    free(r->arena);
    free(r->pic);
}

/* Packet pkt (accepted by the decoder) of eye e's slot in frame f, FOVEATED
 * or (plain) a FULL / REDUCED picture: the slot's picture, then TRM's step
 * into out; returns 1 if out changed. */
static int fovtrm_ref_frame(fovtrm_ref_t *r, const uint8_t *pkt, int red, int plain, uint32_t f, uint32_t w,
                            uint32_t h, uint8_t *out, size_t out_stride)
{
    const uint32_t gw = red ? r->rw : w, gh = red ? r->rh : h;
    if (plain) {
        tdc_pixfmt_unpack(TDC_PIXFMT_RGB888, pkt + TDC_LINK_HEADER_BYTES, gw, gh, r->pic, gw * 3u);
    } else if (!fov_ref_frame(red ? &r->red : &r->full, pkt, f, gw, gh, 0, r->pic, (size_t)gw * 3u)) {
        return 0;
    }
    const tdc_status_t st = red ? tdc_trm_reduced_seq(&r->trm, r->pic, gw * 3u, out, (uint32_t)out_stride, f)
                                : tdc_trm_full_seq(&r->trm, r->pic, gw * 3u, out, (uint32_t)out_stride, f);
    return st == TDC_OK;
}

/* Eye e's FOVEATED packet of frame f for the stream's slot (FULL, or a TRM
 * stream's REDUCED: then rgb, w, h are the reduced grid's) from the
 * picture rgb: the gaze moves across the screen, samples where the sender
 * takes them (ref_fov_lp_samples for kernel log-polar, summed-area averages
 * for log-rectilinear), backward vectors (the edge content pans +3 px per
 * frame) if mv_buf. */
static size_t fov_packet(const tdc_link_encoder_t *enc, tdc_link_kind_t slot, uint32_t e, uint32_t f,
                         const uint8_t *rgb, uint32_t w, uint32_t h, int lr, int16_t *mv_buf, uint8_t *samples)
{
    tdc_fov_params_t p;
    memset(&p, 0, sizeof p);
    p.gaze_x_q8 = (int32_t)lround((0.30 + 0.05 * f + 0.05 * e) * w * 256.0);
    p.gaze_y_q8 = (int32_t)lround((0.45 + 0.02 * f) * h * 256.0);
    p.alpha_q8 = lr ? 256u : 1024u;
    p.disk_q15 = 4077u; /* 12.443 % */
    p.lp_w = tdc_fov_lp_size(FOV_DELTA_Q15, (uint16_t)w);
    p.lp_h = tdc_fov_lp_size(FOV_DELTA_Q15, (uint16_t)h);
    p.transform = lr ? TDC_FOV_LOG_RECT : TDC_FOV_KERNEL_LOG_POLAR;
    const double gx = p.gaze_x_q8 / 256.0, gy = p.gaze_y_q8 / 256.0;
    if (lr) {
        p.lr_k_q4[0] = (uint16_t)lround(16 * ref_fov_lr_k((int)w, p.lp_w, gx));
        p.lr_k_q4[1] = (uint16_t)lround(16 * ref_fov_lr_k((int)h, p.lp_h, gy));
    }
    tdc_fov_geom_t g;
    if (tdc_fov_geom(&g, (uint16_t)w, (uint16_t)h, &p) != TDC_OK) {
        fprintf(stderr, "fw_stream: foveation geometry refused\n");
        exit(1);
    }
    size_t k = 0;
    if (lr) {
        ref_fov_lr_axis_t ax, ay;
        ref_fov_lr_axis(&ax, gx, p.lr_k_q4[0] / 16.0, (int)w, p.lp_w);
        ref_fov_lr_axis(&ay, gy, p.lr_k_q4[1] / 16.0, (int)h, p.lp_h);
        double *sat = ref_fov_lr_sat(rgb, (size_t)w * 3u, (int)w, (int)h, NULL);
        if (!sat) {
            fprintf(stderr, "fw_stream: out of memory\n");
            exit(1);
        }
        ref_fov_lr_buffer(sat, (int)w, (int)h, &ax, &ay, samples, (size_t)p.lp_w * 3u, NULL, NULL);
        free(sat);
        k = (size_t)p.lp_w * p.lp_h;
    } else {
        /* the sender's placement (no jitter, no LOD), the picture's pixel under each */
        const ref_fov_params_t rp = {gx, gy, p.alpha_q8 / 256.0, p.disk_q15 / 32768.0, p.lp_w, p.lp_h, 0, 0, 0};
        ref_fov_geom_t rg;
        ref_fov_geom(&rg, (int)w, (int)h, &rp);
        double *xy = malloc((size_t)p.lp_w * p.lp_h * 2u * sizeof *xy);
        if (!xy) {
            fprintf(stderr, "fw_stream: out of memory\n");
            exit(1);
        }
        k = ref_fov_lp_samples(&rg, g.u0, 0.0, 0.0, TDC_FOV_JITTER_TEXEL, TDC_FOV_LOD_OFF, xy, NULL);
        for (size_t i = 0; i < k; i++) {
            const long xi = lround(fmin(fmax(floor(xy[2 * i]), 0), w - 1.0));
            const long yi = lround(fmin(fmax(floor(xy[2 * i + 1]), 0), h - 1.0));
            memcpy(samples + 3u * i, rgb + ((size_t)yi * w + (size_t)xi) * 3u, 3);
        }
        free(xy);
    }
    for (size_t i = 0; mv_buf && i < k; i++) {
        mv_buf[2 * i] = (int16_t)(e == 0 ? -3 * 16 : (int)(i % 7u) - 3);
        mv_buf[2 * i + 1] = (int16_t)(e == 1 ? 2 * 16 : 0);
    }
    for (uint32_t j = 0; j < h; j++) {
        int32_t x0;
        const uint32_t span = tdc_fov_disk_span(&g, (int32_t)j, &x0);
        memcpy(samples + 3u * k, rgb + ((size_t)j * w + (size_t)x0) * 3u, 3u * (size_t)span);
        k += span;
    }
    return tdc_link_encode_foveated_slot(enc, g_pkt, g_cap, slot, e, f, &p, FOV_DELTA_Q15, samples, mv_buf, NULL);
}

/* A foveation header the decoder must refuse after the payload CRC: byte
 * `at` of it set to v (little-endian int32 if wide), both CRCs recomputed. */
/* The layered streams (see the top): the stream, and with `expect` the
 * frames tdc_layers shows for it.  0, or 1 on a failure (said on stderr). */
static int layers_stream(int hist, uint32_t w, uint32_t h, uint32_t eyes, uint32_t frames, const char *out,
                         const char *expect_path, const tdc_panel_t *panel)
{
    tdc_link_stream_info_t info = {0};
    info.flags = TDC_LINK_STREAM_SUBFRAMES | TDC_LINK_STREAM_LAYERS | (hist ? TDC_LINK_STREAM_LAYER_HIST : 0u);
    info.r_num = info.r_den = 1;
    info.width = (uint16_t)w;
    info.height = (uint16_t)h;
    info.eyes = (uint8_t)eyes;
    info.refresh_hz = 240;
    tdc_link_encoder_t enc;
    tdc_link_encoder_init(&enc, 7, &info);
    const uint32_t tiles = TDC_TILE_COUNT(w, h), bm = TDC_PATTERN_BYTES(w, h);
    const uint16_t set = TDC_LAYER_PKT_TYPES | TDC_LAYER_PKT_FALLOFF;
    g_cap = TDC_LINK_HEADER_BYTES + TDC_LINK_STAGING_LAYERS_BYTES(w, h) + (size_t)bm + 1024u;
    g_pkt = malloc(g_cap);
    uint8_t *bits = calloc(bm + 1u, 1), *planes = malloc((size_t)tiles * 28u), *fb = NULL;
    g_out = fopen(out, "wb");
    FILE *expect = expect_path ? fopen(expect_path, "w") : NULL;
    tdc_lasm_t st[2];
    void *arena[2] = {NULL, NULL};
    const tdc_lasm_config_t cfg = {(uint16_t)w, (uint16_t)h, TDC_LAYER_PKT_TYPES, TDC_LASM_CLAMP_ZENG, 1u, 2u,
                                   (uint8_t)hist, 3277u, panel};
    const size_t an = tdc_lasm_get_size(&cfg);
    if (!g_pkt || !bits || !planes || !g_out || (expect_path && (!expect || !panel || !an))) {
        fprintf(stderr, "fw_stream: out of memory, no panel, or cannot create %s / %s\n", out,
                expect_path ? expect_path : "-");
        return 1;
    }
    if (expect) {
        fb = calloc((size_t)eyes * w * h * 3u, 1);
        for (uint32_t e = 0; e < eyes; e++) {
            arena[e] = aligned_alloc(8, (an + 7u) & ~(size_t)7u);
            if (!fb || !arena[e] || tdc_lasm_init(&st[e], &cfg, arena[e], an) != TDC_OK) {
                fprintf(stderr, "fw_stream: layered assembly set-up failed\n");
                return 1;
            }
        }
    }
    tdc_layer_frame_t lf;
    memset(&lf, 0, sizeof lf);
    for (unsigned t = 0; t < TDC_LAYER_MAX; t++) {
        lf.value[t] = planes + (size_t)tiles * 3u * t;
        lf.mv[t] = (int16_t *)(void *)(planes + (size_t)tiles * 12u + (size_t)tiles * 4u * t);
    }
    lf.falloff = (uint16_t *)(void *)(planes + (size_t)tiles * 28u - (size_t)tiles * 2u);
    put(tdc_link_encode_stream(&enc, g_pkt, g_cap), "stream header");
    for (uint32_t f = 0; f < frames; f++) {
        if ((f & 3u) == 0) {
            for (uint32_t i = 0; i < bm; i++) {
                bits[i] = (uint8_t)(tdc_hash3(i, f, 77u) & 0xFFu);
            }
        }
        for (uint32_t e = 0; e < eyes; e++) {
            const tdc_lcontent_t c = {(uint16_t)w, (uint16_t)h, set, 12, -6, 18, -30, 10, 1, 0, 5u + e};
            tdc_layer_content_subframe(&c, f, bits, &lf);
            if ((f & 3u) == 0) {
                put(tdc_link_encode_pattern(&enc, g_pkt, g_cap, e, f, bits, w, h), "pattern");
            }
            put(tdc_link_encode_layers(&enc, g_pkt, g_cap, e, f, &lf, lf.present, lf.hdr.mv_kind, w, h), "layers");
            if (expect) {
                if (tdc_lasm_ingest(&st[e], f, &lf, (f & 3u) == 0 ? bits : NULL) != TDC_OK ||
                    tdc_lasm_assemble(&st[e], f) != TDC_OK) {
                    fprintf(stderr, "fw_stream: layered assembly failed at frame %u\n", (unsigned)f);
                    return 1;
                }
                const uint8_t *o = tdc_lasm_output(&st[e], NULL);
                for (uint32_t y = 0; y < h; y++) {
                    memcpy(fb + ((size_t)y * eyes + e) * w * 3u, o + (size_t)y * w * 3u, (size_t)w * 3u);
                }
            }
        }
        if (expect) {
            uint64_t hash = 0xcbf29ce484222325ULL;
            for (size_t i = 0; i < (size_t)eyes * w * h * 3u; i++) {
                hash = (hash ^ fb[i]) * 0x100000001b3ULL;
            }
            fprintf(expect, "frame %u %016llx\n", (unsigned)f, (unsigned long long)hash);
        }
    }
    int rc = 0;
    if ((expect && fclose(expect) != 0) || fclose(g_out) != 0) {
        fprintf(stderr, "fw_stream: write error\n");
        rc = 1;
    }
    free(arena[0]);
    free(arena[1]);
    free(fb);
    free(planes);
    free(bits);
    free(g_pkt);
    return rc;
}

static void fov_spoil(size_t n, uint32_t at, int32_t v, int wide)
{
    tdc_link_header_t hh;
    (void)tdc_link_header_unpack(g_pkt, &hh);
    uint8_t *fh = g_pkt + TDC_LINK_HEADER_BYTES;
    if (wide) {
        for (unsigned i = 0; i < 4; i++) {
            fh[at + i] = (uint8_t)((uint32_t)v >> (8u * i));
        }
    } else {
        fh[at] = (uint8_t)v;
    }
    hh.payload_crc = tdc_crc32(fh, n - TDC_LINK_HEADER_BYTES);
    tdc_link_header_pack(g_pkt, &hh);
}

int main(int argc, char **argv)
{
    if (argc < 7 || argc > 9) {
        fprintf(stderr,
                "usage: %s plain|trm|subframes|fov|fov-taa|fovlr|trm-fov|... W H EYES FRAMES OUT.tdcs [EXPECTED [PANEL]]\n",
                argv[0]);
        return 2;
    }
    const char *mode = argv[1];
    const uint32_t w = (uint32_t)atoi(argv[2]), h = (uint32_t)atoi(argv[3]);
    const uint32_t eyes = (uint32_t)atoi(argv[4]), frames = (uint32_t)atoi(argv[5]);
    if (w < 2 || h < 2 || eyes < 1 || eyes > 2 || frames < 1) {
        fprintf(stderr, "fw_stream: bad size\n");
        return 2;
    }
    if (!strcmp(mode, "layers") || !strcmp(mode, "layers-hist")) {
        const tdc_panel_t *panel = NULL;
#define X(p) &p,
        static const tdc_panel_t *const lpanels[] = {TDC_PANEL_LIST(X) NULL};
#undef X
        for (unsigned i = 0; argc == 9 && lpanels[i]; i++) {
            panel = !panel && !strcmp(lpanels[i]->name, argv[8]) ? lpanels[i] : panel;
        }
        return layers_stream(!strcmp(mode, "layers-hist"), w, h, eyes, frames, argv[6], argc == 9 ? argv[7] : NULL,
                             panel);
    }
    const int trm = !strncmp(mode, "trm", 3), sub = !strncmp(mode, "subframes", 9), plain = !strcmp(mode, "plain");
    /* (fov*-clean: the same stream without the damaged packets: make bench-arm's loop rows) */
    const size_t ml = strlen(mode), fov_clean = ml > 6 && !strcmp(mode + ml - 6, "-clean");
    char fmode[16] = "";
    if (ml - (fov_clean ? 6u : 0u) < sizeof fmode) {
        memcpy(fmode, mode, ml - (fov_clean ? 6u : 0u));
    }
    const int fov = !strcmp(fmode, "fov") || !strcmp(fmode, "fov-taa") || !strcmp(fmode, "fovlr");
    const int fov_taa = !strcmp(fmode, "fov-taa"), fov_lr = !strcmp(fmode, "fovlr");
    const int v_motion = !strcmp(mode, "trm-motion"), v_future = !strcmp(mode, "trm-future");
    const int v_rehdr = !strcmp(mode, "trm-rehdr"), v_resend = !strcmp(mode, "trm-resend");
    const int v_resend_ref = !strcmp(mode, "trm-resend-ref"), v_fovtrm = !strcmp(fmode, "trm-fov");
    const uint32_t f0 = !strcmp(mode, "subframes-late") ? 1000u : 0u;
    const int bands = !strncmp(mode, "trm-bands", 9), v_drop = !strcmp(mode, "trm-drop");
    const char *band_how = bands && mode[9] == '-' ? mode + 10 : "";
    if (!trm && !sub && !plain && !fov) {
        fprintf(stderr, "fw_stream: unknown mode %s\n", mode);
        return 2;
    }
    tdc_link_stream_info_t info = {0};
    info.flags = trm ? TDC_LINK_STREAM_REDUCED : sub ? (TDC_LINK_STREAM_SUBFRAMES | TDC_LINK_STREAM_SAMPLE_MV) : 0u;
    if (fov) {
        info.flags = TDC_LINK_STREAM_FOVEATED;
    }
    if (v_motion) {
        info.flags |= TDC_LINK_STREAM_MOTION;
    }
    if (v_fovtrm) {
        info.flags |= TDC_LINK_STREAM_FOVEATED;
    }
    if (bands) {
        info.flags |= TDC_LINK_STREAM_BANDS;
    }
    info.r_num = 1;
    info.r_den = trm ? 2 : 1;
    info.width = (uint16_t)w;
    info.height = (uint16_t)h;
    info.eyes = (uint8_t)eyes;
    info.refresh_hz = sub ? 240 : 90;
    tdc_link_encoder_t enc;
    tdc_link_encoder_init(&enc, 7, &info);

    const uint32_t tx = (w + 1) / 2, ty = (h + 1) / 2;
    const uint32_t rw = TDC_REDUCED_DIM(w, 1u, 2u), rh = TDC_REDUCED_DIM(h, 1u, 2u);
    g_cap = (size_t)w * h * 8u + 1024u; /* a foveated packet: samples, vectors and the disk */
    g_pkt = malloc(g_cap);
    uint8_t *g_resend = malloc(g_cap);
    size_t resend_n = 0;
    uint8_t *rgb = malloc((size_t)w * h * 3u);
    uint8_t *red = malloc((size_t)rw * rh * 3u);
    uint8_t *samples = malloc((size_t)tx * ty * 3u);
    int16_t *mv = malloc((size_t)tx * ty * 2u * sizeof *mv);
    uint8_t *bits = calloc(TDC_PATTERN_BYTES(w, h) + 1u, 1);
    int16_t *pmv = calloc((size_t)w * h * 2u, sizeof *pmv);
    uint8_t *fsamples = fov || v_fovtrm ? malloc((size_t)w * h * 6u) : NULL;
    fov_ref_t fref[2];
    g_out = fopen(argv[6], "wb");
    if (!g_pkt || !rgb || !red || !samples || !mv || !bits || !g_out) {
        fprintf(stderr, "fw_stream: out of memory or cannot create %s\n", argv[6]);
        return 1;
    }
    FILE *expect = NULL;
    uint8_t *fb = NULL;
    fovtrm_ref_t tref[2];
    int fovtrm_exp = 0;
    if (argc == 9 && v_fovtrm) {
#define X(p) &p,
        static const tdc_panel_t *const all[] = {TDC_PANEL_LIST(X) NULL};
#undef X
        const tdc_panel_t *panel = NULL;
        for (unsigned i = 0; all[i]; i++) {
            panel = !panel && !strcmp(all[i]->name, argv[8]) ? all[i] : panel;
        }
        if (!panel) {
            fprintf(stderr, "fw_stream: unknown panel %s\n", argv[8]);
            return 2;
        }
        fovtrm_exp = 1;
        for (uint32_t e = 0; e < eyes && fovtrm_exp; e++) {
            fovtrm_exp = fovtrm_ref_init(&tref[e], panel, w, h, info.refresh_hz);
            for (uint32_t k = 0; k < e && !fovtrm_exp; k++) {
                fovtrm_ref_free(&tref[k]);
            }
        }
        if (!fovtrm_exp) {
            /* the loop refuses the stream on this panel: nothing to expect */
            fprintf(stderr, "fw_stream: TRM refuses panel %s: no expected frames\n", argv[8]);
            (void)remove(argv[7]);
        }
    }
    if (argc >= 8 && (plain || fov || fovtrm_exp)) {
        expect = fopen(argv[7], "w");
        fb = calloc((size_t)eyes * w * h * 3u, 1);
        if (!expect || !fb) {
            fprintf(stderr, "fw_stream: cannot create %s\n", argv[7]);
            return 1;
        }
        for (uint32_t e = 0; fov && e < eyes; e++) {
            fov_ref_init(&fref[e], w, h, fov_taa);
        }
    }
    put(tdc_link_encode_stream(&enc, g_pkt, g_cap), "stream header");
    for (uint32_t f = 0; f < frames; f++) {
        int shown = 0;
        for (uint32_t e = 0; e < eyes; e++) {
            tdc_content_frame(eye_content(e), f, 11u + e, rgb, (int)w, (int)h, (int)(w * 3u));
            if (plain && f == 3 && e == 0) {
                continue; /* the packet never arrives */
            }
            if (fov && !fov_clean && f == 6 && e == eyes - 1u) {
                /* a FULL picture in the foveated stream: shown as it is */
                size_t n = tdc_link_encode_frame(&enc, g_pkt, g_cap, TDC_LINK_KIND_FULL, e, f, TDC_PIXFMT_RGB888, rgb, w,
                                                 h, w * 3u);
                if (fb) {
                    tdc_pixfmt_unpack(TDC_PIXFMT_RGB888, g_pkt + TDC_LINK_HEADER_BYTES, w, h, fb + (size_t)e * w * 3u,
                                      eyes * w * 3u);
                    fref[e].have = 0;
                    shown = 1;
                }
                put(n, "full frame (foveated stream)");
            } else if (fov) {
                size_t n = fov_packet(&enc, TDC_LINK_KIND_FULL, e, f, rgb, w, h, fov_lr, fov_taa ? pmv : NULL, fsamples);
                const int corrupt = !fov_clean && f == 1 && e == 0, spoil = !fov_clean && f == 4 && e == eyes - 1u;
                if (n && spoil) {
                    /* fov: alpha 9.0 (byte 9 of the foveation header); fovlr: gaze x two screens outside */
                    if (fov_lr) {
                        fov_spoil(n, 0, (int32_t)(3 * w * 256u), 1);
                    } else {
                        fov_spoil(n, 9, 9, 0);
                    }
                }
                if (fb && n && !corrupt && !spoil &&
                    fov_ref_frame(&fref[e], g_pkt, f, w, h, 1000000u / info.refresh_hz, fb + (size_t)e * w * 3u,
                                  (size_t)eyes * w * 3u)) {
                    shown = 1;
                }
                if (corrupt) {
                    g_pkt[TDC_LINK_HEADER_BYTES + TDC_FOV_HDR_BYTES + 40u] ^= 0x40u; /* payload CRC must catch it */
                }
                put(n, "foveated frame");
            } else if (plain) {
                const tdc_pixfmt_t fmt = (f == 2 && e == eyes - 1u) ? TDC_PIXFMT_RGB565 : TDC_PIXFMT_RGB888;
                size_t n = tdc_link_encode_frame(&enc, g_pkt, g_cap, TDC_LINK_KIND_FULL, e, f, fmt, rgb, w, h, w * 3u);
                const int corrupt = f == 1 && e == 0 && n > TDC_LINK_HEADER_BYTES + 100u;
                if (fb && !corrupt) {
                    tdc_pixfmt_unpack(fmt, g_pkt + TDC_LINK_HEADER_BYTES, w, h, fb + (size_t)e * w * 3u, eyes * w * 3u);
                    shown = 1;
                }
                if (corrupt) {
                    g_pkt[TDC_LINK_HEADER_BYTES + 100u] ^= 0x40u; /* payload CRC must catch it */
                }
                put(n, "full frame");
            } else if (v_fovtrm) {
                const int red_slot = tdc_link_trm_kind(f, e) == TDC_LINK_KIND_REDUCED;
                const tdc_link_kind_t slot = red_slot ? TDC_LINK_KIND_REDUCED : TDC_LINK_KIND_FULL;
                const uint32_t sw = red_slot ? rw : w, sh = red_slot ? rh : h;
                if (red_slot) {
                    box_reduce(rgb, w, h, red, rw, rh);
                }
                const uint8_t *src = red_slot ? red : rgb;
                const int plain_slot = !fov_clean && f == 6, corrupt = !fov_clean && f == 1 && e == 0;
                const int spoil = !fov_clean && f == 4 && e == 0;
                const size_t n = plain_slot ? tdc_link_encode_frame(&enc, g_pkt, g_cap, slot, e, f, TDC_PIXFMT_RGB888, src,
                                                                    sw, sh, sw * 3u)
                                            : fov_packet(&enc, slot, e, f, src, sw, sh, 0, NULL, fsamples);
                if (n && spoil) {
                    fov_spoil(n, 9, 9, 0); /* alpha 9.0 */
                }
                if (fb && n && !corrupt && !spoil &&
                    fovtrm_ref_frame(&tref[e], g_pkt, red_slot, plain_slot, f, w, h, fb + (size_t)e * w * 3u,
                                     (size_t)eyes * w * 3u)) {
                    shown = 1;
                }
                if (corrupt) {
                    g_pkt[TDC_LINK_HEADER_BYTES + TDC_FOV_HDR_BYTES + 40u] ^= 0x40u; /* payload CRC must catch it */
                }
                put(n, red_slot ? "reduced slot (foveated TRM)" : "full slot (foveated TRM)");
            } else if (trm) {
                if (bands && tdc_link_trm_kind(f, e) == TDC_LINK_KIND_FULL) {
                    put_bands(&enc, TDC_LINK_KIND_FULL, e, f, rgb, w, h, band_how);
                } else if (tdc_link_trm_kind(f, e) == TDC_LINK_KIND_FULL) {
                    size_t n = tdc_link_encode_frame(&enc, g_pkt, g_cap, TDC_LINK_KIND_FULL, e, f, TDC_PIXFMT_RGB888,
                                                     rgb, w, h, w * 3u);
                    if (v_drop && f == 2 && e == 0) {
                        g_pkt[TDC_LINK_HEADER_BYTES + 100u] ^= 0x40u; /* payload CRC must catch it */
                        put(n, "full frame (corrupted)");
                    } else if (v_resend && f == 2 && e == 0) {
                        /* corrupted now, resent intact after eye 1's packet */
                        g_pkt[TDC_LINK_HEADER_BYTES + 100u] ^= 0x40u;
                        put(n, "full frame (corrupted)");
                        g_pkt[TDC_LINK_HEADER_BYTES + 100u] ^= 0x40u;
                        resend_n = n;
                        memcpy(g_resend, g_pkt, n);
                    } else {
                        put(n, "full frame");
                    }
                } else {
                    box_reduce(rgb, w, h, red, rw, rh);
                    if (bands) {
                        put_bands(&enc, TDC_LINK_KIND_REDUCED, e, f, red, rw, rh, band_how);
                        continue;
                    }
                    size_t n = tdc_link_encode_frame(&enc, g_pkt, g_cap, TDC_LINK_KIND_REDUCED, e, f, TDC_PIXFMT_RGB888,
                                                     red, rw, rh, rw * 3u);
                    if ((v_resend || v_resend_ref) && f == 3 && e == 0) {
                        g_pkt[TDC_LINK_HEADER_BYTES + 10u] ^= 0x40u; /* payload CRC must catch it */
                    }
                    put(n, "reduced frame");
                }
                if (v_motion) {
                    for (size_t i = 0; i < (size_t)w * h * 2u; i++) {
                        pmv[i] = (int16_t)((i & 1u) ? 2 * 16 : -3 * 16);
                    }
                    put(tdc_link_encode_motion(&enc, g_pkt, g_cap, e, f, pmv, w, h, 0), "per-pixel motion");
                }
            } else {
                /* Hourglass everywhere (bits 0); sample k = f mod 4 of each tile. */
                const unsigned pos = tdc_ordering_pixel(TDC_ORDER_HOURGLASS, f & 3u);
                if ((f & 3u) == 0) {
                    put(tdc_link_encode_pattern(&enc, g_pkt, g_cap, e, f + f0, bits, w, h), "pattern");
                }
                for (uint32_t y = 0; y < ty; y++) {
                    for (uint32_t x = 0; x < tx; x++) {
                        uint32_t px = 2 * x + (pos & 1u), py = 2 * y + (pos >> 1);
                        px = px < w ? px : w - 1;
                        py = py < h ? py : h - 1;
                        memcpy(&samples[((size_t)y * tx + x) * 3], &rgb[((size_t)py * w + px) * 3], 3);
                        /* Backward MV in Q4: the edge content moves +3 px per frame. */
                        mv[((size_t)y * tx + x) * 2] = (int16_t)(e == 0 ? -3 * 16 : 0);
                        mv[((size_t)y * tx + x) * 2 + 1] = (int16_t)(e == 1 ? 2 * 16 : 0);
                    }
                }
                put(tdc_link_encode_subframe(&enc, g_pkt, g_cap, e, f + f0, TDC_PIXFMT_RGB888, samples, w, h),
                    "subframe");
                put(tdc_link_encode_motion(&enc, g_pkt, g_cap, e, f + f0, mv, w, h, 1), "sample motion");
            }
        }
        if (resend_n && f == 2) {
            memcpy(g_pkt, g_resend, resend_n);
            put(resend_n, "full frame (resent intact)");
            resend_n = 0;
        }
        if (v_future && f == 0) {
            /* valid header CRC, far-future frame index, bad payload CRC */
            tdc_content_frame(eye_content(0), 0, 11u, rgb, (int)w, (int)h, (int)(w * 3u));
            size_t n = tdc_link_encode_frame(&enc, g_pkt, g_cap, TDC_LINK_KIND_FULL, 0, 0x7FFFFFF0u, TDC_PIXFMT_RGB888,
                                             rgb, w, h, w * 3u);
            g_pkt[TDC_LINK_HEADER_BYTES + 7u] ^= 0x01u;
            put(n, "far-future frame (bad payload)");
            if (eyes == 2) {
                /* and the other eye's packet of that frame: every eye of it "lost" */
                n = tdc_link_encode_frame(&enc, g_pkt, g_cap, TDC_LINK_KIND_REDUCED, 1, 0x7FFFFFF0u, TDC_PIXFMT_RGB888,
                                          rgb, rw, rh, rw * 3u);
                g_pkt[TDC_LINK_HEADER_BYTES + 7u] ^= 0x01u;
                put(n, "far-future reduced frame (bad payload)");
            }
        }
        if (v_rehdr) {
            put(tdc_link_encode_stream(&enc, g_pkt, g_cap), "repeated stream header");
        }
        if (expect && shown) {
            uint64_t hash = 0xcbf29ce484222325ULL;
            for (size_t i = 0; i < (size_t)eyes * w * h * 3u; i++) {
                hash = (hash ^ fb[i]) * 0x100000001b3ULL;
            }
            fprintf(expect, "frame %u %016llx\n", (unsigned)f, (unsigned long long)hash);
        }
    }
    if (expect && fclose(expect) != 0) {
        fprintf(stderr, "fw_stream: write error (expected)\n");
        return 1;
    }
    free(fb);
    for (uint32_t e = 0; expect && fov && e < eyes; e++) {
        fov_ref_free(&fref[e]);
    }
    for (uint32_t e = 0; fovtrm_exp && e < eyes; e++) {
        fovtrm_ref_free(&tref[e]);
    }
    free(fsamples);
    if (fclose(g_out) != 0) {
        fprintf(stderr, "fw_stream: write error\n");
        return 1;
    }
    free(g_pkt);
    free(rgb);
    free(red);
    free(samples);
    free(mv);
    free(bits);
    free(pmv);
    free(g_resend);
    return 0;
}
