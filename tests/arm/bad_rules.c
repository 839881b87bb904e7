/*
 * bad_rules.c - an image that breaks both firmware rules on purpose (float
 * arithmetic and the heap), so the image check shows it catches them
 * (tests/arm/check_image_symbols.sh must fail on it and name the symbols).
 * Never part of a firmware build.
 */
#include <stdlib.h>

volatile float g_num = 3.0f, g_den = 7.0f;
volatile double g_dnum = 3.0;
char *volatile g_heap;
int main(void);

int main(void)
{
    g_heap = malloc(16);
    const float q = g_num / g_den;
    const double d = g_dnum * 1.5;
    free(g_heap);
    return (int)q + (int)d;
}
