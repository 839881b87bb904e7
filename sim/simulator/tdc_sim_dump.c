/* tdc_sim_dump.c - tdc-sim --dump DIR (see tdc_sim_dump.h). */
#include "simulator/tdc_sim_dump.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "simulator/tdc_sim_gaze.h"
#include "tdc_png.h"

#define DUMP_MAX_STREAMS 130 /* 64 modes + the reference, 2 eyes */

struct tdc_sim_dump {
    char dir[1024];
    int n, eyes, w, h;
    double full_scale;
    char name[DUMP_MAX_STREAMS][96]; /* stream folder names, eye-major within a stream */
    FILE *y4m[DUMP_MAX_STREAMS];
    FILE *steps;
    uint16_t *px16; /* w*h*3 */
    long frames_written;
    long clipped; /* samples above full scale */
    int failed;
};

static int fail(tdc_sim_dump_t *d, const char *what, const char *path)
{
    if (!d->failed) {
        fprintf(stderr, "tdc-sim: --dump: cannot write %s: %s\n", path, what);
    }
    d->failed = 1;
    return -1;
}

static int make_dir(const char *p)
{
    return mkdir(p, 0755) && errno != EEXIST ? -1 : 0;
}

tdc_sim_dump_t *tdc_sim_dump_open(const char *dir, const char *const *names, int n, int eyes, int w, int h,
                                  double full_scale_cdm2)
{
    if (n * eyes > DUMP_MAX_STREAMS || strlen(dir) > 900) {
        fprintf(stderr, "tdc-sim: --dump: too many streams or folder name too long\n");
        return NULL;
    }
    tdc_sim_dump_t *d = calloc(1, sizeof(*d));
    if (!d || !(d->px16 = malloc(sizeof(uint16_t) * 3 * (size_t)w * h))) {
        fprintf(stderr, "tdc-sim: --dump: out of memory\n");
        free(d);
        return NULL;
    }
    snprintf(d->dir, sizeof(d->dir), "%s", dir);
    d->n = n;
    d->eyes = eyes;
    d->w = w;
    d->h = h;
    d->full_scale = full_scale_cdm2;
    char path[1200];
    if (make_dir(dir)) {
        fprintf(stderr, "tdc-sim: --dump: cannot create %s: %s\n", dir, strerror(errno));
        free(d->px16);
        free(d);
        return NULL;
    }
    for (int s = 0; s < n; s++) {
        for (int e = 0; e < eyes; e++) {
            int k = s * eyes + e;
            snprintf(d->name[k], sizeof(d->name[k]), "%s%s", names[s], eyes == 2 ? (e ? "_R" : "_L") : "");
            snprintf(path, sizeof(path), "%s/%s", dir, d->name[k]);
            if (make_dir(path)) {
                fprintf(stderr, "tdc-sim: --dump: cannot create %s: %s\n", path, strerror(errno));
                d->failed = 1;
                tdc_sim_dump_close(d, NULL, NULL, 0, 0, 0, 0);
                return NULL;
            }
        }
    }
    snprintf(path, sizeof(path), "%s/steps.csv", dir);
    d->steps = fopen(path, "w");
    if (!d->steps || fprintf(d->steps, "eye,step,refresh,t0,t1,gaze_x,gaze_y,gaze_screen_x,gaze_screen_y,shift_x,"
                                       "shift_y\n") < 0) {
        fprintf(stderr, "tdc-sim: --dump: cannot write %s: %s\n", path, strerror(errno));
        d->failed = 1;
        tdc_sim_dump_close(d, NULL, NULL, 0, 0, 0, 0);
        return NULL;
    }
    return d;
}

int tdc_sim_dump_codes(tdc_sim_dump_t *d, int s, int e, long refresh, const uint8_t *codes)
{
    char path[1200], err[1300];
    snprintf(path, sizeof(path), "%s/%s/codes_%06ld.png", d->dir, d->name[s * d->eyes + e], refresh);
    if (tdc_png_write(path, codes, d->w, d->h, 8, 3 * (size_t)d->w, err, sizeof(err))) {
        return fail(d, err, path);
    }
    return 0;
}

/* cd/m^2 -> 16-bit code of the dump's scale (clamped; clipping counted). */
static uint16_t to16(tdc_sim_dump_t *d, float v)
{
    double q = v / d->full_scale * 65535.0 + 0.5;
    if (q >= 65536.0) {
        d->clipped++;
        return 65535;
    }
    return (uint16_t)(q < 0.0 ? 0 : (int)q);
}

static int png16(tdc_sim_dump_t *d, const char *path, const float *rgb)
{
    size_t n = 3 * (size_t)d->w * d->h;
    for (size_t i = 0; i < n; i++) {
        d->px16[i] = to16(d, rgb[i]);
    }
    char err[1300];
    if (tdc_png_write(path, d->px16, d->w, d->h, 16, 3 * (size_t)d->w, err, sizeof(err))) {
        return fail(d, err, path);
    }
    return 0;
}

int tdc_sim_dump_step(tdc_sim_dump_t *d, int s, int e, long step, const float *emitted, const float *rgb,
                      const float *y, double fps)
{
    const int k = s * d->eyes + e;
    char path[1200];
    if (emitted) {
        snprintf(path, sizeof(path), "%s/%s/emitted_%06ld.png", d->dir, d->name[k], step);
        if (png16(d, path, emitted)) {
            return -1;
        }
    }
    snprintf(path, sizeof(path), "%s/%s/retina_%06ld.png", d->dir, d->name[k], step);
    if (png16(d, path, rgb)) {
        return -1;
    }
    snprintf(path, sizeof(path), "%s/%s/retina.y4m", d->dir, d->name[k]);
    if (!d->y4m[k]) {
        /* frame rate as a rational with microhertz resolution */
        d->y4m[k] = fopen(path, "wb");
        if (!d->y4m[k] ||
            fprintf(d->y4m[k], "YUV4MPEG2 W%d H%d F%ld:1000000 Ip A1:1 Cmono16\n", d->w, d->h, lround(fps * 1e6)) < 0) {
            return fail(d, strerror(errno), path);
        }
    }
    size_t np = (size_t)d->w * d->h;
    uint8_t *b = (uint8_t *)d->px16; /* little-endian 16-bit samples, whatever the host */
    for (size_t i = 0; i < np; i++) {
        uint16_t v = to16(d, y[i]);
        b[2 * i] = (uint8_t)(v & 0xff);
        b[2 * i + 1] = (uint8_t)(v >> 8);
    }
    if (fputs("FRAME\n", d->y4m[k]) < 0 || fwrite(b, 2, np, d->y4m[k]) != np) {
        return fail(d, strerror(errno), path);
    }
    d->frames_written++;
    return 0;
}

int tdc_sim_dump_step_row(tdc_sim_dump_t *d, const tdc_retina_frame_t *f)
{
    if (fprintf(d->steps, "%d,%ld,%ld,%.9f,%.9f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", f->eye, f->step, f->refresh, f->t0,
                f->t1, f->gaze[0], f->gaze[1], f->gaze_screen[0], f->gaze_screen[1], f->shift[0], f->shift[1]) < 0) {
        char path[1100];
        snprintf(path, sizeof(path), "%s/steps.csv", d->dir);
        return fail(d, strerror(errno), path);
    }
    return 0;
}

/* A JSON string of a plain name (mode and panel names: letters, digits, '-', '_', '.'). */
static void jstr(FILE *f, const char *s)
{
    fputc('"', f);
    for (; s && *s; s++) {
        fputc(*s == '"' || *s == '\\' ? '_' : *s, f);
    }
    fputc('"', f);
}

int tdc_sim_dump_close(tdc_sim_dump_t *d, const tdc_sim_config_t *cfg, const tdc_retina_display_t *disp, int steps,
                       double fps, long nsteps, double persistence)
{
    char path[1200];
    for (int k = 0; k < d->n * d->eyes; k++) {
        if (d->y4m[k] && fclose(d->y4m[k]) != 0) {
            snprintf(path, sizeof(path), "%s/%s/retina.y4m", d->dir, d->name[k]);
            fail(d, strerror(errno), path);
        }
    }
    if (d->steps && fclose(d->steps) != 0) {
        snprintf(path, sizeof(path), "%s/steps.csv", d->dir);
        fail(d, strerror(errno), path);
    }
    if (cfg && disp && !d->failed) {
        snprintf(path, sizeof(path), "%s/dump.json", d->dir);
        FILE *f = fopen(path, "w");
        if (!f) {
            fail(d, strerror(errno), path);
        } else {
            fprintf(f, "{\n  \"format\": \"tdc-sim dump 1\",\n  \"width\": %d, \"height\": %d, \"eyes\": %d,\n", d->w,
                    d->h, d->eyes);
            fprintf(f, "  \"refresh_hz\": %d, \"steps_per_refresh\": %d, \"fps\": %.6f, \"steps\": %ld,\n",
                    cfg->refresh_hz, steps, fps, nsteps);
            fprintf(f, "  \"display\": {\"panel\": ");
            jstr(f, disp->panel);
            fprintf(f, ", \"kind\": \"%s\", \"ppd\": %.4f, \"ppd_from\": ", cfg->panel == TDC_PANEL_SIM_LCD ? "lcd" : "oled",
                    disp->ppd);
            jstr(f, disp->ppd_from);
            fprintf(f,
                    ", \"distance_m\": %.4f, \"width_m\": %.6f,\n    \"peak_cdm2\": %.4f, \"black_cdm2\": %.6f, "
                    "\"eotf\": \"gamma\", \"gamma\": [%.6f, %.6f, %.6f], \"rgb2y\": [%.4f, %.4f, %.4f],\n"
                    "    \"persistence\": %.4f},\n",
                    disp->distance_m, disp->width_m, disp->peak_cdm2, disp->black_cdm2, disp->gamma[0], disp->gamma[1],
                    disp->gamma[2], disp->rgb2y[0], disp->rgb2y[1], disp->rgb2y[2], persistence);
            fprintf(f,
                    "  \"gaze\": {\"schedule\": \"%s\", \"at\": [%.3f, %.3f], \"tracker_latency_ms\": %.3f, "
                    "\"tracker_noise_deg\": %.4f,\n    \"pursuit\": \"%s\", \"pursuit_gain\": %.4f, "
                    "\"pursuit_lag_ms\": %.3f, \"per_step\": \"steps.csv\"},\n",
                    tdc_sim_gaze_name(cfg->gaze), cfg->gaze_at_x, cfg->gaze_at_y, cfg->gaze_latency_ms,
                    cfg->gaze_noise_deg, cfg->scene.pursuit ? "track" : "fixate", cfg->pursuit_gain,
                    cfg->pursuit_lag_ms);
            fprintf(f,
                    "  \"linear\": {\"full_scale_cdm2\": %.6f, \"clipped_samples\": %ld, \"png\": \"16-bit RGB, "
                    "cd/m^2 = v / 65535 * full_scale_cdm2\", \"y4m\": \"mono16 little-endian luminance, same "
                    "scale\"},\n",
                    d->full_scale, d->clipped);
            fprintf(f, "  \"files\": {\"codes\": \"S/codes_%%06d.png (per refresh of S's own clock)\", \"emitted\": "
                       "\"S/emitted_%%06d.png (per step)\", \"retina\": \"S/retina_%%06d.png (per step)\", "
                       "\"video\": \"S/retina.y4m\"},\n");
            fprintf(f, "  \"streams\": [");
            for (int k = 0; k < d->n * d->eyes; k++) {
                fputs(k ? ", " : "", f);
                jstr(f, d->name[k]);
            }
            fprintf(f, "],\n  \"reference\": \"ref\"\n}\n");
            if (ferror(f) | (fclose(f) != 0)) {
                fail(d, "write error", path);
            }
        }
    }
    int rc = d->failed ? -1 : 0;
    free(d->px16);
    free(d);
    return rc;
}
