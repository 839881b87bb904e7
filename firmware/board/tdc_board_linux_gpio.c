/*
 * tdc_board_linux_gpio.c - the Linux board's GPIO lines (libgpiod 1.6):
 *   --gpio-vsync L  output, toggled at every shown frame (a logic analyser
 *                   or `tdc-gpio vsync` on the host measures the refresh)
 *   --gpio-reset L  input, active low (the host's `tdc-gpio reset` drives
 *                   it): a falling edge restarts the board program
 *                   (re-exec, reset cause "pin")
 * Lines are found by name or offset on --gpio-chip.  Without --gpio-chip
 * the board has no GPIO and these are no-ops.
 */
#include <errno.h>
#include <gpiod.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tdc_board_linux.h"

static struct gpiod_chip *g_chip;
static struct gpiod_line *g_vsync, *g_reset;
static int g_level;

static struct gpiod_line *find(const char *name)
{
    char *end;
    unsigned long off = strtoul(name, &end, 10);
    struct gpiod_line *l = *end == 0 && end != name ? gpiod_chip_get_line(g_chip, (unsigned)off)
                                                    : gpiod_chip_find_line(g_chip, name);
    if (!l) tdc_lx_fail(TDC_LX_EXIT_NO_DEVICE, "gpio: no line '%s' on %s", name, tdc_lx_opts.gpio_chip);
    return l;
}

static void *reset_thread(void *arg)
{
    (void)arg;
    for (;;) {
        struct gpiod_line_event ev;
        if (gpiod_line_event_wait(g_reset, NULL) == 1 && gpiod_line_event_read(g_reset, &ev) == 0 &&
            ev.event_type == GPIOD_LINE_EVENT_FALLING_EDGE) {
            tdc_lx_logf("gpio: reset line asserted: restarting");
            gpiod_chip_close(g_chip); /* frees the lines for the new image */
            /* the same command line, reset cause pin */
            static char *argv_pin[64];
            extern char **environ;
            FILE *f = fopen("/proc/self/cmdline", "r");
            static char buf[4096];
            size_t n = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
            if (f) fclose(f);
            int k = 0;
            for (size_t i = 0; i < n && k < 60; i += strlen(buf + i) + 1) {
                if (!strcmp(buf + i, "--reset-cause")) {
                    i += strlen(buf + i) + 1; /* drop the old cause */
                    continue;
                }
                argv_pin[k++] = buf + i;
            }
            argv_pin[k++] = (char *)"--reset-cause";
            argv_pin[k++] = (char *)"pin";
            argv_pin[k] = NULL;
            execve("/proc/self/exe", argv_pin, environ);
            tdc_lx_logf("gpio: restart failed: %s", strerror(errno));
            _exit(TDC_LX_EXIT_IO);
        }
    }
    return NULL;
}

int tdc_lx_gpio_init(void)
{
    if (!tdc_lx_opts.gpio_chip) return 0;
    g_chip = gpiod_chip_open_lookup(tdc_lx_opts.gpio_chip);
    if (!g_chip) {
        tdc_lx_fail(TDC_LX_EXIT_NO_DEVICE, "gpio: cannot open GPIO chip %s: %s", tdc_lx_opts.gpio_chip, strerror(errno));
        return -1;
    }
    if (tdc_lx_opts.gpio_vsync) {
        if (!(g_vsync = find(tdc_lx_opts.gpio_vsync))) return -1;
        if (gpiod_line_request_output(g_vsync, "tdc-board", 0) != 0) {
            tdc_lx_fail(TDC_LX_EXIT_IO, "gpio: vsync line %s: %s", tdc_lx_opts.gpio_vsync, strerror(errno));
            return -1;
        }
    }
    if (tdc_lx_opts.gpio_reset) {
        if (!(g_reset = find(tdc_lx_opts.gpio_reset))) return -1;
        if (gpiod_line_request_falling_edge_events(g_reset, "tdc-board") != 0) {
            tdc_lx_fail(TDC_LX_EXIT_IO, "gpio: reset line %s: %s", tdc_lx_opts.gpio_reset, strerror(errno));
            return -1;
        }
        const int bad = tdc_lx_thread(reset_thread, NULL) != 0;
        if (bad) {
            tdc_lx_fail(TDC_LX_EXIT_IO, "gpio: cannot start the reset-line thread");
            return -1;
        }
    }
    return 0;
}

void tdc_lx_gpio_vsync(void)
{
    if (g_vsync) {
        g_level ^= 1;
        (void)gpiod_line_set_value(g_vsync, g_level);
    }
}
