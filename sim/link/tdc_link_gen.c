/* tdc_link_gen.c - deterministic synthetic link streams (see tdc_link_gen.h). */
#include "tdc_link_gen.h"

#include "tdc_math.h"

void tdc_link_gen_opts_plain(tdc_link_gen_opts_t *o, uint16_t stream_id, uint16_t w, uint16_t h, uint8_t eyes,
                             uint16_t refresh_hz, tdc_pixfmt_t fmt, uint32_t frames, uint32_t seed)
{
    /* field by field, no memset: this file also builds freestanding */
    const tdc_link_gen_opts_t zero = {0};
    *o = zero;
    o->stream_id = stream_id;
    o->info.r_num = 1;
    o->info.r_den = 1;
    o->info.width = w;
    o->info.height = h;
    o->info.eyes = eyes;
    o->info.refresh_hz = refresh_hz;
    o->fmt = fmt;
    o->frames = frames;
    o->seed = seed;
    o->with_stream_header = 1;
}

void tdc_link_gen_rgb(uint8_t *rgb, uint32_t w, uint32_t h, uint32_t frame, uint32_t eye, uint32_t seed)
{
    /* Smooth ramps (chroma-friendly), a moving hard edge and some noise, so
     * every conversion path and clamp is exercised. */
    for (uint32_t y = 0; y < h; y++) {
        for (uint32_t x = 0; x < w; x++) {
            uint8_t *p = rgb + ((size_t)w * y + x) * 3u;
            const uint32_t n = tdc_mix32(seed ^ (x * 0x9E3779B1u) ^ (y * 0x85EBCA77u) ^ (frame * 0xC2B2AE3Du) ^ eye);
            const int edge = ((x + 3u * frame) % 16u) < 8u;
            p[0] = (uint8_t)(x * 255u / (w > 1 ? w - 1u : 1u));
            p[1] = (uint8_t)(edge ? 230u + (n & 15u) : 20u + (n & 15u));
            p[2] = (uint8_t)((y * 255u / (h > 1 ? h - 1u : 1u)) ^ ((n >> 8) & 31u) ^ (eye * 64u));
        }
    }
}

void tdc_link_gen_mv(int16_t *mv, size_t count, uint32_t frame, uint32_t eye, uint32_t seed)
{
    for (size_t i = 0; i < count; i++) {
        const uint32_t n = tdc_mix32(seed ^ (uint32_t)i ^ (frame << 20) ^ (eye << 30));
        /* Full int16 range now and then, small vectors mostly. */
        const int32_t v = (n & 0x100u) ? (int32_t)(n >> 16) - 32768 : (int32_t)(n & 0xFFu) - 128;
        mv[i] = (int16_t)v;
    }
}

void tdc_link_gen_pattern(uint8_t *bits, size_t nbytes, uint32_t tiles, uint32_t frame, uint32_t eye, uint32_t seed)
{
    for (size_t i = 0; i < nbytes; i++) {
        bits[i] = (uint8_t)tdc_mix32(seed ^ (uint32_t)i ^ (frame * 977u) ^ (eye << 28));
    }
    if (tiles % 8u && nbytes) {
        bits[nbytes - 1u] &= (uint8_t)((1u << (tiles % 8u)) - 1u);
    }
}

static int add(uint8_t *out, size_t cap, size_t *pos, size_t n, tdc_link_gen_packet_t *pk, uint32_t pk_cap,
               uint32_t *count, uint32_t kind, uint32_t eye, uint32_t flags, uint32_t frame)
{
    (void)out;
    (void)cap;
    if (n == 0) {
        return 0;
    }
    if (pk && *count < pk_cap) {
        pk[*count].offset = (uint32_t)*pos;
        pk[*count].size = (uint32_t)n;
        pk[*count].kind = (uint8_t)kind;
        pk[*count].eye = (uint8_t)eye;
        pk[*count].flags = (uint16_t)flags;
        pk[*count].frame = frame;
    }
    (*count)++;
    *pos += n;
    return 1;
}

size_t tdc_link_gen_stream(uint8_t *out, size_t cap, const tdc_link_gen_opts_t *o, uint8_t *scratch,
                           size_t scratch_bytes, tdc_link_gen_packet_t *pk, uint32_t pk_cap, uint32_t *pk_count)
{
    const tdc_link_stream_info_t *in = &o->info;
    const uint32_t w = in->width, h = in->height, tx = TDC_TILES(w), ty = TDC_TILES(h);
    const uint32_t fl = in->flags;
    uint32_t count = 0;
    size_t pos = 0;
    if (scratch_bytes < TDC_LINK_GEN_SCRATCH_BYTES(w, h)) {
        return 0;
    }
    tdc_link_encoder_t enc;
    tdc_link_encoder_init(&enc, o->stream_id, in);
    if (o->with_stream_header && !add(out, cap, &pos, tdc_link_encode_stream(&enc, out + pos, cap - pos), pk, pk_cap,
                                      &count, TDC_LINK_KIND_STREAM, 0, 0, 0)) {
        return 0;
    }
    int16_t *mv = (int16_t *)(void *)scratch; /* scratch is used for one thing at a time */
    for (uint32_t f = o->first_frame; f < o->first_frame + o->frames; f++) {
        for (uint32_t e = 0; e < in->eyes; e++) {
            if (fl & TDC_LINK_STREAM_SUBFRAMES) {
                if ((f & 3u) == 0) {
                    const size_t nb = TDC_PATTERN_BYTES(w, h);
                    tdc_link_gen_pattern(scratch, nb, tx * ty, f, e, o->seed);
                    if (!add(out, cap, &pos, tdc_link_encode_pattern(&enc, out + pos, cap - pos, e, f, scratch, w, h),
                             pk, pk_cap, &count, TDC_LINK_KIND_PATTERN, e, 0, f)) {
                        return 0;
                    }
                }
                tdc_link_gen_rgb(scratch, tx, ty, f, e, o->seed);
                if (!add(out, cap, &pos,
                         tdc_link_encode_subframe(&enc, out + pos, cap - pos, e, f, o->fmt, scratch, w, h), pk, pk_cap,
                         &count, TDC_LINK_KIND_SUBFRAME, e, 0, f)) {
                    return 0;
                }
                if (fl & TDC_LINK_STREAM_SAMPLE_MV) {
                    tdc_link_gen_mv(mv, (size_t)tx * ty * 2u, f, e, o->seed ^ 0x5A5Au);
                    if (!add(out, cap, &pos, tdc_link_encode_motion(&enc, out + pos, cap - pos, e, f, mv, w, h, 1), pk,
                             pk_cap, &count, TDC_LINK_KIND_MOTION, e, TDC_LINK_PKT_MV_PER_SAMPLE, f)) {
                        return 0;
                    }
                }
            } else {
                const tdc_link_kind_t k = (fl & TDC_LINK_STREAM_REDUCED) ? tdc_link_trm_kind(f, e) : TDC_LINK_KIND_FULL;
                const uint32_t fw = k == TDC_LINK_KIND_REDUCED ? TDC_REDUCED_DIM(w, in->r_num, in->r_den) : w;
                const uint32_t fh = k == TDC_LINK_KIND_REDUCED ? TDC_REDUCED_DIM(h, in->r_num, in->r_den) : h;
                tdc_link_gen_rgb(scratch, fw, fh, f, e, o->seed);
                if (!add(out, cap, &pos,
                         tdc_link_encode_frame(&enc, out + pos, cap - pos, k, e, f, o->fmt, scratch, fw, fh, fw * 3u),
                         pk, pk_cap, &count, k, e, 0, f)) {
                    return 0;
                }
            }
            if (fl & TDC_LINK_STREAM_MOTION) {
                tdc_link_gen_mv(mv, (size_t)w * h * 2u, f, e, o->seed);
                if (!add(out, cap, &pos, tdc_link_encode_motion(&enc, out + pos, cap - pos, e, f, mv, w, h, 0), pk,
                         pk_cap, &count, TDC_LINK_KIND_MOTION, e, 0, f)) {
                    return 0;
                }
            }
        }
    }
    if (pk_count) {
        *pk_count = count;
    }
    return pos;
}
