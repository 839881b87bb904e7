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
 * DFU A/B of the board program (docs/boards.md "Updates"): a manifested
 * image whose payload is an ELF program is installed at the reset that
 * activates it as STATE/prog-<slot> with STATE/pending naming the slot, and
 * the program exits TDC_LX_EXIT_RESTART; its launcher
 * (boards/linux/tdc-board-launch) starts that slot on trial and keeps it
 * only if it writes STATE/confirmed (start-up done: display, gadget bound)
 * within N s, else it goes back to the slot in STATE/active.
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
#include <signal.h>
#include <stdlib.h>
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
 * was busy and not reading (a read then just waits for the next ENABLE).
 * Moved under g_lock, so a frame counted under g_lock is either counted
 * before the loss (and before the next host's reset-counters request, which
 * ep0_thread handles after the DISABLE) or not at all. */
static volatile unsigned g_lost;
/* The connection the loop's current run serves: g_lost when that run began
 * reading (main thread only). */
static unsigned g_seen;

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

/* ---- A/B program slots (files beside slots.bin, for the launcher) ---- */
static volatile int g_restart_pending;
int tdc_lx_restart; /* main() returns TDC_LX_EXIT_RESTART */

static void state_path(char *out, size_t cap, const char *name)
{
    snprintf(out, cap, "%s/%s", tdc_lx_opts.state_dir, name);
}

/* Writes a small state file whole or not at all (write, fsync, rename). */
static int state_put(const char *name, const char *text)
{
    char path[512], tmp[520];
    state_path(path, sizeof path, name);
    snprintf(tmp, sizeof tmp, "%s.new", path);
    FILE *f = fopen(tmp, "w");
    if (!f) return -1;
    const int bad = fputs(text, f) < 0 || fflush(f) != 0 || fsync(fileno(f)) != 0;
    if (fclose(f) != 0 || bad) return -1;
    return rename(tmp, path);
}

/* The slot's image, if its payload is a program (ELF), copied out as
 * STATE/prog-<slot> (mode 755) and STATE/pending = slot: 1; not a program
 * (a panel profile, data): 0; a file error: -1 (logged). */
static int install_program(unsigned slot)
{
    uint8_t hdr[TDC_IMAGE_HEADER_LEN + 4];
    const uint32_t base = (uint32_t)slot * SLOT_BYTES;
    if (slot_read(NULL, base, hdr, sizeof hdr) != 0) return -1;
    const uint32_t len = tdc_get_le32(hdr + TDC_IMAGE_OFF_PAYLOAD_LEN);
    if (len < 4u || memcmp(hdr + TDC_IMAGE_HEADER_LEN, "\177ELF", 4) != 0) return 0;
    char path[512], tmp[520], name[16];
    snprintf(name, sizeof name, "prog-%u", slot);
    state_path(path, sizeof path, name);
    snprintf(tmp, sizeof tmp, "%s.new", path);
    const int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0755);
    int bad = fd < 0;
    static uint8_t buf[65536];
    for (uint32_t off = 0; !bad && off < len; off += sizeof buf) {
        const uint32_t n = len - off < sizeof buf ? len - off : (uint32_t)sizeof buf;
        bad = slot_read(NULL, base + TDC_IMAGE_HEADER_LEN + off, buf, n) != 0 || write(fd, buf, n) != (ssize_t)n;
    }
    bad = bad || fsync(fd) != 0;
    if (fd >= 0 && close(fd) != 0) bad = 1;
    char num[16];
    snprintf(num, sizeof num, "%u\n", slot);
    if (bad || rename(tmp, path) != 0 || state_put("pending", num) != 0) {
        tdc_lx_logf("dfu: cannot install slot %u as %s: %s (the running program stays)", slot, path, strerror(errno));
        return -1;
    }
    return 1;
}

/* A USB reset or the board's own (RESET_BOARD, DFU_DETACH): a manifested
 * image becomes the active slot; a program is installed for the launcher,
 * and this one ends once the request is acknowledged (ep0_thread).  Called
 * with the lock held. */
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
        const int prog = install_program(g_proto.dfu_active_slot);
        if (prog == 1) {
            tdc_lx_logf("dfu: slot %u holds a board program: restarting into it on trial (launcher)",
                        g_proto.dfu_active_slot);
            g_restart_pending = 1;
        } else if (prog == 0) {
            tdc_lx_logf("dfu: slot %u is not a program (no ELF header): kept as data, this program runs on",
                        g_proto.dfu_active_slot);
        }
    }
}

/* The slot this program was started from (STATE/trial while on trial, else
 * STATE/active, written by the launcher): the protocol reports its image
 * and version, and the next download goes to the other slot. */
static void load_active_slot(void)
{
    char path[512];
    unsigned k = 2;
    state_path(path, sizeof path, "trial");
    FILE *f = fopen(path, "r");
    if (!f) {
        state_path(path, sizeof path, "active");
        f = fopen(path, "r");
    }
    if (f) {
        if (fscanf(f, "%u", &k) != 1) k = 2;
        fclose(f);
    }
    uint8_t hdr[TDC_IMAGE_HEADER_LEN];
    if (k > 1 || slot_read(NULL, (uint32_t)k * SLOT_BYTES, hdr, sizeof hdr) != 0 ||
        tdc_get_le32(hdr + TDC_IMAGE_OFF_MAGIC) != TDC_IMAGE_MAGIC) {
        return; /* the installed program (no slot) */
    }
    g_proto.dfu_active_slot = (uint8_t)k;
    g_proto.dfu_slot_image[k] = TDC_IMAGE_HEADER_LEN + tdc_get_le32(hdr + TDC_IMAGE_OFF_PAYLOAD_LEN);
    g_proto.cfg.fw_version = tdc_get_le32(hdr + TDC_IMAGE_OFF_FW_VERSION);
    tdc_lx_logf("dfu: running slot %u, firmware %u.%u.%u", k, g_proto.cfg.fw_version >> 16,
                (g_proto.cfg.fw_version >> 8) & 0xFFu, g_proto.cfg.fw_version & 0xFFu);
}

void tdc_lx_ffs_confirm(void)
{
    char num[32];
    snprintf(num, sizeof num, "%ld\n", (long)getpid());
    if (state_put("confirmed", num) != 0) tdc_lx_logf("dfu: cannot write %s/confirmed: %s", tdc_lx_opts.state_dir, strerror(errno));
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
                pthread_mutex_lock(&g_lock);
                if (g_enabled) {
                    tdc_lx_logf("usb: host gone (disconnected or reset): the panel keeps its last frame");
                    g_lost++;
                }
                g_enabled = 0;
                board_reset("USB reset");
                pthread_mutex_unlock(&g_lock);
                break;
            case FUNCTIONFS_UNBIND: tdc_lx_logf("usb: gadget unbound from its controller"); break;
            default: break;
            }
        }
        /* a new program was installed: end this one now that the request
         * that activated it has had its status stage (SIGTERM reaches the
         * main thread: its endpoint read returns, the loop ends) */
        if (g_restart_pending && !tdc_lx_restart) {
            tdc_lx_restart = 1;
            kill(getpid(), SIGTERM);
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

/* Bytes of the next connection that a read waiting through an unplug
 * returned: they start the next run of the loop (its fresh decoder). */
static uint8_t g_carry[16384];
static uint32_t g_carry_n;
/* Set when a run of the loop ends because its host went, until the next
 * run reads: the old run's last partial frame is not shown (the panel keeps
 * its last frame). */
static int g_stale;

int tdc_lx_ffs_stale(void)
{
    /* also while the loop, busy, has not yet read since its host went: a
     * frame it finishes then is the old stream's, and the next host may
     * already be streaming (make test-vm's re-plug saw such a frame flipped
     * and counted as the new stream's first) */
    return g_stale || g_seen != g_lost;
}

unsigned tdc_lx_ffs_conn(void)
{
    return g_seen;
}

int tdc_lx_ffs_read(uint8_t *buf, uint32_t cap, uint32_t *got)
{
    *got = 0;
    if (tdc_lx_stop) return -1;
    if (g_seen != g_lost) {
        g_seen = g_lost;
        g_stale = 1;
        tdc_lx_logf("usb: host gone: stream ended; the next connection starts a new one");
        if (g_ep1 >= 0) close(g_ep1);
        g_ep1 = -1;
        return -2;
    }
    g_stale = 0;
    if (g_carry_n) {
        const uint32_t n = g_carry_n < cap ? g_carry_n : cap;
        memcpy(buf, g_carry, n);
        memmove(g_carry, g_carry + n, g_carry_n - n);
        g_carry_n -= n;
        pthread_mutex_lock(&g_lock);
        tdc_usbp_bulk_out(&g_proto, buf, n);
        pthread_mutex_unlock(&g_lock);
        *got = n;
        return 1;
    }
    if (g_ep1 < 0 && (g_ep1 = open_ep("ep1")) < 0) {
        tdc_lx_logf("usb: cannot open bulk OUT endpoint %s/ep1: %s", tdc_lx_opts.ffs_dir, strerror(errno));
        usleep(100000);
        return 0;
    }
    ssize_t n = read(g_ep1, buf, cap); /* blocks until the host sends (or is configured) */
    if (n > 0 && g_seen != g_lost && (size_t)n <= sizeof g_carry) {
        /* The host went and came back while this read waited (FunctionFS
         * holds a read on a disabled function until it is enabled again):
         * the bytes are the new connection's, not this stream's tail (fed
         * to the old decoder, a half-received packet would swallow the new
         * stream's header; make test-vm's re-plug once waited for a frame
         * that never came at load average 17, before this). */
        g_seen = g_lost;
        memcpy(g_carry, buf, (size_t)n);
        g_carry_n = (uint32_t)n;
        g_stale = 1;
        tdc_lx_logf("usb: host gone: stream ended; the next connection's first %zd bytes start a new one", n);
        return -2;
    }
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
        g_seen = g_lost;
        g_stale = 1;
        return -2;
    }
    return 0;
}

void tdc_lx_ffs_frame_shown(unsigned conn)
{
    pthread_mutex_lock(&g_lock);
    if (conn == g_lost) g_proto.cnt.frames_shown++; /* else: a frame of a host that has gone */
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
    load_active_slot();
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
    const int bad = tdc_lx_thread(ep0_thread, NULL) != 0 || tdc_lx_thread(status_thread, NULL) != 0;
    if (bad) {
        tdc_lx_fail(TDC_LX_EXIT_IO, "usb: cannot start the endpoint threads");
        return -1;
    }
    return bind_udc();
}
