/*
 * tdc_usb_dfu.c - tdc-usb flash and mkimage: image checks on the host, then
 * USB DFU 1.1 download, manifestation (the board's own size/CRC check),
 * read-back verify and reset (docs/usb-protocol.md).
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tdc_usb_cmd.h"

/* ------------------------------------------------------------------ */
/* flash (DFU 1.1)                                                     */
/* ------------------------------------------------------------------ */
tdc_exit_t tdc_usb_read_file(const char *path, const char *op, uint8_t **data, uint32_t *len)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        fprintf(stderr, "tdc-usb: %s: cannot open %s: %s\n", op, path, strerror(errno));
        return TDC_EXIT_FILE;
    }
    long sz = -1;
    if (fseek(f, 0, SEEK_END) == 0) sz = ftell(f);
    if (sz < 0 || sz > (64L << 20)) {
        fprintf(stderr, "tdc-usb: %s: %s: not a regular file or larger than 64 MiB\n", op, path);
        fclose(f);
        return TDC_EXIT_FILE;
    }
    rewind(f);
    *data = malloc(sz > 0 ? (size_t)sz : 1u);
    if (*data == NULL || fread(*data, 1, (size_t)sz, f) != (size_t)sz) {
        fprintf(stderr, "tdc-usb: %s: cannot read %s\n", op, path);
        free(*data);
        *data = NULL;
        fclose(f);
        return TDC_EXIT_FILE;
    }
    fclose(f);
    *len = (uint32_t)sz;
    return TDC_EXIT_OK;
}

static uint16_t dfu_transfer_size(tdc_board_t *b)
{
    struct libusb_config_descriptor *cd = NULL;
    uint16_t size = TDC_DFU_TRANSFER_SIZE;
    if (libusb_get_active_config_descriptor(libusb_get_device(b->h), &cd) != 0) return size;
    for (int i = 0; i < cd->bNumInterfaces; i++) {
        const struct libusb_interface_descriptor *id = &cd->interface[i].altsetting[0];
        if (id->bInterfaceClass != 0xFE || id->bInterfaceSubClass != 0x01) continue;
        size = tdc_usb_dfu_transfer_size(id->extra, id->extra_length, size);
    }
    libusb_free_config_descriptor(cd);
    return size;
}

static tdc_exit_t dfu_getstatus(tdc_board_t *b, uint8_t st[6])
{
    int got = 0;
    tdc_exit_t e = tdc_usb_ctrl_in(b, "DFU_GETSTATUS", LIBUSB_REQUEST_TYPE_CLASS | LIBUSB_RECIPIENT_INTERFACE,
                                   TDC_DFU_GETSTATUS, 0, TDC_USB_IF_DFU, st, 6, &got);
    if (e == TDC_EXIT_OK && got != 6) {
        fprintf(stderr, "tdc-usb: flash: DFU_GETSTATUS returned %d bytes, not 6\n", got);
        return TDC_EXIT_PROTOCOL;
    }
    return e;
}

/* Polls GETSTATUS (honouring bwPollTimeout) until the state is `want` or
 * dfuERROR, within DFU_STATUS_DEADLINE_MS. */
static tdc_exit_t dfu_wait(tdc_board_t *b, uint8_t want, const char *step)
{
    double deadline = tdc_usb_now_s() + DFU_STATUS_DEADLINE_MS / 1000.0;
    for (;;) {
        uint8_t st[6];
        tdc_exit_t e = dfu_getstatus(b, st);
        if (e != TDC_EXIT_OK) return e;
        if (st[4] == TDC_DFU_STATE_ERROR || st[0] != TDC_DFU_OK) {
            fprintf(stderr, "tdc-usb: flash: board rejected the %s: DFU status %s, state %s\n", step,
                    tdc_dfu_status_name((tdc_dfu_status_t)st[0]), tdc_dfu_state_name((tdc_dfu_state_t)st[4]));
            return TDC_EXIT_DFU;
        }
        if (st[4] == want) return TDC_EXIT_OK;
        if (tdc_usb_now_s() > deadline) {
            fprintf(stderr, "tdc-usb: flash: board still in %s after %u ms during the %s\n",
                    tdc_dfu_state_name((tdc_dfu_state_t)st[4]), DFU_STATUS_DEADLINE_MS, step);
            return TDC_EXIT_TIMEOUT;
        }
        unsigned poll_ms = st[1] | (st[2] << 8) | (st[3] << 16);
        struct timespec ts = {poll_ms / 1000u, (long)(poll_ms % 1000u) * 1000000L};
        nanosleep(&ts, NULL);
    }
}

/* Reads the image and checks it on the host, before any board is touched.
 * A standard DFU suffix (dfu-suffix, tdc-usb mkimage) is checked and
 * stripped, as dfu-util does: the board receives the image without it. */
tdc_exit_t tdc_usb_load_image(const char *path, uint16_t vid, uint16_t pid, uint8_t **image, uint32_t *image_len)
{
    uint8_t *img = NULL;
    uint32_t len = 0;
    tdc_exit_t e = tdc_usb_read_file(path, "flash", &img, &len);
    if (e != TDC_EXIT_OK) return e;
    uint32_t file_len = len;
    tdc_dfu_suffix_status_t ss = tdc_dfu_suffix_check(img, file_len, vid, pid, &len);
    if (ss == TDC_DFU_SUFFIX_ERR_CRC || ss == TDC_DFU_SUFFIX_ERR_ID) {
        const uint8_t *sx = img + file_len - TDC_DFU_SUFFIX_LEN;
        if (ss == TDC_DFU_SUFFIX_ERR_CRC)
            fprintf(stderr, "tdc-usb: flash: %s: DFU suffix CRC does not match the file\n", path);
        else
            fprintf(stderr, "tdc-usb: flash: %s: DFU suffix is for USB %04x:%04x, the board is %04x:%04x\n", path,
                    tdc_get_le16(sx + TDC_DFU_SUFFIX_OFF_VID), tdc_get_le16(sx + TDC_DFU_SUFFIX_OFF_PID), vid, pid);
        free(img);
        return ss == TDC_DFU_SUFFIX_ERR_CRC ? TDC_EXIT_IMAGE : TDC_EXIT_INCOMPATIBLE;
    }
    tdc_status_t is = tdc_image_check(img, len, NULL, 0);
    if (is != TDC_OK) {
        fprintf(stderr, "tdc-usb: flash: %s: %s (file %u bytes", path, tdc_status_text(is), len);
        if (len >= TDC_IMAGE_HEADER_LEN && is != TDC_ERR_IMAGE_MAGIC)
            fprintf(stderr, ", header says %u + %u bytes", TDC_IMAGE_HEADER_LEN,
                    tdc_get_le32(img + TDC_IMAGE_OFF_PAYLOAD_LEN));
        fprintf(stderr, ")\n");
        free(img);
        return TDC_EXIT_IMAGE;
    }
    *image = img;
    *image_len = len;
    return TDC_EXIT_OK;
}

tdc_exit_t tdc_usb_cmd_flash(tdc_board_t *b, const opts_t *o, const char *path, const uint8_t *img, uint32_t len)
{
    board_info_t bi;
    tdc_exit_t e = tdc_usb_claim(b, TDC_USB_IF_STREAM);
    if (e == TDC_EXIT_OK) e = tdc_usb_get_info(b, &bi);
    if (e == TDC_EXIT_OK) {
        tdc_status_t is = tdc_image_check(img, len, bi.board, bi.slot);
        if (is != TDC_OK) {
            char target[TDC_IMAGE_BOARD_LEN + 1] = "";
            memcpy(target, img + TDC_IMAGE_OFF_BOARD, TDC_IMAGE_BOARD_LEN);
            fprintf(stderr,
                    "tdc-usb: flash: %s: %s (image %u bytes for board '%s'; board '%s' "
                    "has a %u-byte slot)\n",
                    path, tdc_status_text(is), len, target, bi.board, bi.slot);
            e = TDC_EXIT_INCOMPATIBLE;
        }
    }
    if (e == TDC_EXIT_OK) e = tdc_usb_claim(b, TDC_USB_IF_DFU);
    /* Bring the DFU interface to dfuIDLE. */
    uint8_t st[6];
    if (e == TDC_EXIT_OK) e = dfu_getstatus(b, st);
    if (e == TDC_EXIT_OK && st[4] == TDC_DFU_STATE_ERROR)
        e = tdc_usb_ctrl_out(b, "DFU_CLRSTATUS", LIBUSB_REQUEST_TYPE_CLASS | LIBUSB_RECIPIENT_INTERFACE,
                             TDC_DFU_CLRSTATUS, 0, TDC_USB_IF_DFU, NULL, 0);
    else if (e == TDC_EXIT_OK && st[4] != TDC_DFU_STATE_IDLE)
        e = tdc_usb_ctrl_out(b, "DFU_ABORT", LIBUSB_REQUEST_TYPE_CLASS | LIBUSB_RECIPIENT_INTERFACE, TDC_DFU_ABORT, 0,
                             TDC_USB_IF_DFU, NULL, 0);
    uint16_t xfer = dfu_transfer_size(b);
    double t0 = tdc_usb_now_s();
    uint16_t block = 0;
    for (uint32_t off = 0; e == TDC_EXIT_OK && off < len; off += xfer, block++) {
        uint16_t n = (uint16_t)(len - off < xfer ? len - off : xfer);
        e = tdc_usb_ctrl_out(b, "DFU_DNLOAD", LIBUSB_REQUEST_TYPE_CLASS | LIBUSB_RECIPIENT_INTERFACE, TDC_DFU_DNLOAD,
                             block, TDC_USB_IF_DFU, img + off, n);
        if (e == TDC_EXIT_OK) e = dfu_wait(b, TDC_DFU_STATE_DNLOAD_IDLE, "download");
        tdc_usb_progress(o, "flash", off + n, len, t0);
    }
    tdc_usb_progress_end(o);
    if (e == TDC_EXIT_OK) /* zero-length DNLOAD: end of image, manifest */
        e = tdc_usb_ctrl_out(b, "DFU_DNLOAD (end)", LIBUSB_REQUEST_TYPE_CLASS | LIBUSB_RECIPIENT_INTERFACE,
                             TDC_DFU_DNLOAD, block, TDC_USB_IF_DFU, NULL, 0);
    if (e == TDC_EXIT_OK) e = dfu_wait(b, TDC_DFU_STATE_IDLE, "image (manifestation: size and CRC check on the board)");
    if (e == TDC_EXIT_OK)
        printf("downloaded %u bytes in %.3f s, board checked size and CRC-32 %08x\n", len, tdc_usb_now_s() - t0,
               tdc_get_le32(img + TDC_IMAGE_OFF_PAYLOAD_CRC));
    if (e == TDC_EXIT_OK && o->verify) {
        uint8_t *back = malloc((size_t)len + xfer);
        uint32_t got_total = 0;
        for (block = 0; e == TDC_EXIT_OK && back != NULL; block++) {
            int got = 0;
            e = tdc_usb_ctrl_in(b, "DFU_UPLOAD", LIBUSB_REQUEST_TYPE_CLASS | LIBUSB_RECIPIENT_INTERFACE, TDC_DFU_UPLOAD,
                                block, TDC_USB_IF_DFU, back + got_total, xfer, &got);
            got_total += (uint32_t)got;
            if (got < xfer || got_total > len) break;
        }
        if (e == TDC_EXIT_OK && (back == NULL || got_total != len || memcmp(back, img, len) != 0)) {
            uint32_t first = 0;
            while (back != NULL && first < len && first < got_total && back[first] == img[first]) first++;
            fprintf(stderr,
                    "tdc-usb: flash: verify failed: read back %u of %u bytes, first "
                    "difference at byte %u\n",
                    got_total, len, first);
            e = TDC_EXIT_VERIFY;
        } else if (e == TDC_EXIT_OK) {
            printf("verified %u bytes read back\n", got_total);
        }
        free(back);
    }
    if (e == TDC_EXIT_OK && o->reset) {
        libusb_release_interface(b->h, TDC_USB_IF_DFU);
        int r =
            libusb_control_transfer(b->h, LIBUSB_ENDPOINT_OUT | LIBUSB_REQUEST_TYPE_VENDOR | LIBUSB_RECIPIENT_INTERFACE,
                                    TDC_USB_REQ_RESET_BOARD, 0, TDC_USB_IF_STREAM, NULL, 0, b->timeout_ms);
        /* A board may drop off the bus before the status stage completes. */
        if (r < 0 && r != LIBUSB_ERROR_NO_DEVICE && r != LIBUSB_ERROR_PIPE && r != LIBUSB_ERROR_IO)
            e = tdc_usb_fail(b, "reset request", r);
        else
            printf("board reset requested\n");
    }
    return e;
}

/* ------------------------------------------------------------------ */
tdc_exit_t tdc_usb_cmd_mkimage(const opts_t *o, const char *in, const char *out)
{
    if (o->board == NULL) return tdc_fail(TDC_EXIT_ARGS, "mkimage", "--board", "a board name is required");
    if (o->board[0] == '\0' || strlen(o->board) > TDC_IMAGE_BOARD_LEN)
        return tdc_fail(TDC_EXIT_ARGS, "mkimage", "--board", "'%s' does not fit the image header's %u characters",
                        o->board, TDC_IMAGE_BOARD_LEN);
    uint8_t *payload = NULL;
    uint32_t len = 0;
    tdc_exit_t e = tdc_usb_read_file(in, "mkimage", &payload, &len);
    if (e != TDC_EXIT_OK) return e;
    if (len > (64u << 20) - TDC_IMAGE_HEADER_LEN - TDC_DFU_SUFFIX_LEN) {
        free(payload);
        return tdc_fail(TDC_EXIT_FILE, "mkimage", in, "larger than 64 MiB");
    }
    /* header + payload + DFU suffix in one buffer: the suffix CRC covers both */
    uint8_t *file = malloc((size_t)len + TDC_IMAGE_HEADER_LEN + TDC_DFU_SUFFIX_LEN);
    if (file == NULL) {
        free(payload);
        return tdc_fail(TDC_EXIT_NOMEM, "mkimage", in, "out of memory");
    }
    tdc_image_make_header(file, payload, len, o->fw_version, o->board);
    memcpy(file + TDC_IMAGE_HEADER_LEN, payload, len);
    free(payload);
    const uint32_t img_len = TDC_IMAGE_HEADER_LEN + len;
    tdc_dfu_suffix_make(file + img_len, file, img_len, o->sel.vid, o->sel.pid);
    const uint32_t crc = tdc_get_le32(file + TDC_IMAGE_OFF_PAYLOAD_CRC);
    tdc_out_t w; /* a temporary renamed on success: a failed run leaves OUT as it was */
    int ok = tdc_out_open(&w, out, "wb") == 0 &&
             fwrite(file, 1, img_len + TDC_DFU_SUFFIX_LEN, w.f) == img_len + TDC_DFU_SUFFIX_LEN;
    free(file);
    if (!ok || tdc_out_commit(&w) != 0) {
        int err = errno;
        tdc_out_abort(&w);
        return tdc_fail(TDC_EXIT_FILE, "mkimage", out, "cannot write: %s", strerror(err));
    }
    printf("%s: %u + %u bytes + %u-byte DFU suffix (%04x:%04x), board %s, CRC-32 %08x\n", out, TDC_IMAGE_HEADER_LEN,
           len, TDC_DFU_SUFFIX_LEN, o->sel.vid, o->sel.pid, o->board, crc);
    return TDC_EXIT_OK;
}
