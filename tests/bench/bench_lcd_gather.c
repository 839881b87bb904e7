/*
 * bench_lcd_gather.c - the floor of a per-sub-pixel table lookup on this
 * host (docs/lcd.md §8, the 2x-memcpy goal of the stateful LCD path): 16-bit
 * loads at random indices from a table of 8 KiB, 128 KiB and 384 KiB (the
 * stateful lookup's size), as 8-lane AVX2 gathers, 16-lane AVX-512 gathers
 * (when the CPU has them) and scalar loads, thread CPU time per element,
 * best of 5, beside memcpy of 4 MiB per byte in the same run.  Not in make
 * bench (x86-64 only; make build/gcc-O2/tests/bench/bench_lcd_gather).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

#define NIDX (1u << 22)

static uint32_t scalar_sum(const uint16_t *lut, const uint32_t *idx)
{
    uint32_t s = 0;
    for (uint32_t i = 0; i < NIDX; i++) {
        s += lut[idx[i]];
    }
    return s;
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>

__attribute__((target("avx2"))) static uint32_t gather8_sum(const uint16_t *lut, const uint32_t *idx)
{
    __m256i acc = _mm256_setzero_si256();
    for (uint32_t i = 0; i < NIDX; i += 8u) {
        const __m256i ix = _mm256_loadu_si256((const __m256i *)(const void *)(idx + i));
        acc = _mm256_add_epi32(acc, _mm256_i32gather_epi32((const int *)(const void *)lut, ix, 2));
    }
    return (uint32_t)_mm256_extract_epi32(acc, 0);
}

__attribute__((target("avx512f"))) static uint32_t gather16_sum(const uint16_t *lut, const uint32_t *idx)
{
    __m512i acc = _mm512_setzero_si512();
    for (uint32_t i = 0; i < NIDX; i += 16u) {
        const __m512i ix = _mm512_loadu_si512((const void *)(idx + i));
        acc = _mm512_add_epi32(acc, _mm512_i32gather_epi32(ix, (const void *)lut, 2));
    }
    return (uint32_t)_mm512_reduce_add_epi32(acc);
}
#define HAVE_GATHERS 1
#endif

int main(void)
{
    static const uint32_t sizes[] = {4096u, 65536u, 196608u}; /* entries: 8, 128, 384 KiB */
    uint16_t *lut = malloc(196608u * 2u + 64u);
    uint32_t *idx = malloc(NIDX * sizeof *idx);
    uint8_t *a = malloc(1u << 22), *b = malloc(1u << 22);
    if (!lut || !idx || !a || !b) {
        fprintf(stderr, "bench_lcd_gather: out of memory\n");
        return 1;
    }
    memset(lut, 0x5a, 196608u * 2u + 64u);
    memset(a, 1, 1u << 22);
    double t_copy = 1e9;
    for (int r = 0; r < 5; r++) {
        const double t0 = now_s();
        memcpy(b, a, 1u << 22);
        const double t = now_s() - t0;
        t_copy = t < t_copy ? t : t_copy;
    }
    printf("memcpy %.4f ns per byte\n", t_copy / (1u << 22) * 1e9);
    volatile uint32_t sink = b[7];
    for (unsigned k = 0; k < 3u; k++) {
        uint32_t r = 1u;
        for (uint32_t i = 0; i < NIDX; i++) {
            r = r * 1664525u + 1013904223u;
            idx[i] = (r >> 8) % sizes[k];
        }
        double best[3] = {1e9, 1e9, 1e9};
        for (int rep = 0; rep < 5; rep++) {
            double t0 = now_s();
            sink += scalar_sum(lut, idx);
            double t = now_s() - t0;
            best[0] = t < best[0] ? t : best[0];
#ifdef HAVE_GATHERS
            if (__builtin_cpu_supports("avx2")) {
                t0 = now_s();
                sink += gather8_sum(lut, idx);
                t = now_s() - t0;
                best[1] = t < best[1] ? t : best[1];
            }
            if (__builtin_cpu_supports("avx512f")) {
                t0 = now_s();
                sink += gather16_sum(lut, idx);
                t = now_s() - t0;
                best[2] = t < best[2] ? t : best[2];
            }
#endif
        }
        printf("table %3u KiB, random 16-bit lookups: scalar %.3f ns, 8-lane gather %.3f ns, 16-lane gather %.3f ns "
               "per element (1e9 = not available)\n",
               sizes[k] * 2u / 1024u, best[0] / NIDX * 1e9, best[1] < 1e8 ? best[1] / NIDX * 1e9 : 1e9,
               best[2] < 1e8 ? best[2] / NIDX * 1e9 : 1e9);
    }
    (void)sink;
    return 0;
}
