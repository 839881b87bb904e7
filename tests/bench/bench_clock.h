/*
 * bench_clock.h - the benchmarks' clock and memory-bandwidth yardstick:
 * CPU time of the calling thread (the machine is shared, wall time would
 * count other processes' turns) and the best of 5 memcpy runs of 64 MiB,
 * as bytes read + written per second; and the load average printed beside
 * them.
 */
#ifndef BENCH_CLOCK_H
#define BENCH_CLOCK_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static inline double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static inline double memcpy_bandwidth(void)
{
    const size_t n = 64u << 20;
    uint8_t *a = malloc(n), *b = malloc(n);
    if (!a || !b) {
        free(a);
        free(b);
        return 0;
    }
    memset(a, 1, n), memset(b, 2, n);
    double best = 1e30;
    for (int i = 0; i < 5; i++) {
        double t0 = now_s();
        memcpy(i & 1 ? a : b, i & 1 ? b : a, n);
        double t = now_s() - t0;
        if (t < best) best = t;
    }
    volatile uint8_t sink = a[n / 2] ^ b[n / 3];
    (void)sink;
    free(a), free(b);
    return 2.0 * (double)n / best; /* read + write */
}

/* The first line of /proc/loadavg into buf ("unknown" where it cannot be
 * read): printed beside CPU-time figures so a reader sees how busy the
 * shared machine was. */
static inline const char *bench_loadavg(char *buf, size_t cap)
{
    snprintf(buf, cap, "unknown");
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (!fgets(buf, (int)cap, f)) {
            snprintf(buf, cap, "unknown");
        }
        buf[strcspn(buf, "\n")] = 0;
        fclose(f);
    }
    return buf;
}

#endif
