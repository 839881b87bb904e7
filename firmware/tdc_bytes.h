/*
 * tdc_bytes.h - little-endian load/store of 16/32-bit fields, the lowest
 * layer of every byte format (link packets, tdc_wire.h; pixel, band,
 * layer and foveation payloads; USB protocol; CRC32 words): no struct
 * punning, no alignment or host byte-order assumption (compilers merge the
 * byte accesses into one load on little-endian CPUs).  Depends on nothing
 * of the project.
 */
#ifndef TDC_BYTES_H
#define TDC_BYTES_H

#include <stdint.h>

static inline uint16_t tdc_get_le16(const uint8_t *p)
{
    return (uint16_t)((uint32_t)p[0] | ((uint32_t)p[1] << 8));
}
static inline uint32_t tdc_get_le32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}
static inline void tdc_put_le16(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)((v >> 8) & 0xFFu);
}
static inline void tdc_put_le32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)((v >> 8) & 0xFFu);
    p[2] = (uint8_t)((v >> 16) & 0xFFu);
    p[3] = (uint8_t)(v >> 24);
}
/* int16 as two's complement bits, without implementation-defined
 * conversions: values >= 2^15 read as v - 2^16, negatives written as v + 2^16. */
static inline int16_t tdc_get_le16s(const uint8_t *p)
{
    const int32_t v = (int32_t)tdc_get_le16(p);
    return (int16_t)(v >= 32768 ? v - 65536 : v);
}
static inline void tdc_put_le16s(uint8_t *p, int16_t v)
{
    tdc_put_le16(p, (uint32_t)(v < 0 ? (int32_t)v + 65536 : (int32_t)v));
}
/* int32 likewise (writing needs no helper: (uint32_t)v is defined). */
static inline int32_t tdc_get_le32s(const uint8_t *p)
{
    const uint32_t v = tdc_get_le32(p);
    return v <= 0x7FFFFFFFu ? (int32_t)v : -(int32_t)(~v) - 1;
}

#endif
