/*
 * tdc_gpio_chip.h - the only interface tdc-gpio has to the GPIO library.
 * tdc_gpio_chip.c implements it on libgpiod 1.6 (Debian 12); a libgpiod 2.x
 * port replaces that one file.  Lines are requested one at a time.
 */
#ifndef TDC_GPIO_CHIP_H
#define TDC_GPIO_CHIP_H

#include <stdint.h>

typedef struct tdc_gpio_line tdc_gpio_line_t;

typedef enum {
    TDC_GPIO_OK = 0,
    TDC_GPIO_ERR_NO_CHIP = -1, /* chip not found or not openable */
    TDC_GPIO_ERR_NO_LINE = -2, /* no line with that name/offset on the chip */
    TDC_GPIO_ERR_BUSY = -3,    /* line already requested by another consumer */
    TDC_GPIO_ERR_IO = -4,      /* any other library/kernel error */
    TDC_GPIO_ERR_TIMEOUT = -5  /* no event within the timeout */
} tdc_gpio_status_t;

typedef enum { TDC_EDGE_RISING, TDC_EDGE_FALLING, TDC_EDGE_BOTH } tdc_gpio_edge_t;

/* chip: name ("gpiochip0"), path ("/dev/gpiochip0"), label or number.
 * line: a line name, or a decimal offset.  err: a human-readable reason
 * (errno text, current consumer of a busy line) is written there. */
tdc_gpio_status_t tdc_gpio_open_output(const char *chip, const char *line, int active_low, int initial_active,
                                       tdc_gpio_line_t **out, char *err, int err_cap);
tdc_gpio_status_t tdc_gpio_open_events(const char *chip, const char *line, tdc_gpio_edge_t edge, int active_low,
                                       tdc_gpio_line_t **out, char *err, int err_cap);
tdc_gpio_status_t tdc_gpio_set(tdc_gpio_line_t *l, int active);
/* Waits up to timeout_ms for the next edge; *ts_ns = kernel timestamp. */
tdc_gpio_status_t tdc_gpio_wait_edge(tdc_gpio_line_t *l, unsigned timeout_ms, uint64_t *ts_ns, int *rising);
/* Name of the chip and offset actually used, for messages. */
const char *tdc_gpio_describe(const tdc_gpio_line_t *l);
void tdc_gpio_close(tdc_gpio_line_t *l);

#endif
