/*
 * tdc_crc32.h - CRC-32 (IEEE 802.3 / zlib / PNG: reflected polynomial
 * 0xEDB88320, initial value 0xFFFFFFFF, final XOR 0xFFFFFFFF) for the link
 * protocol.  Check value: crc32("123456789") = 0xCBF43926.
 *
 * The lookup tables (slice-by-8, 8 x 256 uint32) are not typed by hand: they
 * are written at build time into build/gen/tdc_crc32_tables.h by
 * sim/link/tdc_crc32_gen.c from the bitwise definition, and
 * tests/unit/test_link_crc32.c checks them against that definition again.
 *
 * One implementation for the whole firmware: the link decoder, the USB
 * protocol (received-bytes CRC, DFU image checks) and every host tool.  The
 * tables are const (flash); the 8 KiB are in every board image anyway for
 * the link decoder, so the USB side reusing them costs no memory.
 *
 * Incremental use (any chunking gives the same value):
 *     uint32_t c = TDC_CRC32_INIT;
 *     c = tdc_crc32_update(c, a, na);
 *     c = tdc_crc32_update(c, b, nb);
 *     uint32_t crc = tdc_crc32_final(c);
 * or tdc_crc32(data, n) for one buffer.
 */
#ifndef TDC_CRC32_H
#define TDC_CRC32_H

#include <stddef.h>
#include <stdint.h>

#define TDC_CRC32_POLY_REFLECTED 0xEDB88320u
#define TDC_CRC32_INIT 0xFFFFFFFFu

/* Continue a running (non-finalised) CRC state over n bytes. */
uint32_t tdc_crc32_update(uint32_t state, const uint8_t *data, size_t n);

/* Finalise a running state into the CRC value. */
static inline uint32_t tdc_crc32_final(uint32_t state)
{
    return state ^ 0xFFFFFFFFu;
}

/* CRC-32 of one buffer. */
uint32_t tdc_crc32(const uint8_t *data, size_t n);

/* The definition, one byte of register shift: eight bit steps of the
 * reflected polynomial.  The only CRC-32 bit loop: the table generator
 * (sim/link/tdc_crc32_gen.c) and tdc_crc32_bitwise() both use it. */
static inline uint32_t tdc_crc32_shift8(uint32_t c)
{
    for (int b = 0; b < 8; b++) {
        c = (c >> 1) ^ (TDC_CRC32_POLY_REFLECTED & (0u - (c & 1u)));
    }
    return c;
}

/* Bit-at-a-time reference (no table): slow, used by tests. */
uint32_t tdc_crc32_bitwise(const uint8_t *data, size_t n);

/* Entry k of table `table` (0..7; table 0: CRC register after byte k from a
 * zero state; table j: byte k followed by j zero bytes), for tests. */
uint32_t tdc_crc32_table_entry(unsigned table, unsigned k);

#endif /* TDC_CRC32_H */
