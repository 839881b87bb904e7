/* tdc_report.c - CSV, markdown and picture strips of a simulator run. */
#include "report/tdc_report.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "simulator/tdc_sim_gaze.h"
#include "simulator/tdc_sim_jod.h"
#include "tdc_png.h"

static uint8_t enc8(double lin)
{
    double v = lin < 0 ? 0 : (lin > 1 ? 1 : lin);
    return (uint8_t)(255.0 * pow(v, 1.0 / 2.2) + 0.5);
}

/* Error colour map: black -> red -> yellow -> white over [0, 1]. */
static void heat(double e, uint8_t *p)
{
    e = e < 0 ? 0 : (e > 1 ? 1 : e);
    double r = fmin(1.0, 3.0 * e), g = fmin(1.0, fmax(0.0, 3.0 * e - 1.0)), b = fmax(0.0, 3.0 * e - 2.0);
    p[0] = (uint8_t)(255 * r);
    p[1] = (uint8_t)(255 * g);
    p[2] = (uint8_t)(255 * b);
}

static int g_write_failed;

/* A JOD cell: 3 decimals, or n/a (a region without pixels, nothing pooled). */
static const char *fmt_jod(double v, char *buf)
{
    if (isfinite(v)) {
        snprintf(buf, 16, "%.3f", v);
    } else {
        snprintf(buf, 16, "n/a");
    }
    return buf;
}

/* A JOD field of a CSV: 4 decimals, or empty. */
static void csv_jod(FILE *f, double v)
{
    if (isfinite(v)) {
        fprintf(f, ",%.4f", v);
    } else {
        fputc(',', f);
    }
}

int tdc_report_write_failed(void)
{
    return g_write_failed;
}

int tdc_report_strip(const char *outdir, const char *mode, const uint8_t *codes, const double *perc_lin,
                     const double *gt_lin, const double *flipmap, int w, int h, int cw, int ch, int margin)
{
    (void)h;
    int s = cw < 80 ? 4 : (cw < 160 ? 3 : (cw < 320 ? 2 : 1));
    int gap = 4;
    int pw = cw * s, ph = ch * s;
    int W = 4 * pw + 3 * gap, H = ph;
    uint8_t *img = malloc((size_t)W * H * 3);
    if (!img) {
        g_write_failed = 1;
        return -1;
    }
    memset(img, 255, (size_t)W * H * 3);
    for (int y = 0; y < ph; y++) {
        for (int x = 0; x < pw; x++) {
            int sx = x / s, sy = y / s;
            size_t ci = (size_t)sy * cw + sx;
            for (int panel = 0; panel < 4; panel++) {
                uint8_t *p = img + 3 * ((size_t)y * W + panel * (pw + gap) + x);
                if (panel == 0) {
                    const uint8_t *c = codes + 3 * ((size_t)(sy + margin) * w + sx + margin);
                    p[0] = c[0];
                    p[1] = c[1];
                    p[2] = c[2];
                } else if (panel == 1 || panel == 2) {
                    const double *l = (panel == 1 ? perc_lin : gt_lin) + 3 * ci;
                    p[0] = enc8(l[0]);
                    p[1] = enc8(l[1]);
                    p[2] = enc8(l[2]);
                } else {
                    heat(flipmap[ci], p);
                }
            }
        }
    }
    char path[1024], err[256];
    snprintf(path, sizeof(path), "%s/strip_%s.png", outdir, mode);
    int rc = tdc_png_write(path, img, W, H, 8, (size_t)W * 3, err, sizeof(err));
    if (rc) {
        fprintf(stderr, "tdc-sim: %s\n", err);
        g_write_failed = 1;
    }
    free(img);
    return rc;
}

static const char *panel_name(const tdc_sim_config_t *cfg)
{
    return cfg->panel == TDC_PANEL_SIM_LCD ? "lcd" : "oled";
}

/* What every table is read against: the full-resolution rays (--spp per
 * pixel, else 1 at >= 200 Hz and 4 below) and RGB888 link bytes per second
 * of all eyes, and whether any run was judged (the JOD columns). */
typedef struct {
    int eyes, judged;
    double full_rays, full_bytes;
} report_base_t;

static report_base_t report_base(const tdc_sim_config_t *cfg, const tdc_sim_result_t *r, int n)
{
    report_base_t b = {.eyes = cfg->eyes == 2 ? 2 : 1};
    b.full_rays = (double)cfg->width * cfg->height * (cfg->spp > 0 ? cfg->spp : (cfg->refresh_hz >= 200 ? 1 : 4)) *
                  cfg->refresh_hz * b.eyes;
    b.full_bytes = (double)cfg->width * cfg->height * 3.0 * cfg->refresh_hz * b.eyes;
    for (int i = 0; i < n; i++) {
        b.judged |= r[i].judged;
    }
    return b;
}

void tdc_report_csv(FILE *f, const tdc_sim_config_t *cfg, const tdc_sim_result_t *r, int n, int header)
{
    if (header) {
        fprintf(f, "run,scene,panel,mode,display_hz,width,height,evals,psnr_db,psnr_min_db,ssim,flip,flip_max,"
                   "legacy_flicker,rays_per_s,rays_vs_full,link_bytes_per_s,link_vs_full,fw_us_per_frame,"
                   "render_us_per_frame,frames,resets,link_errors,nonfinite,available,eyes,psnr_eye0_db,psnr_eye1_db,"
                   "ssim_eye0,ssim_eye1,flip_eye0,flip_eye1,legacy_terr,note,jod,jod_fovea,jod_periphery,jod_eye0,"
                   "jod_eye1,jod_frames\n");
    }
    const report_base_t base = report_base(cfg, r, n);
    const int eyes = base.eyes;
    for (int i = 0; i < n; i++) {
        const tdc_sim_result_t *x = &r[i];
        double T = x->sim_s > 0 ? x->sim_s : 1.0;
        double fr = x->frames ? (double)x->frames : 1.0;
        char per_eye[160] = ",,,,,", terr[32] = "";
        if (cfg->temporal && isfinite(x->terr)) {
            snprintf(terr, sizeof(terr), "%.3f", x->terr); /* temporal visibility model (--temporal) */
        }
        if (eyes == 2) {
            snprintf(per_eye, sizeof(per_eye), "%.3f,%.3f,%.5f,%.5f,%.5f,%.5f", x->eye_psnr[0], x->eye_psnr[1],
                     x->eye_ssim[0], x->eye_ssim[1], x->eye_flip[0], x->eye_flip[1]);
        }
        fprintf(f,
                "%s,%s,%s,%s,%d,%d,%d,%d,%.3f,%.3f,%.5f,%.5f,%.5f,%.3f,%.0f,%.4f,%.0f,%.4f,%.2f,%.2f,%llu,%u,%u,%d,%d,"
                "%d,%s,%s,\"%s\"",
                cfg->label ? cfg->label : "run", tdc_scene_name(cfg->scene.kind), panel_name(cfg), x->desc->name,
                x->display_hz, cfg->width, cfg->height, x->evals, x->psnr, x->evals ? x->psnr_min : 0.0, x->ssim,
                x->flip, x->flip_max, x->flicker, x->rays / T, x->rays / T / base.full_rays, x->link_bytes / T,
                x->link_bytes / T / base.full_bytes, 1e6 * x->fw_s / fr, 1e6 * x->render_s / fr,
                (unsigned long long)x->frames, x->resets, x->link_errors, x->nonfinite, x->available, eyes, per_eye,
                terr, x->note);
        /* FovVideoVDP (empty under --judge legacy, for a run within the
         * warm-up, or where a region has no pixel) */
        if (x->judged) {
            csv_jod(f, x->jod);
            csv_jod(f, x->jod_fovea);
            csv_jod(f, x->jod_periphery);
            csv_jod(f, x->eye_jod[0]);
            csv_jod(f, eyes == 2 ? x->eye_jod[1] : NAN);
            fprintf(f, ",%d\n", x->jod_frames);
        } else {
            fprintf(f, ",,,,,,\n");
        }
    }
}

void tdc_report_markdown(FILE *f, const tdc_sim_config_t *cfg, const tdc_sim_result_t *r, int n)
{
    /* FovVideoVDP's JOD leads (docs/visual-model.md); the legacy columns
     * say so in their names. */
    const report_base_t base = report_base(cfg, r, n);
    const int eyes = base.eyes, judged = base.judged;
    if (cfg->judge == TDC_JUDGE_LEGACY) {
        fprintf(f, "Judge: legacy (`--judge legacy`): no JOD; PSNR, SSIM, FLIP and the legacy columns only.\n\n");
    } else if (cfg->judge == TDC_JUDGE_SHORT) {
        fprintf(f, "JOD: n/a: the run (%.0f refreshes) is no longer than the judge's %.0f ms warm-up, so nothing "
                   "would be pooled (docs/visual-model.md); PSNR, SSIM, FLIP and the legacy columns only.\n\n",
                floor(cfg->duration_s * cfg->refresh_hz + 1e-9), 1e3 * TDC_SIM_JOD_WARMUP_S);
    }
    if (cfg->metric_every > 1) {
        /* JOD is judged at every refresh whatever K (its retinal signal is
         * sampled apart from the legacy instants) */
        const int k = cfg->metric_every;
        fprintf(f,
                "Legacy columns (PSNR, SSIM, FLIP, flicker, terr) at every %d%s refresh only (`--metric-every "
                "%d`)%s.\n\n",
                k, k == 2 ? "nd" : (k == 3 ? "rd" : "th"), k, judged ? "; JOD at every refresh" : "");
    }
    fprintf(f,
            "| mode |%s Hz | PSNR dB | SSIM | FLIP | flicker (legacy) | rays vs full | link vs full | link MB/s | fw us/frame | "
            "render us/frame |\n",
            judged ? " JOD | JOD fovea | JOD periphery |" : "");
    fprintf(f, "| --- |%s ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n",
            judged ? " ---: | ---: | ---: |" : "");
    for (int i = 0; i < n; i++) {
        const tdc_sim_result_t *x = &r[i];
        char jod[64] = "", b[3][16];
        if (judged && x->judged) {
            snprintf(jod, sizeof(jod), " %s | %s | %s |", fmt_jod(x->jod, b[0]), fmt_jod(x->jod_fovea, b[1]),
                     fmt_jod(x->jod_periphery, b[2]));
        } else if (judged) {
            snprintf(jod, sizeof(jod), " n/a | n/a | n/a |");
        }
        if (!x->available) {
            fprintf(f, "| %s |%s %d | n/a | n/a | n/a | n/a | | | | | |\n", x->desc->name, jod, x->display_hz);
            continue;
        }
        double T = x->sim_s > 0 ? x->sim_s : 1.0;
        double fr = x->frames ? (double)x->frames : 1.0;
        fprintf(f, "| %s |%s %d | %.2f | %.4f | %.4f | %.2f | %.3f | %.3f | %.2f | %.0f | %.0f |\n", x->desc->name,
                jod, x->display_hz, x->psnr, x->ssim, x->flip, x->flicker, x->rays / T / base.full_rays,
                x->link_bytes / T / base.full_bytes, x->link_bytes / T / 1e6, 1e6 * x->fw_s / fr, 1e6 * x->render_s / fr);
    }
    if (eyes == 2) {
        /* stereo: the table above is both eyes (mean figures, the pair's rays and link bytes) */
        fprintf(f,
                "\nPer eye (left = eye 0, right = eye 1):\n\n| mode |%s PSNR L | PSNR R | SSIM L | SSIM R | FLIP L | "
                "FLIP R | flicker L (legacy) | flicker R (legacy) |\n| --- |%s ---: | ---: | ---: | ---: | ---: | ---: | "
                "---: | ---: |\n",
                judged ? " JOD L | JOD R |" : "", judged ? " ---: | ---: |" : "");
        for (int i = 0; i < n; i++) {
            const tdc_sim_result_t *x = &r[i];
            char jod[48] = "", b[2][16];
            if (judged) {
                snprintf(jod, sizeof jod, " %s | %s |", fmt_jod(x->judged ? x->eye_jod[0] : NAN, b[0]),
                         fmt_jod(x->judged ? x->eye_jod[1] : NAN, b[1]));
            }
            if (x->available) {
                fprintf(f, "| %s |%s %.2f | %.2f | %.4f | %.4f | %.4f | %.4f | %.2f | %.2f |\n", x->desc->name, jod,
                        x->eye_psnr[0], x->eye_psnr[1], x->eye_ssim[0], x->eye_ssim[1], x->eye_flip[0], x->eye_flip[1],
                        x->eye_flicker[0], x->eye_flicker[1]);
            }
        }
    }
    int fov = 0;
    for (int i = 0; i < n; i++) {
        fov |= r[i].available && r[i].foveated;
    }
    if (fov) {
        tdc_report_foveation(f, cfg, r, n, 0);
    }
    int any = 0;
    for (int i = 0; i < n; i++) {
        if (r[i].note[0]) {
            if (!any) {
                fprintf(f, "\nNotes:\n\n");
                any = 1;
            }
            fprintf(f, "- `%s`: %s\n", r[i].desc->name, r[i].note);
        }
    }
}

void tdc_report_foveation(FILE *f, const tdc_sim_config_t *cfg, const tdc_sim_result_t *r, int n, int csv)
{
    const report_base_t base = report_base(cfg, r, n);
    const int judged = base.judged;
    if (csv) {
        fprintf(f, "run,mode,gaze,latency_ms,noise_deg,alpha,delta,disk,rays_vs_full,link_vs_full,flip,flip_fovea,"
                   "flip_periphery,flip_ecc,flip_wmedian,legacy_flicker,legacy_flicker_periphery,jod,jod_fovea,"
                   "jod_periphery\n");
    } else {
        /* JOD's fovea is 5 deg around the gaze (FovVideoVDP's regions,
         * docs/visual-model.md), FLIP's the fov disk */
        fprintf(f,
                "\nFoveation (gaze `%s`, tracker latency %.0f ms, noise %.2f deg; alpha %.2f, delta %.3f, disk %.4f of "
                "the distance to the farthest corner, which is also FLIP's foveal region below; JOD's fovea is "
                "within 5 deg of the gaze; FLIP weighted by "
                "eccentricity 2.3/(2.3 + e deg) around the true gaze; weighted median as the thesis's Tables "
                "5.1-5.3):\n\n| mode |%s rays vs full | link vs full | FLIP | FLIP fovea | FLIP periphery | FLIP ecc | "
                "FLIP w-median | flicker (legacy) | flicker periphery (legacy) |\n| --- |%s ---: | ---: | ---: | ---: | "
                "---: | ---: | ---: | ---: | ---: |\n",
                tdc_sim_gaze_name(cfg->gaze), cfg->gaze_latency_ms, cfg->gaze_noise_deg, cfg->fov_alpha, cfg->fov_delta,
                cfg->fov_disk, judged ? " JOD | JOD fovea | JOD periphery |" : "", judged ? " ---: | ---: | ---: |" : "");
    }
    for (int i = 0; i < n; i++) {
        const tdc_sim_result_t *x = &r[i];
        if (!x->available) {
            continue;
        }
        double T = x->sim_s > 0 ? x->sim_s : 1.0;
        char jod[64] = "", b[3][16];
        if (csv) {
            fprintf(f, "%s,%s,%s,%.1f,%.3f,%.3f,%.4f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.3f,%.3f",
                    cfg->label ? cfg->label : "run", x->desc->name, tdc_sim_gaze_name(cfg->gaze), cfg->gaze_latency_ms,
                    cfg->gaze_noise_deg, cfg->fov_alpha, cfg->fov_delta, cfg->fov_disk, x->rays / T / base.full_rays,
                    x->link_bytes / T / base.full_bytes, x->flip, x->flip_fovea, x->flip_periph, x->flip_ecc,
                    x->flip_wmedian, x->flicker, x->flicker_periph);
            csv_jod(f, x->judged ? x->jod : NAN);
            csv_jod(f, x->judged ? x->jod_fovea : NAN);
            csv_jod(f, x->judged ? x->jod_periphery : NAN);
            fputc('\n', f);
        } else {
            if (judged) {
                snprintf(jod, sizeof jod, " %s | %s | %s |", fmt_jod(x->judged ? x->jod : NAN, b[0]),
                         fmt_jod(x->judged ? x->jod_fovea : NAN, b[1]),
                         fmt_jod(x->judged ? x->jod_periphery : NAN, b[2]));
            }
            fprintf(f, "| %s |%s %.4f | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f | %.2f | %.2f |\n", x->desc->name, jod,
                    x->rays / T / base.full_rays, x->link_bytes / T / base.full_bytes, x->flip, x->flip_fovea, x->flip_periph,
                    x->flip_ecc, x->flip_wmedian, x->flicker, x->flicker_periph);
        }
    }
}
