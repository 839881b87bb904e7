/*
 * make_seeds.c - writes the libFuzzer seed corpus for fuzz_link.c
 * (tests/fuzz/corpus/): valid streams for the harness's 19 x 13 stereo
 * panel in every pixel format and stream mode (and the mono variants for
 * the harness's mono build), plus damaged variants; foveated streams
 * (stereo with motion vectors, mono without) with damaged variants, and
 * foveated TRM streams (FOVEATED packets in both slots).
 * Byte 0 of each file is the harness's mode byte (chunking, CRC repair).
 * Usage: make_seeds OUTDIR      (mk/link.mk: make fuzz-seeds)
 */
#include <stdio.h>
#include <string.h>

#include "link/tdc_link_gen.h"
#include "tdc_link_encode.h"

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

/* Foveated streams for the 19 x 13 panel: 4 frames, the gaze moving, alpha
 * and the disk changing; stereo with vectors, mono without (the harness's
 * mono build has no vector buffer); damaged: a flipped foveation-header
 * byte with the CRCs repaired by the harness (mode bit 7), a cut packet. */
static int foveated_seeds(const char *dir)
{
    static uint8_t samples[19 * 13 * 6];
    static int16_t mv[19 * 13 * 2];
    for (size_t i = 0; i < sizeof samples; i++) {
        samples[i] = (uint8_t)(i * 37u + 11u);
    }
    for (size_t i = 0; i < sizeof mv / sizeof mv[0]; i++) {
        mv[i] = (int16_t)((int)(i * 13u % 97u) - 48);
    }
    int bad = 0;
    for (int eyes = 1; eyes <= 2; eyes++) {
        tdc_link_stream_info_t in;
        memset(&in, 0, sizeof in);
        in.flags = TDC_LINK_STREAM_FOVEATED;
        in.r_num = in.r_den = 1;
        in.width = 19;
        in.height = 13;
        in.eyes = (uint8_t)eyes;
        in.refresh_hz = 90;
        tdc_link_encoder_t enc;
        tdc_link_encoder_init(&enc, 21, &in);
        size_t n = tdc_link_encode_stream(&enc, stream, sizeof stream), second = 0;
        for (uint32_t f = 0; f < 4; f++) {
            for (uint32_t e = 0; e < (uint32_t)eyes; e++) {
                tdc_fov_params_t p;
                memset(&p, 0, sizeof p);
                p.gaze_x_q8 = (int32_t)(f * 1100u + e * 300u);
                p.gaze_y_q8 = 1600 + (int32_t)f * 400;
                p.alpha_q8 = (uint16_t)(256u + 512u * f);
                p.disk_q15 = (uint16_t)(f * 3000u);
                p.lp_w = tdc_fov_lp_size(18187, 19);
                p.lp_h = tdc_fov_lp_size(18187, 13);
                if (f == 1 && e == 0) {
                    second = n;
                }
                const size_t k = tdc_link_encode_foveated(&enc, stream + n, sizeof stream - n, e, f, &p, 18187,
                                                          samples, eyes == 2 ? mv : NULL, NULL);
                if (!k) {
                    fprintf(stderr, "make_seeds: foveated encoding failed\n");
                    return 1;
                }
                n += k;
            }
        }
        const uint8_t mono = eyes == 1 ? 0x20 : 0;
        char name[96];
        snprintf(name, sizeof name, "fov-%s-whole", eyes == 1 ? "mono" : "stereo");
        bad |= write_seed(dir, name, mono, stream, n);
        snprintf(name, sizeof name, "fov-%s-chunked", eyes == 1 ? "mono" : "stereo");
        bad |= write_seed(dir, name, (uint8_t)(mono | 0x07), stream, n);
        static uint8_t d[1 << 18];
        memcpy(d, stream, n);
        d[second + TDC_LINK_HEADER_BYTES + 8] ^= 0x08; /* alpha */
        snprintf(name, sizeof name, "fov-%s-alpha-repair", eyes == 1 ? "mono" : "stereo");
        bad |= write_seed(dir, name, (uint8_t)(mono | 0x80), d, n);
        memcpy(d, stream, second + 50);
        memcpy(d + second + 50, stream + second + 90, n - second - 90);
        snprintf(name, sizeof name, "fov-%s-cut", eyes == 1 ? "mono" : "stereo");
        bad |= write_seed(dir, name, (uint8_t)(mono | 0x03), d, n - 40);
    }
    return bad;
}

/* Foveated TRM streams (r = 3/4: the 10 x 7 reduced grid of r = 1/2 has a
 * log-polar buffer below the stage's minimum side): 6 frames, every slot
 * foveated (FOV_REDUCED on the reduced ones), no vectors (refused in TRM
 * streams); mono and stereo, and a stereo one with a reduced packet's
 * gaze byte flipped, CRCs repaired by the harness. */
static int foveated_trm_seeds(const char *dir)
{
    static uint8_t samples[19 * 13 * 6];
    for (size_t i = 0; i < sizeof samples; i++) {
        samples[i] = (uint8_t)(i * 53u + 7u);
    }
    int bad = 0;
    for (int eyes = 1; eyes <= 2; eyes++) {
        tdc_link_stream_info_t in;
        memset(&in, 0, sizeof in);
        in.flags = TDC_LINK_STREAM_FOVEATED | TDC_LINK_STREAM_REDUCED;
        in.r_num = 3;
        in.r_den = 4;
        in.width = 19;
        in.height = 13;
        in.eyes = (uint8_t)eyes;
        in.refresh_hz = 90;
        tdc_link_encoder_t enc;
        tdc_link_encoder_init(&enc, 23, &in);
        size_t n = tdc_link_encode_stream(&enc, stream, sizeof stream), reduced_at = 0;
        for (uint32_t f = 0; f < 6; f++) {
            for (uint32_t e = 0; e < (uint32_t)eyes; e++) {
                const int red = tdc_link_trm_kind(f, e) == TDC_LINK_KIND_REDUCED;
                const uint16_t gw = red ? (uint16_t)TDC_REDUCED_DIM(19, 3, 4) : 19;
                const uint16_t gh = red ? (uint16_t)TDC_REDUCED_DIM(13, 3, 4) : 13;
                tdc_fov_params_t p;
                memset(&p, 0, sizeof p);
                p.gaze_x_q8 = (int32_t)(f * 60u + e * 20u) * gw;
                p.gaze_y_q8 = (int32_t)(100u + f * 25u) * gh;
                p.alpha_q8 = (uint16_t)(256u + 384u * (f % 3u));
                p.disk_q15 = (uint16_t)(f * 2500u);
                p.lp_w = tdc_fov_lp_size(18187, gw);
                p.lp_h = tdc_fov_lp_size(18187, gh);
                if (red && !reduced_at) {
                    reduced_at = n;
                }
                const size_t k = tdc_link_encode_foveated_slot(&enc, stream + n, sizeof stream - n,
                                                               red ? TDC_LINK_KIND_REDUCED : TDC_LINK_KIND_FULL, e, f,
                                                               &p, 18187, samples, NULL, NULL);
                if (!k) {
                    fprintf(stderr, "make_seeds: foveated TRM encoding failed\n");
                    return 1;
                }
                n += k;
            }
        }
        const uint8_t mono = eyes == 1 ? 0x20 : 0;
        char name[96];
        snprintf(name, sizeof name, "fov-trm-%s-whole", eyes == 1 ? "mono" : "stereo");
        bad |= write_seed(dir, name, mono, stream, n);
        if (eyes == 2) {
            bad |= write_seed(dir, "fov-trm-stereo-chunked", 0x05, stream, n);
            static uint8_t d[1 << 18];
            memcpy(d, stream, n);
            d[reduced_at + TDC_LINK_HEADER_BYTES + 2] ^= 0x01; /* the reduced slot's gaze x */
            bad |= write_seed(dir, "fov-trm-stereo-gaze-repair", 0x80, d, n);
        }
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
    bad |= foveated_seeds(argv[1]);
    bad |= foveated_trm_seeds(argv[1]);
    return bad;
}
