/*
 * checkasm.h - bit-exactness checks and benchmarks of optimised kernels
 * against their portable C references (in the style of dav1d's checkasm).
 *
 * The unit is a kernel PAIR: a reference (the portable C kernel, what the
 * boards run) and one optimised version of it (AVX2, AVX-512, Helium MVE,
 * ...).  Pairs of one signature form a FAMILY, which owns the input
 * generator, the comparison and the benchmark; a module (one per firmware
 * stage, e.g. checkasm_trm.c) defines its families and registers its pairs
 * in a table.  A new SIMD kernel of an existing signature is one line:
 *
 *     CHECKASM_KERNEL(&trm_full_row, "mve", checkasm_mve_available,
 *                     tdc_trm_full_row_c, tdc_trm_full_row_mve),
 *
 * The core (checkasm.c) runs every registered pair that this build and CPU
 * can run, with one seeded RNG (reseeded per pair from --seed and the
 * pair's name, so `checkasm --seed S NAME` replays exactly the inputs of a
 * full run), prints the first failing input of each pair (kernel, width,
 * index, both values, the inputs there) and exits 1 when any pair failed.
 *
 *   checkasm [--seed N] [--runs N] [--bench] [--list] [PATTERN...]
 *
 * PATTERN: glob ('*', '?') on the pair's name (family_isa, e.g.
 * trm_full_row_avx2), its family or its ISA (`checkasm avx2`); a plain
 * word selects every pair whose name contains it (`checkasm dhoriz`).
 *
 * Plain C11 with stdio only: builds for the Cortex-M targets too (their
 * harness, tests/arm/checkasm_arm_main.c, calls checkasm_main() with the
 * arguments QEMU was given and provides checkasm_write()); the timer
 * is the one optional part (POSIX clock_gettime on hosts; without a timer
 * --bench says so and only checks).  No floating point: times are integer
 * nanoseconds.
 */
#ifndef CHECKASM_H
#define CHECKASM_H

#include <stddef.h>
#include <stdint.h>

/* Large input/output buffers of a family: on the Cortex-M boards in the
 * external RAM region (the boards' TDC_EXTRAM section, zeroed by crt0), as
 * the tightly coupled data RAM holds 512 KiB; plain .bss on hosts. */
#if defined(__arm__)
#include "tdc_crt0.h"
#define CHECKASM_BIG TDC_EXTRAM
#else
#define CHECKASM_BIG
#endif

/* Any kernel, stored type-erased; its family casts it back to its type. */
typedef void (*checkasm_fn_t)(void);

typedef struct checkasm_kernel checkasm_kernel_t;

/* One kernel signature: how to test and time a pair of it. */
typedef struct {
    const char *name;                          /* "trm_full_row" */
    void (*check)(const checkasm_kernel_t *k); /* random + extreme inputs through both, checkasm_fail() on mismatch */
    void (*bench)(const checkasm_kernel_t *k); /* optional: CHECKASM_BENCH on representative inputs */
} checkasm_family_t;

/* One registration: an optimised kernel beside its reference. */
struct checkasm_kernel {
    const checkasm_family_t *family;
    const char *isa;        /* "avx2", "avx512", "mve" */
    int (*available)(void); /* 1: built in and runnable on this CPU */
    checkasm_fn_t ref, opt;
};

#define CHECKASM_KERNEL(family, isa, available, ref, opt)                        \
    {                                                                            \
        (family), (isa), (available), (checkasm_fn_t)(ref), (checkasm_fn_t)(opt) \
    }

/* The pair's two sides as their real type (T: a function type). */
#define CHECKASM_REF(T, k) ((T *)(k)->ref)
#define CHECKASM_OPT(T, k) ((T *)(k)->opt)

/* A module's registrations (checkasm.c lists the modules). */
typedef struct {
    const char *name; /* "trm" */
    const checkasm_kernel_t *kernels;
    size_t count;
} checkasm_module_t;

/* ---- the one RNG (xorshift64*, reseeded per pair) ---- */
uint32_t checkasm_rand(void);
uint32_t checkasm_rand_below(uint32_t n); /* [0, n), 0 when n == 0 */

/* Check effort: the family's default, or --runs N. */
uint32_t checkasm_runs(uint32_t dflt);
/* The `available` of the Helium (MVE) pairs: 1 in builds for the Helium
 * boards (TDC_TRM_MVE: their start-up enables the MVE unit, so it always
 * runs there), 0 elsewhere (the MVE names are the C kernels: skipped). */
int checkasm_mve_available(void);
/* The `available` of the AArch64 NEON pairs: 1 in AArch64 builds (NEON is
 * part of ARMv8-A: every such CPU runs it), 0 elsewhere. */
int checkasm_neon_available(void);

/* ---- mismatches ---- */
/* First index where two arrays of n elements differ, or -1. */
long checkasm_diff_u8(const uint8_t *a, const uint8_t *b, size_t n);
long checkasm_diff_u16(const uint16_t *a, const uint16_t *b, size_t n);
long checkasm_diff_i32(const int32_t *a, const int32_t *b, size_t n);
/* Reports a mismatch of the running pair: printf-style description of
 * where (width, index) and the values (reference, optimised, the inputs
 * there).  Only the first failure of a pair is printed; returns 1 so a
 * check can `return checkasm_fail(...)`. */
int checkasm_fail(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
/* 1 when the running pair has failed already (stop generating inputs). */
int checkasm_failed(void);

/* ---- benchmarks ---- */
typedef struct {
    const checkasm_kernel_t *k;
    const char *label;
    uint64_t units; /* work per call (pixels), for ns per unit */
    uint64_t t0, best[2];
    uint32_t call, rep;
    int side; /* 0 reference, 1 optimised */
} checkasm_bench_t;

checkasm_bench_t checkasm_bench_start(const checkasm_kernel_t *k, const char *label, uint64_t units);
/* 1: make one more call, with checkasm_bench_fn(); 0: done (printed). */
int checkasm_bench_step(checkasm_bench_t *b);
checkasm_fn_t checkasm_bench_fn(const checkasm_bench_t *b);

/* --marks: called around each side's one call; an instruction-counting
 * emulator records its count there (tests/checkasm/insn_count.sh). */
void checkasm_mark(void);

/* Times `call` (which calls f, a T *) for the reference and the optimised
 * side, best of 50 batches of 20 calls each (short batches: a loaded machine
 * still gives undisturbed ones), and prints ns per unit and the speed-up. */
#define CHECKASM_BENCH(k, label, units, T, f, call)                                                        \
    for (checkasm_bench_t cb_ = checkasm_bench_start((k), (label), (units)); checkasm_bench_step(&cb_);) { \
        T *const f = (T *)checkasm_bench_fn(&cb_);                                                         \
        call;                                                                                              \
    }

/* ---- output ----
 * Every line the core prints goes through this: the host build writes to
 * stdout, a target without stdio streams provides it (semihosting). */
void checkasm_write(const char *s, size_t n);

/* ---- the run ---- */
/* Parses the options above and runs; 0 when every pair agreed, 1 when one
 * failed, 2 for bad usage. */
int checkasm_main(int argc, char **argv);

#endif /* CHECKASM_H */
