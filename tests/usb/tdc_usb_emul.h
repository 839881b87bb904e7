/*
 * tdc_usb_emul.h - an emulated tdc board on an emulated usbdevfs (umockdev).
 *
 * The board is the firmware's own protocol code (firmware/tdc_usbproto.c)
 * behind a umockdev ioctl handler that plays the kernel's usbdevfs: it
 * accepts SUBMITURB, answers REAPURBNDELAY/REAPURB (libusb reaps without
 * blocking) and DISCARDURB (libusb's timeout path).  Programs started with
 * LD_PRELOAD=libumockdev-preload.so.0 and the testbed's UMOCKDEV_DIR see a
 * real-looking /sys and /dev/bus/usb and talk to it through unmodified
 * libusb.  Faults (stall, hang, unplug, flash corruption) are injected here,
 * in the "hardware", never in the program under test.
 */
#ifndef TDC_USB_EMUL_H
#define TDC_USB_EMUL_H

#include <stdint.h>
#include <umockdev.h>

#include "tdc_usbproto.h"

typedef enum {
    EMUL_FAULT_NONE = 0,
    EMUL_FAULT_STALL_BULK,    /* bulk OUT number fault_after completes with -EPIPE */
    EMUL_FAULT_HANG_BULK,     /* bulk OUT number fault_after never completes */
    EMUL_FAULT_UNPLUG,        /* after fault_after bulk OUTs the board is gone (ENODEV) */
    EMUL_FAULT_STALL_INFO,    /* the board-info request stalls */
    EMUL_FAULT_HANG_INFO,     /* the board-info request never completes */
    EMUL_FAULT_CORRUPT_FLASH, /* the flash flips one bit at byte fault_after */
    EMUL_FAULT_STALL_DNLOAD   /* DFU DNLOAD block number fault_after is lost on the wire (-EPIPE) */
} emul_fault_t;

typedef struct emul_board emul_board_t;

/* Adds a board at /dev/bus/usb/<bus>/<dev> with the given serial.
 * slot_bytes: size of each of its two DFU flash slots (A/B). */
emul_board_t *emul_board_add(UMockdevTestbed *tb, int bus, int dev, const char *serial, uint32_t slot_bytes);
/* Feeds every bulk OUT byte to the firmware's link decoder (tdc_link.h)
 * for a w x h mono panel, so the board's error counters and frame count
 * are the decoder's verdicts.  Returns 0, or -1 if the decoder refused. */
int emul_board_attach_link_decoder(emul_board_t *b, uint16_t w, uint16_t h);
void emul_board_set_fault(emul_board_t *b, emul_fault_t fault, uint32_t fault_after);
/* A flash erasing erase_unit bytes in erase_ms: a DFU block starting a
 * unit answers dfuDNBUSY with bwPollTimeout erase_ms and is written once
 * that time has passed (0: writes complete within DNLOAD, the default). */
void emul_board_set_erase(emul_board_t *b, uint32_t erase_ms, uint32_t erase_unit);
void emul_board_free(emul_board_t *b);

/* Snapshot of what the board saw (thread-safe). */
typedef struct {
    uint64_t rx_bytes;
    uint32_t rx_transfers, rx_crc; /* CRC-32 of every byte received */
    uint32_t image_bytes;          /* bytes of the image an UPLOAD returns (newest good one) */
    uint32_t slot_crc;             /* CRC-32 of those bytes in their slot */
    int active_slot;               /* the slot the board runs (A/B) */
    uint32_t active_bytes;         /* bytes of the image in it (0: the factory firmware) */
    uint32_t active_crc;           /* CRC-32 of those bytes */
    int pending;                   /* a manifested image waits for the next reset */
    uint32_t fw_version;           /* of the running firmware (from the image after activation) */
    int resets, activations;       /* board restarts; those that switched slots */
    int reset_requested;
    int dfu_state, dfu_status;
    int busy_replies; /* GETSTATUS answered dfuDNBUSY for a block (set_erase) */
    int early_polls;  /* GETSTATUS sent before that answer's bwPollTimeout ran out */
} emul_board_stats_t;
void emul_board_stats(emul_board_t *b, emul_board_stats_t *out);

#endif
