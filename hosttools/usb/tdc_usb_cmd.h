/*
 * tdc_usb_cmd.h - what the tdc-usb commands share: options, the decoded
 * board info, timing/progress helpers, and the flash commands
 * (tdc_usb_dfu.c).  The listing, info and stream commands and main() are
 * in tdc_usb.c.
 */
#ifndef TDC_USB_CMD_H
#define TDC_USB_CMD_H

#include <stdint.h>

#include "tdc_usb_dev.h"
#include "tdc_usb_reply.h"
#include "tdc_usbproto.h"

#define DEFAULT_TIMEOUT_MS 2000u
#define DFU_STATUS_DEADLINE_MS 10000u /* whole GETSTATUS polling loop of one step */

typedef struct {
    tdc_usb_select_t sel;
    long chunk;
    int progress; /* -1 auto (tty), 0 off, 1 on */
    int verify, reset;
    const char *board;
    uint32_t fw_version;
} opts_t;


double tdc_usb_now_s(void);
void tdc_usb_progress(const opts_t *o, const char *label, uint64_t done, uint64_t total, double t0);
void tdc_usb_progress_end(const opts_t *o);
tdc_exit_t tdc_usb_get_info(tdc_board_t *b, board_info_t *bi);

/* tdc_usb_dfu.c */
tdc_exit_t tdc_usb_read_file(const char *path, const char *op, uint8_t **data, uint32_t *len);
tdc_exit_t tdc_usb_load_image(const char *path, uint16_t vid, uint16_t pid, uint8_t **image, uint32_t *image_len);
tdc_exit_t tdc_usb_cmd_flash(tdc_board_t *b, const opts_t *o, const char *path, const uint8_t *img, uint32_t len);
tdc_exit_t tdc_usb_cmd_mkimage(const opts_t *o, const char *in, const char *out);

#endif
