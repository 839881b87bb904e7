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
 * Static build, no libraries beyond libc/pthread.
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

#include "tdc_link_sink.h"
#include "tdc_usbproto.h"

#define SLOT_BYTES (256u * 1024u)
/* The function's descriptors: the configuration descriptor minus its 9-byte
 * header and minus the 9-byte DFU functional descriptor at its end.  Linux
 * 6.1's FunctionFS accepts class descriptors (type 0x21) only inside HID and
 * CCID interfaces: ffs_do_single_desc() in drivers/usb/gadget/function/f_fs.c,
 * `case USB_TYPE_CLASS | 0x01`, returns -EINVAL for any other interface
 * class ("unknown descriptor"), so this gadget cannot carry it.  tdc-usb
 * then uses the protocol's wTransferSize (1024) and dfu-util needs `-t 1024`
 * (tests/vm/init.sh).  Boards and the umockdev emulation send it. */
#define FN_DESC_LEN (TDC_USB_CONFIG_DESC_LEN - 18u)

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

static void write_descriptors(int ep0)
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
    tdc_usbp_config_descriptor(cfg, 0);
    memcpy(d.fs, cfg + 9, FN_DESC_LEN);
    tdc_usbp_config_descriptor(cfg, 1);
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
    if (write(ep0, &d, sizeof d) != (ssize_t)sizeof d || write(ep0, &s, sizeof s) != (ssize_t)sizeof s) {
        perror("tdc_ffs_board: writing descriptors");
        exit(1);
    }
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

/* Bulk IN: a status report is always queued; each write completes when the host reads. */
static void *bulk_in_thread(void *arg)
{
    (void)arg;
    for (;;) {
        int fd = open_ep("ep2", O_RDWR);
        while (fd >= 0) {
            uint8_t rep[TDC_USB_STATUS_LEN];
            pthread_mutex_lock(&lock);
            tdc_usbp_status_report(&proto, rep);
            pthread_mutex_unlock(&lock);
            if (write(fd, rep, sizeof rep) < 0) break;
        }
        if (fd >= 0) close(fd);
        usleep(20000);
    }
    return NULL;
}

static void handle_setup(int ep0, const struct usb_ctrlrequest *c)
{
    static uint8_t data[4096], reply[4096];
    tdc_usbp_setup_t s = {c->bRequestType, c->bRequest, le16toh(c->wValue), le16toh(c->wIndex), le16toh(c->wLength)};
    uint32_t len = 0;
    if (s.bm_request_type & 0x80u) {
        pthread_mutex_lock(&lock);
        tdc_status_t r = tdc_usbp_control(&proto, &s, NULL, reply, sizeof reply, &len);
        pthread_mutex_unlock(&lock);
        if (r == TDC_OK) {
            if (write(ep0, reply, len) < 0) perror("tdc_ffs_board: ep0 write");
        } else if (read(ep0, NULL, 0) < 0 && errno != EL2HLT) { /* wrong direction = stall */
            perror("tdc_ffs_board: ep0 stall");
        }
        return;
    }
    if (s.w_length > sizeof data) {
        if (write(ep0, NULL, 0) < 0 && errno != EL2HLT) perror("tdc_ffs_board: ep0 stall");
        return;
    }
    /* OUT: the data stage is read first (reading acks the status stage), so
     * a rejected DNLOAD shows up in the next GETSTATUS as dfuERROR, as DFU
     * 1.1 allows.  Requests without data are acked or stalled here. */
    if (s.w_length > 0 && read(ep0, data, s.w_length) != s.w_length) {
        perror("tdc_ffs_board: ep0 read");
        return;
    }
    pthread_mutex_lock(&lock);
    tdc_status_t r = tdc_usbp_control(&proto, &s, data, reply, sizeof reply, &len);
    int reset = tdc_usbp_take_reset(&proto);
    if (reset) board_reboot("RESET_BOARD");
    pthread_mutex_unlock(&lock);
    if (s.w_length == 0) {
        if (r == TDC_OK) {
            if (read(ep0, NULL, 0) < 0) perror("tdc_ffs_board: ep0 ack");
        } else if (write(ep0, NULL, 0) < 0 && errno != EL2HLT) {
            perror("tdc_ffs_board: ep0 stall");
        }
    }
    if (reset) {
        printf("tdc_ffs_board: reset requested\n");
        fflush(stdout);
    }
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
                             .flash = {flash_write, flash_read, NULL, SLOT_BYTES},
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
    write_descriptors(ep0);
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
                handle_setup(ep0, &ev[i].u.setup);
            } else if (ev[i].type == FUNCTIONFS_DISABLE) { /* bus reset (dfu-util -R) or unplug */
                pthread_mutex_lock(&lock);
                board_reboot("USB reset");
                pthread_mutex_unlock(&lock);
            }
        }
    }
}
