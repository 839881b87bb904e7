/*
 * tdc_board_linux.c - the board interface (tdc_board.h) on a Linux board
 * (BOARD=linux: a Raspberry Pi, a Rockchip or i.MX board, the `make
 * test-vm` VM): main, options, start-up, timer, reset cause, log.
 * Transport: tdc_board_linux_ffs.c (USB gadget), or --stream FILE.
 * Panel: tdc_board_linux_drm.c (KMS), or --no-display (one "frame N
 * fnv1a64" line per frame on stdout, as the emulated boards print).
 *
 * Usage: tdc-board [options]      (runs until SIGTERM / SIGINT)
 *   --drm PATH          DRM device (default /dev/dri/card0)
 *   --connector NAME    e.g. HDMI-A-1, DSI-1, Virtual-1 (default: the first connected)
 *   --ffs DIR           FunctionFS mount point (default /dev/ffs-tdcboard)
 *   --udc NAME          USB device controller (default: the first in /sys/class/udc)
 *   --serial S          USB serial number (default: the machine id's first 8 characters, else "0")
 *   --state DIR         DFU A/B slots (default /var/lib/tdc)
 *   --stream FILE       read a .tdcs file instead of USB, exit at its end
 *   --no-display        checksum lines on stdout instead of KMS
 *   --threads N         row workers: TRM's output rows of a frame as N
 *                       bands on N threads, 1 <= N <= 4 (default: the CPUs
 *                       online, at most 4); the bytes do not depend on N
 *   --bench             with --stream: the scan-out conversion into a RAM
 *                       buffer instead of KMS, and at the end one line
 *                       "bench: ..." with the loop thread's CPU time spent
 *                       in transport, loop (decode + stages), panel out,
 *                       the wall and all threads' CPU time (make bench);
 *                       tdc_board_cycles() counts the loop thread's CPU
 *                       nanoseconds, so the loop logs its per-stage means
 *                       every 64 frames
 *   --gpio-chip C --gpio-vsync L --gpio-reset L   (tdc_board_linux_gpio.c)
 *   --syslog            log to syslog as well as stderr
 *   --reset-cause power-on|pin|software|watchdog   (what the unit that restarted us says)
 * Exit: 0 after SIGTERM or the end of --stream; the codes of docs/tools.md
 * for start-up failures (2 no DRM device / no UDC, 14 mode not available);
 * 20 after a DFU update installed a new program (tdc-board-launch starts it).
 */
#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <syslog.h>
#include <time.h>

#include "tdc_board.h"
#include "tdc_board_linux.h"

#ifndef TDC_PANEL_NAME
#error "the board is built per panel: compile with -include tdc_panel_<panel>_config.h"
#endif

tdc_lx_opts_t tdc_lx_opts = {.drm_path = "/dev/dri/card0",
                             .ffs_dir = "/dev/ffs-tdcboard",
                             .serial = "0",
                             .state_dir = "/var/lib/tdc"};
volatile int tdc_lx_stop;
static int g_fail, g_syslog;
static tdc_reset_cause_t g_reset = TDC_RESET_POWER_ON;
static FILE *g_stream;
/* --bench: microseconds spent in the board calls; the rest is the loop */
static int g_bench;
static uint64_t g_t_transport, g_t_panel, g_frames;
static uint32_t *g_bench_fb;

static uint64_t clock_ns(clockid_t c)
{
    struct timespec t;
    clock_gettime(c, &t);
    return (uint64_t)t.tv_sec * 1000000000u + (uint64_t)t.tv_nsec;
}

static uint64_t now_us(void)
{
    return clock_ns(CLOCK_MONOTONIC) / 1000u;
}

/* --bench: the loop thread's CPU time.  On a machine shared with other
 * jobs the wall clock counts the time they hold the core; the thread's CPU
 * time is what the work costs on a core of its own.  With row workers it
 * is band 0 plus the parts that run in order: the frame's critical path
 * when the workers have cores too (the bands are equal rows). */
static uint64_t bench_us(void)
{
    return clock_ns(CLOCK_THREAD_CPUTIME_ID) / 1000u;
}

static void vlog(const char *fmt, va_list ap)
{
    char line[1024];
    vsnprintf(line, sizeof line, fmt, ap);
    fprintf(stderr, "tdc-board: %s\n", line);
    if (g_syslog) syslog(LOG_NOTICE, "%s", line);
}

void tdc_lx_logf(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vlog(fmt, ap);
    va_end(ap);
}

void tdc_lx_fail(int code, const char *fmt, ...)
{
    if (!g_fail) g_fail = code;
    va_list ap;
    va_start(ap, fmt);
    vlog(fmt, ap);
    va_end(ap);
}

tdc_board_status_t tdc_board_init(void)
{
    /* the loop runs once per USB connection (main): set up once */
    static int done;
    if (done) return TDC_BOARD_OK;
    done = 1;
    const uint32_t w = TDC_PANEL_EYES * TDC_PANEL_WIDTH, h = TDC_PANEL_HEIGHT;
    if (g_bench && !(g_bench_fb = malloc((size_t)w * h * 4u))) return TDC_BOARD_ERR_IO; /* once, at start-up */
    if (!tdc_lx_opts.no_display && tdc_lx_drm_init(w, h, TDC_PANEL_REFRESH_HZ) != 0) return TDC_BOARD_ERR_IO;
    if (tdc_lx_gpio_init() != 0) return TDC_BOARD_ERR_IO;
    tdc_lx_workers_init();
    if (tdc_lx_opts.stream) {
        g_stream = fopen(tdc_lx_opts.stream, "rb");
        if (!g_stream) {
            tdc_lx_fail(TDC_LX_EXIT_FILE, "stream: cannot open %s: %s", tdc_lx_opts.stream, strerror(errno));
            return TDC_BOARD_ERR_IO;
        }
        return TDC_BOARD_OK;
    }
    /* the loop's receive buffer is 16 KiB (tdc_main.c g_rx) */
    if (tdc_lx_ffs_init(TDC_PANEL_WIDTH, TDC_PANEL_HEIGHT, TDC_PANEL_REFRESH_HZ * 1000u, 16384u,
                        (uint32_t)TDC_PANEL_EYES * TDC_PANEL_WIDTH * TDC_PANEL_HEIGHT * 4u + 64u) != 0) {
        return TDC_BOARD_ERR_IO;
    }
    tdc_lx_logf("ready: panel %s %ux%u x%u eyes @ %u Hz", TDC_PANEL_NAME, TDC_PANEL_WIDTH, TDC_PANEL_HEIGHT,
                TDC_PANEL_EYES, TDC_PANEL_REFRESH_HZ);
    tdc_lx_ffs_confirm();
    return TDC_BOARD_OK;
}

tdc_board_status_t tdc_board_transport_read(uint8_t *buf, uint32_t cap, uint32_t *got)
{
    *got = 0;
    if (g_stream) {
        const uint64_t t0 = g_bench ? bench_us() : 0;
        const size_t n = fread(buf, 1, cap, g_stream);
        *got = (uint32_t)n;
        if (g_bench) g_t_transport += bench_us() - t0;
        return n ? TDC_BOARD_OK : ferror(g_stream) ? TDC_BOARD_ERR_IO : TDC_BOARD_END;
    }
    return tdc_lx_ffs_read(buf, cap, got) < 0 ? TDC_BOARD_END : TDC_BOARD_OK;
}

tdc_board_status_t tdc_board_panel_show(const uint8_t *fb, uint32_t stride, uint32_t width, uint32_t height,
                                        uint32_t frame_index)
{
    if (g_bench) { /* what the KMS path does per frame: RGB888 -> XRGB8888 (tdc_board_linux_drm.c) */
        const uint64_t t0 = bench_us();
        tdc_lx_xrgb(fb, stride, width, height, (uint8_t *)g_bench_fb, width * 4u);
        g_t_panel += bench_us() - t0;
        g_frames++;
        (void)frame_index;
        return TDC_BOARD_OK;
    }
    if (tdc_lx_opts.no_display) {
        printf("frame %u %016llx\n", (unsigned)frame_index,
               (unsigned long long)tdc_board_frame_checksum(fb, stride, width, height));
        return TDC_BOARD_OK;
    }
    if (tdc_lx_ffs_stale()) {
        tdc_lx_logf("usb: frame %u is not shown: its host has gone", (unsigned)frame_index);
        return TDC_BOARD_OK;
    }
    return tdc_lx_drm_show(fb, stride, width, height) == 0 ? TDC_BOARD_OK : TDC_BOARD_ERR_IO;
}

void tdc_board_vsync_wait(void)
{
    if (!tdc_lx_opts.no_display) tdc_lx_drm_wait();
    tdc_lx_gpio_vsync();
}

/* --bench: nanoseconds of the loop thread's CPU time (bench_us; mod 2^32:
 * a stage under 4 s), so that the loop's per-stage timing line (decode,
 * family, LCD, show: every 64 frames) gives each stage's share of the frame
 * budget; else 0 (no timing line). */
uint32_t tdc_board_cycles(void)
{
    return g_bench ? (uint32_t)clock_ns(CLOCK_THREAD_CPUTIME_ID) : 0u;
}

uint32_t tdc_board_time_us(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (uint32_t)((uint64_t)t.tv_sec * 1000000u + (uint64_t)t.tv_nsec / 1000u);
}

tdc_reset_cause_t tdc_board_reset_cause(void)
{
    return g_reset;
}

void tdc_board_log(const char *msg)
{
    tdc_lx_logf("%s", msg);
}

int tdc_lx_thread(void *(*fn)(void *), void *arg)
{
    sigset_t block, old;
    sigemptyset(&block);
    sigaddset(&block, SIGTERM);
    sigaddset(&block, SIGINT);
    pthread_sigmask(SIG_BLOCK, &block, &old);
    pthread_t t;
    const int rc = pthread_create(&t, NULL, fn, arg);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    return rc == 0 ? 0 : -1;
}

static void on_signal(int sig)
{
    (void)sig;
    tdc_lx_stop = 1;
}

static int usage(void)
{
    fprintf(stderr, "usage: tdc-board [--drm PATH] [--connector NAME] [--ffs DIR] [--udc NAME] [--serial S]\n"
                    "                 [--state DIR] [--stream FILE] [--no-display] [--bench] [--threads N] [--syslog]\n"
                    "                 [--gpio-chip C [--gpio-vsync L] [--gpio-reset L]] [--reset-cause C]\n");
    return TDC_LX_EXIT_ARGS;
}

int main(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        const char **slot = !strcmp(a, "--drm")          ? &tdc_lx_opts.drm_path
                            : !strcmp(a, "--connector")  ? &tdc_lx_opts.connector
                            : !strcmp(a, "--ffs")        ? &tdc_lx_opts.ffs_dir
                            : !strcmp(a, "--udc")        ? &tdc_lx_opts.udc
                            : !strcmp(a, "--serial")     ? &tdc_lx_opts.serial
                            : !strcmp(a, "--state")      ? &tdc_lx_opts.state_dir
                            : !strcmp(a, "--stream")     ? &tdc_lx_opts.stream
                            : !strcmp(a, "--gpio-chip")  ? &tdc_lx_opts.gpio_chip
                            : !strcmp(a, "--gpio-vsync") ? &tdc_lx_opts.gpio_vsync
                            : !strcmp(a, "--gpio-reset") ? &tdc_lx_opts.gpio_reset
                                                         : NULL;
        if (slot) {
            if (!v) return usage();
            *slot = v;
            i++;
        } else if (!strcmp(a, "--reset-cause") && v) {
            static const char *const names[] = {"unknown", "power-on", "pin", "software", "watchdog"};
            unsigned k = 0;
            while (k < 5 && strcmp(v, names[k])) k++;
            if (k == 5) return usage();
            g_reset = (tdc_reset_cause_t)k;
            i++;
        } else if (!strcmp(a, "--threads") && v) {
            char *end;
            const long n = strtol(v, &end, 10);
            if (*end || n < 1 || n > TDC_LX_MAX_WORKERS) return usage();
            tdc_lx_opts.threads = (int)n;
            i++;
        } else if (!strcmp(a, "--no-display")) {
            tdc_lx_opts.no_display = 1;
        } else if (!strcmp(a, "--bench")) {
            tdc_lx_opts.no_display = 1;
            g_bench = 1;
        } else if (!strcmp(a, "--syslog")) {
            g_syslog = 1;
            openlog("tdc-board", LOG_PID, LOG_DAEMON);
        } else {
            return usage();
        }
    }
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal; /* no SA_RESTART: a blocked endpoint read returns EINTR */
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGINT, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);
    setvbuf(stdout, NULL, _IOLBF, 0);
    /* One run of the frame loop per USB connection: when the host goes
     * (unplug, USB reset) the loop shows what it has and returns, and the
     * next connection starts with a fresh link decoder (a half-received
     * packet must not swallow the next stream's header). */
    int rc;
    const uint64_t t0 = now_us(), c0 = bench_us(), p0 = clock_ns(CLOCK_PROCESS_CPUTIME_ID) / 1000u;
    do {
        rc = tdc_fw_run();
    } while (!tdc_lx_stop && !g_fail && !tdc_lx_opts.stream);
    if (g_bench) {
        /* cpu: the loop thread (transport + loop + panel out); proc: every
         * thread (the row workers' work too); wall: with the machine's load */
        const uint64_t cpu = bench_us() - c0;
        printf("bench: frames %llu cpu_us %llu transport_us %llu panel_us %llu loop_us %llu wall_us %llu proc_us %llu "
               "threads %u\n",
               (unsigned long long)g_frames, (unsigned long long)cpu, (unsigned long long)g_t_transport,
               (unsigned long long)g_t_panel, (unsigned long long)(cpu - g_t_transport - g_t_panel),
               (unsigned long long)(now_us() - t0),
               (unsigned long long)(clock_ns(CLOCK_PROCESS_CPUTIME_ID) / 1000u - p0), (unsigned)tdc_board_workers());
    }
    if (g_fail) return g_fail;
    if (tdc_lx_restart) return TDC_LX_EXIT_RESTART;
    return rc;
}
