/*
 * golden_fov.c - bit-exact golden vectors of the foveated remap stage
 * (firmware/tdc_fov.c): alpha 1 / 4 / 8 x gaze (centre, a corner, outside
 * the screen) x disk fraction (0, 12.443 %, 1) x TAA off / on, 5 frames
 * each: the gaze drifts, motion vectors and frame times vary, and before
 * frame 4 the gaze jumps across the screen (the saccade path).  One
 * checksum per frame: FNV-1a 64 over the output codes, and with TAA over
 * the Q8 history too (little-endian).  The log-rectilinear kind
 * (firmware/tdc_fov_lr.c): gaze x disk x TAA likewise, foveal scales per
 * gaze, named lr-....  Freestanding, static buffers (~23 KiB).
 */
#include "golden.h"
#include "tdc_content.h"
#include "tdc_fov.h"
#include "tdc_fov_lr.h"

#define GW 45 /* odd sizes on purpose */
#define GH 29
#define LW 25 /* ~0.555 W, H */
#define LH 16

static uint64_t g_arena[TDC_FOV_MEM_BYTES(GW, GH, 1) / 8u];
static uint64_t g_lr_arena[TDC_FOV_LR_MEM_BYTES(GW) / 8u];
static uint8_t g_lp[LW * LH * 3];
static uint8_t g_disk[GW * GH * 3];
static uint8_t g_out[GW * GH * 3];
static int16_t g_mv[LW * LH * 2];

typedef struct {
    uint16_t alpha_q8, disk_q15;
    int32_t gx, gy; /* Q8 */
    uint8_t taa;
    const char *gname;
    uint16_t k_q4[2]; /* log-rectilinear foveal scales; 0: kernel log-polar */
} fov_vector_t;

static void run_vector(tdc_golden_ctx_t *ctx, const fov_vector_t *v)
{
    char name[80];
    char *o = tdc_golden_put_str(name, v->k_q4[0] ? "lr-a" : "a");
    o = tdc_golden_put_u32(o, v->alpha_q8);
    o = tdc_golden_put_str(o, "-d");
    o = tdc_golden_put_u32(o, v->disk_q15);
    *o++ = '-';
    o = tdc_golden_put_str(o, v->gname);
    o = tdc_golden_put_str(o, v->taa ? "-taa" : "-plain");
    *o = 0;

    const tdc_fov_config_t cfg = {GW, GH, v->taa};
    tdc_fov_t st;
    tdc_fov_lr_t lr;
    if (tdc_fov_init(&st, &cfg, g_arena, sizeof g_arena) != TDC_OK ||
        tdc_fov_lr_init(&lr, GW, g_lr_arena, sizeof g_lr_arena) != TDC_OK || tdc_fov_lr_attach(&st, &lr) != TDC_OK) {
        tdc_golden_emit(ctx, "fov", name, 0, 0); /* a failing init shows as a mismatch */
        return;
    }
    uint32_t seed = 0x9e3779b9u ^ v->alpha_q8 ^ ((uint32_t)v->disk_q15 << 11);
    tdc_fov_params_t p = {v->gx,
                          v->gy,
                          v->alpha_q8,
                          v->disk_q15,
                          LW,
                          LH,
                          {v->k_q4[0], v->k_q4[1]},
                          v->k_q4[0] ? TDC_FOV_LOG_RECT : TDC_FOV_KERNEL_LOG_POLAR,
                          0};
    for (uint32_t t = 0; t < 5u; t++) {
        tdc_content_frame(TDC_CONTENT_TEXT, t, 3u, g_lp, LW, LH, LW * 3);
        tdc_content_frame(TDC_CONTENT_GRADIENT, t, 3u, g_disk, GW, GH, GW * 3);
        for (uint32_t k = 0; k < LW * LH * 2u; k++) {
            g_mv[k] = (int16_t)((int32_t)(tdc_golden_rand(&seed) % 161u) - 80);
        }
        if (t == 4u) {
            p.gaze_x_q8 = GW * 256 - p.gaze_x_q8; /* across the screen */
            p.gaze_y_q8 = GH * 256 - p.gaze_y_q8;
        } else {
            p.gaze_x_q8 += 77;
            p.gaze_y_q8 -= 41;
        }
        const uint32_t dt = 8000u + (tdc_golden_rand(&seed) % 6000u);
        if (tdc_fov_frame(&st, &p, g_lp, LW * 3, g_mv, LW * 2, g_disk, GW * 3, dt, g_out, GW * 3) != TDC_OK) {
            tdc_golden_emit(ctx, "fov", name, t, 0);
            continue;
        }
        uint64_t h = tdc_fnv1a64(TDC_FNV64_INIT, g_out, sizeof g_out);
        if (v->taa) {
            const uint16_t *hist = st.hist[st.cur];
            for (uint32_t i = 0; i < GW * GH * 3u; i++) {
                const uint8_t b[2] = {(uint8_t)hist[i], (uint8_t)(hist[i] >> 8)};
                h = tdc_fnv1a64(h, b, 2);
            }
        }
        tdc_golden_emit(ctx, "fov", name, t, h);
    }
}

void tdc_golden_fov(tdc_golden_ctx_t *ctx);
void tdc_golden_fov(tdc_golden_ctx_t *ctx)
{
    static const uint16_t alphas[] = {256, 1024, 2048};
    static const uint16_t disks[] = {0, 4077, 32768}; /* 0, 12.443 %, 1 */
    static const struct {
        int32_t x, y;
        const char *name;
    } gazes[] = {{GW * 128, GH * 128, "centre"}, {0, GH * 256, "corner"}, {-GW * 16, GH * 300, "outside"}};
    for (unsigned a = 0; a < 3; a++) {
        for (unsigned d = 0; d < 3; d++) {
            for (unsigned g = 0; g < 3; g++) {
                for (uint8_t taa = 0; taa < 2; taa++) {
                    const fov_vector_t v = {alphas[a], disks[d], gazes[g].x, gazes[g].y, taa, gazes[g].name, {0, 0}};
                    run_vector(ctx, &v);
                }
            }
        }
    }
    /* log-rectilinear: the foveal scales the sender's default rule gives here (k S(k) = n) */
    static const uint16_t lr_k[3][2] = {{185, 117}, {371, 235}, {439, 349}};
    for (unsigned d = 0; d < 3; d++) {
        for (unsigned g = 0; g < 3; g++) {
            for (uint8_t taa = 0; taa < 2; taa++) {
                const fov_vector_t v = {256,           disks[d], gazes[g].x, gazes[g].y, taa, gazes[g].name,
                                        {lr_k[g][0], lr_k[g][1]}};
                run_vector(ctx, &v);
            }
        }
    }
}
