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
static inline void tdc_par_set_threads(int n)
{
    (void)n;
}
static inline int tdc_par_threads(void)
{
    return 1;
}
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
