/*
 * make_seeds.c - writes the libFuzzer seed corpus for fuzz_link.c
 * (tests/fuzz/corpus/): valid streams for the harness's 19 x 13 stereo
 * panel in every pixel format and stream mode (and the mono variants for
 * the harness's mono build), plus damaged variants.
 * Byte 0 of each file is the harness's mode byte (chunking, CRC repair).
 * Usage: make_seeds OUTDIR      (mk/link.mk: make fuzz-seeds)
 */
#include <stdio.h>
#include <string.h>

#include "link/tdc_link_gen.h"

static uint8_t stream[1 << 18];
static uint32_t scratch[19 * 13];
static uint8_t file[1 << 18];

static int write_seed(const char *dir, const char *name, uint8_t mode, const uint8_t *p, size_t n)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f) {
        perror(path);
        return 1;
    }
    file[0] = mode;
    memcpy(file + 1, p, n);
    int bad = fwrite(file, 1, n + 1, f) != n + 1;
    bad |= fclose(f) != 0;
    if (bad) {
        perror(path);
    }
    return bad;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
        return 2;
    }
    static const char *const fmt_names[] = {"none", "rgb888", "rgb565", "rgb30", "ycbcr420"};
    int bad = 0;
    for (int mode = 0; mode < 3; mode++) {
        for (int fmt = TDC_PIXFMT_RGB888; fmt < TDC_PIXFMT_COUNT; fmt++) {
            tdc_link_gen_opts_t o;
            memset(&o, 0, sizeof o);
            o.stream_id = (uint16_t)(7 + mode);
            o.fmt = (tdc_pixfmt_t)fmt;
            o.info.width = 19;
            o.info.height = 13;
            o.info.eyes = 2;
            o.info.refresh_hz = 120;
            o.frames = 3;
            o.seed = (uint32_t)(fmt * 31 + mode);
            o.with_stream_header = 1;
            if (mode == 0) { /* TRM stream with motion */
                o.info.flags = TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_MOTION;
                o.info.r_num = 1;
                o.info.r_den = 2;
            } else if (mode == 1) { /* tile-ordered subframes, per-sample MV */
                o.info.flags = TDC_LINK_STREAM_SUBFRAMES | TDC_LINK_STREAM_SAMPLE_MV | TDC_LINK_STREAM_MOTION |
                               TDC_LINK_STREAM_MIRRORS;
                o.info.r_num = o.info.r_den = 1;
                o.frames = 5;
            } else { /* plain full frames */
                o.info.r_num = o.info.r_den = 1;
            }
            uint32_t npk = 0;
            static tdc_link_gen_packet_t pk[64];
            const size_t n =
                tdc_link_gen_stream(stream, sizeof stream, &o, (uint8_t *)scratch, sizeof scratch, pk, 64, &npk);
            if (!n) {
                fprintf(stderr, "make_seeds: generation failed\n");
                return 1;
            }
            char name[96];
            if (mode != 1) {
                /* The same stream for a mono panel (harness mode bit 5). */
                tdc_link_gen_opts_t om = o;
                om.info.eyes = 1;
                static uint8_t mono[1 << 18];
                const size_t nm =
                    tdc_link_gen_stream(mono, sizeof mono, &om, (uint8_t *)scratch, sizeof scratch, NULL, 0, NULL);
                if (!nm) {
                    fprintf(stderr, "make_seeds: generation failed\n");
                    return 1;
                }
                snprintf(name, sizeof name, "m%d-%s-mono", mode, fmt_names[fmt]);
                bad |= write_seed(argv[1], name, 0xA3, mono, nm);
            }
            snprintf(name, sizeof name, "m%d-%s-whole", mode, fmt_names[fmt]);
            bad |= write_seed(argv[1], name, 0x00, stream, n);
            snprintf(name, sizeof name, "m%d-%s-chunked-repair", mode, fmt_names[fmt]);
            bad |= write_seed(argv[1], name, 0x85, stream, n);
            if (fmt == TDC_PIXFMT_RGB888 && npk > 3) {
                /* Damaged variants: garbage between packets, a flipped
                 * payload byte, a truncated packet, a dropped packet, a
                 * lost byte. */
                static uint8_t d[1 << 18];
                size_t m = 0;
                memcpy(d, stream, pk[1].offset);
                m = pk[1].offset;
                memcpy(d + m, "xxTDCxTDCLgarbage", 17);
                m += 17;
                memcpy(d + m, stream + pk[1].offset, n - pk[1].offset);
                m += n - pk[1].offset;
                snprintf(name, sizeof name, "m%d-garbage", mode);
                bad |= write_seed(argv[1], name, 0x03, d, m);
                memcpy(d, stream, n);
                d[pk[2].offset + 40] ^= 0x10;
                snprintf(name, sizeof name, "m%d-bitflip", mode);
                bad |= write_seed(argv[1], name, 0x11, d, n);
                memcpy(d, stream, pk[2].offset + 20);
                memcpy(d + pk[2].offset + 20, stream + pk[3].offset, n - pk[3].offset);
                snprintf(name, sizeof name, "m%d-truncated", mode);
                bad |= write_seed(argv[1], name, 0x01, d, pk[2].offset + 20 + n - pk[3].offset);
                memcpy(d, stream, pk[2].offset);
                memcpy(d + pk[2].offset, stream + pk[3].offset, n - pk[3].offset);
                snprintf(name, sizeof name, "m%d-dropped", mode);
                bad |= write_seed(argv[1], name, 0x80, d, pk[2].offset + n - pk[3].offset);
                /* One byte lost inside packet 2's payload: the next packet's
                 * magic ends up inside the payload that fails its CRC. */
                memcpy(d, stream, pk[2].offset + 45);
                memcpy(d + pk[2].offset + 45, stream + pk[2].offset + 46, n - pk[2].offset - 46);
                snprintf(name, sizeof name, "m%d-lostbyte", mode);
                bad |= write_seed(argv[1], name, 0x02, d, n - 1);
            }
        }
    }
    return bad;
}
