/*
 * tdc_board_linux_ffs.c - the Linux board's transport: a USB gadget made
 * through configfs (libcomposite) with one FunctionFS function whose ep0
 * and bulk endpoints are served by the firmware's protocol code
 * (firmware/tdc_usbproto.c, docs/usb-protocol.md):
 *   ep0     board info, counters, DFU 1.1 into A/B slots (a file in the
 *           state folder stands for the flash)   thread ep0_thread
 *   ep1 OUT link stream bytes: read by the frame loop (tdc_lx_ffs_read)
 *   ep2 IN  status reports, always one queued     thread status_thread
 * The gadget is created if it does not exist (a systemd unit may have made
 * it at boot) and bound to the USB device controller: dwc2 in peripheral
 * mode on a Raspberry Pi (docs/boards.md), dummy_udc in `make test-vm`.
 * Unplug (the host goes away, or the UDC is unbound) shows as ESHUTDOWN
 * on ep1 and FUNCTIONFS_DISABLE on ep0: logged "host gone", the panel
 * keeps its last frame, the loop waits for the next connection.
 */
#include <dirent.h>
#include <endian.h>
#include <errno.h>
#include <fcntl.h>
#include <linux/usb/functionfs.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tdc_board_linux.h"
#include "tdc_ffs.h"
#include "tdc_usbproto.h"

#define GADGET "/sys/kernel/config/usb_gadget/tdc-board"
/* FunctionFS instance names are global: "ffs.<name>", mounted as device <name> */
#define FFS_NAME "tdcboard"
#define FFS_FUNCTION "ffs." FFS_NAME
/* A slot holds the board program or a panel profile image (48-byte header
 * + payload); the static x86-64 program is ~1.2 MB. */
#define SLOT_BYTES (8u * 1024u * 1024u)

static pthread_mutex_t g_lock = PTHREAD_MUTEX_INITIALIZER;
static tdc_usbp_t g_proto;
static int g_ep0 = -1, g_ep1 = -1, g_slots = -1;
static volatile int g_enabled;
/* connections lost (FUNCTIONFS_DISABLE after ENABLE): the reader ends the
 * loop's run when this moves, also when the loss happened while the loop
 * was busy and not reading (a read then just waits for the next ENABLE) */
static volatile unsigned g_lost;

/* ---- DFU slots: one file of 2 * SLOT_BYTES in the state folder ---- */
static int slot_write(void *ctx, uint32_t off, const uint8_t *d, uint32_t n)
{
    (void)ctx;
    return g_slots >= 0 && pwrite(g_slots, d, n, off) == (ssize_t)n ? 0 : -1;
}

static int slot_read(void *ctx, uint32_t off, uint8_t *d, uint32_t n)
{
    (void)ctx;
    if (g_slots < 0) return -1;
    ssize_t r = pread(g_slots, d, n, off);
    if (r < 0) return -1;
    memset(d + r, 0xFF, n - (uint32_t)r); /* beyond the file: erased flash */
    return 0;
}

/* A USB reset or the board's own (RESET_BOARD, DFU_DETACH): a manifested
 * image becomes the active slot.  Called with the lock held. */
static void board_reset(const char *why)
{
    if (tdc_usbp_bus_reset(&g_proto)) {
        uint8_t hdr[TDC_IMAGE_HEADER_LEN];
        if (slot_read(NULL, (uint32_t)g_proto.dfu_active_slot * SLOT_BYTES, hdr, sizeof hdr) == 0) {
            g_proto.cfg.fw_version = tdc_get_le32(hdr + TDC_IMAGE_OFF_FW_VERSION);
        }
        tdc_lx_logf("%s: activated slot %u, firmware %u.%u.%u, %u bytes", why, g_proto.dfu_active_slot,
                    g_proto.cfg.fw_version >> 16, (g_proto.cfg.fw_version >> 8) & 0xFFu,
                    g_proto.cfg.fw_version & 0xFFu, tdc_usbp_slot_image(&g_proto, g_proto.dfu_active_slot));
    }
}

static void *ep0_thread(void *arg)
{
    (void)arg;
    for (;;) {
        struct usb_functionfs_event ev[4];
        ssize_t n = read(g_ep0, ev, sizeof ev);
        if (n < 0) {
            if (errno != EINTR && errno != EAGAIN) {
                tdc_lx_logf("usb: ep0 events: %s", strerror(errno));
                usleep(100000);
            }
            continue;
        }
        for (ssize_t i = 0; i < n / (ssize_t)sizeof ev[0]; i++) {
            switch (ev[i].type) {
            case FUNCTIONFS_SETUP: tdc_ffs_setup(g_ep0, &ev[i].u.setup, &g_proto, &g_lock, board_reset); break;
            case FUNCTIONFS_ENABLE:
                g_enabled = 1;
                tdc_lx_logf("usb: host connected (configuration set)");
                break;
            case FUNCTIONFS_DISABLE:
                if (g_enabled) {
                    tdc_lx_logf("usb: host gone (disconnected or reset): the panel keeps its last frame");
                    g_lost++;
                }
                g_enabled = 0;
                pthread_mutex_lock(&g_lock);
                board_reset("USB reset");
                pthread_mutex_unlock(&g_lock);
                break;
            case FUNCTIONFS_UNBIND: tdc_lx_logf("usb: gadget unbound from its controller"); break;
            default: break;
            }
        }
    }
    return NULL;
}

static int open_ep(const char *name)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", tdc_lx_opts.ffs_dir, name);
    return open(path, O_RDWR | O_CLOEXEC);
}

/* Bulk IN: status reports (tdc_ffs.c). */
static void *status_thread(void *arg)
{
    (void)arg;
    char path[512];
    snprintf(path, sizeof path, "%s/ep2", tdc_lx_opts.ffs_dir);
    tdc_ffs_status_loop(path, &g_proto, &g_lock);
    return NULL;
}

int tdc_lx_ffs_read(uint8_t *buf, uint32_t cap, uint32_t *got)
{
    static unsigned seen;
    *got = 0;
    if (tdc_lx_stop) return -1;
    if (seen != g_lost) {
        seen = g_lost;
        tdc_lx_logf("usb: host gone: stream ended; the next connection starts a new one");
        if (g_ep1 >= 0) close(g_ep1);
        g_ep1 = -1;
        return -2;
    }
    if (g_ep1 < 0 && (g_ep1 = open_ep("ep1")) < 0) {
        tdc_lx_logf("usb: cannot open bulk OUT endpoint %s/ep1: %s", tdc_lx_opts.ffs_dir, strerror(errno));
        usleep(100000);
        return 0;
    }
    ssize_t n = read(g_ep1, buf, cap); /* blocks until the host sends (or is configured) */
    if (n > 0) {
        pthread_mutex_lock(&g_lock);
        tdc_usbp_bulk_out(&g_proto, buf, (uint32_t)n);
        pthread_mutex_unlock(&g_lock);
        *got = (uint32_t)n;
        return 1;
    }
    if (tdc_lx_stop) return -1;
    if (n < 0 && errno != EINTR) {
        /* ESHUTDOWN: the function was disabled under the read (unplug,
         * USB reset): this connection's stream has ended */
        tdc_lx_logf("usb: host gone: stream ended (%s); the panel keeps its last frame", strerror(errno));
        close(g_ep1);
        g_ep1 = -1;
        seen = g_lost;
        return -2;
    }
    return 0;
}

void tdc_lx_ffs_frame_shown(void)
{
    pthread_mutex_lock(&g_lock);
    g_proto.cnt.frames_shown++;
    pthread_mutex_unlock(&g_lock);
}

static int put(const char *dir, const char *name, const char *val)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    int fd = open(path, O_WRONLY | O_CLOEXEC);
    if (fd < 0) return -1;
    ssize_t n = write(fd, val, strlen(val));
    int e = errno;
    close(fd);
    errno = e;
    return n == (ssize_t)strlen(val) ? 0 : -1;
}

static int mkdir_ok(const char *p)
{
    return mkdir(p, 0755) == 0 || errno == EEXIST ? 0 : -1;
}

/* The configfs gadget (idempotent: a unit may have made it at boot). */
static int make_gadget(void)
{
    struct stat st;
    if (stat("/sys/kernel/config/usb_gadget", &st) != 0) {
        (void)mount("none", "/sys/kernel/config", "configfs", 0, NULL);
        if (stat("/sys/kernel/config/usb_gadget", &st) != 0) {
            tdc_lx_fail(TDC_LX_EXIT_NO_DEVICE,
                        "usb: gadget not bound: no /sys/kernel/config/usb_gadget (load libcomposite, mount configfs)");
            return -1;
        }
    }
    static const char *const dirs[] = {GADGET, GADGET "/strings/0x409", GADGET "/functions/" FFS_FUNCTION,
                                       GADGET "/configs/c.1"};
    for (unsigned i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
        if (mkdir_ok(dirs[i]) != 0) { /* EBUSY: another gadget has a FunctionFS instance of that name */
            tdc_lx_fail(TDC_LX_EXIT_IO, "usb: gadget not bound: cannot create %s: %s", dirs[i], strerror(errno));
            return -1;
        }
    }
    char vid[8], pid[8];
    snprintf(vid, sizeof vid, "0x%04x", TDC_USB_VID);
    snprintf(pid, sizeof pid, "0x%04x", TDC_USB_PID);
    if (put(GADGET, "idVendor", vid) || put(GADGET, "idProduct", pid) || put(GADGET, "bcdDevice", "0x0001") ||
        put(GADGET, "bcdUSB", "0x0200") || put(GADGET "/strings/0x409", "manufacturer", "tdc project") ||
        put(GADGET "/strings/0x409", "product", "tdc display controller") ||
        put(GADGET "/strings/0x409", "serialnumber", tdc_lx_opts.serial) ||
        put(GADGET "/configs/c.1", "MaxPower", "100")) {
        /* a bound gadget refuses these writes (EBUSY): already set up */
        if (errno != EBUSY) {
            tdc_lx_fail(TDC_LX_EXIT_IO, "usb: gadget not bound: writing %s: %s", GADGET, strerror(errno));
            return -1;
        }
    }
    if (symlink(GADGET "/functions/" FFS_FUNCTION, GADGET "/configs/c.1/" FFS_FUNCTION) != 0 && errno != EEXIST) {
        tdc_lx_fail(TDC_LX_EXIT_IO, "usb: gadget not bound: linking the function: %s", strerror(errno));
        return -1;
    }
    return 0;
}

static int bind_udc(void)
{
    char udc[256] = "";
    if (tdc_lx_opts.udc) {
        snprintf(udc, sizeof udc, "%s", tdc_lx_opts.udc);
    } else {
        DIR *d = opendir("/sys/class/udc");
        for (struct dirent *e; d && (e = readdir(d)) != NULL;) {
            if (e->d_name[0] != '.') {
                snprintf(udc, sizeof udc, "%s", e->d_name);
                break;
            }
        }
        if (d) closedir(d);
    }
    if (!udc[0]) {
        tdc_lx_fail(TDC_LX_EXIT_NO_DEVICE, "usb: gadget not bound: no USB device controller in /sys/class/udc "
                                           "(Raspberry Pi: dtoverlay=dwc2,dr_mode=peripheral)");
        return -1;
    }
    (void)put(GADGET, "UDC", ""); /* a previous run's binding */
    if (put(GADGET, "UDC", udc) != 0) {
        tdc_lx_fail(TDC_LX_EXIT_IO, "usb: gadget not bound: binding to %s: %s", udc, strerror(errno));
        return -1;
    }
    tdc_lx_logf("usb: gadget bound to %s, serial %s", udc, tdc_lx_opts.serial);
    return 0;
}

int tdc_lx_ffs_init(uint32_t width, uint32_t height, uint32_t refresh_mhz, uint32_t rx_bytes, uint32_t max_packet)
{
    char path[512];
    snprintf(path, sizeof path, "%s/slots.bin", tdc_lx_opts.state_dir);
    if (mkdir_ok(tdc_lx_opts.state_dir) || (g_slots = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0644)) < 0) {
        tdc_lx_logf("dfu: no slot file %s: %s (updates will fail)", path, strerror(errno));
    }
    tdc_usbp_config_t cfg = {.board_name = "linux",
                             .panel_name = TDC_PANEL_NAME,
                             .serial = tdc_lx_opts.serial,
                             .fw_version = 0x000100u,
                             .panel_width = (uint16_t)width,
                             .panel_height = (uint16_t)height,
                             .refresh_mhz = refresh_mhz,
                             .rx_buffer_bytes = rx_bytes,
                             .max_packet_bytes = max_packet,
                             .flash = {slot_write, slot_read, NULL, SLOT_BYTES, NULL}, /* a file: writes within DNLOAD */
                             .sink = NULL,
                             .sink_ctx = NULL};
    if (tdc_usbp_init(&g_proto, &cfg) != TDC_OK) {
        tdc_lx_fail(TDC_LX_EXIT_ARGS, "usb: protocol refused the configuration (serial longer than 31 characters?)");
        return -1;
    }
    if (make_gadget() != 0) return -1;
    if (mkdir_ok(tdc_lx_opts.ffs_dir) != 0) {
        tdc_lx_fail(TDC_LX_EXIT_IO, "usb: gadget not bound: cannot create %s: %s", tdc_lx_opts.ffs_dir, strerror(errno));
        return -1;
    }
    snprintf(path, sizeof path, "%s/ep0", tdc_lx_opts.ffs_dir);
    if (access(path, F_OK) != 0 && mount(FFS_NAME, tdc_lx_opts.ffs_dir, "functionfs", 0, NULL) != 0) {
        tdc_lx_fail(TDC_LX_EXIT_NO_DEVICE, "usb: gadget not bound: cannot mount FunctionFS at %s: %s (usb_f_fs loaded?)",
                    tdc_lx_opts.ffs_dir, strerror(errno));
        return -1;
    }
    if ((g_ep0 = open(path, O_RDWR | O_CLOEXEC)) < 0 || tdc_ffs_write_descriptors(g_ep0) != 0) {
        tdc_lx_fail(TDC_LX_EXIT_IO, "usb: gadget not bound: FunctionFS ep0 %s: %s", path, strerror(errno));
        return -1;
    }
    const int bad = tdc_lx_thread(ep0_thread) != 0 || tdc_lx_thread(status_thread) != 0;
    if (bad) {
        tdc_lx_fail(TDC_LX_EXIT_IO, "usb: cannot start the endpoint threads");
        return -1;
    }
    return bind_udc();
}
