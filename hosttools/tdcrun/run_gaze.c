/*
 * run_gaze.c - tdc-run's inputs for gaze-aware TRM (firmware/tdc_trm_gaze.h):
 * the eye tracker's gaze velocity and the renderer's tile motion vectors per
 * input frame, read from two text files, so that trm50g's claim can be judged
 * on tdc-run's drive frames by any external metric.
 *
 *   --gaze FILE   lines "frame,gx,gy": the gaze velocity over that frame in
 *                 px per frame (screen coordinates, +x right, +y down)
 *   --mv FILE     lines "frame,tx,ty,dx,dy": the content motion of tile
 *                 (tx, ty) over that frame in px per frame (tiles of
 *                 TDC_RUN_GAZE_TILE px, row-major from the top left)
 *
 * Blank lines and lines starting with '#' or a letter (a header) are
 * skipped.  Every full-resolution frame needs its gaze line and all of its
 * tiles (the map is computed before each full frame, as a board does when
 * the FULL packet's MOTION payload arrives); reduced frames need none.
 * Values are stored as the link's MOTION payload: int16 Q4 px per frame.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_run.h"
#include "tdc_trm_gaze.h"

/* |v| of a Q4 component: int16 without -32768 (refused by the firmware) */
#define GAZE_MAX_PX (32767.0 / 16.0)

static int is_skip(const char *s)
{
    while (*s == ' ' || *s == '\t' || *s == '\r') {
        s++;
    }
    return *s == 0 || *s == '#' || (*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z');
}

/* "n,v0,v1,...": the frame index and nd doubles (ni leading unsigned fields in all). */
static int parse_fields(const char *line, int nu, uint64_t *u, int nd, double *d)
{
    const char *p = line, *e;
    for (int i = 0; i < nu; i++) {
        if (tdc_parse_u64_field(p, &e, 1000000, &u[i]) != 0 || *e != ',') {
            return -1;
        }
        p = e + 1;
    }
    for (int i = 0; i < nd; i++) {
        if (tdc_parse_double_field(p, &e, &d[i]) != 0 || *e != (i + 1 < nd ? ',' : '\0') ||
            d[i] < -GAZE_MAX_PX || d[i] > GAZE_MAX_PX) {
            return -1;
        }
        p = e + 1;
    }
    return 0;
}

static int16_t q4(double px)
{
    double v = px * 16.0;
    return (int16_t)(v < 0 ? v - 0.5 : v + 0.5);
}

static int read_file(const char *path, const char *opt, int fields, tdc_run_gaze_t *g)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        return tdc_fail(TDC_EXIT_FILE, NULL, path, "cannot open %s file: %s", opt, strerror(errno));
    }
    char line[256];
    unsigned no = 0;
    int r, rc = TDC_EXIT_OK;
    while ((r = tdc_read_line(f, line, sizeof line, &no)) == 1) {
        if (is_skip(line)) {
            continue;
        }
        uint64_t u[3];
        double d[2];
        int nu = fields == 3 ? 1 : 3;
        if (parse_fields(line, nu, u, 2, d) != 0) {
            rc = tdc_fail(TDC_EXIT_INPUT, NULL, path, "line %u: expected %s with |value| <= %.0f px/frame", no,
                          fields == 3 ? "frame,gx,gy" : "frame,tx,ty,dx,dy", GAZE_MAX_PX);
            break;
        }
        if (u[0] >= (uint64_t)g->frames) {
            continue; /* beyond the frames run */
        }
        size_t fr = (size_t)u[0];
        if (fields == 3) {
            g->gaze[2 * fr] = q4(d[0]);
            g->gaze[2 * fr + 1] = q4(d[1]);
            g->have_gaze[fr] = 1;
        } else {
            if (u[1] >= g->tx || u[2] >= g->ty) {
                rc = tdc_fail(TDC_EXIT_INPUT, NULL, path, "line %u: tile (%llu, %llu) outside the %ux%u tiles of %d px",
                              no, (unsigned long long)u[1], (unsigned long long)u[2], g->tx, g->ty, TDC_RUN_GAZE_TILE);
                break;
            }
            size_t k = fr * g->tx * g->ty + (size_t)u[2] * g->tx + (size_t)u[1];
            g->mv[2 * k] = q4(d[0]);
            g->mv[2 * k + 1] = q4(d[1]);
            if (!g->have_mv[k]) {
                g->have_mv[k] = 1;
                g->tiles_of[fr]++;
            }
        }
    }
    if (rc == TDC_EXIT_OK && r < 0) {
        rc = tdc_fail(TDC_EXIT_INPUT, NULL, path, "line %u: %s", no + 1, r == -1 ? "too long or has a NUL byte" : "read error");
    }
    fclose(f);
    return rc;
}

int tdc_run_gaze_load(tdc_run_gaze_t *g, const char *gaze_path, const char *mv_path, int frames, int w, int h)
{
    memset(g, 0, sizeof *g);
    g->frames = frames;
    g->tx = TDC_TRM_GAZE_TILES_X(w, TDC_RUN_GAZE_TILE);
    g->ty = TDC_TRM_GAZE_TILES_Y(h, TDC_RUN_GAZE_TILE);
    size_t nt = (size_t)frames * g->tx * g->ty;
    g->gaze = calloc((size_t)frames * 2, sizeof *g->gaze);
    g->have_gaze = calloc((size_t)frames, 1);
    g->mv = calloc(nt * 2, sizeof *g->mv);
    g->have_mv = calloc(nt, 1);
    g->tiles_of = calloc((size_t)frames, sizeof *g->tiles_of);
    if (!g->gaze || !g->have_gaze || !g->mv || !g->have_mv || !g->tiles_of) {
        tdc_run_gaze_free(g);
        return tdc_fail(TDC_EXIT_NOMEM, NULL, "gaze inputs", "cannot allocate %zu tiles", nt);
    }
    int rc = read_file(gaze_path, "--gaze", 3, g);
    if (rc == TDC_EXIT_OK) {
        rc = read_file(mv_path, "--mv", 5, g);
    }
    if (rc != TDC_EXIT_OK) {
        tdc_run_gaze_free(g);
    }
    return rc;
}

int tdc_run_gaze_frame(const tdc_run_gaze_t *g, int frame, const char *gaze_path, const char *mv_path,
                       const int16_t **mv, int16_t *gx, int16_t *gy)
{
    if (!g->have_gaze[frame]) {
        return tdc_fail(TDC_EXIT_INPUT, NULL, gaze_path, "no gaze velocity for full frame %d", frame);
    }
    if (g->tiles_of[frame] != g->tx * g->ty) {
        return tdc_fail(TDC_EXIT_INPUT, NULL, mv_path, "full frame %d has %u of its %ux%u tile motion vectors", frame,
                        g->tiles_of[frame], g->tx, g->ty);
    }
    *mv = g->mv + (size_t)frame * g->tx * g->ty * 2;
    *gx = g->gaze[2 * frame];
    *gy = g->gaze[2 * frame + 1];
    return TDC_EXIT_OK;
}

void tdc_run_gaze_free(tdc_run_gaze_t *g)
{
    free(g->gaze);
    free(g->have_gaze);
    free(g->mv);
    free(g->have_mv);
    free(g->tiles_of);
    memset(g, 0, sizeof *g);
}
