/*
 * checkasm.c - the checkasm core: registry walk, RNG, options, failure
 * reports, benchmark timing (interface and conventions in checkasm.h).
 */
#if defined(__unix__) || defined(__APPLE__)
#define _POSIX_C_SOURCE 200809L
#include <time.h>
#define CHECKASM_HAVE_TIMER 1
#define CHECKASM_HOST_STDIO 1
#else
#define CHECKASM_HAVE_TIMER 0
#define CHECKASM_HOST_STDIO 0
#endif

#include "checkasm.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the modules: one line per firmware stage with optimised kernels ---- */
extern const checkasm_module_t checkasm_trm;
extern const checkasm_module_t checkasm_lcd;
extern const checkasm_module_t checkasm_fov;

static const checkasm_module_t *const g_modules[] = {&checkasm_trm, &checkasm_lcd, &checkasm_fov};
#define NMODULES (sizeof g_modules / sizeof g_modules[0])

#define BENCH_CALLS 20u
#define BENCH_REPS 50u
#define DEFAULT_SEED 0x9e3779b97f4a7c15ull

static struct {
    uint64_t seed;
    uint64_t rng;
    uint32_t runs; /* 0: each family's default */
    const checkasm_kernel_t *cur;
    char cur_name[96];
    int cur_failed;
    unsigned failures;
    int quiet; /* the core's self-test: count failures, print nothing */
    long last_index;
    int marks; /* --marks: one call per side between checkasm_mark() calls */
} g = {DEFAULT_SEED, 1, 0, NULL, "", 0, 0, 0, -1, 0};

/* ---- output: one formatted line at a time through checkasm_write() ----
 * (formatted into a static buffer with vsnprintf, which newlib nano does
 * without the heap its stdio streams would need; the Cortex-M harness
 * provides checkasm_write() by semihosting, hosts write to stdout). */
#if CHECKASM_HOST_STDIO
void checkasm_write(const char *s, size_t n)
{
    fwrite(s, 1, n, stdout);
}
#endif

static void vout(const char *fmt, va_list ap)
{
    static char buf[1024];
    const int n = vsnprintf(buf, sizeof buf, fmt, ap);
    if (n > 0) {
        checkasm_write(buf, (size_t)n < sizeof buf ? (size_t)n : sizeof buf - 1u);
    }
}

static void out(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vout(fmt, ap);
    va_end(ap);
}

/* 64-bit numbers as text without printf's 64-bit conversions (newlib
 * nano has none): hex with base 16, decimal with base 10. */
static const char *u64_text(uint64_t v, unsigned base, char buf[24])
{
    char *p = buf + 23;
    *p = '\0';
    do {
        *--p = "0123456789abcdef"[v % base];
        v /= base;
    } while (v);
    return p;
}

/* ---- RNG ---- */

static uint64_t splitmix64(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/* Per pair: seed mixed with the pair's name (FNV-1a), never 0. */
static void rng_seed_for(const char *name)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (const char *p = name; *p; p++) {
        h = (h ^ (uint8_t)*p) * 0x100000001b3ull;
    }
    g.rng = splitmix64(g.seed ^ h) | 1u;
}

uint32_t checkasm_rand(void)
{
    g.rng ^= g.rng >> 12;
    g.rng ^= g.rng << 25;
    g.rng ^= g.rng >> 27;
    return (uint32_t)((g.rng * 0x2545f4914f6cdd1dull) >> 32);
}

uint32_t checkasm_rand_below(uint32_t n)
{
    return n ? (uint32_t)(((uint64_t)checkasm_rand() * n) >> 32) : 0u;
}

uint32_t checkasm_runs(uint32_t dflt)
{
    return g.runs ? g.runs : dflt;
}

int checkasm_mve_available(void)
{
#if defined(TDC_TRM_MVE)
    return 1;
#else
    return 0;
#endif
}

int checkasm_neon_available(void)
{
#if defined(__aarch64__) && defined(__ARM_NEON) && !defined(TDC_NO_SIMD)
    return 1;
#else
    return 0;
#endif
}

/* ---- mismatches ---- */

#define DIFF_BODY                          \
    for (size_t i = 0; i < n; i++) {       \
        if (a[i] != b[i]) {                \
            return g.last_index = (long)i; \
        }                                  \
    }                                      \
    return -1;

long checkasm_diff_u8(const uint8_t *a, const uint8_t *b, size_t n)
{
    DIFF_BODY
}
long checkasm_diff_u16(const uint16_t *a, const uint16_t *b, size_t n)
{
    DIFF_BODY
}
long checkasm_diff_i32(const int32_t *a, const int32_t *b, size_t n)
{
    DIFF_BODY
}

int checkasm_fail(const char *fmt, ...)
{
    if (!g.cur_failed) {
        g.cur_failed = 1;
        g.failures++;
        if (!g.quiet) {
            char hex[24];
            const char *seed = u64_text(g.seed, 16u, hex);
            out("checkasm: FAIL %s (replay: checkasm --seed 0x%s %s):\n  ", g.cur_name, seed, g.cur_name);
            va_list ap;
            va_start(ap, fmt);
            vout(fmt, ap);
            va_end(ap);
            out("\n");
        }
    }
    return 1;
}

int checkasm_failed(void)
{
    return g.cur_failed;
}

/* ---- benchmark timing ---- */

static int timer_ns(uint64_t *ns)
{
#if CHECKASM_HAVE_TIMER
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) {
        return 0;
    }
    *ns = (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
    return 1;
#else
    (void)ns;
    return 0;
#endif
}

checkasm_bench_t checkasm_bench_start(const checkasm_kernel_t *k, const char *label, uint64_t units)
{
    checkasm_bench_t b;
    memset(&b, 0, sizeof b);
    b.k = k;
    b.label = label;
    b.units = units ? units : 1u;
    b.best[0] = b.best[1] = UINT64_MAX;
    return b;
}

checkasm_fn_t checkasm_bench_fn(const checkasm_bench_t *b)
{
    return b->side ? b->k->opt : b->k->ref;
}

/* x / 100 as "int.frac" with two decimals. */
static void print_centi(uint64_t x)
{
    char dec[24];
    out("%8s.%02u", u64_text(x / 100u, 10u, dec), (unsigned)(x % 100u));
}

/* --marks: an instruction-counting emulator (QEMU with
 * tests/arm/tdc_insn_plugin.c, mark=<this function's address>) records its
 * count at every call; kept out of line and not merged away. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
void checkasm_mark(void)
{
#if defined(__GNUC__)
    __asm__ volatile("" ::: "memory");
#endif
}

/* --marks: mark, reference call, mark, mark, optimised call, mark; then one
 * line "mark NAME|LABEL|UNITS" (tests/checkasm/insn_count.sh reads both). */
static int marks_step(checkasm_bench_t *b)
{
    checkasm_mark();
    if (b->call++ == 0u) {
        return 1;
    }
    if (b->side++ == 0) {
        checkasm_mark();
        return 1;
    }
    char dec[24];
    out("mark %s|%s|%s\n", g.cur_name, b->label, u64_text(b->units, 10u, dec));
    return 0;
}

int checkasm_bench_step(checkasm_bench_t *b)
{
    uint64_t now;
    if (g.marks) {
        return marks_step(b);
    }
    if (!timer_ns(&now)) {
        out("  %-24s %-38s no timer on this target: not timed\n", g.cur_name, b->label);
        return 0;
    }
    if (b->call == BENCH_CALLS) {
        const uint64_t dt = now - b->t0;
        b->best[b->side] = dt < b->best[b->side] ? dt : b->best[b->side];
        b->call = 0;
        if (++b->rep == BENCH_REPS) {
            b->rep = 0;
            if (++b->side == 2) {
                /* ns per unit x 100, and the speed-up x 100 */
                const uint64_t per = (uint64_t)BENCH_CALLS * b->units;
                out("  %-24s %-38s", g.cur_name, b->label);
                print_centi(b->best[0] * 100u / per);
                print_centi(b->best[1] * 100u / per);
                print_centi(b->best[1] ? b->best[0] * 100u / b->best[1] : 0u);
                out("x\n");
                return 0;
            }
        }
        if (!timer_ns(&now)) {
            return 0;
        }
    }
    if (b->call == 0) {
        b->t0 = now;
    }
    b->call++;
    return 1;
}

/* ---- the core's self-test: a planted mismatch must be caught ---- */

#define SELFTEST_N 257u
typedef void selftest_fn(const uint8_t *in, uint8_t *out, size_t n);
static size_t g_plant;
static void selftest_ref(const uint8_t *in, uint8_t *out, size_t n)
{
    memcpy(out, in, n);
}
static void selftest_bad(const uint8_t *in, uint8_t *out, size_t n)
{
    memcpy(out, in, n);
    out[g_plant] ^= 1u;
}
static void selftest_check(const checkasm_kernel_t *k)
{
    uint8_t in[SELFTEST_N], a[SELFTEST_N], b[SELFTEST_N];
    for (size_t i = 0; i < SELFTEST_N; i++) {
        in[i] = (uint8_t)checkasm_rand();
    }
    g_plant = checkasm_rand_below(SELFTEST_N);
    CHECKASM_REF(selftest_fn, k)(in, a, SELFTEST_N);
    CHECKASM_OPT(selftest_fn, k)(in, b, SELFTEST_N);
    const long i = checkasm_diff_u8(a, b, SELFTEST_N);
    if (i >= 0) {
        checkasm_fail("index %ld: ref %u, opt %u", i, a[i], b[i]);
    }
}
static const checkasm_family_t selftest_family = {"checkasm_selftest", selftest_check, NULL};

static int selftest(void)
{
    const checkasm_kernel_t k = CHECKASM_KERNEL(&selftest_family, "c", NULL, selftest_ref, selftest_bad);
    g.quiet = 1;
    g.cur = &k;
    g.cur_failed = 0;
    g.last_index = -1;
    rng_seed_for("checkasm_selftest");
    k.family->check(&k);
    const int ok = g.cur_failed && g.last_index == (long)g_plant;
    g.failures -= (unsigned)g.cur_failed;
    g.quiet = 0;
    if (!ok) {
        out("checkasm: FAIL the core's self-test: a mismatch planted at index %lu was %s\n", (unsigned long)g_plant,
               g.cur_failed ? "reported at another index" : "not reported");
    }
    return ok;
}

/* ---- registry walk ---- */

/* Glob match with '*' and '?', iterative (backtracking to the last '*'). */
static int glob_match(const char *pat, const char *s)
{
    const char *star = NULL, *resume = NULL;
    while (*s) {
        if (*pat == '*') {
            star = pat++;
            resume = s;
        } else if (*pat == '?' || *pat == *s) {
            pat++;
            s++;
        } else if (star) {
            pat = star + 1;
            s = ++resume;
        } else {
            return 0;
        }
    }
    while (*pat == '*') {
        pat++;
    }
    return *pat == '\0';
}

static void kernel_name(const checkasm_kernel_t *k, char *buf, size_t cap)
{
    snprintf(buf, cap, "%s_%s", k->family->name, k->isa);
}

static int selected(const checkasm_kernel_t *k, const char *name, char **pats, int npats)
{
    if (npats == 0) {
        return 1;
    }
    for (int i = 0; i < npats; i++) {
        if (!strpbrk(pats[i], "*?") && strstr(name, pats[i])) {
            return 1; /* a plain word: part of the name */
        }
        if (glob_match(pats[i], name) || glob_match(pats[i], k->family->name) || glob_match(pats[i], k->isa)) {
            return 1;
        }
    }
    return 0;
}

static int usage(int status)
{
    char hex[24];
    out("usage: checkasm [--seed N] [--runs N] [--bench | --marks] [--list] [PATTERN...]\n"
           "  checks every registered optimised kernel against its C reference, bit for bit\n"
           "  --seed N   RNG seed (default 0x%s); each kernel reseeds from it and its name\n"
           "  --runs N   inputs per kernel (default: each family's own)\n"
           "  --bench    then time reference and optimised kernel (ns per unit, speed-up)\n"
           "  --marks    then call each once between checkasm_mark() calls (instruction\n"
           "             counts under QEMU: tests/checkasm/insn_count.sh)\n"
           "  --list     list the registered kernels and whether this CPU runs them\n"
           "  PATTERN    glob on the kernel name (family_isa), its family or its ISA;\n"
           "             a plain word selects the kernels whose name contains it\n",
           u64_text(DEFAULT_SEED, 16u, hex));
    return status;
}

int checkasm_main(int argc, char **argv)
{
    int bench = 0, list = 0, npats = 0;
    char **pats = argv + 1;
    for (int i = 1; i < argc; i++) {
        char *end = NULL;
        if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
            return usage(0);
        } else if (strcmp(argv[i], "--bench") == 0) {
            bench = 1;
        } else if (strcmp(argv[i], "--marks") == 0) {
            bench = g.marks = 1;
        } else if (strcmp(argv[i], "--list") == 0) {
            list = 1;
        } else if ((strcmp(argv[i], "--seed") == 0 || strcmp(argv[i], "--runs") == 0) && i + 1 < argc) {
            const unsigned long long v = strtoull(argv[i + 1], &end, 0);
            if (!end || *end || end == argv[i + 1]) {
                out("checkasm: %s: not a number: '%s'\n", argv[i], argv[i + 1]);
                return usage(2);
            }
            if (argv[i][2] == 's') {
                g.seed = v;
            } else {
                g.runs = (uint32_t)(v > UINT32_MAX ? UINT32_MAX : v);
            }
            i++;
        } else if (argv[i][0] == '-') {
            out("checkasm: unknown option '%s'\n", argv[i]);
            return usage(2);
        } else {
            pats[npats++] = argv[i]; /* compacted in place: npats <= i */
        }
    }
    char name[96];
    if (list) {
        for (size_t m = 0; m < NMODULES; m++) {
            for (size_t j = 0; j < g_modules[m]->count; j++) {
                const checkasm_kernel_t *k = &g_modules[m]->kernels[j];
                kernel_name(k, name, sizeof name);
                if (selected(k, name, pats, npats)) {
                    out("%-30s module %-6s family %-20s isa %-8s %s\n", name, g_modules[m]->name, k->family->name,
                           k->isa, k->available() ? "runs here" : "not available here");
                }
            }
        }
        return 0;
    }
    if (!selftest()) {
        return 1;
    }
    char hex[24];
    out("checkasm: seed 0x%s\n", u64_text(g.seed, 16u, hex));
    unsigned checked = 0, skipped = 0, matched = 0;
    for (size_t m = 0; m < NMODULES; m++) {
        for (size_t j = 0; j < g_modules[m]->count; j++) {
            const checkasm_kernel_t *k = &g_modules[m]->kernels[j];
            kernel_name(k, name, sizeof name);
            if (!selected(k, name, pats, npats)) {
                continue;
            }
            matched++;
            if (!k->available()) {
                out("checkasm: %-28s not available on this build/CPU: skipped\n", name);
                skipped++;
                continue;
            }
            g.cur = k;
            snprintf(g.cur_name, sizeof g.cur_name, "%s", name);
            g.cur_failed = 0;
            rng_seed_for(name);
            k->family->check(k);
            checked++;
            out("checkasm: %-28s %s\n", name, g.cur_failed ? "FAILED" : "ok (bit-exact)");
        }
    }
    if (npats > 0 && matched == 0) {
        out("checkasm: no registered kernel matches the pattern(s) (see --list)\n");
        return 2;
    }
    out("checkasm: %u kernels checked, %u failed, %u not available here\n", checked, g.failures, skipped);
    if (g.failures || !bench) {
        return g.failures ? 1 : 0;
    }
    out("checkasm --bench: best of %u x %u calls, ns per unit (pixel unless named)\n", BENCH_REPS, BENCH_CALLS);
    out("  %-24s %-38s %11s %11s %11s\n", "kernel", "input", "C", "optimised", "speed-up");
    for (size_t m = 0; m < NMODULES; m++) {
        for (size_t j = 0; j < g_modules[m]->count; j++) {
            const checkasm_kernel_t *k = &g_modules[m]->kernels[j];
            kernel_name(k, name, sizeof name);
            if (!selected(k, name, pats, npats) || !k->available() || !k->family->bench) {
                continue;
            }
            g.cur = k;
            snprintf(g.cur_name, sizeof g.cur_name, "%s", name);
            rng_seed_for(name);
            k->family->bench(k);
        }
    }
    return 0;
}

#ifndef CHECKASM_NO_MAIN
int main(int argc, char **argv)
{
    return checkasm_main(argc, argv);
}
#endif
