/*
 * tdc_gpio_chip.c - tdc_gpio_chip.h on libgpiod 1.6 (the API Debian 12
 * ships).  Every libgpiod call of tdc-gpio is in this file.
 * Event timestamps: libgpiod 1.6 returns the kernel's timestamp of the edge
 * (CLOCK_MONOTONIC on Linux >= 5.7 by default), taken in the interrupt
 * handler, so user-space scheduling delay does not enter the jitter figures.
 */
#include "tdc_gpio_chip.h"

#include <errno.h>
#include <gpiod.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CONSUMER "tdc-gpio"

struct tdc_gpio_line {
    struct gpiod_chip *chip;
    struct gpiod_line *line;
    char desc[96];
};

static tdc_gpio_status_t find_line(const char *chip, const char *line, tdc_gpio_line_t **out, char *err, int err_cap)
{
    tdc_gpio_line_t *l = calloc(1, sizeof *l);
    if (l == NULL) return TDC_GPIO_ERR_IO;
    errno = 0;
    l->chip = gpiod_chip_open_lookup(chip);
    if (l->chip == NULL) {
        snprintf(err, (size_t)err_cap, "cannot open GPIO chip '%s': %s", chip,
                 errno != 0 ? strerror(errno) : "not found");
        free(l);
        return TDC_GPIO_ERR_NO_CHIP;
    }
    char *end = NULL;
    unsigned long off = strtoul(line, &end, 10);
    if (end != line && *end == '\0') {
        if (off >= gpiod_chip_num_lines(l->chip)) {
            snprintf(err, (size_t)err_cap, "chip %s has %u lines, no offset %lu", gpiod_chip_name(l->chip),
                     gpiod_chip_num_lines(l->chip), off);
            tdc_gpio_close(l);
            return TDC_GPIO_ERR_NO_LINE;
        }
        l->line = gpiod_chip_get_line(l->chip, (unsigned)off);
    } else {
        l->line = gpiod_chip_find_line(l->chip, line);
    }
    if (l->line == NULL) {
        snprintf(err, (size_t)err_cap, "no line '%s' on chip %s (%s)", line, gpiod_chip_name(l->chip),
                 gpiod_chip_label(l->chip));
        tdc_gpio_close(l);
        return TDC_GPIO_ERR_NO_LINE;
    }
    snprintf(l->desc, sizeof l->desc, "%s line %u%s%s", gpiod_chip_name(l->chip), gpiod_line_offset(l->line),
             gpiod_line_name(l->line) ? " " : "", gpiod_line_name(l->line) ? gpiod_line_name(l->line) : "");
    if (gpiod_line_is_used(l->line)) {
        snprintf(err, (size_t)err_cap, "%s is in use by '%s'", l->desc,
                 gpiod_line_consumer(l->line) ? gpiod_line_consumer(l->line) : "the kernel");
        tdc_gpio_close(l);
        return TDC_GPIO_ERR_BUSY;
    }
    *out = l;
    return TDC_GPIO_OK;
}

/* libgpiod 1.6 has one request call per direction and edge kind, each with
 * the consumer name and the flags; arg is the initial level or the edge. */
typedef int (*request_fn)(struct gpiod_line *line, int flags, int arg);

static int request_output(struct gpiod_line *line, int flags, int initial_active)
{
    return gpiod_line_request_output_flags(line, CONSUMER, flags, initial_active ? 1 : 0);
}

static int request_events(struct gpiod_line *line, int flags, int edge)
{
    return edge == TDC_EDGE_RISING    ? gpiod_line_request_rising_edge_events_flags(line, CONSUMER, flags)
           : edge == TDC_EDGE_FALLING ? gpiod_line_request_falling_edge_events_flags(line, CONSUMER, flags)
                                      : gpiod_line_request_both_edges_events_flags(line, CONSUMER, flags);
}

/* Finds the line and requests it; a refused request closes it again and
 * says why (EBUSY: another consumer took it in between). */
static tdc_gpio_status_t open_line(const char *chip, const char *line, int active_low, request_fn request, int arg,
                                   tdc_gpio_line_t **out, char *err, int err_cap)
{
    tdc_gpio_line_t *l = NULL;
    tdc_gpio_status_t st = find_line(chip, line, &l, err, err_cap);
    if (st != TDC_GPIO_OK) return st;
    if (request(l->line, active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0, arg) != 0) {
        int e = errno;
        snprintf(err, (size_t)err_cap, "cannot request %s: %s", l->desc, strerror(e));
        tdc_gpio_close(l);
        return e == EBUSY ? TDC_GPIO_ERR_BUSY : TDC_GPIO_ERR_IO;
    }
    *out = l;
    return TDC_GPIO_OK;
}

tdc_gpio_status_t tdc_gpio_open_output(const char *chip, const char *line, int active_low, int initial_active,
                                       tdc_gpio_line_t **out, char *err, int err_cap)
{
    return open_line(chip, line, active_low, request_output, initial_active, out, err, err_cap);
}

tdc_gpio_status_t tdc_gpio_open_events(const char *chip, const char *line, tdc_gpio_edge_t edge, int active_low,
                                       tdc_gpio_line_t **out, char *err, int err_cap)
{
    return open_line(chip, line, active_low, request_events, (int)edge, out, err, err_cap);
}

tdc_gpio_status_t tdc_gpio_set(tdc_gpio_line_t *l, int active)
{
    return gpiod_line_set_value(l->line, active ? 1 : 0) == 0 ? TDC_GPIO_OK : TDC_GPIO_ERR_IO;
}

tdc_gpio_status_t tdc_gpio_wait_edge(tdc_gpio_line_t *l, unsigned timeout_ms, uint64_t *ts_ns, int *rising)
{
    struct timespec to = {(time_t)(timeout_ms / 1000u), (long)(timeout_ms % 1000u) * 1000000L};
    int r = gpiod_line_event_wait(l->line, &to);
    if (r == 0) return TDC_GPIO_ERR_TIMEOUT;
    if (r < 0) return TDC_GPIO_ERR_IO;
    struct gpiod_line_event ev;
    if (gpiod_line_event_read(l->line, &ev) != 0) return TDC_GPIO_ERR_IO;
    *ts_ns = (uint64_t)ev.ts.tv_sec * 1000000000u + (uint64_t)ev.ts.tv_nsec;
    *rising = ev.event_type == GPIOD_LINE_EVENT_RISING_EDGE;
    return TDC_GPIO_OK;
}

const char *tdc_gpio_describe(const tdc_gpio_line_t *l)
{
    return l->desc;
}

void tdc_gpio_close(tdc_gpio_line_t *l)
{
    if (l == NULL) return;
    if (l->line != NULL && gpiod_line_is_requested(l->line)) gpiod_line_release(l->line);
    if (l->chip != NULL) gpiod_chip_close(l->chip);
    free(l);
}
