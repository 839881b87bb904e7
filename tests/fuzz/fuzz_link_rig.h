/*
 * fuzz_link_rig.h - the decoder buffers the link fuzzers share: staging,
 * and a full and a reduced frame per eye (full rows of width * 3 bytes);
 * every other buffer NULL for the caller to add.
 */
#ifndef FUZZ_LINK_RIG_H
#define FUZZ_LINK_RIG_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "tdc_link.h"

static inline tdc_link_buffers_t fuzz_frame_buffers(uint8_t *staging, size_t staging_bytes, uint16_t width,
                                                    uint8_t *full[2], uint8_t *reduced[2], size_t reduced_bytes)
{
    tdc_link_buffers_t b;
    memset(&b, 0, sizeof b);
    b.staging = staging;
    b.staging_bytes = staging_bytes;
    b.full_stride = (uint32_t)width * 3u;
    b.reduced_bytes = reduced_bytes;
    for (int e = 0; e < 2; e++) {
        b.full[e] = full[e];
        b.reduced[e] = reduced[e];
    }
    return b;
}

#endif
