/*
 * make_seeds_fov.c - seed corpus of fuzz_fov (tests/fuzz/corpus-fov): valid
 * foveated packets (header + payload) for a 48 x 32 panel: gaze at the
 * centre, a corner and outside, alpha 1 / 4 / 8, disk 0 / 12.443 % / 1,
 * with and without motion vectors; two log-rectilinear packets (gaze at
 * the centre with vectors, outside without); payload bytes from a fixed PRNG.
 * Usage: make_seeds_fov OUTDIR   (make fuzz-seeds-fov; deliberate, like fuzz-seeds)
 */
#include <stdio.h>
#include <stdlib.h>

#include "tdc_fov_link.h"

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: make_seeds_fov OUTDIR\n");
        return 2;
    }
    static const int32_t gz[][2] = {{24 * 256, 16 * 256}, {0, 32 * 256}, {-40 * 256, 10 * 256}};
    static const uint16_t alpha[] = {256, 1024, 2048}, disk[] = {0, 4077, 32768};
    static uint8_t buf[TDC_FOV_HDR_BYTES + 48 * 32 * 10];
    uint32_t rng = 2463534242u, n = 0;
    for (int g = 0; g < 3; g++)
        for (int a = 0; a < 3; a++)
            for (int d = 0; d < 3; d++) {
                if (g != 0 && a != 1) continue;
                const uint8_t flags = (uint8_t)((g + a + d) & 1);
                tdc_fov_params_t p = {
                    gz[g][0], gz[g][1], alpha[a], disk[d], tdc_fov_lp_size(18187, 48), tdc_fov_lp_size(18187, 32), {0, 0}, 0, 0};
                if (tdc_fov_hdr_pack(buf, 48, 32, &p, 18187, flags) != TDC_OK) {
                    fprintf(stderr, "make_seeds_fov: pack refused\n");
                    return 1;
                }
                tdc_fov_hdr_t h;
                if (tdc_fov_hdr_parse(buf, 48, 32, &h) != TDC_FOV_HDR_OK) {
                    fprintf(stderr, "make_seeds_fov: parse refused its own header\n");
                    return 1;
                }
                for (uint32_t i = 0; i < h.payload_bytes; i++) {
                    rng ^= rng << 13, rng ^= rng >> 17, rng ^= rng << 5;
                    buf[TDC_FOV_HDR_BYTES + i] =
                        (uint8_t)(flags && i >= h.payload_bytes - 4u * (uint32_t)(h.g.lp_w - h.g.u0) * h.g.lp_h
                                      ? (rng & 0x1Fu) /* small motion vectors */
                                      : rng >> 24);
                }
                char path[512];
                snprintf(path, sizeof path, "%s/fov-g%d-a%u-d%u%s", argv[1], g, alpha[a], disk[d], flags ? "-mv" : "");
                FILE *f = fopen(path, "wb");
                if (!f ||
                    fwrite(buf, 1, TDC_FOV_HDR_BYTES + h.payload_bytes, f) != TDC_FOV_HDR_BYTES + h.payload_bytes) {
                    fprintf(stderr, "make_seeds_fov: cannot write %s\n", path);
                    return 1;
                }
                fclose(f);
                n++;
            }
    /* the log-rectilinear kind (after the others: their bytes stay what they were) */
    for (int g = 0; g < 3; g += 2) {
        const uint8_t flags = g == 0;
        tdc_fov_params_t p = {gz[g][0],
                              gz[g][1],
                              256,
                              4077,
                              tdc_fov_lp_size(18187, 48),
                              tdc_fov_lp_size(18187, 32),
                              {(uint16_t)(g ? 1800 : 190), (uint16_t)(g ? 130 : 120)},
                              TDC_FOV_LOG_RECT,
                              0};
        tdc_fov_hdr_t h;
        if (tdc_fov_hdr_pack(buf, 48, 32, &p, 18187, flags) != TDC_OK ||
            tdc_fov_hdr_parse(buf, 48, 32, &h) != TDC_FOV_HDR_OK) {
            fprintf(stderr, "make_seeds_fov: log-rectilinear header refused\n");
            return 1;
        }
        for (uint32_t i = 0; i < h.payload_bytes; i++) {
            rng ^= rng << 13, rng ^= rng >> 17, rng ^= rng << 5;
            buf[TDC_FOV_HDR_BYTES + i] = (uint8_t)(flags && i >= h.payload_bytes - 4u * (uint32_t)h.g.lp_w * h.g.lp_h
                                                       ? (rng & 0x1Fu)
                                                       : rng >> 24);
        }
        char path[512];
        snprintf(path, sizeof path, "%s/fovlr-g%d%s", argv[1], g, flags ? "-mv" : "");
        FILE *f = fopen(path, "wb");
        if (!f || fwrite(buf, 1, TDC_FOV_HDR_BYTES + h.payload_bytes, f) != TDC_FOV_HDR_BYTES + h.payload_bytes) {
            fprintf(stderr, "make_seeds_fov: cannot write %s\n", path);
            return 1;
        }
        fclose(f);
        n++;
    }
    printf("%u seeds\n", n);
    return 0;
}
