/* golden_common.c - checksum and line formatting shared by all golden stages
 * (freestanding: no stdio, so the ARM runner uses it unchanged). */
#include "golden.h"

uint64_t tdc_fnv1a64(uint64_t h, const void *data, size_t n)
{
    const uint8_t *p = (const uint8_t *)data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 0x100000001b3ULL;
    }
    return h;
}

/* Appends s to line[*n], leaving room for the frame number and checksum. */
static void put_str(char *line, size_t *n, size_t cap, const char *s)
{
    while (*s && *n < cap) {
        line[(*n)++] = *s++;
    }
}

void tdc_golden_emit(tdc_golden_ctx_t *ctx, const char *stage, const char *vector, uint32_t frame,
                     uint64_t checksum)
{
    char line[160];
    size_t len = 0;
    const size_t cap = sizeof line - 32; /* room for frame + hex + newline */
    put_str(line, &len, cap, stage);
    put_str(line, &len, cap, "/");
    put_str(line, &len, cap, vector);
    char *o = line + len;
    *o++ = ' ';
    char dec[12];
    int n = 0;
    do {
        dec[n++] = (char)('0' + frame % 10u);
        frame /= 10u;
    } while (frame && n < 11);
    while (n) {
        *o++ = dec[--n];
    }
    *o++ = ' ';
    for (int i = 15; i >= 0; i--) {
        *o++ = "0123456789abcdef"[(checksum >> (4 * i)) & 15u];
    }
    *o++ = '\n';
    *o = 0;
    ctx->lines++;
    ctx->write_line(ctx, line);
}

char *tdc_golden_put_str(char *o, const char *s)
{
    while (*s) {
        *o++ = *s++;
    }
    return o;
}

char *tdc_golden_put_u32(char *o, uint32_t v)
{
    char d[12];
    int n = 0;
    do {
        d[n++] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v);
    while (n) {
        *o++ = d[--n];
    }
    return o;
}
