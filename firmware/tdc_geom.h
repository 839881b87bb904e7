/*
 * tdc_geom.h - frame geometry shared by every stage, the link and the host:
 * the reduced size of TRM, the 2x2 tile grid of tile-ordered assembly and
 * its pattern bitmap.  One definition each; stage headers, the wire format
 * (tdc_wire.h), the renderer and the double references use these.
 *
 * Macros (constant expressions, for static buffers and compile-time
 * bounds) in unsigned arithmetic; inline functions of the same rules for
 * run-time code.
 */
#ifndef TDC_GEOM_H
#define TDC_GEOM_H

#include <stddef.h>
#include <stdint.h>

/* Reduced size for the TRM ratio r = num/den: round(n * num / den), at
 * least 1 (docs/design.md §4.1).  n * num < 2^32 for n <= 65535 and num <= 65535. */
#define TDC_REDUCED_DIM(n, num, den)                                                   \
    ((((uint32_t)(n) * (uint32_t)(num)) + (uint32_t)(den) / 2u) / (uint32_t)(den) < 1u \
         ? 1u                                                                          \
         : (((uint32_t)(n) * (uint32_t)(num)) + (uint32_t)(den) / 2u) / (uint32_t)(den))

static inline uint32_t tdc_reduced_dim(uint32_t n, uint32_t num, uint32_t den)
{
    return TDC_REDUCED_DIM(n, num, den);
}

/* 2x2 tiles along a side of n pixels (partial tiles at odd sizes count). */
#define TDC_TILES(n) (((uint32_t)(n) + 1u) / 2u)
/* Tiles of a w x h frame. */
#define TDC_TILE_COUNT(w, h) ((size_t)TDC_TILES(w) * TDC_TILES(h))
/* Bytes of a tile-pattern bitmap (1 bit per tile, row-major, LSB first). */
#define TDC_PATTERN_BYTES(w, h) ((TDC_TILE_COUNT(w, h) + 7u) / 8u)

#endif /* TDC_GEOM_H */
