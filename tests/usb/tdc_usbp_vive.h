/*
 * tdc_usbp_vive.h - the protocol configuration of the test boards that
 * report an HTC Vive panel (2160 x 1200 at 90 Hz): the emulated board
 * (tdc_usb_emul.c), the protocol's unit test and its fuzzer differ only in
 * names, firmware version, receive buffer and the flash behind them.
 * Header-only, so the fuzzer (its own include path) takes it by path.
 */
#ifndef TDC_USBP_VIVE_H
#define TDC_USBP_VIVE_H

#include "tdc_usbproto.h"

/* rx_bytes is both the receive buffer and the largest packet. */
static inline tdc_usbp_config_t tdc_usbp_vive_config(const char *board, const char *serial, uint32_t fw_version,
                                                     uint32_t rx_bytes, tdc_usbp_flash_t flash)
{
    const tdc_usbp_config_t cfg = {.board_name = board,
                                   .panel_name = "htc-vive",
                                   .serial = serial,
                                   .fw_version = fw_version,
                                   .panel_width = 2160,
                                   .panel_height = 1200,
                                   .refresh_mhz = 90000u,
                                   .rx_buffer_bytes = rx_bytes,
                                   .max_packet_bytes = rx_bytes,
                                   .flash = flash};
    return cfg;
}

#endif
