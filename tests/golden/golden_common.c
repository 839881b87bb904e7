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

static char *put_str(char *o, const char *end, const char *s)
{
    while (*s && o < end) {
        *o++ = *s++;
    }
    return o;
}

void tdc_golden_emit(tdc_golden_ctx_t *ctx, const char *stage, const char *vector, uint32_t frame,
                     uint64_t checksum)
{
    char line[160];
    char *o = line;
    const char *end = line + sizeof line - 20; /* room for frame + hex + newline */
    o = put_str(o, end, stage);
    o = put_str(o, end, "/");
    o = put_str(o, end, vector);
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
