/*
 * tdc_board_linux.h - the parts of the Linux board (BOARD=linux) behind
 * tdc_board.h, shared by its files:
 *   tdc_board_linux.c      main, options, init, time, reset cause, log
 *   tdc_board_linux_drm.c  panel out: DRM/KMS atomic mode-set, two dumb
 *                          buffers, page flips, vsync from flip events
 *   tdc_board_linux_ffs.c  transport: configfs USB gadget + FunctionFS
 *                          serving the USB protocol (firmware/tdc_usbproto.c)
 *   tdc_board_linux_gpio.c reset / boot input lines, vsync output (libgpiod)
 * The board layer sets OS resources up once at start-up (DRM buffers,
 * gadget, threads); the frame loop it drives stays the no-heap fixed-point
 * code of firmware/.  Every failure is logged as one line naming what
 * failed and why; tdc_lx_fail() records the exit code main() returns.
 */
#ifndef TDC_BOARD_LINUX_H
#define TDC_BOARD_LINUX_H

#include <stdint.h>

/* Exit codes: the shared table of docs/tools.md (common/tdc_tool.h). */
enum {
    TDC_LX_EXIT_OK = 0,
    TDC_LX_EXIT_ARGS = 1,
    TDC_LX_EXIT_NO_DEVICE = 2, /* no DRM device, no USB device controller */
    TDC_LX_EXIT_IO = 4,        /* a driver call failed */
    TDC_LX_EXIT_TIMEOUT = 5,   /* no page-flip event */
    TDC_LX_EXIT_FILE = 7,      /* state folder / slot file */
    TDC_LX_EXIT_REFUSED = 14,  /* mode not available, no atomic KMS */
    TDC_LX_EXIT_RESTART = 20   /* a DFU update installed a new program: the launcher starts it */
};

typedef struct {
    const char *drm_path;  /* /dev/dri/card0 */
    const char *connector; /* "Virtual-1", "HDMI-A-1", ...; NULL: the first connected */
    const char *ffs_dir;   /* FunctionFS mount point */
    const char *udc;       /* NULL: the first in /sys/class/udc */
    const char *serial;
    const char *state_dir; /* DFU A/B slots */
    const char *stream;    /* NULL: USB; else a .tdcs file as transport (no gadget) */
    const char *gpio_chip; /* NULL: no GPIO */
    const char *gpio_vsync, *gpio_reset;
    int no_display;        /* frames checksummed on stdout instead of KMS (bench, tests) */
    int threads;           /* row workers (--threads N); 0: the CPUs online, at most TDC_LX_MAX_WORKERS */
} tdc_lx_opts_t;

/* The most row workers the board starts (tdc_board_linux_workers.c); the
 * loop is built for as many (mk/linuxboard.mk, TDC_CFG_ROW_WORKERS). */
#define TDC_LX_MAX_WORKERS 4

extern tdc_lx_opts_t tdc_lx_opts;

/* Log one line "tdc-board: what: why" (stderr, and syslog with --syslog). */
void tdc_lx_logf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Records a start-up failure's exit code (the first one wins) and logs it. */
void tdc_lx_fail(int code, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Starts a thread with SIGTERM/SIGINT blocked in it, so that they reach the
 * main thread (its blocked endpoint read returns EINTR); 0 or -1. */
int tdc_lx_thread(void *(*fn)(void *), void *arg);
/* The scan-out conversion RGB888 (stride) -> XRGB8888 (pitch) of w x h
 * pixels, in bands on the row workers (tdc_board_linux_drm.c). */
void tdc_lx_xrgb(const uint8_t *fb, uint32_t stride, uint32_t w, uint32_t h, uint8_t *dst, uint32_t pitch);
/* Starts the row workers (--threads) once (a thread that does not start:
 * fewer, logged). */
void tdc_lx_workers_init(void);
/* Set by SIGTERM/SIGINT: the transport reports its end, the loop returns. */
extern volatile int tdc_lx_stop;

/* DRM/KMS (tdc_board_linux_drm.c) */
int tdc_lx_drm_init(uint32_t width, uint32_t height, uint32_t refresh_hz);
int tdc_lx_drm_show(const uint8_t *fb, uint32_t stride, uint32_t width, uint32_t height);
void tdc_lx_drm_wait(void);

/* USB gadget (tdc_board_linux_ffs.c) */
int tdc_lx_ffs_init(uint32_t width, uint32_t height, uint32_t refresh_mhz, uint32_t rx_bytes, uint32_t max_packet);
/* Bulk OUT into buf: 1 with *got bytes, 0 nothing yet, -1 stop (SIGTERM),
 * -2 host gone (the connection's stream ended). */
int tdc_lx_ffs_read(uint8_t *buf, uint32_t cap, uint32_t *got);
/* A flip of a frame of connection conn (tdc_lx_ffs_conn() when it was
 * committed) completed: counted only if that host is still there. */
void tdc_lx_ffs_frame_shown(unsigned conn);
unsigned tdc_lx_ffs_conn(void);
/* 1 when the frame about to be shown belongs to a host that has gone (the
 * run ends, or will at its next read): not shown (tdc_board_panel_show). */
int tdc_lx_ffs_stale(void);
/* Start-up done (display up, gadget bound): STATE/confirmed, which keeps a
 * program on trial (boards/linux/tdc-board-launch). */
void tdc_lx_ffs_confirm(void);
/* Set when a DFU reset installed a program: main returns TDC_LX_EXIT_RESTART. */
extern int tdc_lx_restart;

/* GPIO (tdc_board_linux_gpio.c) */
int tdc_lx_gpio_init(void);
void tdc_lx_gpio_vsync(void);

#endif
