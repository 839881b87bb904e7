/*
 * tdc_par.h - threading of the simulator's own stages (source, eye,
 * metrics) over rows, with OpenMP (gcc's libgomp).
 *
 * Why OpenMP and not pthreads: every parallel loop here is "for each row,
 * independently", which is one pragma in OpenMP; a pthread pool would be a
 * few hundred lines of our own (queue, barrier, per-call closures) doing
 * the same.  Built without -fopenmp (another compiler, a sanitizer build
 * that lacks it) the pragmas vanish and the loops run serially.
 *
 * Results never depend on the thread count: a row's values are computed by
 * the same operations whichever thread runs it, and every reduction keeps
 * per-row partial sums that are added in row order afterwards
 * (tdc_par_sum_rows), never in thread order.
 */
#ifndef TDC_PAR_H
#define TDC_PAR_H

#include <stddef.h>

/* Loops of less work than tdc_par_min_work (pixels or samples) run serial:
 * a parallel region costs a barrier, and on an oversubscribed host a
 * barrier waits for a descheduled thread (tiny test images would spend
 * their time there).  Default 32768; 0 threads everything (tests). */
extern long tdc_par_min_work;

#ifdef _OPENMP
#include <omp.h>
#define TDC_PAR_PRAGMA(x) _Pragma(#x)
#define TDC_PAR_FOR(work) TDC_PAR_PRAGMA(omp parallel for schedule(dynamic, 4) if ((long)(work) >= tdc_par_min_work))
/* A parallel region whose threads share the bands of TDC_PAR_BANDS (each
 * thread allocates its own scratch once per region, then takes bands). */
#define TDC_PAR_REGION(work) TDC_PAR_PRAGMA(omp parallel if ((long)(work) >= tdc_par_min_work))
#define TDC_PAR_BANDS TDC_PAR_PRAGMA(omp for schedule(dynamic, 1))
static inline void tdc_par_set_threads(int n)
{
    omp_set_num_threads(n > 0 ? n : 1);
}
static inline int tdc_par_threads(void)
{
    return omp_get_max_threads();
}
#else
#define TDC_PAR_FOR(work)
#define TDC_PAR_REGION(work)
#define TDC_PAR_BANDS
static inline void tdc_par_set_threads(int n)
{
    (void)n;
}
static inline int tdc_par_threads(void)
{
    return 1;
}
#endif

/* Vector row kernels.  TDC_SIMD before an element-wise loop vectorises it
 * whatever gcc's -O2 cost model says (`omp simd`; nothing without OpenMP,
 * where clang's -O2 vectoriser does it); TDC_SIMD_CLONES before a function
 * makes gcc on x86-64 build an AVX2 clone beside the default one, picked at
 * load time (the default clone is the plain C fallback).  Element-wise loops
 * without reassociation (C11 mode: no FMA contraction) give the same bits in
 * every clone, so results stay independent of the CPU and thread count.
 * Sanitizer builds keep the single plain version. */
#ifdef _OPENMP
#define TDC_SIMD _Pragma("omp simd")
#else
#define TDC_SIMD
#endif
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define TDC_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define TDC_SIMD_CLONES
#endif

/* Sum of per-row partial sums in row order (thread-count independent). */
static inline double tdc_par_sum_rows(const double *rows, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++) {
        s += rows[i];
    }
    return s;
}

#endif
