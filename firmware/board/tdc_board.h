/*
 * tdc_board.h - the narrow interface between the frame loop (tdc_main.c)
 * and a board: transport in, panel out, vsync, timer, reset cause, log.
 *
 * Implementations:
 *   firmware/board/tdc_board_emulated.c  mps2-an500, mps3-an547 under QEMU:
 *       transport = a .tdcs stream file read through semihosting (path from
 *       QEMU's -append), panel = one FNV-1a checksum line per frame on stdout
 *   firmware/board/tdc_board_stm32h7.c   STM32H747I-DISCO: LTDC frame
 *       buffer address, vsync, DWT timer and reset cause are real register
 *       code; the USB HS bulk transport and the DSI panel set-up are stubs
 *       that say so
 *   tests/arm/tdc_board_host.c           host test double (stdio), the
 *       reference the emulated boards' checksums are compared with
 */
#ifndef TDC_BOARD_H
#define TDC_BOARD_H

#include <stddef.h>
#include <stdint.h>

/* Large static buffers (frame buffer, link staging, stage arenas) go to the
 * board's external RAM region (PSRAM / SDRAM / DDR).  On the host it is
 * plain .bss. */
#if defined(__arm__)
#include "tdc_crt0.h"
#else
#define TDC_EXTRAM
#endif

typedef enum {
    TDC_RESET_UNKNOWN = 0,
    TDC_RESET_POWER_ON,
    TDC_RESET_PIN,
    TDC_RESET_SOFTWARE,
    TDC_RESET_WATCHDOG,
    TDC_RESET_BROWNOUT,
    TDC_RESET_LOW_POWER
} tdc_reset_cause_t;

typedef enum {
    TDC_BOARD_OK = 0,
    TDC_BOARD_END = 1,                 /* transport closed (emulated: end of the stream file) */
    TDC_BOARD_ERR_IO = -1,             /* transport or panel failure */
    TDC_BOARD_ERR_NOT_IMPLEMENTED = -2 /* a stub on this board (see its source) */
} tdc_board_status_t;

/* Clocks are up and memory is zeroed when this runs (startup + crt0);
 * brings up transport and panel. */
tdc_board_status_t tdc_board_init(void);

/* Transport in: up to cap link-stream bytes into buf, *got = bytes read
 * (0: nothing arrived yet).  TDC_BOARD_END when the stream has ended. */
tdc_board_status_t tdc_board_transport_read(uint8_t *buf, uint32_t cap, uint32_t *got);

/* Panel out: frame `frame_index` is complete in fb (all eyes side by side,
 * RGB888 drive codes, rows stride bytes apart): show it. */
/* Checksum of a shown RGB888 frame (64-bit FNV-1a over the visible bytes of
 * each row): what the emulated boards and the host build of the frame loop
 * print per frame, so their outputs compare bit for bit. */
static inline uint64_t tdc_board_frame_checksum(const uint8_t *fb, uint32_t stride, uint32_t width, uint32_t height)
{
    uint64_t h = 0xcbf29ce484222325ULL;
    for (uint32_t y = 0; y < height; y++) {
        const uint8_t *row = fb + (size_t)y * stride;
        for (uint32_t i = 0; i < width * 3u; i++) {
            h ^= row[i];
            h *= 0x100000001b3ULL;
        }
    }
    return h;
}

tdc_board_status_t tdc_board_panel_show(const uint8_t *fb, uint32_t stride, uint32_t width, uint32_t height,
                                        uint32_t frame_index);

/* Blocks until the panel's next vertical blanking (no-op when emulated). */
void tdc_board_vsync_wait(void);

/* Row workers (a board with several cores; docs/boards.md "Real time"):
 * tdc_board_workers() is how many bands of a frame's rows may run at once
 * (1: one core, and then the loop never calls tdc_board_run_bands);
 * tdc_board_run_bands(fn, arg, n) runs fn(arg, i) for i < n <= workers at
 * once, i = 0 on the caller, the others on threads the board created at
 * start-up, and returns when all have.  Only a loop built with
 * TDC_CFG_ROW_WORKERS > 1 (tdc_fw_config.h) calls them: the Linux board
 * (whose scan-out conversion uses them too); the host double's stub has
 * one worker and runs bands in order (tests/arm/tdc_board_stub.c). */
typedef void tdc_board_band_fn(void *arg, uint32_t band);
uint32_t tdc_board_workers(void);
void tdc_board_run_bands(tdc_board_band_fn *fn, void *arg, uint32_t n);

/* Free-running microsecond timer (wraps at 2^32). */
uint32_t tdc_board_time_us(void);

/* CPU cycle counter for the loop's per-stage timing (wraps at 2^32), or
 * 0 on boards that have none or whose timing would change their golden
 * logs (emulated, Linux): the loop then logs no timing. */
uint32_t tdc_board_cycles(void);

/* Why the controller last reset. */
tdc_reset_cause_t tdc_board_reset_cause(void);

/* One line of diagnostic text (emulated: stderr; STM32: dropped until the
 * USB control channel exists). */
void tdc_board_log(const char *msg);

/* The frame loop: returns when the transport ends (emulated boards and the
 * host double); 0 if the stream was processed, non-zero on a board error. */
int tdc_fw_run(void);

#endif
