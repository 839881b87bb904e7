/* tdc_powtab.c - tables of x^a for a fixed a (see tdc_powtab.h). */
#include "metrics/tdc_powtab.h"

#include <pthread.h>

void tdc_powtab_init(tdc_powtab_t *t, double a)
{
    t->a = a;
    for (int i = 0; i <= TDC_POWTAB_N; i++) {
        t->man[i] = pow(1.0 + (double)i / TDC_POWTAB_N, a);
    }
    t->man[TDC_POWTAB_N + 1] = t->man[TDC_POWTAB_N];
    for (int e = 0; e < 2048; e++) {
        t->ex[e] = exp2(a * (double)(e - 1023));
    }
}

static tdc_powtab_t g_tabs[TDC_POWTAB_COUNT];
static pthread_once_t g_once = PTHREAD_ONCE_INIT;

static void metrics_init(void)
{
    tdc_powtab_init(&g_tabs[TDC_POWTAB_ENCODE], 1.0 / 2.2);
    tdc_powtab_init(&g_tabs[TDC_POWTAB_CBRT], 1.0 / 3.0);
    tdc_powtab_init(&g_tabs[TDC_POWTAB_HYAB], 0.7);
}

const tdc_powtab_t *tdc_powtab_metrics(tdc_powtab_id_t id)
{
    pthread_once(&g_once, metrics_init);
    return &g_tabs[id];
}
