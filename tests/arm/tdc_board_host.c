/*
 * tdc_board_host.c - host test double of the board interface: runs the
 * firmware frame loop (firmware/board/tdc_main.c, built for the same panel
 * and stages as a board image) on the host, so its panel checksums are the
 * reference the emulated boards must reproduce bit for bit.
 *   transport: the .tdcs file argv[1], read in 16 KiB chunks
 *   panel:     "frame N fnv1a64" lines on stdout (same format as
 *              firmware/board/tdc_board_emulated.c)
 *   the rest:  tdc_board_stub.c (no vsync, timer at 0, power-on reset)
 * Usage: tdc_fw_host STREAM.tdcs [DUMP_DIR]
 *   DUMP_DIR: also every shown frame as DUMP_DIR/shown-K.ppm (K = 0, 1, ..
 *   in the order shown; binary PPM, the header QEMU's screendump writes) and
 *   a line "K END_OFFSET" in DUMP_DIR/offsets: the stream bytes read when
 *   it was shown (16 KiB reads: it is shown by then and not before the
 *   previous read's end), "K end" for a frame shown only at the stream's
 *   end.  make test-vm compares the Linux board's scan-out with these.
 */
#include <stdio.h>

#include "tdc_board.h"

static FILE *g_in, *g_offsets;
static const char *g_dump;
static unsigned long long g_pos;
static unsigned g_shown;
static int g_ended;

tdc_board_status_t tdc_board_init(void)
{
    return g_in ? TDC_BOARD_OK : TDC_BOARD_ERR_IO;
}

tdc_board_status_t tdc_board_transport_read(uint8_t *buf, uint32_t cap, uint32_t *got)
{
    const size_t n = fread(buf, 1, cap, g_in);
    *got = (uint32_t)n;
    g_pos += n;
    if (n == 0) {
        g_ended = 1;
        return ferror(g_in) ? TDC_BOARD_ERR_IO : TDC_BOARD_END;
    }
    return TDC_BOARD_OK;
}

tdc_board_status_t tdc_board_panel_show(const uint8_t *fb, uint32_t stride, uint32_t width, uint32_t height,
                                        uint32_t frame_index)
{
    const uint64_t h = tdc_board_frame_checksum(fb, stride, width, height);
    printf("frame %u %016llx\n", (unsigned)frame_index, (unsigned long long)h);
    if (g_dump) {
        char path[4096];
        snprintf(path, sizeof path, "%s/shown-%u.ppm", g_dump, g_shown);
        FILE *f = fopen(path, "wb");
        int ok = f && fprintf(f, "P6\n%u %u\n255\n", (unsigned)width, (unsigned)height) > 0;
        for (uint32_t y = 0; ok && y < height; y++) {
            ok = fwrite(fb + (size_t)y * stride, 3, width, f) == width;
        }
        if (!f || fclose(f) != 0 || !ok) {
            perror(path);
            return TDC_BOARD_ERR_IO;
        }
        if (g_ended) {
            fprintf(g_offsets, "%u end\n", g_shown);
        } else {
            fprintf(g_offsets, "%u %llu\n", g_shown, g_pos);
        }
        g_shown++;
    }
    return TDC_BOARD_OK;
}

void tdc_board_log(const char *msg)
{
    fprintf(stderr, "[host] %s\n", msg);
}

int main(int argc, char **argv)
{
    if (argc != 2 && argc != 3) {
        fprintf(stderr, "usage: %s STREAM.tdcs [DUMP_DIR]\n", argv[0]);
        return 2;
    }
    if (argc == 3) {
        char path[4096];
        g_dump = argv[2];
        snprintf(path, sizeof path, "%s/offsets", g_dump);
        if (!(g_offsets = fopen(path, "w"))) {
            perror(path);
            return 2;
        }
    }
    g_in = fopen(argv[1], "rb");
    if (!g_in) {
        perror(argv[1]);
        return 2;
    }
    const int rc = tdc_fw_run();
    fclose(g_in);
    if (g_offsets && fclose(g_offsets) != 0) {
        perror("offsets");
        return 2;
    }
    return rc;
}
