/*
 * tdc_usb_reply.h - tdc-usb's parsing of what a board sends back (board
 * info, DFU functional descriptor, string descriptors, status reports),
 * separate from libusb so it can be fuzzed (tests/fuzz/fuzz_usbreply.c).
 * Every function takes the bytes received and their count and reads
 * nothing beyond them.
 */
#ifndef TDC_USB_REPLY_H
#define TDC_USB_REPLY_H

#include <stdint.h>

#include "tdc_usbproto.h"

typedef struct {
    uint32_t fw_version;
    char board[TDC_USB_INFO_NAME_LEN + 1], panel[TDC_USB_INFO_NAME_LEN + 1];
    unsigned width, height;
    uint32_t refresh_mhz, rx_buf, max_pkt, slot;
    uint32_t rx_xfers, rx_crc, link_crc, link_bad, overruns, dfu_errors, stalls, frames;
    uint64_t rx_bytes;
} board_info_t;

/* BOARD_INFO reply of got bytes: 0 and *bi filled (names NUL-terminated),
 * or -1 when it is short, has another magic or protocol version. */
int tdc_usb_parse_info(const uint8_t *raw, int got, board_info_t *bi);

/* wTransferSize of the DFU functional descriptor (type 0x21, DFU 1.0's
 * 7 bytes or 1.1's 9) among an interface's extra descriptors; dflt when
 * there is none or its value is outside 64..4096. */
uint16_t tdc_usb_dfu_transfer_size(const uint8_t *extra, int len, uint16_t dflt);

/* A string descriptor of r bytes as ASCII into out (cap bytes, always
 * NUL-terminated; non-ASCII characters become '?'): the length, or -1 when
 * it is not a string descriptor. */
int tdc_usb_string_decode(const uint8_t *buf, int r, char *out, int cap);

/* A bulk IN status report of got bytes: 0, or -1 when short or with
 * another magic. */
typedef struct {
    uint32_t seq, errors, frames;
    uint8_t dfu_state, dfu_status;
} tdc_usb_status_t;
int tdc_usb_parse_status(const uint8_t *st, int got, tdc_usb_status_t *out);

#endif
