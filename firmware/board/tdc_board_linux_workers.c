/*
 * tdc_board_linux_workers.c - the Linux board's row workers (tdc_board.h
 * tdc_board_workers / tdc_board_run_bands): threads started once at
 * start-up that run bands of a frame's output rows beside the loop's own
 * thread (TRM's rows: tdc_fw_trm.c, tdc_trm_band).  At HTC Vive stereo
 * size a TRM frame is ~4 x 10^7 ns of row work in two calls per eye, so
 * one wake-up and one join per call (a mutex and two condition variables,
 * tens of microseconds) is noise; the threads sleep between frames.
 */
#include <pthread.h>
#include <stdint.h>
#include <unistd.h>

#include "tdc_board.h"
#include "tdc_board_linux.h"

static pthread_mutex_t g_mu = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t g_go = PTHREAD_COND_INITIALIZER, g_joined = PTHREAD_COND_INITIALIZER;
static uint32_t g_workers = 1;   /* the loop's thread + started threads */
static uint64_t g_round;         /* bumped per tdc_board_run_bands call */
static tdc_board_band_fn *g_fn;  /* this round's work */
static void *g_arg;
static uint32_t g_bands, g_left; /* bands this round, started threads not yet done */

static void *worker(void *arg)
{
    const uint32_t band = (uint32_t)(uintptr_t)arg;
    uint64_t seen = 0;
    pthread_mutex_lock(&g_mu);
    for (;;) {
        while (g_round == seen) {
            pthread_cond_wait(&g_go, &g_mu);
        }
        seen = g_round;
        if (band < g_bands) {
            tdc_board_band_fn *fn = g_fn;
            void *a = g_arg;
            pthread_mutex_unlock(&g_mu);
            fn(a, band);
            pthread_mutex_lock(&g_mu);
        }
        if (--g_left == 0u) {
            pthread_cond_signal(&g_joined);
        }
    }
    return NULL;
}

void tdc_lx_workers_init(void)
{
    long want = tdc_lx_opts.threads;
    if (want <= 0) {
        want = sysconf(_SC_NPROCESSORS_ONLN);
        want = want < 1 ? 1 : (want > TDC_LX_MAX_WORKERS ? TDC_LX_MAX_WORKERS : want);
    }
    for (uint32_t i = 1; i < (uint32_t)want; i++) {
        if (tdc_lx_thread(worker, (void *)(uintptr_t)i) != 0) {
            tdc_lx_logf("row workers: thread %u not started: running %u", (unsigned)i, (unsigned)g_workers);
            return; /* fewer workers: the same bytes, slower */
        }
        g_workers = i + 1u;
    }
}

uint32_t tdc_board_workers(void)
{
    return g_workers;
}

void tdc_board_run_bands(tdc_board_band_fn *fn, void *arg, uint32_t n)
{
    n = n < g_workers ? n : g_workers;
    if (n > 1u) {
        pthread_mutex_lock(&g_mu);
        g_fn = fn;
        g_arg = arg;
        g_bands = n;
        g_left = g_workers - 1u; /* every started thread answers each round */
        g_round++;
        pthread_cond_broadcast(&g_go);
        pthread_mutex_unlock(&g_mu);
    }
    fn(arg, 0);
    if (n > 1u) {
        pthread_mutex_lock(&g_mu);
        while (g_left != 0u) {
            pthread_cond_wait(&g_joined, &g_mu);
        }
        pthread_mutex_unlock(&g_mu);
    }
}
