/*
 * tdc-gpio - reset a tdc board, put it in its bootloader, and measure the
 * panel's vsync / tearing-effect line (refresh rate, jitter, missed frames).
 * All GPIO library calls are in tdc_gpio_chip.c (libgpiod 1.6).
 * Usage and exit codes: docs/hosttools.md.
 */
#include <errno.h>
#include <getopt.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tdc_gpio_chip.h"
#include "tdc_tool.h"
#include "tdc_vsync_stats.h"


#define MAX_EDGES 100000

static const char usage_text[] = "usage: tdc-gpio <command> --chip CHIP --line LINE [options]\n"
                                 "  CHIP: gpiochipN, /dev/gpiochipN, a chip label or a number\n"
                                 "  LINE: a line name or an offset on that chip\n"
                                 "commands:\n"
                                 "  reset   pulse the board's reset line (active for --pulse-ms)\n"
                                 "  boot    hold --boot-line active, pulse reset, keep boot active --hold-ms,\n"
                                 "          so the board starts its bootloader (then: tdc-usb flash)\n"
                                 "  vsync   timestamp the edges of a vsync/TE line (kernel timestamps) and\n"
                                 "          report refresh rate, jitter and missed frames\n"
                                 "options:\n"
                                 "  --active-low         the reset (or vsync) line is active low\n"
                                 "  --boot-line LINE     boot: the boot-mode line (same chip)\n"
                                 "  --boot-active-low    boot: the boot-mode line is active low\n"
                                 "  --pulse-ms N         reset pulse length (default 10)\n"
                                 "  --hold-ms N          boot: keep boot active after reset (default 200)\n"
                                 "  --edge E             vsync: rising (default), falling or both\n"
                                 "  --count N            vsync: edges to record (default 121, max 100000)\n"
                                 "  --expect-hz F        vsync: nominal refresh to count missed frames (default:\n"
                                 "                       the median interval)\n"
                                 "  --timeout-ms N       vsync: give up when no edge arrives for N ms (default 1000)\n"
                                 "  -h, --help           this text\n"
                                 "exit codes (docs/tools.md): 0 OK, 1 ARGS, 2 NO_DEVICE (no chip), 4 IO, 5 TIMEOUT,\n"
                                 "  15 NO_LINE, 16 BUSY\n";

static tdc_exit_t report(const char *cmd, tdc_gpio_status_t st, const char *err)
{
    if (st == TDC_GPIO_OK) return TDC_EXIT_OK;
    fprintf(stderr, "tdc-gpio: %s: %s\n", cmd, err);
    switch (st) {
    case TDC_GPIO_ERR_NO_CHIP: return TDC_EXIT_NO_DEVICE;
    case TDC_GPIO_ERR_NO_LINE: return TDC_EXIT_NO_LINE;
    case TDC_GPIO_ERR_BUSY: return TDC_EXIT_BUSY;
    case TDC_GPIO_ERR_TIMEOUT: return TDC_EXIT_TIMEOUT;
    default: return TDC_EXIT_IO;
    }
}

static void sleep_ms(unsigned ms)
{
    struct timespec ts = {(time_t)(ms / 1000u), (long)(ms % 1000u) * 1000000L};
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {
    }
}

typedef struct {
    const char *chip, *line, *boot_line;
    int active_low, boot_active_low;
    unsigned pulse_ms, hold_ms, timeout_ms;
    long count;
    double expect_hz;
    tdc_gpio_edge_t edge;
} opts_t;

static tdc_exit_t pulse_reset(const opts_t *o, const char *cmd)
{
    char err[256] = "";
    tdc_gpio_line_t *rst = NULL;
    tdc_gpio_status_t st = tdc_gpio_open_output(o->chip, o->line, o->active_low, 1, &rst, err, sizeof err);
    if (st != TDC_GPIO_OK) return report(cmd, st, err);
    sleep_ms(o->pulse_ms);
    st = tdc_gpio_set(rst, 0);
    printf("%s: reset pulse %u ms on %s\n", cmd, o->pulse_ms, tdc_gpio_describe(rst));
    tdc_gpio_close(rst);
    return report(cmd, st, "cannot release reset");
}

static tdc_exit_t cmd_boot(const opts_t *o)
{
    char err[256] = "";
    tdc_gpio_line_t *boot = NULL;
    tdc_gpio_status_t st = tdc_gpio_open_output(o->chip, o->boot_line, o->boot_active_low, 1, &boot, err, sizeof err);
    if (st != TDC_GPIO_OK) return report("boot", st, err);
    tdc_exit_t e = pulse_reset(o, "boot");
    if (e == TDC_EXIT_OK) {
        sleep_ms(o->hold_ms);
        printf("boot: boot-mode line %s held %u ms after reset: board should be in its "
               "bootloader\n",
               tdc_gpio_describe(boot), o->hold_ms);
    }
    tdc_gpio_set(boot, 0);
    tdc_gpio_close(boot);
    return e;
}

static volatile sig_atomic_t stop_requested;
static void on_sigint(int sig)
{
    (void)sig;
    stop_requested = 1;
}

static tdc_exit_t cmd_vsync(const opts_t *o)
{
    char err[256] = "";
    tdc_gpio_line_t *l = NULL;
    tdc_gpio_status_t st = tdc_gpio_open_events(o->chip, o->line, o->edge, o->active_low, &l, err, sizeof err);
    if (st != TDC_GPIO_OK) return report("vsync", st, err);
    uint64_t *ts = malloc((size_t)o->count * sizeof *ts);
    if (ts == NULL) {
        tdc_gpio_close(l);
        return TDC_EXIT_IO;
    }
    signal(SIGINT, on_sigint);
    long n = 0;
    while (n < o->count && !stop_requested) {
        int rising = 0;
        st = tdc_gpio_wait_edge(l, o->timeout_ms, &ts[n], &rising);
        if (st != TDC_GPIO_OK) break;
        n++;
    }
    char desc[128];
    snprintf(desc, sizeof desc, "%s", tdc_gpio_describe(l));
    tdc_gpio_close(l);
    tdc_exit_t e = TDC_EXIT_OK;
    if (st == TDC_GPIO_ERR_TIMEOUT) {
        fprintf(stderr, "tdc-gpio: vsync: no edge on %s for %u ms after %ld edges%s\n", desc, o->timeout_ms, n,
                n < 2 ? " (is the panel running?)" : "");
        e = TDC_EXIT_TIMEOUT;
    } else if (st != TDC_GPIO_OK) {
        fprintf(stderr, "tdc-gpio: vsync: reading events on %s failed: %s\n", desc, strerror(errno));
        e = TDC_EXIT_IO;
    }
    tdc_vsync_stats_t s;
    if (n >= 2 && tdc_vsync_analyse(ts, (size_t)n, o->expect_hz, &s) == 0) {
        printf("vsync on %s: %zu edges, refresh %.3f Hz (nominal period %.1f us), "
               "jitter rms %.1f us p-p %.1f us, interval %.1f..%.1f us, missed frames %u\n",
               desc, s.edges, s.refresh_hz, s.period_us, s.jitter_rms_us, s.jitter_pp_us, s.min_interval_us,
               s.max_interval_us, s.missed);
    } else if (e == TDC_EXIT_OK) {
        fprintf(stderr, "tdc-gpio: vsync: fewer than 2 edges, nothing to measure\n");
        e = TDC_EXIT_TIMEOUT;
    }
    free(ts);
    return e;
}

static int parse_ulong(const char *s, unsigned long lo, unsigned long hi, unsigned long *v)
{
    uint64_t x;
    if (tdc_parse_u64(s, lo, hi, &x) != 0) return -1;
    *v = (unsigned long)x;
    return 0;
}

int main(int argc, char **argv)
{
    opts_t o = {.pulse_ms = 10, .hold_ms = 200, .timeout_ms = 1000, .count = 121, .edge = TDC_EDGE_RISING};
    enum { O_CHIP = 256, O_LINE, O_BOOT, O_AL, O_BAL, O_PULSE, O_HOLD, O_EDGE, O_COUNT, O_HZ, O_TMO };
    static const struct option lopts[] = {{"chip", 1, 0, O_CHIP},
                                          {"line", 1, 0, O_LINE},
                                          {"boot-line", 1, 0, O_BOOT},
                                          {"active-low", 0, 0, O_AL},
                                          {"boot-active-low", 0, 0, O_BAL},
                                          {"pulse-ms", 1, 0, O_PULSE},
                                          {"hold-ms", 1, 0, O_HOLD},
                                          {"edge", 1, 0, O_EDGE},
                                          {"count", 1, 0, O_COUNT},
                                          {"expect-hz", 1, 0, O_HZ},
                                          {"timeout-ms", 1, 0, O_TMO},
                                          {"help", 0, 0, 'h'},
                                          {0, 0, 0, 0}};
    int c;
    unsigned long v;
    tdc_tool_set_name("tdc-gpio");
    opterr = 0; /* tdc_fail_getopt() writes the one line */
    while ((c = getopt_long(argc, argv, ":h", lopts, NULL)) != -1) {
        const char *bad = NULL;
        switch (c) {
        case O_CHIP: o.chip = optarg; break;
        case O_LINE: o.line = optarg; break;
        case O_BOOT: o.boot_line = optarg; break;
        case O_AL: o.active_low = 1; break;
        case O_BAL: o.boot_active_low = 1; break;
        case O_PULSE:
            if (parse_ulong(optarg, 1, 60000, &v))
                bad = "--pulse-ms";
            else
                o.pulse_ms = (unsigned)v;
            break;
        case O_HOLD:
            if (parse_ulong(optarg, 0, 60000, &v))
                bad = "--hold-ms";
            else
                o.hold_ms = (unsigned)v;
            break;
        case O_TMO:
            if (parse_ulong(optarg, 1, 600000, &v))
                bad = "--timeout-ms";
            else
                o.timeout_ms = (unsigned)v;
            break;
        case O_COUNT:
            if (parse_ulong(optarg, 2, MAX_EDGES, &v))
                bad = "--count";
            else
                o.count = (long)v;
            break;
        case O_HZ:
            if (tdc_parse_double(optarg, 1e-3, 99999.0, &o.expect_hz)) bad = "--expect-hz";
            break;
        case O_EDGE:
            if (strcmp(optarg, "rising") == 0)
                o.edge = TDC_EDGE_RISING;
            else if (strcmp(optarg, "falling") == 0)
                o.edge = TDC_EDGE_FALLING;
            else if (strcmp(optarg, "both") == 0)
                o.edge = TDC_EDGE_BOTH;
            else
                bad = "--edge";
            break;
        case 'h': fputs(usage_text, stdout); return TDC_EXIT_OK;
        default: return tdc_fail_getopt(c, argv);
        }
        if (bad != NULL) {
            return tdc_fail_option(NULL, bad, optarg, "see tdc-gpio --help");
        }
    }
    if (optind != argc - 1) {
        return tdc_fail_usage(NULL, optind < argc ? "one command, got %d words" : "no command (reset, boot or vsync)",
                              argc - optind);
    }
    const char *cmd = argv[optind];
    if (strcmp(cmd, "reset") != 0 && strcmp(cmd, "boot") != 0 && strcmp(cmd, "vsync") != 0) {
        fprintf(stderr, "tdc-gpio: unknown command '%s'\n", cmd);
        return TDC_EXIT_ARGS;
    }
    if (o.chip == NULL || o.line == NULL || (strcmp(cmd, "boot") == 0 && o.boot_line == NULL)) {
        fprintf(stderr, "tdc-gpio: %s needs --chip and --line%s\n", cmd,
                strcmp(cmd, "boot") == 0 ? " and --boot-line" : "");
        return TDC_EXIT_ARGS;
    }
    if (strcmp(cmd, "reset") == 0) return (int)pulse_reset(&o, "reset");
    if (strcmp(cmd, "boot") == 0) return (int)cmd_boot(&o);
    return (int)cmd_vsync(&o);
}
