/*
 * bench_fov.c - foveated streams: costs against full rate and the remap's
 * speed against the memory bound (make bench; figures in docs/foveation.md).
 *
 * 1. Per panel at its native resolution, alpha = 4, delta = 0.555 (log-polar
 *    buffer floor(0.555 W) x floor(0.555 H)), disk 12.443 % of the distance
 *    to the farthest corner, gaze at the centre and off-centre: rays traced
 *    (log-polar columns [u0, w) x h + disk pixels on the screen; exact counts
 *    from the firmware's own geometry) and link bytes (32-byte packet header +
 *    32-byte foveation header + the payload of tdc_fov_payload_bytes: 3 B per
 *    sample + 4 B motion vector per log-polar sample for fov-taa) against full rate (W x H rays, 32 + 3 W H
 *    bytes).  Goal (issue 14): <= 35 % each.  Also the eq. 5.1 curve: the
 *    ray share per disk fraction and where it is lowest (thesis: 10-20 %,
 *    12.443 % observed).
 * 2. Remap throughput on one core at 1080 x 1200 (HTC Vive eye): ns per output
 *    pixel, fov and fov-taa (and fovlr, fovlr-taa: the log-rectilinear kind),
 *    against memcpy bandwidth measured in the same
 *    run: bound = bytes touched per output pixel / memcpy bandwidth.
 *    Goal: >= 50 % of the bound.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tdc_fov.h"
#include "ref_fov.h"
#include "ref_fov_lr.h"
#include "tdc_fov_link.h"
#include "tdc_fov_lr.h"
#include "tdc_panels.h"
#include "bench_clock.h"
#include "tdc_must.h"

#define HDR_BYTES 64.0 /* link packet header 32 + foveation header 32 */

static void params(tdc_fov_params_t *p, int W, int H, double gx, double gy, double disk)
{
    p->gaze_x_q8 = (int32_t)lround(gx * W * 256);
    p->gaze_y_q8 = (int32_t)lround(gy * H * 256);
    p->alpha_q8 = 1024;
    p->disk_q15 = (uint16_t)lround(disk * 32768);
    p->lp_w = tdc_fov_lp_size(18187, (uint16_t)W); /* delta 0.555 as the link header carries it */
    p->lp_h = tdc_fov_lp_size(18187, (uint16_t)H);
    p->lr_k_q4[0] = p->lr_k_q4[1] = 0;
    p->transform = TDC_FOV_KERNEL_LOG_POLAR;
    p->zero = 0;
}

/* The log-polar samples some display pixel reads: the remap's taps (eq. 4.4's
 * columns [u - 2 sigma, u + 2 sigma], at least floor(u) and floor(u) + 1,
 * rows floor(v) and the next, periodic) from the double reference's eq. 2.2
 * at every pixel outside the disk's blend band.  Samples of [u0, w) x h that
 * no pixel reads lie off the screen (the buffer covers the circle of radius
 * R): traced and sent today, the share this prints is what a sender that
 * skipped them would save. */
static double lp_read_share(int W, int H, double gx, double gy, const tdc_fov_geom_t *fg)
{
    ref_fov_params_t rp = {gx * W, gy * H, 4.0, 0.12443, fg->lp_w, fg->lp_h, 0, 0, 0};
    ref_fov_geom_t g;
    ref_fov_geom(&g, W, H, &rp);
    unsigned char *hit = calloc((size_t)fg->lp_w * fg->lp_h, 1);
    if (!hit) return -1;
    for (int j = 0; j < H; j++) {
        for (int i = 0; i < W; i++) {
            const double x = i + 0.5, y = j + 0.5, r = hypot(x - g.cx, y - g.cy);
            if (r <= g.r_disk - 4) continue; /* the disk only */
            double u, v;
            ref_fov_to_lp(&g, x, y, &u, &v);
            const double sig = fmin(fmax(ref_fov_sigma_u(&g, r, u), 0.5), 2.0);
            int lo = (int)ceil(u - 2 * sig), hi = (int)floor(u + 2 * sig);
            lo = lo > (int)floor(u) ? (int)floor(u) : lo;
            hi = hi < (int)floor(u) + 1 ? (int)floor(u) + 1 : hi;
            const int j0 = (int)floor(v) % g.lp_h, j1 = (j0 + 1) % g.lp_h;
            for (int t = lo; t <= hi; t++) {
                const int c = t < g.u0 ? g.u0 : (t > g.lp_w - 1 ? g.lp_w - 1 : t);
                hit[(size_t)j0 * g.lp_w + c] = hit[(size_t)j1 * g.lp_w + c] = 1;
            }
        }
    }
    long n = 0;
    for (int j = 0; j < g.lp_h; j++)
        for (int c = g.u0; c < g.lp_w; c++) n += hit[(size_t)j * g.lp_w + c];
    free(hit);
    return (double)n / ((double)(g.lp_w - g.u0) * g.lp_h);
}

static int costs(void)
{
    const tdc_panel_t *panels[] = {
#define P(sym) &sym,
        TDC_PANEL_LIST(P)};
    int miss = 0;
    printf("rays and link bytes against full rate (alpha 4, delta 0.555, disk 12.443 %%); goal <= 35 %% each\n");
    printf("%-10s %-10s %-10s %7s %7s %9s %10s %9s %9s %9s %8s %9s\n", "panel", "size", "gaze", "l", "u0", "disk px",
           "rays", "rays %", "fov B %", "taa B %", "lp read", "rays % r");
    for (unsigned k = 0; k < sizeof panels / sizeof panels[0]; k++) {
        const int W = panels[k]->width, H = panels[k]->height;
        static const double gz[][2] = {{0.5, 0.5}, {0.3, 0.4}};
        for (int g = 0; g < 2; g++) {
            tdc_fov_params_t p;
            params(&p, W, H, gz[g][0], gz[g][1], 0.12443);
            tdc_fov_geom_t fg;
            if (tdc_fov_geom(&fg, (uint16_t)W, (uint16_t)H, &p) != TDC_OK) return 1;
            const double lps = (double)(fg.lp_w - fg.u0) * fg.lp_h, dk = tdc_fov_disk_pixels(&fg);
            const double full_b = 32.0 + 3.0 * W * H;
            const double rays = lps + dk;
            const double fb = HDR_BYTES + tdc_fov_payload_bytes(&fg, 0), tb = HDR_BYTES + tdc_fov_payload_bytes(&fg, 1);
            char sz[24];
            snprintf(sz, sizeof sz, "%dx%d", W, H);
            const double rd = lp_read_share(W, H, gz[g][0], gz[g][1], &fg);
            printf("%-10s %-10s %-10s %7u %7u %9.0f %10.0f %8.2f%% %8.2f%% %8.2f%% %7.1f%% %8.2f%%\n", panels[k]->name,
                   sz, g ? "(.3W,.4H)" : "centre", fg.l, fg.u0, dk, rays, 100 * rays / (W * H), 100 * fb / full_b,
                   100 * tb / full_b, 100 * rd, 100 * (lps * rd + dk) / (W * H));
            miss |= rays / (W * H) > 0.35 || tb / full_b > 0.35;
        }
    }
    /* eq. 5.1: ray share per disk fraction (1920x1080, centre gaze) */
    printf("\neq. 5.1 ray share per disk fraction, 1920x1080, gaze at the centre (exact counts):\n");
    double best = 1e9, best_x = 0;
    for (int i = 0; i <= 60; i++) {
        const double x = i * 0.005;
        tdc_fov_params_t p;
        params(&p, 1920, 1080, 0.5, 0.5, x);
        tdc_fov_geom_t fg;
        TDC_MUST(tdc_fov_geom(&fg, 1920, 1080, &p));
        const double thesis = ((double)(fg.lp_w - fg.l) * fg.lp_h + tdc_fov_disk_pixels(&fg)) / (1920.0 * 1080);
        const double ours = ((double)(fg.lp_w - fg.u0) * fg.lp_h + tdc_fov_disk_pixels(&fg)) / (1920.0 * 1080);
        if (ours < best) best = ours, best_x = x;
        if (i % 5 == 0 || fabs(x - 0.125) < 1e-9) {
            printf(
                "  disk %5.1f %%: l = %4u, rays %6.2f %% (eq. 5.1, columns from l), %6.2f %% (columns from u0 = %u)\n",
                100 * x, fg.l, 100 * thesis, 100 * ours, fg.u0);
        }
    }
    printf("  lowest ray share %.2f %% at disk %.1f %% (thesis: 10-20 %%, 12.443 %% observed)\n", 100 * best,
           100 * best_x);
    return miss;
}

static void fill(uint8_t *p, size_t n, uint32_t seed)
{
    for (size_t i = 0; i < n; i++) {
        seed = seed * 1664525u + 1013904223u;
        p[i] = (uint8_t)(seed >> 24);
    }
}

static void throughput(int lr, double bw)
{
    enum { W = 1080, H = 1200 };
    tdc_fov_params_t p;
    params(&p, W, H, 0.45, 0.5, 0.12443);
    if (lr) { /* log-rectilinear, the sender's default foveal scales */
        p.alpha_q8 = 256;
        p.transform = TDC_FOV_LOG_RECT;
        p.lr_k_q4[0] = (uint16_t)lround(16 * ref_fov_lr_k(W, p.lp_w, p.gaze_x_q8 / 256.0));
        p.lr_k_q4[1] = (uint16_t)lround(16 * ref_fov_lr_k(H, p.lp_h, p.gaze_y_q8 / 256.0));
    }
    tdc_fov_geom_t fg;
    TDC_MUST(tdc_fov_geom(&fg, W, H, &p));
    uint8_t *lp = malloc((size_t)p.lp_w * p.lp_h * 3), *dk = malloc(W * H * 3), *out = malloc(W * H * 3);
    int16_t *mv = malloc((size_t)p.lp_w * p.lp_h * 4);
    fill(lp, (size_t)p.lp_w * p.lp_h * 3, 1);
    fill(dk, W * H * 3, 2);
    for (size_t k = 0; k < (size_t)p.lp_w * p.lp_h; k++) {
        mv[2 * k] = -24; /* backward MVs of a (1.5, -0.5) px pan */
        mv[2 * k + 1] = 8;
    }
    const double lps = (double)(p.lp_w - fg.u0) * p.lp_h / (W * H), dks = tdc_fov_disk_pixels(&fg) / (double)(W * H);
    if (!lr) {
        printf("\nremap throughput, %dx%d (one eye), one core; memcpy bandwidth %.2f GB/s (read + write)\n", W, H,
               bw / 1e9);
        const tdc_fov_config_t c0 = {W, H, 0}, c1 = {W, H, 1};
        printf("  stage memory: %zu B without TAA (radial table %zu nodes x %zu B + %zu B per column), %zu B with TAA\n",
               tdc_fov_get_size(&c0), (size_t)TDC_FOV_RAD_NODES(W, H), sizeof(tdc_fov_node_t),
               (tdc_fov_get_size(&c0) - TDC_ARENA_ROUND(TDC_FOV_RAD_NODES(W, H) * sizeof(tdc_fov_node_t))) / W,
               tdc_fov_get_size(&c1));
    }
    static uint64_t lr_mem[TDC_FOV_LR_MEM_BYTES(W) / 8u];
    tdc_fov_lr_t lrs;
    TDC_MUST(tdc_fov_lr_init(&lrs, W, lr_mem, sizeof lr_mem));
    /* variants: fov, fov-taa (gaze still: the radial table and the column
     * reciprocals are built once), fov with the gaze moving 1 px per frame
     * (both rebuilt every frame, as with an eye tracker), fov with the C tap
     * kernels (geometry and taps) instead of AVX2; the log-rectilinear kind with and without TAA */
    typedef struct {
        int taa, move, simd;
        const char *name;
    } variant_t;
    static const variant_t var_lp[] = {{0, 0, 1, "fov"}, {1, 0, 1, "fov-taa"}, {0, 1, 1, "fov-move"}, {0, 0, 0, "fov-C"}};
    static const variant_t var_lr[] = {{0, 0, 1, "fovlr"}, {1, 0, 1, "fovlr-taa"}};
    const variant_t *var = lr ? var_lr : var_lp;
    const unsigned nvar = lr ? 2u : 4u;
    for (unsigned vi = 0; vi < nvar; vi++) {
        const int taa = var[vi].taa;
        tdc_fov_config_t cfg = {W, H, (uint8_t)taa};
        size_t n = tdc_fov_get_size(&cfg);
        void *mem = malloc(n);
        tdc_fov_t st;
        TDC_MUST(tdc_fov_init(&st, &cfg, mem, n));
        TDC_MUST(tdc_fov_lr_attach(&st, &lrs));
        tdc_fov_set_simd(&st, var[vi].simd);
        TDC_MUST(tdc_fov_frame(&st, &p, lp, (size_t)p.lp_w * 3, mv, (size_t)p.lp_w * 2, dk, W * 3, 11111, out, W * 3));
        double best = 1e30;
        tdc_fov_params_t pr = p;
        for (int r = 0; r < 5; r++) {
            pr.gaze_x_q8 += var[vi].move ? (r & 1 ? -256 : 256) : 0;
            const double t0 = now_s();
            TDC_MUST(
                tdc_fov_frame(&st, &pr, lp, (size_t)p.lp_w * 3, mv, (size_t)p.lp_w * 2, dk, W * 3, 11111, out, W * 3));
            const double t = now_s() - t0;
            best = t < best ? t : best;
        }
        /* bytes touched per output pixel: output 3, disk pixels 3 each, the
         * carried log-polar samples 3 each (each read from cache after the
         * first); TAA: + motion vectors 4 per sample, history read 6 + write 6 */
        const double bytes = 3 + 3 * dks + 3 * lps + (taa ? 4 * lps + 12 : 0);
        const double ns = 1e9 * best / (W * H), bound = 1e9 * bytes / bw;
        printf("  %-8s %7.2f ns/px (%6.1f Mpx/s, %5.1f ms/frame); %5.2f B/px touched -> bound %.3f ns/px: %5.1f %% of "
               "the bound (goal >= 50 %%)\n",
               var[vi].name, ns, 1e-6 * W * H / best, 1e3 * best, bytes, bound, 100 * bound / ns);
        if (var[vi].move) {
            printf("           (radial tables built: %u in %d frames)\n", (unsigned)st.rad_builds, 6);
        }
        free(mem);
    }
    free(lp), free(dk), free(out), free(mv);
}

int main(void)
{
    const int miss = costs();
    const double bw = memcpy_bandwidth();
    throughput(0, bw);
    throughput(1, bw);
    printf("\ncost goal (<= 35 %% rays and link bytes): %s\n", miss ? "MISSED (see the table)" : "met on every panel");
    return 0;
}
