/*
 * tdc_vm_mkstream.c - writes the two .tdcs link streams `make test-vm`
 * sends to the gadget board (whose sink is the firmware link decoder for a
 * 32x24 mono panel): OUT_DIR/clean.tdcs (stream 1, 24 full frames) and
 * OUT_DIR/damaged.tdcs (stream 2, the same frames with one payload bit
 * flipped in packet 5: the board must count 1 CRC error and 23 frames).
 * Host program (sim/link generator).  Usage: tdc_vm_mkstream OUT_DIR
 */
#include <stdio.h>
#include <string.h>

#include "link/tdc_link_gen.h"
#include "tdc_link.h"

enum { W = 32, H = 24, FRAMES = 24 };

static int write_stream(const char *dir, const char *name, uint16_t id, int damage)
{
    static uint8_t out[256 * 1024], scratch[TDC_LINK_GEN_SCRATCH_BYTES(W, H)];
    tdc_link_gen_packet_t pk[FRAMES + 1];
    tdc_link_gen_opts_t o;
    tdc_link_gen_opts_plain(&o, id, W, H, 1, 90, TDC_PIXFMT_RGB888, FRAMES, 11);
    uint32_t npk = 0;
    size_t n = tdc_link_gen_stream(out, sizeof out, &o, scratch, sizeof scratch, pk, FRAMES + 1, &npk);
    if (n == 0 || npk != FRAMES + 1) {
        fprintf(stderr, "tdc_vm_mkstream: generator failed\n");
        return -1;
    }
    if (damage) out[pk[5].offset + TDC_LINK_HEADER_BYTES + 17] ^= 0x04u;
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (f == NULL || fwrite(out, 1, n, f) != n || fclose(f) != 0) {
        perror(path);
        return -1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: tdc_vm_mkstream OUT_DIR\n");
        return 1;
    }
    return write_stream(argv[1], "clean.tdcs", 1, 0) || write_stream(argv[1], "damaged.tdcs", 2, 1);
}
