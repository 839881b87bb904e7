/*
 * tdc_ffs.c - the USB protocol (firmware/tdc_usbproto.c) on a Linux
 * FunctionFS function: its descriptors and the handling of ep0 SETUP
 * events.  Shared by the Linux board (tdc_board_linux_ffs.c) and the
 * test-vm fixture tests/vm/tdc_ffs_board.c.
 */
#include <endian.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "tdc_ffs.h"

/* The function's descriptors: the configuration descriptor minus its 9-byte
 * header and minus the 9-byte DFU functional descriptor at its end: Linux
 * 6.1's FunctionFS accepts class descriptors (type 0x21) only inside HID
 * and CCID interfaces (ffs_do_single_desc() in
 * drivers/usb/gadget/function/f_fs.c, `case USB_TYPE_CLASS | 0x01`), so
 * hosts use the protocol's wTransferSize of 1024 (dfu-util: -t 1024). */
#define FN_DESC_LEN (TDC_USB_CONFIG_DESC_LEN - 18u)

int tdc_ffs_write_descriptors(int ep0)
{
    struct {
        struct usb_functionfs_descs_head_v2 head;
        uint32_t fs_count, hs_count;
        uint8_t fs[FN_DESC_LEN], hs[FN_DESC_LEN];
    } __attribute__((packed)) d;
    uint8_t cfg[TDC_USB_CONFIG_DESC_LEN];
    d.head.magic = htole32(FUNCTIONFS_DESCRIPTORS_MAGIC_V2);
    d.head.length = htole32(sizeof d);
    d.head.flags = htole32(FUNCTIONFS_HAS_FS_DESC | FUNCTIONFS_HAS_HS_DESC);
    d.fs_count = htole32(4);
    d.hs_count = htole32(4);
    (void)tdc_usbp_config_descriptor(cfg, 0);
    memcpy(d.fs, cfg + 9, FN_DESC_LEN);
    (void)tdc_usbp_config_descriptor(cfg, 1);
    memcpy(d.hs, cfg + 9, FN_DESC_LEN);
    /* FunctionFS numbers a function's strings from 1 (its own table below) */
    d.fs[8] = d.hs[8] = 1;   /* iInterface of the streaming interface */
    d.fs[31] = d.hs[31] = 2; /* iInterface of the DFU interface */
    struct {
        struct usb_functionfs_strings_head head;
        uint16_t code;
        char s1[sizeof "tdc link stream"], s2[sizeof "tdc DFU (A/B slot)"];
    } __attribute__((packed)) s;
    s.head.magic = htole32(FUNCTIONFS_STRINGS_MAGIC);
    s.head.length = htole32(sizeof s);
    s.head.str_count = htole32(2);
    s.head.lang_count = htole32(1);
    s.code = htole16(0x0409);
    memcpy(s.s1, "tdc link stream", sizeof s.s1);
    memcpy(s.s2, "tdc DFU (A/B slot)", sizeof s.s2);
    if (write(ep0, &d, sizeof d) != (ssize_t)sizeof d || write(ep0, &s, sizeof s) != (ssize_t)sizeof s) return -1;
    return 0;
}

static void stall(int ep0, int in)
{
    /* FunctionFS: an I/O in the wrong direction stalls ep0 (EL2HLT) */
    if ((in ? read(ep0, NULL, 0) : write(ep0, NULL, 0)) < 0 && errno != EL2HLT) {
        fprintf(stderr, "usb: ep0: stall: %s\n", strerror(errno));
    }
}

void tdc_ffs_setup(int ep0, const struct usb_ctrlrequest *c, tdc_usbp_t *proto, pthread_mutex_t *lock,
                   void (*on_reset)(const char *why))
{
    static uint8_t data[4096], reply[4096];
    tdc_usbp_setup_t s = {c->bRequestType, c->bRequest, le16toh(c->wValue), le16toh(c->wIndex), le16toh(c->wLength)};
    uint32_t len = 0;
    if (s.bm_request_type & 0x80u) {
        pthread_mutex_lock(lock);
        tdc_status_t r = tdc_usbp_control(proto, &s, NULL, reply, sizeof reply, &len);
        pthread_mutex_unlock(lock);
        if (r != TDC_OK) {
            stall(ep0, 1);
        } else if (write(ep0, reply, len) < 0) {
            fprintf(stderr, "usb: ep0: reply: %s\n", strerror(errno));
        }
        return;
    }
    if (s.w_length > sizeof data) {
        stall(ep0, 0);
        return;
    }
    /* OUT: the data stage is read first (reading acks the status stage), so
     * a refused DNLOAD shows up in the next GETSTATUS as dfuERROR (DFU 1.1). */
    if (s.w_length > 0 && read(ep0, data, s.w_length) != s.w_length) {
        fprintf(stderr, "usb: ep0: data stage: %s\n", strerror(errno));
        return;
    }
    pthread_mutex_lock(lock);
    tdc_status_t r = tdc_usbp_control(proto, &s, data, reply, sizeof reply, &len);
    if (tdc_usbp_take_reset(proto)) on_reset("RESET_BOARD");
    pthread_mutex_unlock(lock);
    if (s.w_length == 0) {
        if (r != TDC_OK) {
            stall(ep0, 0);
        } else if (read(ep0, NULL, 0) < 0) {
            fprintf(stderr, "usb: ep0: status stage: %s\n", strerror(errno));
        }
    }
}

void tdc_ffs_status_loop(const char *ep2_path, tdc_usbp_t *proto, pthread_mutex_t *lock)
{
    for (;;) {
        int fd = open(ep2_path, O_RDWR | O_CLOEXEC);
        while (fd >= 0) {
            uint8_t rep[TDC_USB_STATUS_LEN];
            pthread_mutex_lock(lock);
            tdc_usbp_status_report(proto, rep);
            pthread_mutex_unlock(lock);
            if (write(fd, rep, sizeof rep) < 0) break; /* disabled / unbound: reopen */
        }
        if (fd >= 0) close(fd);
        usleep(20000);
    }
}
