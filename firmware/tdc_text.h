/*
 * tdc_text.h - numbers to text without printf, for the boards' logs, the
 * emulated panel's frame lines and the golden/bench runners (no stdio on a
 * board, and the same bytes on every target).
 *
 * Each function appends at o and returns the new end; it writes nothing at
 * or past `end` (one past the last writable char), or, with end == NULL,
 * trusts the caller's buffer to hold everything.  No terminating NUL is
 * written: the caller adds one where it needs a C string.  (`end` is a
 * plain char *: as a const pointer into a buffer not yet written, gcc -O0
 * takes it for a read of uninitialised bytes, -Wmaybe-uninitialized.)
 */
#ifndef TDC_TEXT_H
#define TDC_TEXT_H

#include <stddef.h>
#include <stdint.h>

static inline char *tdc_text_str(char *o, char *end, const char *s)
{
    while (*s && (!end || o < end)) {
        *o++ = *s++;
    }
    return o;
}

/* Decimal, no leading zeros ("0" for 0); at most 10 digits. */
static inline char *tdc_text_u32(char *o, char *end, uint32_t v)
{
    char d[10];
    unsigned n = 0;
    do {
        d[n++] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v);
    while (n && (!end || o < end)) {
        *o++ = d[--n];
    }
    return o;
}

/* Lower-case hexadecimal of the low `digits` nibbles of v (1..16), with
 * leading zeros: tdc_text_hex(o, end, h, 16) is a 64-bit checksum. */
static inline char *tdc_text_hex(char *o, char *end, uint64_t v, unsigned digits)
{
    for (unsigned i = digits; i-- > 0u && (!end || o < end);) {
        *o++ = "0123456789abcdef"[(v >> (4u * i)) & 15u];
    }
    return o;
}

#endif /* TDC_TEXT_H */
