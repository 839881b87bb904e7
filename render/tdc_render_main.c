/*
 * tdc-render - command-line front end of the companion renderer: renders
 * frames of a scene file or a built-in scene in one of the modes, writes
 * PNG images (linear light encoded with the 2.2 transfer) and/or a .tdcs
 * link stream through the link encoder, and prints per-stage timings.
 *
 *   tdc-render --builtin fence --frames 0:8 --mode full --png out/ --stream out/fence.tdcs --shadow-mv
 *   tdc-render --scene render/scenes/example.scene --mode gt --gt-samples 256 --png out/
 *   tdc-render --list | --print-scene NAME
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "tdc_link.h"
#include "tdc_render.h"
#include "tdc_render_stream.h"
#include "tdc_tool.h"

static void usage(FILE *f)
{
    fprintf(f, "usage: tdc-render (--scene FILE | --builtin NAME) [options]\n"
                    "       tdc-render --list | --print-scene NAME\n"
                    "options:\n"
                    "  --mode full|reduced|subframe|gt|trm   (trm: full and reduced frames alternate)\n"
                    "  --frames A:B         frames A..B-1 (default 0:1)\n"
                    "  --size WxH           output size (default: the scene's)\n"
                    "  --threads N          worker threads (default 2)\n"
                    "  --seed S             random seed (default 1)\n"
                    "  --gt-samples N       ground-truth samples per pixel (default 64)\n"
                    "  --reduced-factor R   r of reduced frames (default 0.5)\n"
                    "  --reduced-ss N --reduced-sigma S  rays per reduced pixel per axis (1..8, default 2) and the\n"
                    "                       Gaussian resolve's sigma in full-res px (default 2.5; 1 and 0.05: point-sampled)\n"
                    "  --shadow-mv --dual-mv --no-reflect-mv --bounces N\n"
                    "  --dual-trace         dual MVs by a previous-frame ray per pixel, not the G-buffer lookup\n"
                    "  --png DIR            write DIR/<scene>-<mode>-<frame>.png (+ -mv.png for motion)\n"
                    "  --layers             with --png: also the layers -shade, -vis, -refl, -mv-refl (Zeng §4);\n"
                    "                       with --mode subframe --stream: a layered stream (LAYERS packets)\n"
                    "  --indirect [--indirect-reuse]  one diffuse bounce per pixel [6-cone reuse over frames, §4.3]\n"
                    "  --stream FILE        write a .tdcs link stream (full, reduced, subframe, trm)\n"
                    "  --quiet              no per-frame lines\n"
                    "exit codes (docs/tools.md): 0 OK, 1 ARGS, 7 FILE, 13 INPUT (scene), 14 REFUSED (renderer\n"
                    "  or link encoder), 17 NOMEM\n");
}

static int parse_int(const char *s, int lo, int hi, int *out)
{
    return tdc_parse_int(s, lo, hi, out);
}

/* A:B with 0 <= A < B <= 10^7 */
static int parse_frames(const char *s, int *a, int *b)
{
    uint64_t x, y;
    const char *e;
    if (tdc_parse_u64_field(s, &e, 10000000, &x) != 0 || *e != ':' ||
        tdc_parse_u64_field(e + 1, &e, 10000000, &y) != 0 || *e != '\0' || y <= x)
        return -1;
    *a = (int)x, *b = (int)y;
    return 0;
}

/* MV visualisation: hue = direction, brightness = length (saturates at 8 px). */
static void mv_to_rgb(const int16_t *mv, size_t n, float *rgb)
{
    for (size_t i = 0; i < n; i++) {
        double dx = mv[2 * i] / 16.0, dy = mv[2 * i + 1] / 16.0;
        double len = sqrt(dx * dx + dy * dy), a = atan2(dy, dx);
        double v = len / 8 > 1 ? 1 : len / 8;
        rgb[3 * i] = (float)(v * (0.5 + 0.5 * cos(a)));
        rgb[3 * i + 1] = (float)(v * (0.5 + 0.5 * cos(a - 2.094)));
        rgb[3 * i + 2] = (float)(v * (0.5 + 0.5 * cos(a + 2.094)));
    }
}

int main(int argc, char **argv)
{
    tdc_tool_set_name("tdc-render");
    const char *scene_file = NULL, *builtin = NULL, *png_dir = NULL, *stream_path = NULL, *mode_s = "full";
    int f0 = 0, f1 = 1, quiet = 0, layers = 0, w = 0, h = 0;
    tdc_render_config_t cfg;
    tdc_render_default_config(&cfg);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return TDC_EXIT_OK;
        } else if (!strcmp(a, "--list")) {
            for (int k = 0; k < tdc_scene_builtin_count; k++) printf("%s\n", tdc_scene_builtin_names[k]);
            return 0;
        } else if (!strcmp(a, "--print-scene") && v) {
            const char *t = tdc_scene_builtin_text(v);
            if (!t) {
                return tdc_fail(TDC_EXIT_ARGS, NULL, "--print-scene", "unknown built-in scene '%s'", v);
            }
            fputs(t, stdout);
            return 0;
        } else if (!strcmp(a, "--scene") && v)
            scene_file = argv[++i];
        else if (!strcmp(a, "--builtin") && v)
            builtin = argv[++i];
        else if (!strcmp(a, "--mode") && v)
            mode_s = argv[++i];
        else if (!strcmp(a, "--png") && v)
            png_dir = argv[++i];
        else if (!strcmp(a, "--stream") && v)
            stream_path = argv[++i];
        else if (!strcmp(a, "--quiet"))
            quiet = 1;
        else if (!strcmp(a, "--shadow-mv"))
            cfg.shadow_mv = 1;
        else if (!strcmp(a, "--dual-mv"))
            cfg.dual_mv = 1;
        else if (!strcmp(a, "--dual-trace"))
            cfg.dual_mv = cfg.dual_trace = 1;
        else if (!strcmp(a, "--layers"))
            layers = 1;
        else if (!strcmp(a, "--indirect"))
            cfg.indirect = 1;
        else if (!strcmp(a, "--indirect-reuse"))
            cfg.indirect = cfg.indirect_reuse = 1;
        else if (!strcmp(a, "--no-reflect-mv"))
            cfg.reflect_mv = 0;
        else if (!strcmp(a, "--frames") && v) {
            if (parse_frames(argv[++i], &f0, &f1) != 0)
                return tdc_fail_option(NULL, a, argv[i], "want A:B with 0 <= A < B <= 10000000");
        } else if (!strcmp(a, "--size") && v) {
            unsigned uw, uh;
            if (tdc_parse_size(argv[++i], 16384, &uw, &uh) != 0)
                return tdc_fail_option(NULL, a, argv[i], "want WxH within 1..16384");
            w = (int)uw, h = (int)uh;
        } else if (!strcmp(a, "--threads") && v) {
            if (parse_int(argv[++i], 1, 64, &cfg.threads)) goto bad;
        } else if (!strcmp(a, "--bounces") && v) {
            if (parse_int(argv[++i], 0, 3, &cfg.max_bounces)) goto bad;
        } else if (!strcmp(a, "--gt-samples") && v) {
            if (parse_int(argv[++i], 1, 4096, &cfg.gt_samples)) goto bad;
        } else if (!strcmp(a, "--seed") && v) {
            int s;
            if (parse_int(argv[++i], 0, 0x7FFFFFFF, &s)) goto bad;
            cfg.seed = (uint32_t)s;
        } else if (!strcmp(a, "--reduced-factor") && v) {
            if (tdc_parse_double(argv[++i], 0.01, 1.0, &cfg.reduced_factor)) goto bad;
        } else if (!strcmp(a, "--reduced-ss") && v) {
            if (parse_int(argv[++i], 1, 8, &cfg.reduced_ss)) goto bad;
        } else if (!strcmp(a, "--reduced-sigma") && v) {
            if (tdc_parse_double(argv[++i], 0.01, 20.0, &cfg.reduced_sigma)) goto bad;
        } else {
            static const char *const valued[] = {"--print-scene", "--scene",   "--builtin", "--mode",
                                                 "--png",         "--stream",  "--frames",  "--size",
                                                 "--threads",     "--bounces", "--gt-samples", "--seed",
                                                 "--reduced-factor", "--reduced-ss", "--reduced-sigma"};
            int needs = 0;
            for (size_t k = 0; k < sizeof valued / sizeof valued[0]; k++) needs |= !v && !strcmp(a, valued[k]);
            return tdc_fail_usage(NULL, needs ? "option '%s' needs a value" : "unknown option '%s'", a);
        }
        continue;
    bad:
        return tdc_fail_option(NULL, a, argv[i], "see tdc-render --help");
    }
    if (!!scene_file == !!builtin) {
        return tdc_fail_usage(NULL, "give exactly one of --scene FILE and --builtin NAME");
    }
    int trm = 0;
    tdc_render_mode_t mode;
    if (!strcmp(mode_s, "full"))
        mode = TDC_RENDER_FULL;
    else if (!strcmp(mode_s, "reduced"))
        mode = TDC_RENDER_REDUCED;
    else if (!strcmp(mode_s, "subframe"))
        mode = TDC_RENDER_SUBFRAME;
    else if (!strcmp(mode_s, "gt"))
        mode = TDC_RENDER_GROUND_TRUTH;
    else if (!strcmp(mode_s, "trm")) {
        mode = TDC_RENDER_FULL;
        trm = 1;
    } else {
        return tdc_fail_option(NULL, "--mode", mode_s, "want full, reduced, subframe, gt or trm");
    }
    if (stream_path && mode == TDC_RENDER_GROUND_TRUTH) {
        return tdc_fail(TDC_EXIT_ARGS, NULL, "--stream", "ground truth is not streamed (use --png)");
    }
    cfg.width = w;
    cfg.height = h;
    char err[512];
    int rc = TDC_EXIT_OK;
    tdc_render_t *r = NULL;
    tdc_render_stream_t *stream = NULL;
    float *rgb = NULL, *vis = NULL, *lsh = NULL, *lvis = NULL, *lrefl = NULL, *lind = NULL;
    int16_t *mv = NULL, *mvs = NULL, *mvd = NULL, *mvr = NULL, *msurf = NULL;
    float *lsw = NULL;
    uint8_t *lsrc = NULL;
    if (scene_file && tdc_in_check(scene_file) != 0) {
        return tdc_fail(TDC_EXIT_FILE, NULL, scene_file, "cannot read: %s", strerror(errno));
    }
    tdc_scene_t *scene = malloc(sizeof *scene);
    if (!scene) return tdc_fail(TDC_EXIT_NOMEM, NULL, "scene", "out of memory");
    tdc_scene_status_t st = scene_file ? tdc_scene_load(scene_file, scene, err, sizeof err)
                                       : tdc_scene_builtin(builtin, scene, err, sizeof err);
    if (st != TDC_SCENE_OK) {
        rc = tdc_fail(st == TDC_SCENE_ERR_NOMEM     ? TDC_EXIT_NOMEM
                      : st == TDC_SCENE_ERR_IO      ? TDC_EXIT_FILE
                      : st == TDC_SCENE_ERR_UNKNOWN ? TDC_EXIT_ARGS
                                                    : TDC_EXIT_INPUT,
                      NULL, NULL, "%s", err);
        free(scene);
        return rc;
    }
    /* Output names come from the scene: confined to --png DIR (issue 19:
     * 'name ../escaped' wrote outside it). */
    if (png_dir && !tdc_safe_name(scene->name)) {
        rc = tdc_fail(TDC_EXIT_INPUT, NULL, scene_file ? scene_file : builtin,
                      "scene name '%s' cannot name a file in %s", scene->name, png_dir);
        goto done;
    }
    r = tdc_render_open(scene, &cfg, err, sizeof err);
    if (!r) {
        rc = tdc_fail(TDC_EXIT_REFUSED, NULL, "renderer", "%s", err);
        goto done;
    }
    tdc_render_features_t ft;
    tdc_render_get_features(r, &ft);
    int W, H;
    tdc_render_output_size(r, TDC_RENDER_FULL, &W, &H);
    printf("scene %s: %dx%d, %d objects, %llu triangles, features: mirrors=%d motion=%d (camera %d, objects %d) "
           "moving-blocker=%d lights=%d area-lights=%d\n",
           scene->name, W, H, scene->nobjects, (unsigned long long)ft.triangles, ft.mirrors, ft.motion, ft.camera_moves,
           ft.objects_move, ft.moving_blocker, ft.lights, ft.area_lights);
    if (png_dir && mkdir(png_dir, 0777) != 0 && errno != EEXIST) {
        rc = tdc_fail(TDC_EXIT_FILE, NULL, png_dir, "cannot create the output folder: %s", strerror(errno));
        goto done;
    }

    size_t npix = (size_t)W * H;
    rgb = malloc(npix * 3 * sizeof(float));
    vis = malloc(npix * 3 * sizeof(float));
    mv = malloc(npix * 2 * sizeof(int16_t));
    mvs = malloc(npix * 2 * sizeof(int16_t));
    mvd = malloc(npix * 2 * sizeof(int16_t));
    lsh = malloc(npix * 3 * sizeof(float));
    lvis = malloc(npix * 3 * sizeof(float)); /* grey for the PNG */
    lrefl = malloc(npix * 3 * sizeof(float));
    lind = malloc(npix * 3 * sizeof(float));
    mvr = malloc(npix * 2 * sizeof(int16_t));
    msurf = malloc(npix * 2 * sizeof(int16_t));
    lsw = malloc(npix * sizeof(float));
    lsrc = malloc(npix);
    if (!rgb || !vis || !mv || !mvs || !mvd || !lsh || !lvis || !lrefl || !lind || !mvr || !msurf || !lsw || !lsrc) {
        rc = tdc_fail(TDC_EXIT_NOMEM, NULL, "frame buffers", "out of memory for %dx%d", W, H);
        goto done;
    }
    int lstream = stream_path && layers && mode == TDC_RENDER_SUBFRAME && !trm;
    if (stream_path) {
        stream = tdc_render_stream_create(stream_path, r,
                                          lstream                           ? TDC_RSTREAM_LAYERS
                                          : trm || mode == TDC_RENDER_REDUCED ? TDC_RSTREAM_TRM
                                          : mode == TDC_RENDER_SUBFRAME     ? TDC_RSTREAM_SUBFRAMES
                                                                            : TDC_RSTREAM_FULL,
                                          err, sizeof err);
        if (!stream) {
            rc = tdc_fail(TDC_EXIT_FILE, NULL, stream_path, "%s", err);
            goto done;
        }
        printf("stream %s: flags 0x%04x%s\n", stream_path, (unsigned)tdc_render_stream_flags(stream),
               ft.motion ? "" : " (static scene: no motion vectors)");
    }

    tdc_render_stats_t tot;
    memset(&tot, 0, sizeof tot);
    int ran_frames[TDC_STAGE_COUNT] = {0}, dual_lookups = 0;
    /* Frames before A, rendered first and not counted ("as in a renderer
     * that runs on"): the dual and shadow vectors of frame A read frame
     * A - 1's G-buffer (Zeng eqs. 6 and 4); and a run that writes nothing
     * but its timings warms up on one frame of each kind it renders, since
     * the first frame of a kind pays its buffers' page faults and cold
     * caches (720x800 discs, TRM: the first full frame of a run drew in
     * 38-40 ms, the next in 34-35 ms). */
    int warm = 0;
    if (!png_dir && !stream_path && mode != TDC_RENDER_GROUND_TRUTH) warm = trm ? 2 : 1;
    else if ((cfg.dual_mv || cfg.shadow_mv) && !cfg.dual_trace && mode == TDC_RENDER_FULL && !trm) warm = 1;
    warm = warm < f0 ? warm : f0;
    for (int f = f0 - warm; f < f1 && !rc; f++) {
        tdc_render_mode_t m = mode;
        if (trm) m = tdc_link_trm_kind((uint32_t)f, 0) == TDC_LINK_KIND_REDUCED ? TDC_RENDER_REDUCED : TDC_RENDER_FULL;
        int lay = layers && (png_dir || lstream) && (m == TDC_RENDER_FULL || m == TDC_RENDER_SUBFRAME);
        tdc_render_out_t out = {.rgb = rgb,
                                .mv = mv,
                                .mv_shadow = cfg.shadow_mv || lstream ? mvs : NULL,
                                .shadow_weight = lstream ? lsw : NULL,
                                .mv_dual = cfg.dual_mv ? mvd : NULL,
                                .shade = lay ? lsh : NULL,
                                .vis = lay ? lvis : NULL,
                                .refl = lay ? lrefl : NULL,
                                .indirect = lay && cfg.indirect ? lind : NULL,
                                .mv_surf = lstream ? msurf : NULL,
                                .mv_refl = lay ? mvr : NULL,
                                .shadow_src = lstream ? lsrc : NULL};
        if (f < f0) { /* warm-up: not counted, not written */
            if (tdc_render_frame(r, (uint32_t)f, m, &out, NULL) < 0)
                rc = tdc_fail(TDC_EXIT_REFUSED, NULL, "renderer", "frame %d failed", f);
            continue;
        }
        tdc_render_stats_t s;
        if (tdc_render_frame(r, (uint32_t)f, m, &out, &s) < 0) {
            rc = tdc_fail(TDC_EXIT_REFUSED, NULL, "renderer", "frame %d failed", f);
            break;
        }
        if (lstream && tdc_render_stream_layers(stream, (uint32_t)f, &out) < 0)
            rc = tdc_fail(TDC_EXIT_FILE, NULL, stream_path, "link encoder or file rejected the layers of frame %d", f);
        uint64_t rays = 0;
        for (int k = 0; k < TDC_RAY_KIND_COUNT; k++) {
            rays += s.rays[k];
            tot.rays[k] += s.rays[k];
        }
        for (int k = 0; k < TDC_STAGE_COUNT; k++) {
            tot.ms[k] += s.ms[k];
            ran_frames[k] += s.ran[k];
        }
        tot.wall_ms += s.wall_ms;
        dual_lookups += s.dual_lookup;
        if (!quiet) {
            /* and the frame's CPU ms per stage that ran (a timing run's per-frame record) */
            printf("frame %4d %-12s %4dx%-4d %8.2f ms  %9llu rays %s cpu", f, tdc_render_mode_name(m), s.out_w,
                   s.out_h, s.wall_ms, (unsigned long long)rays, s.frame_static ? "static" : "");
            for (int k = 0; k < TDC_STAGE_COUNT; k++)
                if (s.ran[k]) printf(" %s=%.3f", tdc_render_stage_name((tdc_render_stage_t)k), s.ms[k]);
            putchar('\n');
        }
        if (png_dir) {
            char path[1024];
            snprintf(path, sizeof path, "%s/%s-%s-%04d.png", png_dir, scene->name, tdc_render_mode_name(m), f);
            if (tdc_render_write_png(path, rgb, s.out_w, s.out_h, err, sizeof err) < 0)
                rc = tdc_fail(TDC_EXIT_FILE, NULL, NULL, "%s", err);
            if (lay) {
                size_t np = (size_t)s.out_w * s.out_h;
                for (size_t i = np; i-- > 0;) lvis[3 * i] = lvis[3 * i + 1] = lvis[3 * i + 2] = lvis[i];
                const float *img[4] = {lsh, lvis, lrefl, lind};
                const char *suffix[4] = {"shade", "vis", "refl", "indirect"};
                for (int k = 0; k < (cfg.indirect ? 4 : 3); k++) {
                    snprintf(path, sizeof path, "%s/%s-%s-%04d-%s.png", png_dir, scene->name, tdc_render_mode_name(m),
                             f, suffix[k]);
                    if (tdc_render_write_png(path, img[k], s.out_w, s.out_h, err, sizeof err) < 0)
                        rc = tdc_fail(TDC_EXIT_FILE, NULL, NULL, "%s", err);
                }
                if (ft.motion) {
                    mv_to_rgb(mvr, np, vis);
                    snprintf(path, sizeof path, "%s/%s-%s-%04d-mv-refl.png", png_dir, scene->name,
                             tdc_render_mode_name(m), f);
                    if (tdc_render_write_png(path, vis, s.out_w, s.out_h, err, sizeof err) < 0)
                        rc = tdc_fail(TDC_EXIT_FILE, NULL, NULL, "%s", err);
                }
            }
            if ((m == TDC_RENDER_FULL || m == TDC_RENDER_SUBFRAME) && ft.motion) {
                const int16_t *src[3] = {mv, cfg.shadow_mv ? mvs : NULL, cfg.dual_mv ? mvd : NULL};
                const char *suffix[3] = {"mv", "mv-shadow", "mv-dual"};
                for (int k = 0; k < 3; k++) {
                    if (!src[k]) continue;
                    mv_to_rgb(src[k], (size_t)s.out_w * s.out_h, vis);
                    snprintf(path, sizeof path, "%s/%s-%s-%04d-%s.png", png_dir, scene->name, tdc_render_mode_name(m),
                             f, suffix[k]);
                    if (tdc_render_write_png(path, vis, s.out_w, s.out_h, err, sizeof err) < 0)
                        rc = tdc_fail(TDC_EXIT_FILE, NULL, NULL, "%s", err);
                }
            }
        }
        if (stream && !lstream && tdc_render_stream_frame(stream, (uint32_t)f, m, rgb, mv) < 0) {
            rc = tdc_fail(TDC_EXIT_FILE, NULL, stream_path, "link encoder or file rejected a packet of frame %d", f);
        }
    }
    int nf = f1 - f0;
    printf("per-stage CPU time over %d frames (summed over %d threads; skipped stages are not entered):\n", nf,
           cfg.threads);
    for (int k = 0; k < TDC_STAGE_COUNT; k++)
        printf("  %-10s %10.3f ms  %s\n", tdc_render_stage_name((tdc_render_stage_t)k), tot.ms[k],
               ran_frames[k] ? "" : "skipped");
    uint64_t all = 0;
    for (int k = 0; k < TDC_RAY_KIND_COUNT; k++) all += tot.rays[k];
    printf("rays: primary %llu shadow %llu reflect %llu mv %llu; wall %.1f ms, %.2f Mrays/s\n",
           (unsigned long long)tot.rays[0], (unsigned long long)tot.rays[1], (unsigned long long)tot.rays[2],
           (unsigned long long)tot.rays[3], tot.wall_ms, tot.wall_ms > 0 ? all / tot.wall_ms / 1e3 : 0.0);
    if (cfg.dual_mv || cfg.shadow_mv)
        printf("%s MVs: the previous frame's G-buffer read in %d of %d frames (the others traced a ray per "
               "candidate)\n", cfg.dual_mv && cfg.shadow_mv ? "dual and shadow" : cfg.dual_mv ? "dual" : "shadow",
               dual_lookups, nf);
    if (stream) {
        uint32_t np;
        uint64_t nb;
        if (tdc_render_stream_close(stream, &np, &nb) < 0 && rc == TDC_EXIT_OK)
            rc = tdc_fail(TDC_EXIT_FILE, NULL, stream_path, "closing the stream failed");
        else
            printf("stream: %u packets, %llu bytes\n", np, (unsigned long long)nb);
        stream = NULL;
    }
done:
    if (stream) {
        uint32_t np;
        uint64_t nb;
        tdc_render_stream_close(stream, &np, &nb);
    }
    if (r) tdc_render_close(r);
    free(scene);
    free(rgb);
    free(vis);
    free(mv);
    free(mvs);
    free(mvd);
    free(lsh);
    free(lvis);
    free(lrefl);
    free(lind);
    free(mvr);
    free(msurf);
    free(lsw);
    free(lsrc);
    return rc;
}
