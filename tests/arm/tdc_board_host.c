/*
 * tdc_board_host.c - host test double of the board interface: runs the
 * firmware frame loop (firmware/board/tdc_main.c, built for the same panel
 * and stages as a board image) on the host, so its panel checksums are the
 * reference the emulated boards must reproduce bit for bit.
 *   transport: the .tdcs file argv[1], read in 16 KiB chunks
 *   panel:     "frame N fnv1a64" lines on stdout (same format as
 *              firmware/board/tdc_board_emulated.c)
 *   the rest:  tdc_board_stub.c (no vsync, timer at 0, power-on reset)
 * Usage: tdc_fw_host STREAM.tdcs
 */
#include <stdio.h>

#include "tdc_board.h"

static FILE *g_in;

tdc_board_status_t tdc_board_init(void)
{
    return g_in ? TDC_BOARD_OK : TDC_BOARD_ERR_IO;
}

tdc_board_status_t tdc_board_transport_read(uint8_t *buf, uint32_t cap, uint32_t *got)
{
    const size_t n = fread(buf, 1, cap, g_in);
    *got = (uint32_t)n;
    if (n == 0) {
        return ferror(g_in) ? TDC_BOARD_ERR_IO : TDC_BOARD_END;
    }
    return TDC_BOARD_OK;
}

tdc_board_status_t tdc_board_panel_show(const uint8_t *fb, uint32_t stride, uint32_t width, uint32_t height,
                                        uint32_t frame_index)
{
    const uint64_t h = tdc_board_frame_checksum(fb, stride, width, height);
    printf("frame %u %016llx\n", (unsigned)frame_index, (unsigned long long)h);
    return TDC_BOARD_OK;
}

void tdc_board_log(const char *msg)
{
    fprintf(stderr, "[host] %s\n", msg);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s STREAM.tdcs\n", argv[0]);
        return 2;
    }
    g_in = fopen(argv[1], "rb");
    if (!g_in) {
        perror(argv[1]);
        return 2;
    }
    const int rc = tdc_fw_run();
    fclose(g_in);
    return rc;
}
