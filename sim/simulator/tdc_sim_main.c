/*
 * tdc-sim - host simulator: every display mode through renderer -> link ->
 * firmware -> panel -> eye -> metrics, with cost figures.  See --help.
 */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "image/tdc_image_source.h"
#include "tdc_tool.h"
#include "report/tdc_report.h"
#include "simulator/tdc_sim.h"
#include "simulator/tdc_sim_gaze.h"
#include "simulator/tdc_sim_jod.h"
#include "simulator/tdc_sim_render.h"
#include "tdc_par.h"

static void usage(FILE *f)
{
    int n;
    const tdc_mode_desc_t *const *m = tdc_sim_modes(&n);
    fprintf(f, "usage: tdc-sim [options]\n"
               "Simulates display modes through the whole data path (renderer -> link encoder ->\n"
               "firmware via the link decoder -> panel -> eye -> metrics vs ground truth).\n\n"
               "  -R, --renderer SCENE    use the Embree renderer (render): a built-in renderer scene\n"
               "                          (discs text panorama room mirror fence bigmesh glossy blocker) or a scene file\n"
               "      --threads N         threads of the renderer and of the simulator's own stages (source,\n"
               "                          eye, metrics; default 2); results do not depend on it\n"
               "      --image FILE        pan/zoom/rotate across a photograph (PNG or JPEG; exact area-sampled\n"
               "                          ground truth); pan from --speed/--angle (default 0), with\n"
               "      --zoom Z            screen pixels per image pixel at t = 0 (default 1)\n"
               "      --zoom-rate R       d ln(zoom)/dt in 1/s (default 0)\n"
               "      --rotate DEG_PER_S  rotation speed (default 0)\n"
               "  -s, --scene NAME        built-in procedural scene (default pan):");
    for (int i = 0; i < TDC_SCENE_COUNT; i++) {
        fprintf(f, " %s", tdc_scene_name((tdc_scene_kind_t)i));
    }
    fprintf(f,
            "\n"
            "  -m, --mode LIST         comma-separated modes, or 'all', 'trm-family' (90 Hz comparison),\n"
            "                          'asm-family' (240 Hz comparison); default trm-family\n"
            "  -p, --panel oled|lcd    panel simulation (default oled)\n"
            "      --profile NAME      firmware panel profile (default htc-vive, or the first LCD profile)\n"
            "      --lcd-mode M        LCD inverse: gamma, exact (default), od17, od33, state, state-pair\n"
            "      --lcd-bits N        LCD history / state bits 4..8 (default 8)\n"
            "      --backlight B       LCD backlight: hold, strobe or strobe:DUTY:PHASE (default: the panel's)\n"
            "  -r, --refresh HZ        run clock / display refresh (default 90)\n"
            "  -g, --size WxH          resolution of one eye (default: the panel profile's, e.g.\n"
            "                          1080x1200 for htc-vive); a smaller size is a window of the panel\n"
            "                          at its native pixel density\n"
            "      --eyes 1|2          eyes (default: the profile's; htc-vive and rift-cv1 have 2)\n"
            "      --stereo, --mono    --eyes 2, --eyes 1.  Stereo (TRM §7.2): both eyes through one\n"
            "                          stereo link stream and the firmware per eye; TRM modes send one\n"
            "                          eye full and the other reduced, swapped every frame\n"
            "      --disparity PX      procedural / --image stereo: the eyes' views differ by PX pixels (default 4)\n"
            "      --ipd M             renderer stereo: camera offset between the eyes in scene units\n"
            "                          (default 0.063)\n"
            "      --start-frame N     renderer: the run starts at the scene's frame N (a multiple of 4;\n"
            "                          default 0): another stretch of the animation, another content\n"
            "      --no-reflect-mv     renderer: primary MVs at mirror hits instead of reflected MVs\n"
            "                          (TDRT §3.1.2, Figs. 5-6)\n"
            "      --fov-lod MODE      fov modes: prefilter of the log-polar samples (thesis §4.1.2): the\n"
            "                          renderer's texture LOD, the other sources' box average in linear\n"
            "                          light: footprint (default; the sample's display cell), thesis\n"
            "                          (eq. 4.3's bias 3 S1(u^alpha)^3), off (one display pixel / point)\n"
            "      --fov-jitter J      fov-taa: the Halton jitter moves a log-polar sample by at most\n"
            "                          half a texel and half a display pixel (pixel, default) or half\n"
            "                          a texel (texel: the thesis's render-target jitter, ~12 px at a\n"
            "                          headset's screen edge)\n"
            "  -d, --duration S        simulated seconds (default 0.5)\n"
            "  -n, --frames N          simulated refreshes (overrides --duration)\n"
            "  -w, --window N          legacy eye: fused window in refreshes (default 2 below 200 Hz,\n"
            "                          else 4); the retinal signal (--dump) has none\n"
            "      --spp N             rays per pixel of full frames (default 4 below 200 Hz, else 1)\n"
            "      --speed PX_PER_S    main motion speed (default: the scene's)\n"
            "      --angle DEG         main motion direction (default 0 = +x)\n"
            "      --cut-time S        scene 'cut': time of the cut (default duration / 2)\n"
            "      --persistence F     OLED duty cycle (default 0.2 below 200 Hz, else 1 = hold)\n"
            "      --pursuit track|fixate  eye tracks the main motion or fixates (default track)\n"
            "      --pursuit-gain G    smooth-pursuit gain (default 1)\n"
            "      --temporal          legacy temporal visibility model: the legacy eye's error through a\n"
            "                          temporal CSF (Watson 1986, sim/eye/tdc_eye_temporal.h): legacy_terr\n"
            "      --metric-every K    the legacy columns (PSNR, SSIM, FLIP, flicker, terr) at every K-th\n"
            "                          refresh only (default 1: every refresh); the judge's JOD is still\n"
            "                          computed at every refresh.  Take K odd: an even K samples one phase\n"
            "                          of TRM's and interlace's 2-refresh alternation\n"
            "      --judge jod|legacy  the judge (docs/visual-model.md).  Default: FovVideoVDP on the\n"
            "                          retinal signal: JOD per mode and eye, fovea / periphery, in the report,\n"
            "                          summary.csv, series.csv (per refresh), -o DIR's jod.csv,\n"
            "                          jod_series.csv and heatmap_<mode>.png (eye 0's visible-difference\n"
            "                          map), unless the run is no longer than its 250 ms warm-up (nothing\n"
            "                          to pool); jod: judged even then; legacy: PSNR/SSIM/FLIP and the\n"
            "                          legacy columns only, 4-7x less CPU at 128x96 (sweeps without JOD)\n"
            "      --no-jod            --judge legacy (--jod: --judge jod)\n"
            "      --dump DIR          the retinal signal as files (docs/eye.md): per refresh and eye the drive\n"
            "                          codes, per step the emitted light and the retinal image of every mode\n"
            "                          and of the reference (16-bit linear PNG, Y4M), dump.json, steps.csv\n"
            "      --retina-steps N    retinal signal: steps per refresh, 1..16 (default: 4 on an LCD,\n"
            "                          round(1 / persistence) up to 8 on an OLED)\n"
            "      --pursuit-lag MS    retinal signal: the eye pursues the velocity of MS ago (default 0)\n"
            "      --ppd X             pixels per degree of the view (FLIP; default: the profile's, e.g.\n"
            "                          11.4 for htc-vive; 67.02, FLIP's desktop default, for profiles\n"
            "                          without one)\n"
            "      --trm-s S           TRM motion sensitivity s (default: firmware default)\n"
            "      --trm-sigma PX|scaled  sigma of TRM's D in full-res px (default 2.5, TRM §4.3); scaled:\n"
            "                          1.25 / r (2.5 at r = 1/2, the same in reduced px at every r; the\n"
            "                          firmware's D takes 0.25-3.5 px, so r < 0.36 is refused)\n"
            "      --gaze pursuit|fixed|saccade  where the eye looks (foveated modes and the gaze\n"
            "                          metrics; default pursuit: follows the pursued motion from the centre)\n"
            "      --gaze-at X,Y       --gaze fixed: that point in pixels (default the centre)\n"
            "      --gaze-latency MS   eye-tracker latency (default 0)\n"
            "      --gaze-noise DEG    eye-tracker noise, sigma per axis in degrees (default 0)\n"
            "      --fov-alpha A       fov modes: K(x) = x^A, 1..8 (default 4)\n"
            "      --fov-delta D       fov modes: log-polar buffer downscale, (0, 1] (default 0.555)\n"
            "      --fov-disk F        fov modes: disk radius / distance to the farthest corner, 0..1\n"
            "                          (default 0.12443); also the foveal region of the gaze metrics\n"
            "      --gt-ss N           ground-truth supersampling N x N (default 4)\n"
            "      --strip-at K        evaluation index of the picture strips (default middle)\n"
            "  -S, --seed N            scene seed (default 1)\n"
            "  -o, --out DIR           output folder: summary.csv, summary.md, series.csv, strip_*.png\n"
            "  -l, --label TEXT        run label in the report\n"
            "  -q, --quiet             no progress bar\n"
            "      --times             print the wall seconds per stage (source, link, firmware, panel,\n"
            "                          eye, metrics) on stderr\n"
            "      --list              list the modes\n"
            "  -h, --help              this help\n\nmodes:\n");
    for (int i = 0; i < n; i++) {
        fprintf(f, "  %-18s %s%s\n", m[i]->name, m[i]->what, m[i]->fixed_hz ? " (fixed rate)" : "");
    }
    fprintf(f, "\nexit codes (docs/tools.md): 0 OK, 1 ARGS, 7 FILE, 13 INPUT (malformed image or scene),\n"
               "14 REFUSED (a stage error or refused configuration: the run is not a result), 17 NOMEM;\n"
               "--dump: 7 FILE when a file could not be written, 13 INPUT when the panel profile has no photometry\n");
}

/* *explicit: 0 when a group ('all', a family) was named. */
static int add_modes(const char *list, const tdc_mode_desc_t **out, int *n, int cap, int *explicit)
{
    *explicit = 1;
    static const char *const trm_family[] = {"full",  "half",  "interlace", "bfi", "ncsfi",
                                             "trm50", "trm40", "trm25",     "asw"};
    static const char *const asm_family[] = {"full",
                                             "full60",
                                             "taa60",
                                             "asm-hourglass",
                                             "asm-bowtie",
                                             "asm-adaptive",
                                             "asm-hourglass-smv",
                                             "asm-bowtie-smv",
                                             "asm-adaptive-smv"};
    char buf[1024];
    snprintf(buf, sizeof(buf), "%s", list);
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        if (strcmp(tok, "all") == 0) {
            *explicit = 0;
            int nm;
            const tdc_mode_desc_t *const *m = tdc_sim_modes(&nm);
            for (int i = 0; i < nm && *n < cap; i++) {
                out[(*n)++] = m[i];
            }
        } else if (strcmp(tok, "trm-family") == 0 || strcmp(tok, "asm-family") == 0) {
            int tf = strcmp(tok, "trm-family") == 0;
            *explicit = 0;
            int cnt = tf ? 9 : 9;
            for (int i = 0; i < cnt && *n < cap; i++) {
                out[(*n)++] = tdc_sim_mode_find(tf ? trm_family[i] : asm_family[i]);
            }
        } else {
            const tdc_mode_desc_t *m = tdc_sim_mode_find(tok);
            if (!m) {
                fprintf(stderr, "tdc-sim: unknown mode '%s' (see --list)\n", tok);
                return -1;
            }
            if (*n < cap) {
                out[(*n)++] = m;
            }
        }
    }
    return 0;
}

static int mkdir_p(const char *dir)
{
    char tmp[1024];
    snprintf(tmp, sizeof(tmp), "%s", dir);
    for (char *p = tmp + 1; *p; p++) {
        if (*p == '/') {
            *p = 0;
            if (mkdir(tmp, 0755) && errno != EEXIST) {
                return -1;
            }
            *p = '/';
        }
    }
    if (mkdir(tmp, 0755) && errno != EEXIST) {
        return -1;
    }
    struct stat st; /* EEXIST: a folder, not a file of that name */
    if (stat(tmp, &st) != 0 || !S_ISDIR(st.st_mode)) {
        errno = ENOTDIR;
        return -1;
    }
    return 0;
}

/* OUTDIR/NAME opened for writing, or NULL after the one-line FILE message. */
static FILE *out_open(const char *dir, const char *name, char *path, size_t cap)
{
    snprintf(path, cap, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f) {
        tdc_fail(TDC_EXIT_FILE, NULL, path, "cannot write: %s", strerror(errno));
    }
    return f;
}

/* Closes an output; FILE (with its message) when anything of it was not written. */
static int out_close(FILE *f, const char *path)
{
    const int err = ferror(f);
    if (fclose(f) != 0 || err) {
        return tdc_fail(TDC_EXIT_FILE, NULL, path, "write failed: %s", strerror(errno ? errno : EIO));
    }
    return TDC_EXIT_OK;
}

static int parse_num(const char *s, double lo, double hi, double *v, const char *what)
{
    /* tdc_parse_double refuses nan/inf and overflow (issue 19: -r nan passed
     * the range check and failed later as "invalid configuration") */
    if (tdc_parse_double(s, lo, hi, v) != 0) {
        fprintf(stderr, "tdc-sim: bad %s '%s' (expected %g .. %g)\n", what, s, lo, hi);
        return -1;
    }
    return 0;
}

/* Exit code of a source that could not be opened: FILE when the file
 * itself could not be read, INPUT when its contents are malformed. */
static int image_exit(const char *err)
{
    return strstr(err, "cannot open") || strstr(err, "No such file") ? TDC_EXIT_FILE : TDC_EXIT_INPUT;
}

int main(int argc, char **argv)
{
    enum {
        O_SPEED = 256,
        O_ANGLE,
        O_CUT,
        O_PERS,
        O_PURSUIT,
        O_GAIN,
        O_TEMPORAL,
        O_EVERY,
        O_PPD,
        O_TRMS,
        O_TRMSIGMA,
        O_GTSS,
        O_STRIP,
        O_LIST,
        O_SPP,
        O_PROFILE,
        O_THREADS,
        O_EYES,
        O_STEREO,
        O_MONO,
        O_DISP,
        O_IPD,
        O_START,
        O_NOREFLMV,
        O_FOVLOD,
        O_FOVJIT,
        O_TIMES,
        O_IMAGE,
        O_ZOOM,
        O_ZOOMRATE,
        O_ROTATE,
        O_LCDMODE,
        O_LCDBITS,
        O_BACKLIGHT,
        O_GAZE,
        O_GAZE_AT,
        O_GAZE_LAT,
        O_GAZE_NOISE,
        O_FOV_ALPHA,
        O_FOV_DELTA,
        O_FOV_DISK,
        O_DUMP,
        O_JOD,
        O_NOJOD,
        O_JUDGE,
        O_RSTEPS,
        O_LAG
    };
    static const struct option opts[] = {{"scene", required_argument, 0, 's'},
                                         {"mode", required_argument, 0, 'm'},
                                         {"panel", required_argument, 0, 'p'},
                                         {"profile", required_argument, 0, O_PROFILE},
                                         {"refresh", required_argument, 0, 'r'},
                                         {"size", required_argument, 0, 'g'},
                                         {"duration", required_argument, 0, 'd'},
                                         {"frames", required_argument, 0, 'n'},
                                         {"window", required_argument, 0, 'w'},
                                         {"spp", required_argument, 0, O_SPP},
                                         {"speed", required_argument, 0, O_SPEED},
                                         {"angle", required_argument, 0, O_ANGLE},
                                         {"cut-time", required_argument, 0, O_CUT},
                                         {"persistence", required_argument, 0, O_PERS},
                                         {"pursuit", required_argument, 0, O_PURSUIT},
                                         {"pursuit-gain", required_argument, 0, O_GAIN},
                                         {"temporal", no_argument, 0, O_TEMPORAL},
                                         {"metric-every", required_argument, 0, O_EVERY},
                                         {"ppd", required_argument, 0, O_PPD},
                                         {"trm-s", required_argument, 0, O_TRMS},
                                         {"trm-sigma", required_argument, 0, O_TRMSIGMA},
                                         {"gt-ss", required_argument, 0, O_GTSS},
                                         {"strip-at", required_argument, 0, O_STRIP},
                                         {"seed", required_argument, 0, 'S'},
                                         {"out", required_argument, 0, 'o'},
                                         {"label", required_argument, 0, 'l'},
                                         {"quiet", no_argument, 0, 'q'},
                                         {"list", no_argument, 0, O_LIST},
                                         {"renderer", required_argument, 0, 'R'},
                                         {"threads", required_argument, 0, O_THREADS},
                                         {"eyes", required_argument, 0, O_EYES},
                                         {"stereo", no_argument, 0, O_STEREO},
                                         {"mono", no_argument, 0, O_MONO},
                                         {"disparity", required_argument, 0, O_DISP},
                                         {"ipd", required_argument, 0, O_IPD},
                                         {"start-frame", required_argument, 0, O_START},
                                         {"no-reflect-mv", no_argument, 0, O_NOREFLMV},
                                         {"fov-lod", required_argument, 0, O_FOVLOD},
                                         {"fov-jitter", required_argument, 0, O_FOVJIT},
                                         {"times", no_argument, 0, O_TIMES},
                                         {"image", required_argument, 0, O_IMAGE},
                                         {"zoom", required_argument, 0, O_ZOOM},
                                         {"zoom-rate", required_argument, 0, O_ZOOMRATE},
                                         {"rotate", required_argument, 0, O_ROTATE},
                                         {"lcd-mode", required_argument, 0, O_LCDMODE},
                                         {"lcd-bits", required_argument, 0, O_LCDBITS},
                                         {"backlight", required_argument, 0, O_BACKLIGHT},
                                         {"gaze", required_argument, 0, O_GAZE},
                                         {"gaze-at", required_argument, 0, O_GAZE_AT},
                                         {"gaze-latency", required_argument, 0, O_GAZE_LAT},
                                         {"gaze-noise", required_argument, 0, O_GAZE_NOISE},
                                         {"fov-alpha", required_argument, 0, O_FOV_ALPHA},
                                         {"fov-delta", required_argument, 0, O_FOV_DELTA},
                                         {"fov-disk", required_argument, 0, O_FOV_DISK},
                                         {"dump", required_argument, 0, O_DUMP},
                                         {"jod", no_argument, 0, O_JOD},
                                         {"no-jod", no_argument, 0, O_NOJOD},
                                         {"judge", required_argument, 0, O_JUDGE},
                                         {"retina-steps", required_argument, 0, O_RSTEPS},
                                         {"pursuit-lag", required_argument, 0, O_LAG},
                                         {"help", no_argument, 0, 'h'},
                                         {0, 0, 0, 0}};
    tdc_sim_config_t cfg;
    tdc_sim_default_config(&cfg);
    const char *mode_list = "trm-family";
    const char *renderer = NULL;
    const char *image = NULL;
    tdc_image_motion_t im;
    tdc_image_motion_default(&im);
    int threads = 2;
    int size_given = 0, ppd_given = 0, eyes = 0;
    tdc_sim_times_t times;
    double disparity = 4.0, ipd = 0.063;
    long start_frame = 0;
    int reflect_mv = 1;
    int fov_lod = TDC_FOV_LOD_FOOTPRINT;
    long frames = -1;
    int jod = -1; /* the judge: FovVideoVDP (-1: unless the run is within its warm-up; 1: --judge jod,
                     always), 0: --judge legacy / --no-jod */
    double v;
    int c;
    tdc_tool_set_name("tdc-sim");
    opterr = 0; /* tdc_fail_getopt() writes the one line */
    while ((c = getopt_long(argc, argv, ":R:s:m:p:r:g:d:n:w:S:o:l:qh", opts, NULL)) != -1) {
        switch (c) {
        case 's': {
            int k = tdc_scene_from_name(optarg);
            if (k < 0) {
                fprintf(stderr, "tdc-sim: unknown scene '%s' (see --help)\n", optarg);
                return TDC_EXIT_ARGS;
            }
            cfg.scene.kind = (tdc_scene_kind_t)k;
            break;
        }
        case 'm':
            if (optarg[0] == '\0') {
                fprintf(stderr, "tdc-sim: bad mode list '' (-m needs at least one mode)\n");
                return TDC_EXIT_ARGS;
            }
            mode_list = optarg;
            break;
        case 'R': renderer = optarg; break;
        case O_EYES:
            if (strcmp(optarg, "1") != 0 && strcmp(optarg, "2") != 0) {
                fprintf(stderr, "tdc-sim: bad eyes '%s' (1 or 2)\n", optarg);
                return TDC_EXIT_ARGS;
            }
            eyes = optarg[0] - '0';
            break;
        case O_STEREO: eyes = 2; break;
        case O_TIMES: cfg.times = &times; break;
        case O_MONO: eyes = 1; break;
        case O_DISP:
            if (parse_num(optarg, -1000, 1000, &v, "disparity")) {
                return TDC_EXIT_ARGS;
            }
            disparity = v;
            break;
        case O_IPD:
            if (parse_num(optarg, -10, 10, &v, "ipd")) {
                return TDC_EXIT_ARGS;
            }
            ipd = v;
            break;
        case O_START:
            if (parse_num(optarg, 0, 1e6, &v, "start-frame")) {
                return TDC_EXIT_ARGS;
            }
            if (v != floor(v) || fmod(v, 4.0) != 0.0) {
                fprintf(stderr, "tdc-sim: --start-frame: %s is not a multiple of 4 (the subframe cycle)\n", optarg);
                return TDC_EXIT_ARGS;
            }
            start_frame = (long)v;
            break;
        case O_NOREFLMV: reflect_mv = 0; break;
        case O_FOVLOD:
            if (!strcmp(optarg, "footprint")) {
                fov_lod = TDC_FOV_LOD_FOOTPRINT;
            } else if (!strcmp(optarg, "thesis")) {
                fov_lod = TDC_FOV_LOD_THESIS;
            } else if (!strcmp(optarg, "off")) {
                fov_lod = TDC_FOV_LOD_OFF;
            } else {
                fprintf(stderr, "tdc-sim: --fov-lod: %s is not footprint, thesis or off\n", optarg);
                return TDC_EXIT_ARGS;
            }
            cfg.fov_lod = fov_lod;
            break;
        case O_FOVJIT:
            if (!strcmp(optarg, "pixel")) {
                cfg.fov_jitter = TDC_FOV_JITTER_PIXEL;
            } else if (!strcmp(optarg, "texel")) {
                cfg.fov_jitter = TDC_FOV_JITTER_TEXEL;
            } else {
                fprintf(stderr, "tdc-sim: --fov-jitter: %s is not pixel or texel\n", optarg);
                return TDC_EXIT_ARGS;
            }
            break;
        case O_IMAGE: image = optarg; break;
        case O_ZOOM:
            if (parse_num(optarg, 1e-3, 1e3, &im.zoom, "zoom")) {
                return TDC_EXIT_ARGS;
            }
            break;
        case O_ZOOMRATE:
            if (parse_num(optarg, -20, 20, &im.zoom_rate, "zoom-rate")) {
                return TDC_EXIT_ARGS;
            }
            break;
        case O_ROTATE:
            if (parse_num(optarg, -3600, 3600, &im.rotate_dps, "rotate")) {
                return TDC_EXIT_ARGS;
            }
            break;
        case O_THREADS:
            if (parse_num(optarg, 1, 64, &v, "threads")) {
                return TDC_EXIT_ARGS;
            }
            threads = (int)v;
            break;
        case 'p':
            if (strcmp(optarg, "oled") == 0) {
                cfg.panel = TDC_PANEL_SIM_OLED;
            } else if (strcmp(optarg, "lcd") == 0) {
                cfg.panel = TDC_PANEL_SIM_LCD;
            } else {
                fprintf(stderr, "tdc-sim: panel must be oled or lcd\n");
                return TDC_EXIT_ARGS;
            }
            break;
        case O_PROFILE: cfg.panel_profile = optarg; break;
        case O_LCDMODE: {
            static const char *const names[] = {"gamma", "exact", "od17", "od33", "state", "state-pair"};
            int k = -1;
            for (int i = 0; i < 6; i++) {
                k = strcmp(optarg, names[i]) == 0 ? i : k;
            }
            if (k < 0) {
                fprintf(stderr, "tdc-sim: --lcd-mode '%s': gamma, exact, od17, od33, state or state-pair\n", optarg);
                return TDC_EXIT_ARGS;
            }
            cfg.lcd_mode = k;
            break;
        }
        case O_LCDBITS:
            if (parse_num(optarg, 4, 8, &v, "lcd-bits")) {
                return TDC_EXIT_ARGS;
            }
            cfg.lcd_bits = (int)v;
            break;
        case O_BACKLIGHT: {
            double d = 0.3, ph = 0.7;
            char extra;
            if (strcmp(optarg, "hold") == 0) {
                cfg.backlight = 0;
            } else if (strcmp(optarg, "strobe") == 0 || (sscanf(optarg, "strobe:%lf:%lf%c", &d, &ph, &extra) == 2 &&
                                                         d > 0.0 && d <= 1.0 && ph >= 0.0 && ph + d <= 1.0)) {
                cfg.backlight = 1;
                cfg.strobe_duty = d;
                cfg.strobe_phase = ph;
            } else {
                fprintf(stderr, "tdc-sim: --backlight '%s': hold, strobe or strobe:DUTY:PHASE (DUTY + PHASE <= 1)\n",
                        optarg);
                return TDC_EXIT_ARGS;
            }
            break;
        }
        case 'r':
            if (parse_num(optarg, 1, 1000, &v, "refresh")) {
                return TDC_EXIT_ARGS;
            }
            cfg.refresh_hz = (int)v;
            break;
        case 'g': {
            unsigned w, h; /* overflow-checked: 4294967328x24 is refused, not 32x24 */
            if (tdc_parse_size(optarg, 4096, &w, &h) != 0 || w < 8 || h < 8) {
                fprintf(stderr, "tdc-sim: bad size '%s' (WxH, 8 .. 4096)\n", optarg);
                return TDC_EXIT_ARGS;
            }
            cfg.width = w;
            cfg.height = h;
            size_given = 1;
            break;
        }
        case 'd':
            if (parse_num(optarg, 1e-3, 1e6, &v, "duration")) {
                return TDC_EXIT_ARGS;
            }
            cfg.duration_s = v;
            break;
        case 'n':
            if (parse_num(optarg, 1, 1e8, &v, "frames")) {
                return TDC_EXIT_ARGS;
            }
            frames = (long)v;
            break;
        case 'w':
            if (parse_num(optarg, 1, 16, &v, "window")) {
                return TDC_EXIT_ARGS;
            }
            cfg.window_frames = (int)v;
            break;
        case O_SPP:
            if (parse_num(optarg, 1, 64, &v, "spp")) {
                return TDC_EXIT_ARGS;
            }
            cfg.spp = (int)v;
            break;
        case O_SPEED:
            if (parse_num(optarg, 0, 1e6, &v, "speed")) {
                return TDC_EXIT_ARGS;
            }
            cfg.scene.speed = v;
            break;
        case O_ANGLE:
            if (parse_num(optarg, -360, 360, &v, "angle")) {
                return TDC_EXIT_ARGS;
            }
            cfg.scene.angle_deg = v;
            break;
        case O_CUT:
            if (parse_num(optarg, 0, 1e6, &v, "cut time")) {
                return TDC_EXIT_ARGS;
            }
            cfg.scene.cut_time = v;
            break;
        case O_PERS:
            if (parse_num(optarg, 0.01, 1, &v, "persistence")) {
                return TDC_EXIT_ARGS;
            }
            cfg.persistence = v;
            break;
        case O_PURSUIT:
            if (strcmp(optarg, "track") == 0) {
                cfg.scene.pursuit = 1;
            } else if (strcmp(optarg, "fixate") == 0) {
                cfg.scene.pursuit = 0;
            } else {
                fprintf(stderr, "tdc-sim: --pursuit track|fixate\n");
                return TDC_EXIT_ARGS;
            }
            break;
        case O_GAIN:
            if (parse_num(optarg, 0, 1.5, &v, "pursuit gain")) {
                return TDC_EXIT_ARGS;
            }
            cfg.pursuit_gain = v;
            break;
        case O_TEMPORAL:
            cfg.temporal = 1;
            break;
        case O_EVERY:
            if (parse_num(optarg, 1, 1e6, &v, "metric-every")) {
                return TDC_EXIT_ARGS;
            }
            cfg.metric_every = (int)v;
            break;
        case O_GAZE: {
            const int k = tdc_sim_gaze_from_name(optarg);
            if (k < 0) {
                fprintf(stderr, "tdc-sim: bad gaze '%s' (pursuit, fixed or saccade)\n", optarg);
                return TDC_EXIT_ARGS;
            }
            cfg.gaze = k;
            break;
        }
        case O_GAZE_AT: {
            char *comma = strchr(optarg, ',');
            if (!comma) {
                fprintf(stderr, "tdc-sim: bad gaze-at '%s' (X,Y in pixels)\n", optarg);
                return TDC_EXIT_ARGS;
            }
            *comma = '\0';
            double y;
            if (parse_num(optarg, 0, 65535, &v, "gaze-at x") || parse_num(comma + 1, 0, 65535, &y, "gaze-at y")) {
                return TDC_EXIT_ARGS;
            }
            cfg.gaze_at_x = v;
            cfg.gaze_at_y = y;
            break;
        }
        case O_GAZE_LAT:
            if (parse_num(optarg, 0, 1000, &v, "gaze-latency")) {
                return TDC_EXIT_ARGS;
            }
            cfg.gaze_latency_ms = v;
            break;
        case O_GAZE_NOISE:
            if (parse_num(optarg, 0, 30, &v, "gaze-noise")) {
                return TDC_EXIT_ARGS;
            }
            cfg.gaze_noise_deg = v;
            break;
        case O_FOV_ALPHA:
            if (parse_num(optarg, 1, 8, &v, "fov-alpha")) {
                return TDC_EXIT_ARGS;
            }
            cfg.fov_alpha = v;
            break;
        case O_FOV_DELTA:
            if (parse_num(optarg, 0.01, 1, &v, "fov-delta")) {
                return TDC_EXIT_ARGS;
            }
            cfg.fov_delta = v;
            break;
        case O_FOV_DISK:
            if (parse_num(optarg, 0, 1, &v, "fov-disk")) {
                return TDC_EXIT_ARGS;
            }
            cfg.fov_disk = v;
            break;
        case O_PPD:
            if (parse_num(optarg, 1, 1000, &v, "ppd")) {
                return TDC_EXIT_ARGS;
            }
            cfg.flip_ppd = v;
            ppd_given = 1;
            break;
        case O_JOD:
            jod = 1;
            break;
        case O_NOJOD:
            jod = 0;
            break;
        case O_JUDGE:
            if (strcmp(optarg, "jod") && strcmp(optarg, "legacy")) {
                fprintf(stderr, "tdc-sim: --judge '%s': jod or legacy\n", optarg);
                return TDC_EXIT_ARGS;
            }
            jod = !strcmp(optarg, "jod");
            break;
        case O_DUMP:
            if (optarg[0] == '\0') {
                fprintf(stderr, "tdc-sim: --dump: empty folder name\n");
                return TDC_EXIT_ARGS;
            }
            cfg.dump_dir = optarg;
            break;
        case O_RSTEPS:
            if (parse_num(optarg, 1, 16, &v, "retina-steps")) {
                return TDC_EXIT_ARGS;
            }
            if (v != floor(v)) {
                fprintf(stderr, "tdc-sim: bad retina-steps '%s' (an integer 1 .. 16)\n", optarg);
                return TDC_EXIT_ARGS;
            }
            cfg.retina_steps = (int)v;
            break;
        case O_LAG:
            if (parse_num(optarg, 0, 500, &v, "pursuit-lag")) {
                return TDC_EXIT_ARGS;
            }
            cfg.pursuit_lag_ms = v;
            break;
        case O_TRMS:
            if (parse_num(optarg, 0, 1000, &v, "trm-s")) {
                return TDC_EXIT_ARGS;
            }
            cfg.trm_s = (int)v;
            break;
        case O_TRMSIGMA:
            if (!strcmp(optarg, "scaled")) {
                cfg.trm_sigma = -1.0;
            } else if (parse_num(optarg, 0.25, 3.5, &v, "trm-sigma")) {
                return TDC_EXIT_ARGS;
            } else {
                cfg.trm_sigma = v;
            }
            break;
        case O_GTSS:
            if (parse_num(optarg, 1, 16, &v, "gt-ss")) {
                return TDC_EXIT_ARGS;
            }
            cfg.scene.gt_ss = (int)v;
            break;
        case O_STRIP:
            if (parse_num(optarg, 0, 1e9, &v, "strip-at")) {
                return TDC_EXIT_ARGS;
            }
            cfg.strip_at = (int)v;
            break;
        case 'S':
            if (parse_num(optarg, 0, 4294967295.0, &v, "seed")) {
                return TDC_EXIT_ARGS;
            }
            cfg.seed = (uint32_t)v;
            break;
        case 'o': cfg.outdir = optarg; break;
        case 'l': cfg.label = optarg; break;
        case 'q': cfg.progress = 0; break;
        case O_LIST: {
            int n;
            const tdc_mode_desc_t *const *m = tdc_sim_modes(&n);
            for (int i = 0; i < n; i++) {
                printf("%s\n", m[i]->name);
            }
            return 0;
        }
        case 'h': usage(stdout); return 0;
        default: return tdc_fail_getopt(c, argv);
        }
    }
    tdc_par_set_threads(threads);
    if (optind < argc) {
        fprintf(stderr, "tdc-sim: unexpected argument '%s'\n", argv[optind]);
        return TDC_EXIT_ARGS;
    }
    /* native geometry from the panel profile unless overridden */
    const tdc_panel_t *prof = tdc_sim_panel_find(cfg.panel_profile, cfg.panel == TDC_PANEL_SIM_LCD);
    if (!prof) {
        fprintf(stderr, "tdc-sim: --profile %s: no such %spanel profile (see make help)\n",
                cfg.panel_profile ? cfg.panel_profile : "(default)", cfg.panel == TDC_PANEL_SIM_LCD ? "LCD " : "");
        return TDC_EXIT_ARGS;
    }
    if (!size_given) {
        cfg.width = prof->width;
        cfg.height = prof->height;
    }
    cfg.eyes = eyes ? eyes : prof->eyes;
    cfg.ppd_from = ppd_given ? "--ppd" : (prof->ppd_x100 ? "profile" : "default");
    if (!ppd_given && prof->ppd_x100) {
        cfg.flip_ppd = prof->ppd_x100 / 100.0;
    }
    /* the gaze point is a pixel of the view */
    if (cfg.gaze_at_x >= 0 && (cfg.gaze_at_x >= cfg.width || cfg.gaze_at_y >= cfg.height)) {
        fprintf(stderr, "tdc-sim: --gaze-at %g,%g: outside the %dx%d view\n", cfg.gaze_at_x, cfg.gaze_at_y, cfg.width,
                cfg.height);
        return TDC_EXIT_ARGS;
    }
    if (frames > 0) {
        cfg.duration_s = (double)frames / cfg.refresh_hz;
    }
    /* The judge pools the refreshes after its warm-up: a run no longer than
     * that has no JOD and, unless --judge jod asks for the judge anyway (its
     * cost: make bench-fvvdp), is not judged. */
    const long run_refreshes = (long)floor(cfg.duration_s * cfg.refresh_hz + 1e-9);
    cfg.judge = !jod ? TDC_JUDGE_LEGACY
                     : (jod < 0 && run_refreshes <= tdc_sim_jod_warmup(cfg.refresh_hz) ? TDC_JUDGE_SHORT
                                                                                         : TDC_JUDGE_JOD);
    jod = cfg.judge == TDC_JUDGE_JOD;
    if (cfg.dump_dir || jod) {
        /* the retinal signal: its frame rate and the panel's photometry */
        double pers = cfg.persistence > 0 ? cfg.persistence : (cfg.refresh_hz >= 200 ? 1.0 : 0.2);
        int steps = tdc_retina_steps(cfg.retina_steps, cfg.panel == TDC_PANEL_SIM_LCD, pers);
        if ((long)cfg.refresh_hz * steps > 2000) {
            fprintf(stderr, "tdc-sim: --retina-steps: %d Hz x %d steps = %ld retinal frames/s, above 2000\n",
                    cfg.refresh_hz, steps, (long)cfg.refresh_hz * steps);
            return TDC_EXIT_ARGS;
        }
        tdc_retina_display_t disp;
        char why[256];
        if (tdc_retina_display_from_panel(prof, cfg.flip_ppd, cfg.ppd_from, cfg.width, &disp, why, sizeof(why))) {
            fprintf(stderr, "tdc-sim: %s: %s\n", cfg.dump_dir ? "--dump" : "the judge (--judge jod)", why);
            return TDC_EXIT_INPUT;
        }
    }
    if (cfg.scene.cut_time < 0) {
        cfg.scene.cut_time = cfg.duration_s / 2;
    }
    cfg.scene.width = cfg.width;
    cfg.scene.height = cfg.height;
    cfg.scene.seed = cfg.seed;
    const tdc_mode_desc_t *modes[64];
    int nm = 0;
    if (add_modes(mode_list, modes, &nm, 64, &cfg.strict)) {
        return TDC_EXIT_ARGS;
    }
    if (!cfg.label) {
        cfg.label = renderer ? renderer : (image ? image : tdc_scene_name(cfg.scene.kind));
    }
    if (cfg.outdir && mkdir_p(cfg.outdir)) {
        return tdc_fail(TDC_EXIT_FILE, NULL, cfg.outdir, "cannot create the output folder: %s", strerror(errno));
    }
    tdc_source_t *src = NULL;
    if (image && renderer) {
        fprintf(stderr, "tdc-sim: --image and --renderer exclude each other\n");
        return TDC_EXIT_ARGS;
    }
    if (image) {
        char err[512];
        if (tdc_in_check(image) != 0) {
            return tdc_fail(TDC_EXIT_FILE, "--image", image, "cannot read: %s", strerror(errno));
        }
        if (cfg.scene.speed < 0) {
            cfg.scene.speed = 0.0;
        }
        src = tdc_image_source_open(image, &cfg.scene, &im, err, sizeof(err));
        if (!src) {
            fprintf(stderr, "tdc-sim: --image %s\n", err);
            return image_exit(err);
        }
        if (cfg.eyes == 2) {
            /* stereo: as the procedural scenes, the eyes see the photograph
             * shifted by -+disparity / 2 screen pixels at t = 0, i.e. the
             * image point at the screen centre c0 moves by +-disparity / (2 z0) */
            double A[4], b[2];
            tdc_image_source_map(src, 0.0, A, b);
            double c0x = A[0] * 0.5 * cfg.width + A[1] * 0.5 * cfg.height + b[0];
            double c0y = A[2] * 0.5 * cfg.width + A[3] * 0.5 * cfg.height + b[1];
            src->destroy(src);
            tdc_image_motion_t eye = im;
            eye.cy = c0y;
            eye.cx = c0x + 0.5 * disparity / im.zoom;
            src = tdc_image_source_open(image, &cfg.scene, &eye, err, sizeof(err));
            eye.cx = c0x - 0.5 * disparity / im.zoom;
            cfg.right = src ? tdc_image_source_open(image, &cfg.scene, &eye, err, sizeof(err)) : NULL;
            if (!cfg.right) {
                fprintf(stderr, "tdc-sim: --image %s\n", err);
                if (src) {
                    src->destroy(src);
                }
                return image_exit(err);
            }
        }
        cfg.scene.speed = tdc_image_source_max_speed(src, cfg.duration_s); /* evaluation margin */
    } else if (renderer) {
        char err[256];
        for (int e = 0; e < cfg.eyes; e++) {
            tdc_source_t *s =
                tdc_sim_render_source(renderer, cfg.width, cfg.height, cfg.refresh_hz,
                                      cfg.scene.gt_ss > 0 ? cfg.scene.gt_ss * cfg.scene.gt_ss : 16, threads,
                                      cfg.eyes == 2 ? (e ? 0.5 : -0.5) * ipd : 0.0, err, sizeof(err));
            if (!s) {
                fprintf(stderr, "tdc-sim: renderer: %s\n", err);
                if (e) {
                    src->destroy(src);
                }
                return image_exit(err);
            }
            tdc_sim_render_options(s, start_frame, reflect_mv, fov_lod, cfg.seed);
            if (e) {
                cfg.right = s;
            } else {
                src = s;
            }
        }
        cfg.scene.speed = 0.0; /* margins from the measured pursuit instead */
        cfg.spp = 1;           /* the renderer traces one ray per pixel centre */
    } else {
        /* stereo: the eyes see the scene shifted by -+disparity / 2 */
        tdc_scene_params_t sp = cfg.scene;
        sp.shift_x = cfg.eyes == 2 ? -0.5 * disparity : 0.0;
        src = tdc_scene_create(&sp, NULL);
        if (src && cfg.eyes == 2) {
            sp.shift_x = 0.5 * disparity;
            cfg.right = tdc_scene_create(&sp, NULL);
            if (!cfg.right) {
                src->destroy(src);
                src = NULL;
            }
        }
    }
    if (!src) {
        fprintf(stderr, "tdc-sim: cannot create scene\n");
        return TDC_EXIT_NOMEM;
    }
    tdc_sim_result_t *res = calloc((size_t)nm, sizeof(*res));
    FILE *series = NULL;
    char path[1200], series_path[1200];
    if (cfg.outdir && !(series = out_open(cfg.outdir, "series.csv", series_path, sizeof series_path))) {
        free(res);
        src->destroy(src);
        if (cfg.right) {
            cfg.right->destroy(cfg.right);
        }
        return TDC_EXIT_FILE;
    }
    /* The judge (FovVideoVDP; --judge legacy leaves it out): a consumer of
     * the retinal signal. */
    FILE *jod_series = NULL;
    tdc_sim_jod_t *judge = NULL;
    char jod_path[1200];
    int jod_rc = TDC_EXIT_OK;
    if (jod) {
        if (cfg.outdir && !(jod_series = out_open(cfg.outdir, "jod_series.csv", jod_path, sizeof jod_path))) {
            jod_rc = TDC_EXIT_FILE;
        }
        judge = jod_rc == TDC_EXIT_OK ? tdc_sim_jod_new(jod_series, cfg.outdir != NULL) : NULL;
        cfg.retina_cb = judge ? tdc_sim_jod_cb : NULL;
        cfg.retina_ctx = judge;
    }
    int rc = res && (!jod || judge) ? tdc_sim_run(&cfg, src, modes, nm, res, series) : (jod_rc ? -2 : -1);
    int file_rc = series ? out_close(series, series_path) : TDC_EXIT_OK;
    if (judge) {
        rc = rc ? rc : tdc_sim_jod_finish(judge);
        for (int i = 0; rc == 0 && i < nm; i++) {
            /* the JOD columns of summary.csv and the report (mean of the eyes) */
            int ne = cfg.eyes == 2 ? 2 : 1, ok = 1;
            double sum[3] = {0.0, 0.0, 0.0};
            for (int e = 0; e < ne; e++) {
                tdc_fvvdp_jods_t jr = {NAN, NAN, NAN};
                ok &= tdc_sim_jod_result(judge, res[i].desc->name, e, &jr, &res[i].jod_frames) == 0;
                res[i].eye_jod[e] = ok ? jr.all : NAN;
                sum[0] += jr.all;
                sum[1] += jr.fovea;
                sum[2] += jr.periphery;
            }
            res[i].judged = ok;
            res[i].jod = sum[0] / ne;
            res[i].jod_fovea = sum[1] / ne;
            res[i].jod_periphery = sum[2] / ne;
        }
        if (rc == 0) {
            tdc_sim_jod_write(judge, stdout);
            if (cfg.outdir) {
                FILE *f = out_open(cfg.outdir, "jod.csv", path, sizeof path);
                int bad = !f || tdc_sim_jod_write(judge, f);
                bad |= f && out_close(f, path);
                bad |= tdc_sim_jod_heatmaps(judge, cfg.outdir) != 0;
                bad |= tdc_sim_jod_series_merge(judge, series_path, cfg.eyes == 2 ? 2 : 1,
                                                          cfg.refresh_hz) != 0;
                file_rc = bad ? TDC_EXIT_FILE : file_rc;
            }
        }
        tdc_sim_jod_free(judge);
    }
    if (jod_series && out_close(jod_series, jod_path)) {
        file_rc = TDC_EXIT_FILE;
    }
    if (rc == 0 && cfg.times) {
        fprintf(stderr,
                "tdc-sim: stage wall seconds: source %.2f link %.2f firmware %.2f panel %.2f eye %.2f metrics %.2f "
                "total %.2f\n",
                times.source_s, times.link_s, times.firmware_s, times.panel_s, times.eye_s, times.metrics_s,
                times.total_s);
    }
    if (rc == 0) {
        tdc_report_markdown(stdout, &cfg, res, nm);
        if (cfg.outdir) {
            FILE *f = out_open(cfg.outdir, "summary.csv", path, sizeof path);
            if (f) {
                tdc_report_csv(f, &cfg, res, nm, 1);
                file_rc = out_close(f, path) ? TDC_EXIT_FILE : file_rc;
            } else {
                file_rc = TDC_EXIT_FILE;
            }
            f = out_open(cfg.outdir, "foveation.csv", path, sizeof path);
            if (f) {
                tdc_report_foveation(f, &cfg, res, nm, 1);
                file_rc = out_close(f, path) ? TDC_EXIT_FILE : file_rc;
            } else {
                file_rc = TDC_EXIT_FILE;
            }
            f = out_open(cfg.outdir, "summary.md", path, sizeof path);
            if (!f) {
                file_rc = TDC_EXIT_FILE;
            } else {
                fprintf(f,
                        "Run `%s`: scene `%s`, %s panel, %d Hz clock, %s%dx%d, %.2f px/deg, %.3f s, window %d "
                        "refreshes.\n\n",
                        cfg.label, tdc_scene_name(cfg.scene.kind), cfg.panel == TDC_PANEL_SIM_LCD ? "LCD" : "OLED",
                        cfg.refresh_hz, cfg.eyes == 2 ? "stereo 2x" : "", cfg.width, cfg.height, cfg.flip_ppd,
                        cfg.duration_s, cfg.window_frames > 0 ? cfg.window_frames : (cfg.refresh_hz >= 200 ? 4 : 2));
                tdc_report_markdown(f, &cfg, res, nm);
                file_rc = out_close(f, path) ? TDC_EXIT_FILE : file_rc;
            }
        }
        for (int i = 0; i < nm; i++) {
            if (res[i].nonfinite) {
                fprintf(stderr, "tdc-sim: mode %s produced non-finite values\n", res[i].desc->name);
                rc = 1;
            }
        }
    }
    free(res);
    src->destroy(src);
    if (cfg.right) {
        cfg.right->destroy(cfg.right);
    }
    /* a stage error, a refused configuration or non-finite output: the
     * run is not a result (docs/tools.md: REFUSED); an output not written
     * (a strip, a summary, a --dump file: rc -2) is FILE, never success */
    if (rc == -2) {
        return TDC_EXIT_FILE;
    }
    if (rc != 0) {
        return TDC_EXIT_REFUSED;
    }
    return file_rc != TDC_EXIT_OK || tdc_report_write_failed() ? TDC_EXIT_FILE : TDC_EXIT_OK;
}
