/* golden_common.c - checksum and line formatting shared by all golden stages
 * (freestanding: no stdio, so the ARM runner uses it unchanged). */
#include "golden.h"

#include "tdc_text.h"

uint64_t tdc_fnv1a64(uint64_t h, const void *data, size_t n)
{
    const uint8_t *p = (const uint8_t *)data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 0x100000001b3ULL;
    }
    return h;
}

void tdc_golden_emit(tdc_golden_ctx_t *ctx, const char *stage, const char *vector, uint32_t frame, uint64_t checksum)
{
    char line[160];
    char *name_end = line + sizeof line - 32; /* room for frame + hex + newline */
    char *o = tdc_text_str(line, name_end, stage);
    o = tdc_text_str(o, name_end, "/");
    o = tdc_text_str(o, name_end, vector);
    *o++ = ' ';
    o = tdc_text_u32(o, NULL, frame);
    *o++ = ' ';
    o = tdc_text_hex(o, NULL, checksum, 16u);
    *o++ = '\n';
    *o = 0;
    ctx->lines++;
    ctx->write_line(ctx, line);
}

char *tdc_golden_put_str(char *o, const char *s)
{
    return tdc_text_str(o, NULL, s);
}

char *tdc_golden_put_u32(char *o, uint32_t v)
{
    return tdc_text_u32(o, NULL, v);
}

char *tdc_golden_put_head(char *o, const char *content, uint32_t w, uint32_t h, uint32_t rn, uint32_t rd)
{
    o = tdc_golden_put_str(o, content);
    *o++ = '-';
    o = tdc_golden_put_u32(o, w);
    *o++ = 'x';
    o = tdc_golden_put_u32(o, h);
    o = tdc_golden_put_str(o, "-r");
    o = tdc_golden_put_u32(o, rn);
    *o++ = '_';
    return tdc_golden_put_u32(o, rd);
}

void tdc_golden_put_panel(char *o, const char *panel)
{
    *o++ = '-';
    *tdc_golden_put_str(o, panel) = 0;
}
