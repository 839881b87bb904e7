/*
 * tdc_board_stub.c - the part of the board interface (tdc_board.h) a host
 * double of the board has no hardware for: no vertical blanking to wait
 * for, a timer that stays at 0 (the loop's "time us" line is then 0, so
 * host outputs compare byte for byte), a power-on reset, one core (no row
 * workers: bands run in order).  Linked by the
 * host build of the frame loop (tdc_board_host.c) and its fuzz harness
 * (tests/fuzz/fuzz_frameloop.c), which each give transport, panel and log.
 */
#include "tdc_board.h"

void tdc_board_vsync_wait(void)
{
}

uint32_t tdc_board_cycles(void)
{
    return 0;
}

uint32_t tdc_board_time_us(void)
{
    return 0;
}

tdc_reset_cause_t tdc_board_reset_cause(void)
{
    return TDC_RESET_POWER_ON;
}

uint32_t tdc_board_workers(void)
{
    return 1;
}

void tdc_board_run_bands(tdc_board_band_fn *fn, void *arg, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++) {
        fn(arg, i);
    }
}
