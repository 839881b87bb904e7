/*
 * tdc_free.h - releasing a host state's heap blocks in one statement:
 *   TDC_FREE_ALL(st->a, st->b, st);
 * frees each pointer in order (NULL ones included, as free() allows), so a
 * state's release lists its blocks once instead of one free() per line.
 */
#ifndef TDC_FREE_H
#define TDC_FREE_H

#include <stddef.h>
#include <stdlib.h>

#define TDC_FREE_ALL(...)                                                          \
    do {                                                                           \
        void *tdc_free_p_[] = {__VA_ARGS__};                                       \
        for (size_t i_ = 0; i_ < sizeof tdc_free_p_ / sizeof tdc_free_p_[0]; i_++) { \
            free(tdc_free_p_[i_]);                                                 \
        }                                                                          \
    } while (0)

#endif
