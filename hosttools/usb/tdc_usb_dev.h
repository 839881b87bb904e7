/*
 * tdc_usb_dev.h - the libusb layer of tdc-usb: named exit codes, board
 * selection, and transfer wrappers that always carry an explicit timeout
 * and turn every libusb error into one message naming it.
 */
#ifndef TDC_USB_DEV_H
#define TDC_USB_DEV_H

#include <stdint.h>
#include <libusb.h>

#include "tdc_tool.h"

/* Exit codes: the shared table of every tdc program (docs/tools.md). */

typedef struct {
    uint16_t vid, pid;
    int bus, address;    /* -1 = any */
    const char *serial;  /* NULL = any */
    unsigned timeout_ms; /* every transfer */
} tdc_usb_select_t;

typedef struct {
    libusb_context *ctx;
    libusb_device_handle *h;
    int bus, address;
    char serial[64];
    unsigned timeout_ms;
    const char *op;        /* what we are doing, for messages */
    uint8_t ep_out, ep_in; /* bulk endpoints of the streaming interface */
} tdc_board_t;

/* Maps a libusb error to the exit code and prints
 * "tdc-usb: <op>: <what>: LIBUSB_ERROR_X (text)". */
tdc_exit_t tdc_usb_fail(const tdc_board_t *b, const char *what, int libusb_err);

/* Enumerates; one callback per matching board (after the serial filter).
 * Returns the number of matches, or a negative libusb error. */
typedef void (*tdc_usb_list_fn)(void *ctx, libusb_device *dev, libusb_device_handle *h, const char *serial,
                                int open_err);
int tdc_usb_enumerate(libusb_context *ctx, const tdc_usb_select_t *sel, tdc_usb_list_fn fn, void *fn_ctx);

/* Opens exactly one board; refuses none or several with a message. */
tdc_exit_t tdc_usb_open(libusb_context *ctx, const tdc_usb_select_t *sel, tdc_board_t *b);
void tdc_usb_close(tdc_board_t *b);
tdc_exit_t tdc_usb_claim(tdc_board_t *b, int iface);

/* Transfers.  Return TDC_EXIT_OK or the mapped error (message printed). */
tdc_exit_t tdc_usb_ctrl_in(tdc_board_t *b, const char *what, uint8_t type, uint8_t req, uint16_t value, uint16_t index,
                           uint8_t *data, uint16_t len, int *got);
tdc_exit_t tdc_usb_ctrl_out(tdc_board_t *b, const char *what, uint8_t type, uint8_t req, uint16_t value, uint16_t index,
                            const uint8_t *data, uint16_t len);
tdc_exit_t tdc_usb_bulk(tdc_board_t *b, const char *what, uint8_t ep, uint8_t *data, int len, int *done);

/* String descriptor as ASCII with an explicit timeout. */
int tdc_usb_string_ascii(libusb_device_handle *h, uint8_t index, char *out, int cap, unsigned timeout_ms);

#endif
