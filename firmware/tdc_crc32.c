/*
 * tdc_crc32.c - CRC-32 for the link protocol, slice-by-8: eight bytes per
 * step through eight 1 KiB tables (8 KiB: put them in DTCM on a Cortex-M7).
 * The tables come from build/gen/tdc_crc32_tables.h, written by
 * sim/link/tdc_crc32_gen.c at build time.
 */
#include "tdc_crc32.h"

#include "tdc_crc32_tables.h"
#include "tdc_bytes.h"

uint32_t tdc_crc32_update(uint32_t state, const uint8_t *data, size_t n)
{
    uint32_t c = state;
    /* One base register per table.  Why: GCC otherwise keeps one base and
     * adds each table's offset to the index (eight extra adds per eight
     * bytes: 34 instructions per step on the Cortex-M7, 28 with the bases
     * in registers; link decode RGB888 16.7 -> see docs/boards.md).  The
     * empty asm only hides that the eight pointers are one symbol plus
     * constants; it emits no instruction. */
    const uint32_t *t0 = tdc_crc32_tab[0], *t1 = tdc_crc32_tab[1], *t2 = tdc_crc32_tab[2], *t3 = tdc_crc32_tab[3];
    const uint32_t *t4 = tdc_crc32_tab[4], *t5 = tdc_crc32_tab[5], *t6 = tdc_crc32_tab[6], *t7 = tdc_crc32_tab[7];
#if defined(__GNUC__)
    __asm__("" : "+r"(t0), "+r"(t1), "+r"(t2), "+r"(t3), "+r"(t4), "+r"(t5), "+r"(t6), "+r"(t7));
#endif
    /* Eight bytes at a time, read as two little-endian words byte by byte
     * (no alignment or endianness assumptions; compilers merge the loads). */
    while (n >= 8u) {
        const uint32_t lo = c ^ tdc_get_le32(data);
        const uint32_t hi = tdc_get_le32(data + 4);
        c = t7[lo & 0xFFu] ^ t6[(lo >> 8) & 0xFFu] ^ t5[(lo >> 16) & 0xFFu] ^ t4[lo >> 24] ^ t3[hi & 0xFFu] ^
            t2[(hi >> 8) & 0xFFu] ^ t1[(hi >> 16) & 0xFFu] ^ t0[hi >> 24];
        data += 8;
        n -= 8u;
    }
    while (n--) {
        c = (c >> 8) ^ t0[(c ^ *data++) & 0xFFu];
    }
    return c;
}

uint32_t tdc_crc32(const uint8_t *data, size_t n)
{
    return tdc_crc32_final(tdc_crc32_update(TDC_CRC32_INIT, data, n));
}

uint32_t tdc_crc32_bitwise(const uint8_t *data, size_t n)
{
    uint32_t c = TDC_CRC32_INIT;
    for (size_t i = 0; i < n; i++) {
        c = tdc_crc32_shift8(c ^ data[i]);
    }
    return tdc_crc32_final(c);
}

uint32_t tdc_crc32_table_entry(unsigned table, unsigned k)
{
    return tdc_crc32_tab[table & 7u][k & 0xFFu];
}
