/*
 * tdc_usb_emul.c - emulated tdc board: the firmware protocol code behind a
 * umockdev usbdevfs ioctl handler (see tdc_usb_emul.h).
 *
 * How a transfer flows: the client (libusb in the child process) issues
 * SUBMITURB; we resolve the urb and its buffer from the client's memory,
 * run the firmware on it, write the IN data, status and actual_length into
 * our copies, and queue the urb as "done".  The umockdev socket flushes the
 * copies back to the client.  libusb then polls with REAPURBNDELAY and we
 * hand back the urb pointer with umockdev_ioctl_data_set_ptr().  An urb the
 * board never answers stays "in flight" until libusb's timeout discards it.
 */
#include "tdc_usb_emul.h"
#include "tdc_link_sink.h"
#include "tdc_usbp_vive.h"

#include <errno.h>
#include <sys/ioctl.h>
#include <linux/usbdevice_fs.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define EMUL_MAX_URBS 64

struct emul_board {
    UMockdevTestbed *tb;
    UMockdevIoctlBase *handler;
    char devnode[64];
    char serial[32];
    pthread_mutex_t lock;
    tdc_usbp_t proto;
    uint8_t *slot;
    uint32_t slot_bytes;
    emul_fault_t fault;
    uint32_t fault_after;
    uint32_t bulk_out_count;
    int gone;
    int reset_requested;
    int resets, activations;
    UMockdevIoctlData *done[EMUL_MAX_URBS]; /* completed, waiting to be reaped (FIFO) */
    int n_done;
    UMockdevIoctlData *flying[EMUL_MAX_URBS]; /* never answered (hang faults) */
    int n_flying;
    tdc_link_sink_t *sink; /* optional: the firmware's link decoder as the sink */
    uint32_t erase_ms, erase_unit; /* slow erase: a block starting an erase unit is written later */
    double busy_until;             /* a deferred block is written once this time has passed */
    int busy_replies, early_polls;
};

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* tdc_usbp_flash_t.busy_ms: like a flash that erases erase_unit bytes at a
 * time, taking erase_ms (0: every write within the request). */
static uint32_t emul_flash_busy_ms(void *ctx, uint32_t offset, uint32_t len)
{
    emul_board_t *b = ctx;
    (void)len;
    return b->erase_ms != 0u && offset % b->erase_unit == 0u ? b->erase_ms : 0u;
}

int emul_board_attach_link_decoder(emul_board_t *b, uint16_t w, uint16_t h)
{
    tdc_link_sink_t *sink = calloc(1, sizeof *sink);
    if (sink == NULL || tdc_link_sink_init(sink, w, h) != 0) {
        free(sink);
        return -1;
    }
    pthread_mutex_lock(&b->lock);
    b->sink = sink;
    b->proto.cfg.sink = tdc_link_sink_feed;
    b->proto.cfg.sink_ctx = sink;
    pthread_mutex_unlock(&b->lock);
    return 0;
}

/* A/B flash (2 slots of slot_bytes) in RAM, with an optional bit flip to
 * emulate a bad cell (fault_after: offset inside the slot written). */
static int emul_flash_write(void *ctx, uint32_t offset, const uint8_t *data, uint32_t len)
{
    emul_board_t *b = ctx;
    if ((uint64_t)offset + len > 2u * (uint64_t)b->slot_bytes) return -1;
    memcpy(b->slot + offset, data, len);
    const uint32_t in_slot = offset % b->slot_bytes, base = offset - in_slot;
    if (b->fault == EMUL_FAULT_CORRUPT_FLASH && b->fault_after >= in_slot && b->fault_after < in_slot + len)
        b->slot[base + b->fault_after] ^= 0x10u;
    return 0;
}

static int emul_flash_read(void *ctx, uint32_t offset, uint8_t *data, uint32_t len)
{
    emul_board_t *b = ctx;
    if ((uint64_t)offset + len > 2u * (uint64_t)b->slot_bytes) return -1;
    memcpy(data, b->slot + offset, len);
    return 0;
}

/* The board restarts (a USB bus reset or its own reset): activation of a
 * manifested image, which then runs, so BOARD_INFO reports its version. */
static void board_reboot(emul_board_t *b)
{
    b->resets++;
    if (tdc_usbp_bus_reset(&b->proto)) {
        const uint8_t *hdr = b->slot + (size_t)b->proto.dfu_active_slot * b->slot_bytes;
        b->proto.cfg.fw_version = tdc_get_le32(hdr + TDC_IMAGE_OFF_FW_VERSION);
        b->activations++;
    }
}

static void urb_finish(emul_board_t *b, UMockdevIoctlData *urb_data, int status, int actual)
{
    /* through _update() so umockdev knows the copy is dirty and flushes it */
    umockdev_ioctl_data_update(urb_data, G_STRUCT_OFFSET(struct usbdevfs_urb, status), (guint8 *)&status,
                               sizeof status);
    umockdev_ioctl_data_update(urb_data, G_STRUCT_OFFSET(struct usbdevfs_urb, actual_length), (guint8 *)&actual,
                               sizeof actual);
    if (b->n_done < EMUL_MAX_URBS) b->done[b->n_done++] = g_object_ref(urb_data);
}

/* Runs one submitted urb through the firmware.  Returns 0 if answered,
 * 1 if the board keeps it (hang fault). */
static int urb_run(emul_board_t *b, UMockdevIoctlData *urb_data, UMockdevIoctlData *buf)
{
    struct usbdevfs_urb *urb = (struct usbdevfs_urb *)urb_data->data;
    uint8_t *data = buf != NULL ? buf->data : NULL;
    int len = urb->buffer_length;

    if (urb->type == USBDEVFS_URB_TYPE_CONTROL) {
        tdc_usbp_setup_t setup;
        uint8_t reply[TDC_DFU_TRANSFER_SIZE];
        uint32_t reply_len = 0;
        if (data == NULL || len < 8) {
            urb_finish(b, urb_data, -EINVAL, 0);
            return 0;
        }
        tdc_usbp_parse_setup(data, &setup);
        int is_info = (setup.bm_request_type & 0x60u) == 0x40u && setup.b_request == TDC_USB_REQ_BOARD_INFO;
        if (is_info && b->fault == EMUL_FAULT_HANG_INFO) return 1;
        if ((setup.bm_request_type & 0xE0u) == 0x80u && setup.b_request == 0x00u) {
            /* standard GET_STATUS (lsusb -v asks): the device's USB stack
             * answers it, not the protocol code: bus powered, no remote wake */
            uint8_t zero[2] = {0, 0};
            int n = setup.w_length < 2 ? setup.w_length : 2;
            if (n > len - 8) n = len - 8;
            umockdev_ioctl_data_update(buf, 8, zero, n);
            urb_finish(b, urb_data, 0, n);
            return 0;
        }
        if (b->fault == EMUL_FAULT_STALL_DNLOAD && (setup.bm_request_type & 0x7Fu) == 0x21u &&
            setup.b_request == TDC_DFU_DNLOAD && setup.w_length > 0 && setup.w_value == b->fault_after) {
            urb_finish(b, urb_data, -EPIPE, 0); /* never reaches the firmware */
            return 0;
        }
        if (is_info && b->fault == EMUL_FAULT_STALL_INFO) {
            urb_finish(b, urb_data, -EPIPE, 0);
            return 0;
        }
        /* The board writes a deferred block in the background, done at
         * busy_until; a host asking before then gets dfuDNBUSY again. */
        if (b->proto.dfu_block_armed && now_s() >= b->busy_until) (void)tdc_usbp_dfu_work(&b->proto);
        const int early = b->proto.dfu_block_armed;
        tdc_status_t r = tdc_usbp_control(&b->proto, &setup, data + 8, reply, (uint32_t)sizeof reply, &reply_len);
        if (r == TDC_OK && setup.b_request == TDC_DFU_GETSTATUS && (setup.bm_request_type & 0x7Fu) == 0x21u &&
            b->proto.dfu_block_armed) {
            b->early_polls += early;
            b->busy_replies += !early;
            if (!early) b->busy_until = now_s() + b->proto.dfu_block_ms / 1000.0;
        }
        if (r != TDC_OK) {
            urb_finish(b, urb_data, -EPIPE, 0);
            return 0;
        }
        if (setup.bm_request_type & 0x80u) {
            if ((int)reply_len > len - 8) reply_len = (uint32_t)(len - 8);
            umockdev_ioctl_data_update(buf, 8, reply, (int)reply_len);
            urb_finish(b, urb_data, 0, (int)reply_len);
        } else {
            urb_finish(b, urb_data, 0, setup.w_length);
        }
        if (tdc_usbp_take_reset(&b->proto)) { /* RESET_BOARD: the board resets itself */
            b->reset_requested++;
            board_reboot(b);
        }
        return 0;
    }
    if (urb->type == USBDEVFS_URB_TYPE_BULK && urb->endpoint == TDC_USB_EP_LINK_OUT) {
        b->bulk_out_count++;
        if (b->fault == EMUL_FAULT_HANG_BULK && b->bulk_out_count >= b->fault_after) return 1;
        if (b->fault == EMUL_FAULT_STALL_BULK && b->bulk_out_count >= b->fault_after) {
            urb_finish(b, urb_data, -EPIPE, 0);
            return 0;
        }
        tdc_usbp_bulk_out(&b->proto, data, (uint32_t)len);
        urb_finish(b, urb_data, 0, len);
        if (b->fault == EMUL_FAULT_UNPLUG && b->bulk_out_count >= b->fault_after) b->gone = 1;
        return 0;
    }
    if (urb->type == USBDEVFS_URB_TYPE_BULK && urb->endpoint == TDC_USB_EP_STATUS_IN) {
        uint8_t rep[TDC_USB_STATUS_LEN];
        tdc_usbp_status_report(&b->proto, rep);
        int n = len < (int)sizeof rep ? len : (int)sizeof rep;
        if (n > 0) umockdev_ioctl_data_update(buf, 0, rep, n);
        urb_finish(b, urb_data, 0, n);
        return 0;
    }
    urb_finish(b, urb_data, -EPIPE, 0); /* no such endpoint */
    return 0;
}

static UMockdevIoctlData *pop_first(UMockdevIoctlData **list, int *n)
{
    if (*n == 0) return NULL;
    UMockdevIoctlData *d = list[0];
    memmove(list, list + 1, (size_t)(*n - 1) * sizeof list[0]);
    (*n)--;
    return d;
}

static gboolean emul_handle_ioctl(UMockdevIoctlBase *handler, UMockdevIoctlClient *client, gpointer user_data)
{
    emul_board_t *b = user_data;
    UMockdevIoctlData *arg = umockdev_ioctl_client_get_arg(client);
    gulong request = umockdev_ioctl_client_get_request(client);
    (void)handler;

    pthread_mutex_lock(&b->lock);
    if (b->gone && request != USBDEVFS_REAPURBNDELAY && request != USBDEVFS_REAPURB && request != USBDEVFS_DISCARDURB &&
        request != USBDEVFS_RELEASEINTERFACE) {
        pthread_mutex_unlock(&b->lock);
        umockdev_ioctl_client_complete(client, -1, ENODEV);
        return TRUE;
    }
    switch (request) {
    case USBDEVFS_GET_CAPABILITIES: {
        UMockdevIoctlData *d = umockdev_ioctl_data_resolve(arg, 0, sizeof(uint32_t), NULL);
        uint32_t caps = USBDEVFS_CAP_BULK_CONTINUATION | USBDEVFS_CAP_NO_PACKET_SIZE_LIM | USBDEVFS_CAP_ZERO_PACKET |
                        USBDEVFS_CAP_REAP_AFTER_DISCONNECT;
        if (d != NULL) umockdev_ioctl_data_update(d, 0, (guint8 *)&caps, sizeof caps);
        umockdev_ioctl_client_complete(client, 0, 0);
        break;
    }
    case USBDEVFS_GETDRIVER: /* no kernel driver bound */ umockdev_ioctl_client_complete(client, -1, ENODATA); break;
    case USBDEVFS_RESET: /* libusb_reset_device(): a USB bus reset (dfu-util -R) */
        board_reboot(b);
        umockdev_ioctl_client_complete(client, 0, 0);
        break;
    case USBDEVFS_CLAIMINTERFACE:
    case USBDEVFS_RELEASEINTERFACE:
    case USBDEVFS_SETINTERFACE:
    case USBDEVFS_CLEAR_HALT:
    case USBDEVFS_RESETEP:
    case USBDEVFS_SETCONFIGURATION:
    case USBDEVFS_DISCONNECT_CLAIM: umockdev_ioctl_client_complete(client, 0, 0); break;
    case USBDEVFS_SUBMITURB: {
        UMockdevIoctlData *urb_data = umockdev_ioctl_data_resolve(arg, 0, sizeof(struct usbdevfs_urb), NULL);
        if (urb_data == NULL) {
            umockdev_ioctl_client_complete(client, -1, EFAULT);
            break;
        }
        struct usbdevfs_urb *urb = (struct usbdevfs_urb *)urb_data->data;
        UMockdevIoctlData *buf = NULL;
        if (urb->buffer_length > 0)
            buf = umockdev_ioctl_data_resolve(urb_data, G_STRUCT_OFFSET(struct usbdevfs_urb, buffer),
                                              (gsize)urb->buffer_length, NULL);
        if (urb_run(b, urb_data, buf) == 1 && b->n_flying < EMUL_MAX_URBS)
            b->flying[b->n_flying++] = g_object_ref(urb_data);
        umockdev_ioctl_client_complete(client, 0, 0);
        break;
    }
    case USBDEVFS_REAPURB:
    case USBDEVFS_REAPURBNDELAY: {
        UMockdevIoctlData *urb_data = pop_first(b->done, &b->n_done);
        if (urb_data == NULL) {
            /* Nothing to reap.  A vanished device reports ENODEV like the kernel. */
            umockdev_ioctl_client_complete(client, -1, b->gone ? ENODEV : EAGAIN);
            break;
        }
        UMockdevIoctlData *ptr = umockdev_ioctl_data_resolve(arg, 0, sizeof(void *), NULL);
        umockdev_ioctl_data_set_ptr(ptr, 0, urb_data);
        umockdev_ioctl_client_complete(client, 0, 0);
        g_object_unref(urb_data);
        break;
    }
    case USBDEVFS_DISCARDURB: {
        gulong addr = (gulong) * (void **)arg->data;
        int found = -1;
        for (int i = 0; i < b->n_flying; i++)
            if (b->flying[i]->client_addr == addr) found = i;
        if (found < 0) {
            umockdev_ioctl_client_complete(client, -1, EINVAL);
            break;
        }
        UMockdevIoctlData *urb_data = b->flying[found];
        memmove(b->flying + found, b->flying + found + 1, (size_t)(b->n_flying - found - 1) * sizeof b->flying[0]);
        b->n_flying--;
        int st = -ENOENT, zero = 0;
        umockdev_ioctl_data_update(urb_data, G_STRUCT_OFFSET(struct usbdevfs_urb, status), (guint8 *)&st, sizeof st);
        umockdev_ioctl_data_update(urb_data, G_STRUCT_OFFSET(struct usbdevfs_urb, actual_length), (guint8 *)&zero,
                                   sizeof zero);
        if (b->n_done < EMUL_MAX_URBS)
            b->done[b->n_done++] = urb_data; /* reference moves */
        else
            g_object_unref(urb_data);
        umockdev_ioctl_client_complete(client, 0, 0);
        break;
    }
    default:
        if (getenv("TDC_EMUL_DEBUG") != NULL) fprintf(stderr, "emul: unhandled ioctl 0x%lx\n", (unsigned long)request);
        umockdev_ioctl_client_complete(client, -1, ENOTTY);
        break;
    }
    pthread_mutex_unlock(&b->lock);
    return TRUE;
}

static void hex_append(char *dst, size_t cap, const uint8_t *p, uint32_t n)
{
    size_t len = strlen(dst);
    /* two digits and the NUL must fit: len + 2 < cap (it was len + 3, which
     * dropped the last byte of a buffer sized 2n + 1: issue 19) */
    for (uint32_t i = 0; i < n && len + 2 < cap; i++, len += 2) snprintf(dst + len, cap - len, "%02x", p[i]);
}

emul_board_t *emul_board_add(UMockdevTestbed *tb, int bus, int dev, const char *serial, uint32_t slot_bytes)
{
    emul_board_t *b = calloc(1, sizeof *b);
    if (b == NULL) return NULL;
    b->tb = tb;
    b->slot = calloc(2, slot_bytes); /* A/B */
    b->slot_bytes = slot_bytes;
    pthread_mutex_init(&b->lock, NULL);
    snprintf(b->devnode, sizeof b->devnode, "/dev/bus/usb/%03d/%03d", bus, dev);
    snprintf(b->serial, sizeof b->serial, "%s", serial);

    const tdc_usbp_config_t cfg =
        tdc_usbp_vive_config("emul", b->serial, 0x000100u, 16384u,
                             (tdc_usbp_flash_t){emul_flash_write, emul_flash_read, b, slot_bytes, emul_flash_busy_ms});
    if (tdc_usbp_init(&b->proto, &cfg) != TDC_OK) {
        fprintf(stderr, "tdc_usb_emul: board protocol init failed\n");
        emul_board_free(b);
        return NULL;
    }

    b->handler = umockdev_ioctl_base_new();
    g_signal_connect(b->handler, "handle-ioctl", G_CALLBACK(emul_handle_ioctl), b);
    if (!umockdev_testbed_attach_ioctl(tb, b->devnode, b->handler, NULL)) {
        emul_board_free(b);
        return NULL;
    }

    /* sysfs: the kernel's copy of the descriptors, as libusb reads it */
    uint8_t desc[18 + TDC_USB_CONFIG_DESC_LEN];
    tdc_usbp_device_descriptor(desc);
    tdc_usbp_config_descriptor(desc + 18, 1);
    char hex[2 * sizeof desc + 1] = "";
    hex_append(hex, sizeof hex, desc, (uint32_t)sizeof desc);
    char rec[1024];
    snprintf(rec, sizeof rec,
             "P: /devices/pci0000:00/0000:00:14.0/usb%d/%d-%d\n"
             "N: bus/usb/%03d/%03d\n"
             "E: SUBSYSTEM=usb\nE: DEVTYPE=usb_device\nE: DRIVER=usb\n"
             "E: BUSNUM=%03d\nE: DEVNUM=%03d\nE: DEVNAME=/dev/bus/usb/%03d/%03d\n"
             "E: ID_SERIAL_SHORT=%s\n"
             "A: busnum=%d\\n\nA: devnum=%d\\n\nA: bConfigurationValue=1\\n\n"
             "A: speed=480\\n\nA: serial=%s\\n\nA: idVendor=%04x\\n\nA: idProduct=%04x\\n\n"
             "H: descriptors=%s\n",
             bus, bus, dev, bus, dev, bus, dev, bus, dev, serial, bus, dev, serial, TDC_USB_VID, TDC_USB_PID, hex);
    GError *err = NULL;
    if (!umockdev_testbed_add_from_string(tb, rec, &err)) {
        fprintf(stderr, "emul: add_from_string: %s\n", err != NULL ? err->message : "?");
        g_clear_error(&err);
        emul_board_free(b);
        return NULL;
    }
    return b;
}

void emul_board_set_fault(emul_board_t *b, emul_fault_t fault, uint32_t fault_after)
{
    pthread_mutex_lock(&b->lock);
    b->fault = fault;
    b->fault_after = fault_after;
    pthread_mutex_unlock(&b->lock);
}

void emul_board_set_erase(emul_board_t *b, uint32_t erase_ms, uint32_t erase_unit)
{
    pthread_mutex_lock(&b->lock);
    b->erase_ms = erase_ms;
    b->erase_unit = erase_unit;
    pthread_mutex_unlock(&b->lock);
}

void emul_board_stats(emul_board_t *b, emul_board_stats_t *out)
{
    pthread_mutex_lock(&b->lock);
    out->rx_bytes = b->proto.cnt.rx_bytes;
    out->rx_transfers = b->proto.cnt.rx_transfers;
    out->rx_crc = ~b->proto.cnt.rx_crc;
    /* the image that is uploaded: the manifested one waiting for activation, else the running one */
    const unsigned in = b->proto.dfu_active_slot ^ 1u;
    const unsigned up = b->proto.dfu_pending && b->proto.dfu_slot_image[in] ? in : b->proto.dfu_active_slot;
    out->image_bytes = b->proto.dfu_slot_image[up];
    out->slot_crc = tdc_crc32(b->slot + (size_t)up * b->slot_bytes, out->image_bytes);
    out->active_slot = b->proto.dfu_active_slot;
    out->active_bytes = b->proto.dfu_slot_image[b->proto.dfu_active_slot];
    out->active_crc = tdc_crc32(b->slot + (size_t)b->proto.dfu_active_slot * b->slot_bytes, out->active_bytes);
    out->pending = b->proto.dfu_pending;
    out->fw_version = b->proto.cfg.fw_version;
    out->resets = b->resets;
    out->activations = b->activations;
    out->dfu_status = (int)b->proto.dfu_status;
    out->reset_requested = b->reset_requested;
    out->dfu_state = (int)b->proto.dfu_state;
    out->busy_replies = b->busy_replies;
    out->early_polls = b->early_polls;
    pthread_mutex_unlock(&b->lock);
}

void emul_board_free(emul_board_t *b)
{
    if (b == NULL) return;
    if (b->handler != NULL) {
        umockdev_testbed_detach_ioctl(b->tb, b->devnode, NULL);
        g_object_unref(b->handler);
    }
    for (int i = 0; i < b->n_done; i++) g_object_unref(b->done[i]);
    for (int i = 0; i < b->n_flying; i++) g_object_unref(b->flying[i]);
    pthread_mutex_destroy(&b->lock);
    free(b->sink);
    free(b->slot);
    free(b);
}
