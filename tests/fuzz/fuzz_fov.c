/*
 * fuzz_fov.c - libFuzzer target of the foveated packet's kind-specific
 * path: a 32-byte foveation header and its payload, checked against a
 * 48 x 32 panel (tdc_fov_hdr_parse, tdc_fov_payload_check); an accepted
 * packet is unpacked (log-polar rows, disk spans, motion vectors) and
 * remapped twice by tdc_fov_frame with TAA, the second time with the gaze
 * moved (reprojection, the saccade rule); log-rectilinear headers with the
 * stage's log-rectilinear scratch attached.  ASan + UBSan catch what goes
 * wrong; refusals are the expected outcome for most inputs.
 * Seeds: tests/fuzz/corpus-fov (make fuzz-seeds-fov).
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "tdc_fov.h"
#include "tdc_fov_link.h"
#include "tdc_fov_lr.h"

#define FW 48
#define FH 32

static uint64_t g_arena[TDC_FOV_MEM_BYTES(FW, FH, 1) / 8u];
static uint64_t g_lr_arena[TDC_FOV_LR_MEM_BYTES(FW) / 8u];
static uint8_t g_lp[FW * FH * 3], g_img[FW * FH * 3];
static int16_t g_mv[FW * FH * 2];

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < TDC_FOV_HDR_BYTES) {
        return 0;
    }
    tdc_fov_hdr_t h;
    if (tdc_fov_hdr_parse(data, FW, FH, &h) != TDC_FOV_HDR_OK ||
        tdc_fov_payload_check(&h, (uint32_t)(size - TDC_FOV_HDR_BYTES)) != TDC_FOV_HDR_OK) {
        return 0;
    }
    const uint8_t *p = data + TDC_FOV_HDR_BYTES;
    const size_t cols = (size_t)(h.g.lp_w - h.g.u0);
    for (int j = 0; j < h.g.lp_h; j++, p += cols * 3) {
        memcpy(g_lp + ((size_t)j * h.g.lp_w + h.g.u0) * 3, p, cols * 3);
    }
    for (int j = 0; j < FH; j++) {
        int32_t x0;
        const uint32_t n = tdc_fov_disk_span(&h.g, j, &x0);
        memcpy(g_img + ((size_t)j * FW + (size_t)x0) * 3, p, (size_t)n * 3);
        p += (size_t)n * 3;
    }
    const int taa = h.flags & TDC_FOV_FLAG_MV;
    if (taa) {
        for (int j = 0; j < h.g.lp_h; j++) {
            for (size_t i = 0; i < cols; i++, p += 4) {
                int16_t *m = g_mv + ((size_t)j * h.g.lp_w + h.g.u0 + i) * 2;
                m[0] = (int16_t)(uint16_t)(p[0] | p[1] << 8);
                m[1] = (int16_t)(uint16_t)(p[2] | p[3] << 8);
            }
        }
    }
    const tdc_fov_config_t cfg = {FW, FH, 1};
    tdc_fov_t st;
    tdc_fov_lr_t lr;
    if (tdc_fov_init(&st, &cfg, g_arena, sizeof g_arena) != TDC_OK ||
        tdc_fov_lr_init(&lr, FW, g_lr_arena, sizeof g_lr_arena) != TDC_OK || tdc_fov_lr_attach(&st, &lr) != TDC_OK) {
        __builtin_trap();
    }
    tdc_fov_params_t q = h.p;
    for (int f = 0; f < 2; f++) {
        if (tdc_fov_frame(&st, &q, g_lp, (size_t)h.g.lp_w * 3, taa ? g_mv : NULL, (size_t)h.g.lp_w * 2, g_img, FW * 3,
                          (uint32_t)(1000u + data[0] * 100u), g_img, FW * 3) != TDC_OK &&
            f == 0) {
            __builtin_trap(); /* the header was accepted: the stage must take it */
        }
        q.gaze_x_q8 += data[1] - 128;
        q.gaze_y_q8 += data[2] - 128;
    }
    return 0;
}
