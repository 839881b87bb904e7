/*
 * tdc_ffs_board.c - a tdc board made of the Linux USB gadget stack: a
 * FunctionFS function whose ep0 / bulk endpoints are served by the
 * firmware's protocol code (firmware/tdc_usbproto.c), bound to dummy_hcd
 * inside the `make test-vm` VM.  The host side (tdc-usb, libusb, usbfs,
 * usbcore) then talks to it through the real kernel.
 *
 * Bulk OUT bytes go through the firmware's link decoder (32x24 mono panel),
 * so the counters tdc-usb reports are the decoder's verdicts.
 * Usage: tdc_ffs_board <functionfs mount dir> <serial>
 * Writes descriptors and strings to ep0, prints "ready" on stdout once the
 * endpoints exist (the init script then binds the UDC), and serves forever.
 * Static build, no libraries beyond libc/pthread.  The Linux board
 * (BOARD=linux, firmware/board/tdc_board_linux_ffs.c) is the product; this
 * fixture stays for the protocol checks on a 32x24 test panel.
 */
#include <endian.h>
#include <errno.h>
#include <fcntl.h>
#include <linux/usb/functionfs.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tdc_ffs.h" /* descriptors and ep0 requests, shared with the Linux board */
#include "tdc_link_sink.h"
#include "tdc_usbproto.h"

#define SLOT_BYTES (256u * 1024u)

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static tdc_usbp_t proto;
static uint8_t slot[2 * SLOT_BYTES]; /* A/B: slot k at k * SLOT_BYTES */
static char dir[256];
static tdc_link_sink_t link_sink; /* the firmware link decoder, 32x24 mono */

static int flash_write(void *ctx, uint32_t off, const uint8_t *d, uint32_t n)
{
    (void)ctx;
    if ((uint64_t)off + n > 2u * SLOT_BYTES) return -1;
    memcpy(slot + off, d, n);
    return 0;
}

static int flash_read(void *ctx, uint32_t off, uint8_t *d, uint32_t n)
{
    (void)ctx;
    if ((uint64_t)off + n > 2u * SLOT_BYTES) return -1;
    memcpy(d, slot + off, n);
    return 0;
}

/* The board restarts (USB bus reset, seen as FUNCTIONFS_DISABLE, or its
 * own reset after RESET_BOARD): a manifested image becomes the running one.
 * Called with the lock held. */
static void board_reboot(const char *why)
{
    if (tdc_usbp_bus_reset(&proto)) {
        const uint8_t *hdr = slot + (size_t)proto.dfu_active_slot * SLOT_BYTES;
        proto.cfg.fw_version = tdc_get_le32(hdr + TDC_IMAGE_OFF_FW_VERSION);
        printf("tdc_ffs_board: %s: activated slot %u, firmware %u.%u.%u, %u bytes\n", why, proto.dfu_active_slot,
               proto.cfg.fw_version >> 16, (proto.cfg.fw_version >> 8) & 0xFFu, proto.cfg.fw_version & 0xFFu,
               tdc_usbp_slot_image(&proto, proto.dfu_active_slot));
        fflush(stdout);
    }
}

static int open_ep(const char *name, int flags)
{
    char path[300];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return open(path, flags);
}

/* Bulk OUT: link packets into the protocol's accounting. */
static void *bulk_out_thread(void *arg)
{
    static uint8_t buf[65536];
    (void)arg;
    for (;;) {
        int fd = open_ep("ep1", O_RDWR);
        while (fd >= 0) {
            ssize_t n = read(fd, buf, sizeof buf);
            if (n < 0) break; /* disabled / unbound: reopen */
            pthread_mutex_lock(&lock);
            tdc_usbp_bulk_out(&proto, buf, (uint32_t)n);
            pthread_mutex_unlock(&lock);
        }
        if (fd >= 0) close(fd);
        usleep(20000);
    }
    return NULL;
}

/* Bulk IN: status reports (firmware/board/tdc_ffs.c). */
static void *bulk_in_thread(void *arg)
{
    (void)arg;
    char path[300];
    snprintf(path, sizeof path, "%s/ep2", dir);
    tdc_ffs_status_loop(path, &proto, &lock);
    return NULL;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: tdc_ffs_board <functionfs dir> <serial>\n");
        return 1;
    }
    snprintf(dir, sizeof dir, "%s", argv[1]);
    tdc_usbp_config_t cfg = {.board_name = "vm-gadget",
                             .panel_name = "vm-32x24",
                             .serial = argv[2],
                             .fw_version = 0x000100u,
                             .panel_width = 32,
                             .panel_height = 24,
                             .refresh_mhz = 90000u,
                             .rx_buffer_bytes = 16384u,
                             .max_packet_bytes = 65536u,
                             .flash = {flash_write, flash_read, NULL, SLOT_BYTES, NULL}, /* writes within DNLOAD */
                             .sink = tdc_link_sink_feed,
                             .sink_ctx = &link_sink};
    if (tdc_link_sink_init(&link_sink, 32, 24) != 0) {
        fprintf(stderr, "tdc_ffs_board: link decoder init failed\n");
        return 1;
    }
    if (tdc_usbp_init(&proto, &cfg) != TDC_OK) {
        fprintf(stderr, "tdc_ffs_board: USB protocol init failed\n");
        return 1;
    }
    int ep0 = open_ep("ep0", O_RDWR);
    if (ep0 < 0) {
        perror("tdc_ffs_board: open ep0");
        return 1;
    }
    if (tdc_ffs_write_descriptors(ep0) != 0) {
        perror("tdc_ffs_board: writing descriptors");
        return 1;
    }
    pthread_t t1, t2;
    pthread_create(&t1, NULL, bulk_out_thread, NULL);
    pthread_create(&t2, NULL, bulk_in_thread, NULL);
    printf("ready\n");
    fflush(stdout);
    for (;;) {
        struct usb_functionfs_event ev[4];
        ssize_t n = read(ep0, ev, sizeof ev);
        if (n < 0) {
            if (errno == EINTR || errno == EAGAIN) continue;
            perror("tdc_ffs_board: ep0 events");
            usleep(20000);
            continue;
        }
        for (ssize_t i = 0; i < n / (ssize_t)sizeof ev[0]; i++) {
            if (ev[i].type == FUNCTIONFS_SETUP) {
                tdc_ffs_setup(ep0, &ev[i].u.setup, &proto, &lock, board_reboot);
            } else if (ev[i].type == FUNCTIONFS_DISABLE) { /* bus reset (dfu-util -R) or unplug */
                pthread_mutex_lock(&lock);
                board_reboot("USB reset");
                pthread_mutex_unlock(&lock);
            }
        }
    }
}
