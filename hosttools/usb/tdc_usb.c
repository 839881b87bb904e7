/*
 * tdc-usb - talk to a tdc display-controller board over USB (libusb-1.0):
 * list boards, show board info, stream link packets, flash firmware (DFU 1.1,
 * in tdc_usb_dfu.c).
 * Protocol: docs/usb-protocol.md.  Usage and exit codes: docs/hosttools.md.
 */
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "tdc_usb_cmd.h"
#include "tdc_usb_dev.h"
#include "tdc_usbproto.h"

static const char usage_text[] = "usage: tdc-usb [options] <command> [args]\n"
                                 "commands:\n"
                                 "  list                     boards (USB %04x:%04x) with bus, address and serial\n"
                                 "  info                     firmware, board, panel, buffer sizes, error counters\n"
                                 "  stream FILE|-            send a link stream (or stdin, e.g. live tdc-sim output)\n"
                                 "                           over bulk OUT; progress, throughput, board counters\n"
                                 "  flash IMAGE              DFU download with size and CRC checks, verify, reset\n"
                                 "  mkimage --board B [--fw-version X.Y.Z] IN.bin OUT.img\n"
                                 "                           wrap a raw binary: tdc image header + DFU suffix\n"
                                 "options:\n"
                                 "  --bus N --address N      select the board by USB bus and device address\n"
                                 "  --serial S               select the board by serial number\n"
                                 "  --vid V --pid P          other USB IDs (default %04x:%04x, pid.codes test PID)\n"
                                 "  --timeout MS             timeout of every USB transfer (default %u)\n"
                                 "  --chunk BYTES            stream: bytes per bulk transfer (default: board buffer)\n"
                                 "  --progress/--no-progress stream/flash: force the progress bar on or off\n"
                                 "  --no-verify --no-reset   flash: skip the read-back, do not reset afterwards\n"
                                 "  -h, --help               this text\n"
                                 "exit codes: 0 OK, 1 ARGS, 2 NO_DEVICE, 3 AMBIGUOUS, 4 IO, 5 TIMEOUT,\n"
                                 "  6 DISCONNECTED, 7 FILE, 8 IMAGE, 9 INCOMPATIBLE, 10 DFU, 11 VERIFY, 12 PROTOCOL\n";

static void usage(FILE *f)
{
    fprintf(f, usage_text, TDC_USB_VID, TDC_USB_PID, TDC_USB_VID, TDC_USB_PID, DEFAULT_TIMEOUT_MS);
}


double tdc_usb_now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void tdc_usb_progress(const opts_t *o, const char *label, uint64_t done, uint64_t total, double t0)
{
    if (o->progress == 0 || (o->progress < 0 && !isatty(2))) return;
    double dt = tdc_usb_now_s() - t0;
    double mbs = dt > 0 ? (double)done / dt / 1e6 : 0.0;
    if (total > 0) {
        int w = 30, fill = (int)((double)w * (double)done / (double)total);
        fprintf(stderr, "\r%s [%.*s%*s] %5.1f%% %.2f MB/s ", label, fill, "##############################", w - fill,
                "", 100.0 * (double)done / (double)total, mbs);
    } else {
        fprintf(stderr, "\r%s %llu bytes %.2f MB/s ", label, (unsigned long long)done, mbs);
    }
    fflush(stderr);
}

void tdc_usb_progress_end(const opts_t *o)
{
    if (o->progress == 1 || (o->progress < 0 && isatty(2))) fputc('\n', stderr);
}

/* ------------------------------------------------------------------ */
/* Board info                                                          */
/* ------------------------------------------------------------------ */

tdc_exit_t tdc_usb_get_info(tdc_board_t *b, board_info_t *bi)
{
    uint8_t raw[TDC_USB_INFO_LEN];
    int got = 0;
    tdc_exit_t e = tdc_usb_ctrl_in(b, "board-info request", LIBUSB_REQUEST_TYPE_VENDOR | LIBUSB_RECIPIENT_INTERFACE,
                                   TDC_USB_REQ_BOARD_INFO, 0, TDC_USB_IF_STREAM, raw, sizeof raw, &got);
    if (e != TDC_EXIT_OK) return e;
    if (tdc_usb_parse_info(raw, got, bi) != 0) {
        fprintf(stderr,
                "tdc-usb: %s: board info malformed (%d bytes, magic %08x, protocol %u; "
                "tdc-usb speaks protocol %u)\n",
                b->op, got, got >= 4 ? tdc_get_le32(raw) : 0u,
                got >= 6 ? tdc_get_le16(raw + TDC_USB_INFO_OFF_PROTO) : 0u, TDC_USB_PROTO_VERSION);
        return TDC_EXIT_PROTOCOL;
    }
    return TDC_EXIT_OK;
}

static void print_counters(const board_info_t *bi)
{
    printf("counters: rx_transfers %u rx_bytes %llu link_crc_errors %u link_malformed %u "
           "rx_overruns %u dfu_errors %u stalls %u frames %u\n",
           bi->rx_xfers, (unsigned long long)bi->rx_bytes, bi->link_crc, bi->link_bad, bi->overruns, bi->dfu_errors,
           bi->stalls, bi->frames);
}

static tdc_exit_t cmd_info(tdc_board_t *b)
{
    board_info_t bi;
    tdc_exit_t e = tdc_usb_claim(b, TDC_USB_IF_STREAM);
    if (e == TDC_EXIT_OK) e = tdc_usb_get_info(b, &bi);
    if (e != TDC_EXIT_OK) return e;
    printf("board: bus %03d address %03d serial %s\n", b->bus, b->address, b->serial);
    printf("firmware: %u.%u.%u (protocol %u)\n", bi.fw_version >> 16, (bi.fw_version >> 8) & 0xFFu,
           bi.fw_version & 0xFFu, TDC_USB_PROTO_VERSION);
    printf("board: %s\npanel: %s %ux%u @ %u.%03u Hz\n", bi.board, bi.panel, bi.width, bi.height, bi.refresh_mhz / 1000u,
           bi.refresh_mhz % 1000u);
    printf("buffers: link rx %u bytes, max link packet %u bytes, flash slot %u bytes\n", bi.rx_buf, bi.max_pkt,
           bi.slot);
    print_counters(&bi);
    return TDC_EXIT_OK;
}

/* ------------------------------------------------------------------ */
/* list                                                                */
/* ------------------------------------------------------------------ */
static void list_cb(void *ctx, libusb_device *dev, libusb_device_handle *h, const char *serial, int open_err)
{
    const opts_t *o = ctx;
    printf("bus %03u address %03u serial %s", libusb_get_bus_number(dev), libusb_get_device_address(dev),
           open_err == 0 ? serial : "?");
    if (open_err != 0) {
        printf(" (cannot open: %s)\n", libusb_error_name(open_err));
        return;
    }
    tdc_board_t b = {.h = h, .timeout_ms = o->sel.timeout_ms, .op = "list"};
    uint8_t raw[TDC_USB_INFO_LEN];
    int got = libusb_control_transfer(h, LIBUSB_ENDPOINT_IN | LIBUSB_REQUEST_TYPE_VENDOR | LIBUSB_RECIPIENT_INTERFACE,
                                      TDC_USB_REQ_BOARD_INFO, 0, TDC_USB_IF_STREAM, raw, sizeof raw, b.timeout_ms);
    board_info_t bi;
    if (tdc_usb_parse_info(raw, got, &bi) == 0)
        printf(" board %s panel %s fw %u.%u.%u\n", bi.board, bi.panel, bi.fw_version >> 16,
               (bi.fw_version >> 8) & 0xFFu, bi.fw_version & 0xFFu);
    else
        printf(" (board info: %s)\n", got < 0 ? libusb_error_name(got) : "malformed");
}

static tdc_exit_t cmd_list(libusb_context *ctx, opts_t *o)
{
    int n = tdc_usb_enumerate(ctx, &o->sel, list_cb, o);
    if (n < 0) {
        tdc_board_t b = {.op = "list"};
        return tdc_usb_fail(&b, "listing USB devices", n);
    }
    if (n == 0) {
        fprintf(stderr, "tdc-usb: list: no tdc board (USB %04x:%04x) found\n", o->sel.vid, o->sel.pid);
        return TDC_EXIT_NO_DEVICE;
    }
    return TDC_EXIT_OK;
}

/* ------------------------------------------------------------------ */
/* stream                                                              */
/* ------------------------------------------------------------------ */
/* Opened before the board, so a missing file is reported as such. */
static tdc_exit_t open_stream_file(const char *path, FILE **f)
{
    const int in = strcmp(path, "-") == 0;
    *f = in ? stdin : tdc_in_check(path) == 0 ? fopen(path, "rb") : NULL;
    if (*f == NULL) {
        fprintf(stderr, "tdc-usb: stream: cannot open %s: %s\n", path, strerror(errno));
        return TDC_EXIT_FILE;
    }
    return TDC_EXIT_OK;
}

static tdc_exit_t cmd_stream(tdc_board_t *b, const opts_t *o, const char *path, FILE *f)
{
    uint64_t total = 0;
    if (f != stdin && fseek(f, 0, SEEK_END) == 0) {
        long sz = ftell(f);
        total = sz > 0 ? (uint64_t)sz : 0;
        rewind(f);
    }
    board_info_t bi;
    tdc_exit_t e = tdc_usb_claim(b, TDC_USB_IF_STREAM);
    if (e == TDC_EXIT_OK) e = tdc_usb_get_info(b, &bi);
    if (e == TDC_EXIT_OK) /* counters (and the board's receive CRC) start with this stream */
        e = tdc_usb_ctrl_out(b, "reset-counters request", LIBUSB_REQUEST_TYPE_VENDOR | LIBUSB_RECIPIENT_INTERFACE,
                             TDC_USB_REQ_RESET_COUNTERS, 0, TDC_USB_IF_STREAM, NULL, 0);
    if (e != TDC_EXIT_OK) {
        if (f != stdin) fclose(f);
        return e;
    }
    long chunk = o->chunk > 0 ? o->chunk : (long)bi.rx_buf;
    if (chunk <= 0 || chunk > (1L << 20)) chunk = 16384;
    uint8_t *buf = malloc((size_t)chunk);
    if (buf == NULL) {
        fclose(f);
        return TDC_EXIT_FILE;
    }
    uint64_t sent = 0;
    uint32_t crc = TDC_CRC32_INIT;
    double t0 = tdc_usb_now_s(), last = 0;
    size_t n;
    while (e == TDC_EXIT_OK && (n = fread(buf, 1, (size_t)chunk, f)) > 0) {
        int done = 0;
        e = tdc_usb_bulk(b, "bulk OUT of link packets", b->ep_out, buf, (int)n, &done);
        sent += (uint64_t)done;
        crc = tdc_crc32_update(crc, buf, (uint32_t)done);
        if (e == TDC_EXIT_OK && done != (int)n) {
            fprintf(stderr, "tdc-usb: stream: board took %d of %zu bytes\n", done, n);
            e = TDC_EXIT_PROTOCOL;
        }
        double t = tdc_usb_now_s();
        if (t - last > 0.1) {
            tdc_usb_progress(o, "stream", sent, total, t0);
            last = t;
        }
    }
    const int read_err = ferror(f) ? (errno ? errno : EIO) : 0; /* before libusb calls change errno */
    tdc_usb_progress(o, "stream", sent, total, t0);
    tdc_usb_progress_end(o);
    double dt = tdc_usb_now_s() - t0;
    if (f != stdin) fclose(f);
    free(buf);
    if (e != TDC_EXIT_OK) {
        fprintf(stderr, "tdc-usb: stream: stopped after %llu bytes\n", (unsigned long long)sent);
        return e;
    }
    if (read_err) {
        fprintf(stderr, "tdc-usb: stream: cannot read %s: %s\n", path, strerror(read_err));
        return TDC_EXIT_FILE;
    }
    printf("sent %llu bytes in %.3f s: %.2f MB/s\n", (unsigned long long)sent, dt,
           dt > 0 ? (double)sent / dt / 1e6 : 0.0);
    /* The board's status (bulk IN) and its counters. */
    uint8_t st[TDC_USB_STATUS_LEN];
    int got = 0;
    e = tdc_usb_bulk(b, "bulk IN status report", b->ep_in, st, sizeof st, &got);
    if (e != TDC_EXIT_OK) return e;
    tdc_usb_status_t sr;
    if (tdc_usb_parse_status(st, got, &sr) != 0) {
        fprintf(stderr, "tdc-usb: stream: status report malformed (%d bytes)\n", got);
        return TDC_EXIT_PROTOCOL;
    }
    printf("status: seq %u errors %u frames %u\n", sr.seq, sr.errors, sr.frames);
    e = tdc_usb_get_info(b, &bi);
    if (e != TDC_EXIT_OK) return e;
    print_counters(&bi);
    if (bi.rx_bytes != sent || bi.rx_crc != ~crc) {
        fprintf(stderr,
                "tdc-usb: stream: board received %llu bytes with CRC-32 %08x, host sent "
                "%llu bytes with CRC-32 %08x\n",
                (unsigned long long)bi.rx_bytes, bi.rx_crc, (unsigned long long)sent, ~crc);
        return TDC_EXIT_VERIFY;
    }
    printf("board received all %llu bytes, CRC-32 %08x matches\n", (unsigned long long)sent, ~crc);
    return TDC_EXIT_OK;
}

/* Option numbers: decimal or 0x hex, whole string, range-checked (never wrapped). */
static int parse_long(const char *s, long lo, long hi, long *out)
{
    uint64_t v;
    if (tdc_parse_u64(s, (uint64_t)lo, (uint64_t)hi, &v) != 0) return -1;
    *out = (long)v;
    return 0;
}

/* X.Y.Z with X <= 65535, Y, Z <= 255, as 0x00XXYYZZ. */
static int parse_version(const char *s, uint32_t *out)
{
    uint64_t a, b, c;
    const char *e;
    if (tdc_parse_u64_field(s, &e, 0xFFFF, &a) != 0 || *e != '.' || tdc_parse_u64_field(e + 1, &e, 255, &b) != 0 ||
        *e != '.' || tdc_parse_u64_field(e + 1, &e, 255, &c) != 0 || *e != '\0')
        return -1;
    *out = (uint32_t)(a << 16 | b << 8 | c);
    return 0;
}

/* Every failure ends with "tdc-usb: exit N (NAME)" (docs/hosttools.md). */
static int finish(int e)
{
    if (e != TDC_EXIT_OK) fprintf(stderr, "tdc-usb: exit %d (%s)\n", e, tdc_exit_name(e));
    return e;
}

int main(int argc, char **argv)
{
    opts_t o = {.sel = {TDC_USB_VID, TDC_USB_PID, -1, -1, NULL, DEFAULT_TIMEOUT_MS},
                .progress = -1,
                .verify = 1,
                .reset = 1,
                .fw_version = 0x000100u};
    enum {
        O_BUS = 256,
        O_ADDR,
        O_SERIAL,
        O_VID,
        O_PID,
        O_TIMEOUT,
        O_CHUNK,
        O_PROG,
        O_NOPROG,
        O_NOVERIFY,
        O_NORESET,
        O_BOARD,
        O_FWV
    };
    static const struct option lopts[] = {{"bus", 1, 0, O_BUS},
                                          {"address", 1, 0, O_ADDR},
                                          {"serial", 1, 0, O_SERIAL},
                                          {"vid", 1, 0, O_VID},
                                          {"pid", 1, 0, O_PID},
                                          {"timeout", 1, 0, O_TIMEOUT},
                                          {"chunk", 1, 0, O_CHUNK},
                                          {"progress", 0, 0, O_PROG},
                                          {"no-progress", 0, 0, O_NOPROG},
                                          {"no-verify", 0, 0, O_NOVERIFY},
                                          {"no-reset", 0, 0, O_NORESET},
                                          {"board", 1, 0, O_BOARD},
                                          {"fw-version", 1, 0, O_FWV},
                                          {"help", 0, 0, 'h'},
                                          {0, 0, 0, 0}};
    int c;
    long v;
    tdc_tool_set_name("tdc-usb");
    opterr = 0; /* tdc_fail_getopt() writes the one line */
    while ((c = getopt_long(argc, argv, ":h", lopts, NULL)) != -1) {
        const char *bad = NULL;
        switch (c) {
        case O_BUS:
            if (parse_long(optarg, 1, 255, &v))
                bad = "--bus";
            else
                o.sel.bus = (int)v;
            break;
        case O_ADDR:
            if (parse_long(optarg, 1, 127, &v))
                bad = "--address";
            else
                o.sel.address = (int)v;
            break;
        case O_SERIAL: o.sel.serial = optarg; break;
        case O_VID:
            if (parse_long(optarg, 0, 0xFFFF, &v))
                bad = "--vid";
            else
                o.sel.vid = (uint16_t)v;
            break;
        case O_PID:
            if (parse_long(optarg, 0, 0xFFFF, &v))
                bad = "--pid";
            else
                o.sel.pid = (uint16_t)v;
            break;
        case O_TIMEOUT:
            if (parse_long(optarg, 1, 600000, &v))
                bad = "--timeout";
            else
                o.sel.timeout_ms = (unsigned)v;
            break;
        case O_CHUNK:
            if (parse_long(optarg, 1, 1L << 20, &v))
                bad = "--chunk";
            else
                o.chunk = v;
            break;
        case O_PROG: o.progress = 1; break;
        case O_NOPROG: o.progress = 0; break;
        case O_NOVERIFY: o.verify = 0; break;
        case O_NORESET: o.reset = 0; break;
        case O_BOARD: o.board = optarg; break;
        case O_FWV:
            if (parse_version(optarg, &o.fw_version)) bad = "--fw-version";
            break;
        case 'h': usage(stdout); return TDC_EXIT_OK;
        default: return finish(tdc_fail_getopt(c, argv));
        }
        if (bad != NULL) {
            return finish(tdc_fail_option(NULL, bad, optarg, "see tdc-usb --help"));
        }
    }
    if (optind >= argc) {
        return finish(tdc_fail_usage(NULL, "no command (list, info, stream, flash or mkimage)"));
    }
    const char *cmd = argv[optind];
    int nargs = argc - optind - 1;
    char **args = argv + optind + 1;
    int want = strcmp(cmd, "stream") == 0 || strcmp(cmd, "flash") == 0 ? 1
               : strcmp(cmd, "mkimage") == 0                           ? 2
               : strcmp(cmd, "list") == 0 || strcmp(cmd, "info") == 0  ? 0
                                                                       : -1;
    if (want < 0 || nargs != want) {
        return finish(want < 0 ? tdc_fail_usage(NULL, "unknown command '%s'", cmd)
                               : tdc_fail_usage(cmd, "wants %d argument(s), got %d", want, nargs));
    }
    if (strcmp(cmd, "mkimage") == 0) return finish(tdc_usb_cmd_mkimage(&o, args[0], args[1]));

    libusb_context *ctx = NULL;
    int r = libusb_init(&ctx);
    if (r != 0) {
        fprintf(stderr, "tdc-usb: libusb_init failed: %s (%s)\n", libusb_error_name(r), libusb_strerror(r));
        return finish(TDC_EXIT_IO);
    }
    tdc_exit_t e;
    if (strcmp(cmd, "list") == 0) {
        e = cmd_list(ctx, &o);
    } else {
        tdc_board_t b;
        memset(&b, 0, sizeof b);
        b.op = cmd;
        FILE *f = NULL;
        uint8_t *img = NULL;
        uint32_t len = 0;
        /* Local inputs first: a bad file is reported even without a board. */
        e = strcmp(cmd, "stream") == 0  ? open_stream_file(args[0], &f)
            : strcmp(cmd, "flash") == 0 ? tdc_usb_load_image(args[0], o.sel.vid, o.sel.pid, &img, &len)
                                        : TDC_EXIT_OK;
        if (e == TDC_EXIT_OK) e = tdc_usb_open(ctx, &o.sel, &b);
        if (e == TDC_EXIT_OK) {
            if (strcmp(cmd, "info") == 0)
                e = cmd_info(&b);
            else if (strcmp(cmd, "stream") == 0)
                e = cmd_stream(&b, &o, args[0], f);
            else
                e = tdc_usb_cmd_flash(&b, &o, args[0], img, len);
            tdc_usb_close(&b);
        } else if (f != NULL && f != stdin) {
            fclose(f);
        }
        free(img);
    }
    libusb_exit(ctx);
    return finish(e);
}
