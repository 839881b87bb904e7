/*
 * golden.h - bit-exact golden vectors.  Each stage has
 * tests/golden/golden_<stage>.c defining
 *     void tdc_golden_<stage>(tdc_golden_ctx_t *ctx);
 * which generates deterministic inputs, runs the firmware stage and reports
 * one checksum per output frame through tdc_golden_emit().  The same code
 * runs on the host (gcc/clang, -O0/-O2, sanitizers) and on the ARM boards
 * under QEMU, so it is freestanding: no malloc, no stdio, static buffers.
 * Expected values live in tests/golden/STAGE.expected.
 */
#ifndef TDC_GOLDEN_H
#define TDC_GOLDEN_H

#include <stddef.h>
#include <stdint.h>

typedef struct tdc_golden_ctx {
    /* Called with one finished line "stage/vector frame checksum\n". */
    void (*write_line)(struct tdc_golden_ctx *ctx, const char *line);
    void *user;
    uint32_t lines;
} tdc_golden_ctx_t;

/* 64-bit FNV-1a, continued from h (start with TDC_FNV64_INIT). */
#define TDC_FNV64_INIT 0xcbf29ce484222325ULL
uint64_t tdc_fnv1a64(uint64_t h, const void *data, size_t n);

/* Checksum emitted for a frame whose stage call failed: shows as a mismatch
 * against the expected file (FNV-1a of real outputs is never asked to be 0). */
#define TDC_GOLDEN_FAILED 0u

/* Formats and writes "stage/vector frame %016x\n". */
void tdc_golden_emit(tdc_golden_ctx_t *ctx, const char *stage, const char *vector, uint32_t frame, uint64_t checksum);

/* Vector-name builders (no stdio): append s / decimal v at o, return the
 * new end.  The caller's buffer must hold the whole name. */
char *tdc_golden_put_str(char *o, const char *s);
char *tdc_golden_put_u32(char *o, uint32_t v);
/* The head the TRM-family vector names share: "<content>-<w>x<h>-r<rn>_<rd>". */
char *tdc_golden_put_head(char *o, const char *content, uint32_t w, uint32_t h, uint32_t rn, uint32_t rd);
/* ... and their end: "-<panel>" and the terminating NUL. */
void tdc_golden_put_panel(char *o, const char *panel);

/* Deterministic PRNG (xorshift32): same sequence on every CPU. */
static inline uint32_t tdc_golden_rand(uint32_t *state)
{
    uint32_t x = *state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *state = x;
    return x;
}

#endif
