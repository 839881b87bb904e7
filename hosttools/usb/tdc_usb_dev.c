/*
 * tdc_usb_dev.c - board selection and transfers for tdc-usb (libusb-1.0).
 * Every transfer passes b->timeout_ms; every libusb error is reported by
 * its name (libusb_error_name) and mapped to a named exit code.
 */
#include "tdc_usb_dev.h"
#include "tdc_usbproto.h"
#include "tdc_usb_reply.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

tdc_exit_t tdc_usb_fail(const tdc_board_t *b, const char *what, int err)
{
    const char *op = b != NULL && b->op != NULL ? b->op : "usb";
    const char *hint = "";
    tdc_exit_t code = TDC_EXIT_IO;
    switch (err) {
    case LIBUSB_ERROR_TIMEOUT:
        code = TDC_EXIT_TIMEOUT;
        hint = " (the board did not answer in time; is it running the tdc firmware?)";
        break;
    case LIBUSB_ERROR_NO_DEVICE:
        code = TDC_EXIT_DISCONNECTED;
        hint = " (the board was unplugged or reset)";
        break;
    case LIBUSB_ERROR_PIPE: hint = " (the board stalled the endpoint: it rejected the request)"; break;
    case LIBUSB_ERROR_ACCESS:
        hint = " (no permission: install hosttools/usb/60-tdc-board.rules, see docs/hosttools.md)";
        break;
    default: break;
    }
    if (b != NULL && b->timeout_ms != 0 && err == LIBUSB_ERROR_TIMEOUT)
        fprintf(stderr, "tdc-usb: %s: %s failed after %u ms: %s (%s)%s\n", op, what, b->timeout_ms,
                libusb_error_name(err), libusb_strerror(err), hint);
    else
        fprintf(stderr, "tdc-usb: %s: %s failed: %s (%s)%s\n", op, what, libusb_error_name(err), libusb_strerror(err),
                hint);
    return code;
}

int tdc_usb_string_ascii(libusb_device_handle *h, uint8_t index, char *out, int cap, unsigned timeout_ms)
{
    uint8_t buf[255];
    out[0] = '\0';
    if (index == 0) return 0;
    int r = libusb_control_transfer(h, LIBUSB_ENDPOINT_IN, LIBUSB_REQUEST_GET_DESCRIPTOR,
                                    (uint16_t)((LIBUSB_DT_STRING << 8) | index), 0x0409, buf, sizeof buf, timeout_ms);
    if (r < 0) return r;
    int n = tdc_usb_string_decode(buf, r, out, cap);
    return n < 0 ? LIBUSB_ERROR_IO : n;
}

int tdc_usb_enumerate(libusb_context *ctx, const tdc_usb_select_t *sel, tdc_usb_list_fn fn, void *fn_ctx)
{
    libusb_device **list = NULL;
    ssize_t n = libusb_get_device_list(ctx, &list);
    if (n < 0) return (int)n;
    int matches = 0;
    for (ssize_t i = 0; i < n; i++) {
        libusb_device *dev = list[i];
        struct libusb_device_descriptor dd;
        if (libusb_get_device_descriptor(dev, &dd) != 0) continue;
        if (dd.idVendor != sel->vid || dd.idProduct != sel->pid) continue;
        if (sel->bus >= 0 && libusb_get_bus_number(dev) != sel->bus) continue;
        if (sel->address >= 0 && libusb_get_device_address(dev) != sel->address) continue;
        libusb_device_handle *h = NULL;
        char serial[64] = "";
        int err = libusb_open(dev, &h);
        if (err == 0) {
            int r = tdc_usb_string_ascii(h, dd.iSerialNumber, serial, sizeof serial, sel->timeout_ms);
            if (r < 0) {
                err = r;
                snprintf(serial, sizeof serial, "?");
            }
        }
        if (sel->serial != NULL && (err != 0 || strcmp(serial, sel->serial) != 0)) {
            if (h != NULL) libusb_close(h);
            continue;
        }
        matches++;
        if (fn != NULL) fn(fn_ctx, dev, h, serial, err);
        if (h != NULL) libusb_close(h);
    }
    libusb_free_device_list(list, 1);
    return matches;
}

/* Bulk endpoint addresses of the streaming interface, from the descriptor:
 * a gadget stack may renumber them (Linux's dummy_hcd gives 0x02/0x81). */
static void find_endpoints(tdc_board_t *b, libusb_device *dev)
{
    struct libusb_config_descriptor *cd = NULL;
    b->ep_out = TDC_USB_EP_LINK_OUT;
    b->ep_in = TDC_USB_EP_STATUS_IN;
    if (libusb_get_active_config_descriptor(dev, &cd) != 0) return;
    for (int i = 0; i < cd->bNumInterfaces; i++) {
        const struct libusb_interface_descriptor *id = &cd->interface[i].altsetting[0];
        if (id->bInterfaceNumber != TDC_USB_IF_STREAM || id->bInterfaceClass != 0xFF) continue;
        for (int k = 0; k < id->bNumEndpoints; k++) {
            const struct libusb_endpoint_descriptor *ep = &id->endpoint[k];
            if ((ep->bmAttributes & 0x03) != LIBUSB_TRANSFER_TYPE_BULK) continue;
            if (ep->bEndpointAddress & LIBUSB_ENDPOINT_IN)
                b->ep_in = ep->bEndpointAddress;
            else
                b->ep_out = ep->bEndpointAddress;
        }
    }
    libusb_free_config_descriptor(cd);
}

typedef struct {
    int count;
    libusb_device *first;
    char first_serial[64];
    int first_err;
    char others[512];
} pick_t;

static void pick_cb(void *ctx, libusb_device *dev, libusb_device_handle *h, const char *serial, int open_err)
{
    pick_t *p = ctx;
    (void)h;
    size_t len = strlen(p->others);
    snprintf(p->others + len, sizeof p->others - len, "\n  bus %03u address %03u serial %s", libusb_get_bus_number(dev),
             libusb_get_device_address(dev), open_err == 0 ? serial : libusb_error_name(open_err));
    if (p->count++ == 0) {
        p->first = libusb_ref_device(dev);
        snprintf(p->first_serial, sizeof p->first_serial, "%s", serial);
        p->first_err = open_err;
    }
}

tdc_exit_t tdc_usb_open(libusb_context *ctx, const tdc_usb_select_t *sel, tdc_board_t *b)
{
    pick_t p;
    memset(&p, 0, sizeof p);
    b->ctx = ctx;
    b->h = NULL;
    b->timeout_ms = sel->timeout_ms;
    int n = tdc_usb_enumerate(ctx, sel, pick_cb, &p);
    if (n < 0) {
        if (p.first != NULL) libusb_unref_device(p.first);
        return tdc_usb_fail(b, "listing USB devices", n);
    }
    if (n == 0) {
        fprintf(stderr,
                "tdc-usb: %s: no tdc board (USB %04x:%04x)%s found; is it plugged in "
                "and running the tdc firmware? (see `tdc-usb list`)\n",
                b->op, sel->vid, sel->pid,
                sel->bus >= 0 || sel->address >= 0 || sel->serial != NULL ? " matching --bus/--address/--serial" : "");
        return TDC_EXIT_NO_DEVICE;
    }
    if (n > 1) {
        fprintf(stderr,
                "tdc-usb: %s: %d tdc boards match; choose one with --bus/--address "
                "or --serial:%s\n",
                b->op, n, p.others);
        libusb_unref_device(p.first);
        return TDC_EXIT_AMBIGUOUS;
    }
    b->bus = libusb_get_bus_number(p.first);
    b->address = libusb_get_device_address(p.first);
    snprintf(b->serial, sizeof b->serial, "%s", p.first_serial);
    find_endpoints(b, p.first);
    int err = libusb_open(p.first, &b->h);
    libusb_unref_device(p.first);
    if (err != 0) {
        b->h = NULL;
        return tdc_usb_fail(b, "opening the board", err);
    }
    return TDC_EXIT_OK;
}

void tdc_usb_close(tdc_board_t *b)
{
    if (b->h != NULL) libusb_close(b->h);
    b->h = NULL;
}

tdc_exit_t tdc_usb_claim(tdc_board_t *b, int iface)
{
    /* A kernel driver should never be bound to a vendor or DFU interface,
     * but detach one if some generic driver grabbed it. */
    libusb_set_auto_detach_kernel_driver(b->h, 1);
    int err = libusb_claim_interface(b->h, iface);
    if (err != 0) {
        char what[48];
        snprintf(what, sizeof what, "claiming interface %d", iface);
        return tdc_usb_fail(b, what, err);
    }
    return TDC_EXIT_OK;
}

/*
 * A transfer cut by an unplug does not always fail with NO_DEVICE: the host
 * controller may kill the URB (-EPROTO, -ESHUTDOWN: LIBUSB_ERROR_IO) before
 * the hub driver has noticed the disconnect.  Before reporting an I/O-class
 * error, ask the device for its status a few times (50 ms apart, 100 ms
 * timeout each, 0.5 s in all): NO_DEVICE then means it went away; an answer
 * means the error was real and is reported as it was.
 */
static int reclassify_gone(tdc_board_t *b, int err)
{
    if (b == NULL || b->h == NULL) return err;
    if (err != LIBUSB_ERROR_IO && err != LIBUSB_ERROR_OTHER && err != LIBUSB_ERROR_OVERFLOW &&
        err != LIBUSB_ERROR_INTERRUPTED)
        return err;
    for (int i = 0; i < 5; i++) {
        uint8_t st[2];
        int r =
            libusb_control_transfer(b->h, LIBUSB_ENDPOINT_IN | LIBUSB_REQUEST_TYPE_STANDARD | LIBUSB_RECIPIENT_DEVICE,
                                    LIBUSB_REQUEST_GET_STATUS, 0, 0, st, sizeof st, 100);
        if (r == LIBUSB_ERROR_NO_DEVICE) return LIBUSB_ERROR_NO_DEVICE;
        if (r >= 0) return err;
        struct timespec ts = {0, 50 * 1000 * 1000};
        nanosleep(&ts, NULL);
    }
    return err;
}

tdc_exit_t tdc_usb_ctrl_in(tdc_board_t *b, const char *what, uint8_t type, uint8_t req, uint16_t value, uint16_t index,
                           uint8_t *data, uint16_t len, int *got)
{
    int r = libusb_control_transfer(b->h, (uint8_t)(LIBUSB_ENDPOINT_IN | type), req, value, index, data, len,
                                    b->timeout_ms);
    if (r < 0) return tdc_usb_fail(b, what, reclassify_gone(b, r));
    *got = r;
    return TDC_EXIT_OK;
}

tdc_exit_t tdc_usb_ctrl_out(tdc_board_t *b, const char *what, uint8_t type, uint8_t req, uint16_t value, uint16_t index,
                            const uint8_t *data, uint16_t len)
{
    /* libusb takes a non-const buffer for both directions; OUT data is only read */
    int r = libusb_control_transfer(b->h, (uint8_t)(LIBUSB_ENDPOINT_OUT | type), req, value, index,
                                    (unsigned char *)(uintptr_t)data, len, b->timeout_ms);
    if (r < 0) return tdc_usb_fail(b, what, reclassify_gone(b, r));
    if (r != len) {
        fprintf(stderr, "tdc-usb: %s: %s: board took %d of %u bytes\n", b->op, what, r, len);
        return TDC_EXIT_PROTOCOL;
    }
    return TDC_EXIT_OK;
}

tdc_exit_t tdc_usb_bulk(tdc_board_t *b, const char *what, uint8_t ep, uint8_t *data, int len, int *done)
{
    int n = 0;
    int r = libusb_bulk_transfer(b->h, ep, data, len, &n, b->timeout_ms);
    *done = n;
    if (r != 0) return tdc_usb_fail(b, what, reclassify_gone(b, r));
    return TDC_EXIT_OK;
}
