/*
 * tdc_fw_trm.c - the TRM stream family of the board frame loop (stream flag
 * REDUCED; tdc_fw_family.h): a FULL or REDUCED picture per eye and frame,
 * the slot TRM's schedule has due (tdc_link_trm_kind), through tdc_trm into
 * the eye's part of the frame buffer; whole or as row bands.
 */
#include "tdc_fw_family.h"

#if TDC_CFG_TRM
#include "tdc_fw_trm.h"

uint8_t tdc_fw_reduced[FW_EYES][(size_t)FW_RW * FW_RH * 3u] TDC_EXTRAM;
tdc_trm_t tdc_fw_trm[FW_EYES];

static void trm_wire(tdc_link_buffers_t *b)
{
    for (uint32_t e = 0; e < FW_EYES; e++) {
        b->reduced[e] = tdc_fw_reduced[e];
    }
    b->reduced_bytes = sizeof tdc_fw_reduced[0];
}

#if TDC_CFG_ROW_WORKERS > 1
/* Row buffers of the workers after the first (whose are each eye's own);
 * the eyes run one after the other, so they share these. */
static uint64_t g_rowmem[TDC_CFG_ROW_WORKERS - 1][TDC_TRM_ROWBUF_BYTES(FW_W, FW_RW) / 8u];
static tdc_trm_rowbuf_t g_rowbuf[TDC_CFG_ROW_WORKERS];
static uint32_t g_workers = 1; /* bands per frame for this stream */

/* One frame's bands: band i of `rows` rows is [rows i / n, rows (i+1) / n),
 * D(I)'s rows first (d_rows of them; 0: none), then the output rows. */
typedef struct {
    const tdc_trm_t *t;
    uint32_t n, d_rows;
    int output; /* 0: D(I)'s rows, 1: the output rows */
    uint64_t count[TDC_CFG_ROW_WORKERS][3];
} trm_bands_t;

static void trm_band_job(void *arg, uint32_t i)
{
    trm_bands_t *j = arg;
    const tdc_trm_rowbuf_t own = tdc_trm_rowbuf_own(j->t);
    const tdc_trm_rowbuf_t *b = i ? &g_rowbuf[i] : &own;
    const uint64_t rows = j->output ? j->t->cfg.height : j->d_rows;
    const uint32_t r0 = (uint32_t)(rows * i / j->n), r1 = (uint32_t)(rows * (i + 1u) / j->n);
    if (j->output) {
        tdc_trm_band(j->t, r0, r1, b, j->count[i]);
    } else {
        tdc_trm_d_band(j->t, r0, r1, b);
    }
}

/* After _begin: D(I) of a full frame, then the frame's output rows, as
 * bands on the board's workers (tdc_trm_split/_d_band/_band/_join), or
 * nothing with one worker (_end runs it all). */
static tdc_status_t trm_run_bands(tdc_trm_t *t)
{
    const uint32_t have = tdc_board_workers();
    trm_bands_t j = {t, have < g_workers ? have : g_workers, 0, 0, {{0}}};
    if (j.n <= 1u) {
        return TDC_OK;
    }
    const tdc_status_t st = tdc_trm_split(t, &j.d_rows);
    if (st != TDC_OK) {
        return st;
    }
    if (j.d_rows) {
        tdc_board_run_bands(trm_band_job, &j, j.n);
    }
    j.output = 1;
    tdc_board_run_bands(trm_band_job, &j, j.n);
    uint64_t sum[3] = {0, 0, 0};
    for (uint32_t i = 0; i < j.n; i++) {
        for (int c = 0; c < 3; c++) {
            sum[c] += j.count[i][c];
        }
    }
    tdc_trm_join(t, sum);
    return TDC_OK;
}
#endif

tdc_status_t tdc_fw_trm_full(uint32_t e, const uint8_t *in, uint32_t stride, uint8_t *fb, uint32_t frame)
{
#if TDC_CFG_ROW_WORKERS > 1
    tdc_status_t st = tdc_trm_full_begin(&tdc_fw_trm[e], in, stride, fb, FW_STRIDE);
    st = st == TDC_OK ? trm_run_bands(&tdc_fw_trm[e]) : st;
    return st == TDC_OK ? tdc_trm_full_end(&tdc_fw_trm[e], frame) : st;
#else
    return tdc_trm_full_seq(&tdc_fw_trm[e], in, stride, fb, FW_STRIDE, frame);
#endif
}

tdc_status_t tdc_fw_trm_reduced(uint32_t e, const uint8_t *in, uint32_t stride, uint8_t *fb, uint32_t frame)
{
#if TDC_CFG_ROW_WORKERS > 1
    tdc_status_t st = tdc_trm_reduced_begin(&tdc_fw_trm[e], in, stride, fb, FW_STRIDE, frame);
    st = st == TDC_OK ? trm_run_bands(&tdc_fw_trm[e]) : st;
    return st == TDC_OK ? tdc_trm_reduced_end(&tdc_fw_trm[e]) : st;
#else
    return tdc_trm_reduced_seq(&tdc_fw_trm[e], in, stride, fb, FW_STRIDE, frame);
#endif
}

int tdc_fw_trm_setup(const tdc_link_stream_info_t *si, uint16_t hz, uint8_t *const mem[], size_t bytes)
{
    for (uint32_t e = 0; e < FW_EYES; e++) {
        tdc_trm_config_t cfg;
        /* the rate the panel really runs: the stream's if the panel has it,
         * else the panel's own (a 60 Hz panel refuses TRM whatever the
         * stream claims) */
        tdc_trm_default_config(&cfg, (uint16_t)FW_W, (uint16_t)FW_H, hz);
        cfg.r_num = si->r_num;
        cfg.r_den = si->r_den;
        cfg.reduced_in_stream = 1;
        cfg.keep_residual = 0; /* rho recomputed from the kept codes: 4.5 B/px, docs/boards.md */
        const size_t need = tdc_trm_get_size(&cfg);
        if (need == 0 || need > bytes ||
            tdc_trm_init(&tdc_fw_trm[e], &cfg, &TDC_PANEL_SYMBOL, mem[e], bytes) != TDC_OK) {
            tdc_board_log("TRM refused the stream (ratio, refresh or size): frames keep the last image");
            return -1;
        }
    }
#if TDC_CFG_ROW_WORKERS > 1
    g_workers = 1;
    for (uint32_t i = 1; i < TDC_CFG_ROW_WORKERS; i++) {
        if (tdc_trm_rowbuf_init(&tdc_fw_trm[0], &g_rowbuf[i], g_rowmem[i - 1u], sizeof g_rowmem[0]) != TDC_OK) {
            break; /* unreachable: sized for the largest ratio; fewer bands then */
        }
        g_workers = i + 1u;
    }
#endif
    return 0;
}

/* A plain TRM stream: TRM's arena at the start of the mode arena. */
static int trm_configure(const tdc_link_stream_info_t *si, uint16_t hz)
{
    uint8_t *mem[FW_EYES];
    for (uint32_t e = 0; e < FW_EYES; e++) {
        mem[e] = (uint8_t *)tdc_fw_mode_arena[e];
    }
    return tdc_fw_trm_setup(si, hz, mem, sizeof tdc_fw_mode_arena[0]);
}

uint32_t tdc_fw_trm_needs(uint32_t e, uint32_t frame)
{
    return KIND_BIT(tdc_link_trm_kind(frame, e));
}

/* The frame index ties a reduced frame to the full frame before it: if that
 * one was lost, rejected or out of order (or this is the stream's start),
 * the reduced frame is shown without residual, never with stale state
 * (tdc_trm_reduced_seq). */
int tdc_fw_trm_eye(uint32_t e, uint32_t frame, uint32_t kinds, uint8_t *fb, tdc_res_t **residual)
{
    tdc_status_t st;
    if (kinds & KIND_BIT(TDC_LINK_KIND_FULL)) {
        st = tdc_fw_trm_full(e, fb, FW_STRIDE, fb, frame); /* in place: D(I) is taken first */
    } else if (kinds & KIND_BIT(TDC_LINK_KIND_REDUCED)) {
        uint32_t rw = 0, rh = 0;
        tdc_link_reduced_size(&tdc_fw.dec, &rw, &rh);
        st = tdc_fw_trm_reduced(e, tdc_fw_reduced[e], rw * 3u, fb, frame);
    } else {
        return FW_EYE_NOTHING;
    }
    /* NULL (rho is recomputed, not stored): the LCD inverse drops the light
     * it cannot reach and counts it (tdc_lcd_stats_t) */
    *residual = tdc_trm_residual(&tdc_fw_trm[e]);
    return st == TDC_OK ? FW_EYE_UPDATED : FW_EYE_REFUSED;
}

/* TRM's full-res path (D rows as its kernel rows arrive, then the output
 * rows whose U rows are done) or reduced path (output rows whose reduced
 * rows are there); the last band closes the stage's frame. */
tdc_status_t tdc_fw_trm_band(uint32_t e, uint32_t frame, uint32_t kind, const tdc_band_hdr_t *bh, uint8_t *fb,
                             uint32_t *done, uint32_t *covered, tdc_res_t **residual)
{
    tdc_trm_t *t = &tdc_fw_trm[e];
    const int last = bh->index + 1u == bh->count;
    const uint32_t avail = *done;
    tdc_status_t st = TDC_OK;
    if (kind == TDC_LINK_KIND_FULL) {
        if (bh->index == 0u) {
            st = tdc_trm_full_begin(t, fb, FW_STRIDE, fb, FW_STRIDE); /* in place: D reads a row before it is written */
        }
        if (st == TDC_OK) {
            st = last ? tdc_trm_full_end(t, frame) : tdc_trm_full_rows(t, avail, done);
        }
    } else {
        uint32_t rw = 0, rh = 0;
        tdc_link_reduced_size(&tdc_fw.dec, &rw, &rh);
        if (bh->index == 0u) {
            st = tdc_trm_reduced_begin(t, tdc_fw_reduced[e], rw * 3u, fb, FW_STRIDE, frame);
        }
        if (st == TDC_OK) {
            st = last ? tdc_trm_reduced_end(t) : tdc_trm_reduced_rows(t, avail, done);
        }
        *covered = rh ? (uint32_t)(((uint64_t)avail * FW_H) / rh) : FW_H;
    }
    *residual = tdc_trm_residual(t);
    return st;
}

/* (also for a foveated TRM stream: both run TRM's instances) */
static void trm_log(const tdc_link_counters_t *c)
{
    (void)c;
    if (tdc_fw.fam && (tdc_fw.fam->flags & TDC_LINK_STREAM_REDUCED)) {
        uint32_t unpaired = 0;
        for (uint32_t e = 0; e < FW_EYES; e++) {
            unpaired += tdc_fw_trm[e].stats.reduced_unpaired;
        }
        tdc_fw_log_kv("reduced frames without their full frame (no residual): ", unpaired);
    }
}

const tdc_fw_family_t tdc_fw_family_trm = {
    "trm",          TDC_LINK_STREAM_REDUCED, trm_wire, trm_configure, tdc_fw_trm_needs,
    tdc_fw_trm_eye, tdc_fw_trm_band,         trm_log};
#else
TDC_FW_FAMILY_NOT_BUILT(trm);
#endif
