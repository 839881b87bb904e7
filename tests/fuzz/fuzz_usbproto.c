/*
 * fuzz_usbproto.c - libFuzzer harness of the board side of the USB protocol
 * (firmware/tdc_usbproto.c): any sequence of control requests (any SETUP,
 * any data stage, any reply buffer size down to NULL/0), bulk OUT
 * transfers, status reports, bus resets, flash write failures and complete
 * valid downloads, on an A/B flash of two 4 KiB slots.
 *
 * Input: records, each starting with an op byte:
 *   op % 6 == 0  control: 8 SETUP bytes, 1 byte reply capacity selector,
 *                then the OUT data stage (wLength bytes, zero-padded)
 *   op % 6 == 1  bulk OUT: 1 length byte, then that many bytes
 *   op % 6 == 2  status report
 *   op % 6 == 3  USB bus reset (activation)
 *   op % 6 == 4  toggle a failing flash write
 *   op % 6 == 5  a whole valid download: 1 length byte (payload 0..255 x 8),
 *                1 board-name selector, payload from the following bytes
 * Aborts (besides the sanitizers) when:
 *   - a result is not OK/STALL/ARG, or an IN reply is longer than wLength or
 *     the buffer, or a state/status is outside DFU 1.1's;
 *   - TDC_ERR_ARG changed the DFU state or status (a caller error must not
 *     advance anything: the GETSTATUS-with-a-short-buffer finding);
 *   - the running slot's bytes changed, except by an activation, and an
 *     activated slot does not hold a valid image for this board (a failed
 *     download never destroys the last good image);
 *   - an UPLOAD returns bytes other than the start of the newest good image.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_usbproto.h"
#include "../usb/tdc_usbp_vive.h"

#define SLOT 4096u
#define BOARD "fuzzboard"

static uint8_t flash[2 * SLOT];
static int fail_write;

static int fw(void *ctx, uint32_t off, const uint8_t *d, uint32_t n)
{
    (void)ctx;
    if (fail_write || (uint64_t)off + n > 2u * SLOT) return -1;
    memcpy(flash + off, d, n);
    return 0;
}

static int fr(void *ctx, uint32_t off, uint8_t *d, uint32_t n)
{
    (void)ctx;
    if ((uint64_t)off + n > 2u * SLOT) return -1;
    memcpy(d, flash + off, n);
    return 0;
}

static tdc_usbp_t s;
static uint8_t shadow[SLOT]; /* the running slot as it must stay */
static uint32_t upload_off;  /* bytes of the current upload returned so far */
static uint8_t upload_src[SLOT];
static uint32_t upload_len;

static void check_state(void)
{
    if ((unsigned)s.dfu_state > TDC_DFU_STATE_ERROR || (unsigned)s.dfu_status > TDC_DFU_ERR_STALLEDPKT ||
        s.dfu_active_slot > 1u || s.dfu_slot_image[0] > SLOT || s.dfu_slot_image[1] > SLOT)
        abort();
    if (memcmp(flash + (size_t)s.dfu_active_slot * SLOT, shadow, SLOT) != 0)
        abort(); /* the running image was touched */
}

static void control(const uint8_t *raw, uint8_t capsel, const uint8_t *data)
{
    static uint8_t reply[1100];
    tdc_usbp_setup_t st;
    tdc_usbp_parse_setup(raw, &st);
    /* capacities: NULL/0, tiny, short of 6, exact, the whole buffer */
    static const uint32_t caps[8] = {0, 1, 5, 6, 64, 104, 1024, 1100};
    const uint32_t cap = caps[capsel & 7u];
    const tdc_dfu_state_t st0 = s.dfu_state;
    const tdc_dfu_status_t ss0 = s.dfu_status;
    const int is_upload_start = (st.bm_request_type & 0xE0u) == 0xA0u && st.b_request == TDC_DFU_UPLOAD &&
                                (st.w_index & 0xFFu) == TDC_USB_IF_DFU && st0 == TDC_DFU_STATE_IDLE;
    if (is_upload_start) { /* what it must return: the newest good image */
        const unsigned in = s.dfu_active_slot ^ 1u;
        const unsigned up = s.dfu_pending && s.dfu_slot_image[in] ? in : s.dfu_active_slot;
        upload_len = s.dfu_slot_image[up];
        memcpy(upload_src, flash + (size_t)up * SLOT, upload_len);
        upload_off = 0;
    }
    uint32_t n = 0xDEADu;
    tdc_status_t r = tdc_usbp_control(&s, &st, data, cap ? reply : NULL, cap, &n);
    if (r != TDC_OK && r != TDC_ERR_STALL && r != TDC_ERR_ARG) abort();
    if (r == TDC_OK && (n > st.w_length || n > cap)) abort();
    if (r == TDC_ERR_ARG && (s.dfu_state != st0 || s.dfu_status != ss0)) abort();
    if (r == TDC_OK && (st.bm_request_type & 0xE0u) == 0xA0u && st.b_request == TDC_DFU_UPLOAD &&
        (st.w_index & 0xFFu) == TDC_USB_IF_DFU && (st0 == TDC_DFU_STATE_IDLE || st0 == TDC_DFU_STATE_UPLOAD_IDLE)) {
        if (upload_off + n > upload_len || memcmp(reply, upload_src + upload_off, n) != 0) abort();
        upload_off += n;
    }
    (void)tdc_usbp_take_reset(&s);
}

static void bus_reset(void)
{
    if (tdc_usbp_bus_reset(&s)) {
        const uint32_t len = s.dfu_slot_image[s.dfu_active_slot];
        const uint8_t *img = flash + (size_t)s.dfu_active_slot * SLOT;
        if (len == 0 || tdc_image_check(img, len, BOARD, SLOT) != TDC_OK)
            abort(); /* booted something that is not a checked image */
        memcpy(shadow, img, SLOT);
    }
    if (s.dfu_state != TDC_DFU_STATE_IDLE || s.dfu_status != TDC_DFU_OK) abort();
}

static void full_download(uint32_t payload, const char *board, const uint8_t *src, size_t avail)
{
    static uint8_t img[SLOT + 2048];
    if (payload + TDC_IMAGE_HEADER_LEN > sizeof img) payload = (uint32_t)sizeof img - TDC_IMAGE_HEADER_LEN;
    for (uint32_t i = 0; i < payload; i++) img[TDC_IMAGE_HEADER_LEN + i] = i < avail ? src[i] : (uint8_t)i;
    tdc_image_make_header(img, img + TDC_IMAGE_HEADER_LEN, payload, 0x010203u, board);
    const uint32_t len = payload + TDC_IMAGE_HEADER_LEN;
    uint8_t raw[8], status[6];
    uint32_t n;
    uint16_t block = 0;
    for (uint32_t off = 0;; off += TDC_DFU_TRANSFER_SIZE, block++) {
        const uint16_t k =
            (uint16_t)(off >= len ? 0 : (len - off < TDC_DFU_TRANSFER_SIZE ? len - off : TDC_DFU_TRANSFER_SIZE));
        raw[0] = 0x21;
        raw[1] = TDC_DFU_DNLOAD;
        tdc_put_le16(raw + 2, block);
        tdc_put_le16(raw + 4, 1);
        tdc_put_le16(raw + 6, k);
        tdc_usbp_setup_t st;
        tdc_usbp_parse_setup(raw, &st);
        if (tdc_usbp_control(&s, &st, img + (off < len ? off : 0), NULL, 0, &n) != TDC_OK) return;
        check_state();
        for (int i = 0; i < 2; i++) { /* GETSTATUS (twice: manifest, then idle) */
            tdc_usbp_setup_t g = {0xA1, TDC_DFU_GETSTATUS, 0, 1, 6};
            if (tdc_usbp_control(&s, &g, NULL, status, sizeof status, &n) != TDC_OK) return;
            check_state();
        }
        if (k == 0) break;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    memset(flash, 0xFF, sizeof flash);
    memcpy(shadow, flash, SLOT);
    fail_write = 0;
    upload_len = upload_off = 0;
    const tdc_usbp_config_t cfg =
        tdc_usbp_vive_config(BOARD, "F1", 0x000100u, 8192u, (tdc_usbp_flash_t){fw, fr, NULL, SLOT, NULL});
    if (tdc_usbp_init(&s, &cfg) != TDC_OK) abort();
    size_t p = 0;
    while (p < size) {
        const uint8_t op = data[p++];
        switch (op % 6u) {
        case 0: {
            uint8_t raw[8] = {0};
            for (int i = 0; i < 8 && p < size; i++) raw[i] = data[p++];
            const uint8_t capsel = p < size ? data[p++] : 0;
            const uint16_t wlen = tdc_get_le16(raw + 6);
            static uint8_t out[65536];
            size_t k = wlen;
            if (k > size - p) k = size - p;
            memcpy(out, data + p, k);
            memset(out + k, 0, (size_t)wlen - k);
            p += k;
            /* OUT requests always come with their data stage; NULL when wLength is 0 */
            control(raw, capsel, (raw[0] & 0x80u) || wlen == 0 ? NULL : out);
            break;
        }
        case 1: {
            const uint32_t n = p < size ? data[p++] : 0;
            const uint32_t k = n < size - p ? n : (uint32_t)(size - p);
            tdc_usbp_bulk_out(&s, k ? data + p : NULL, k);
            p += k;
            break;
        }
        case 2: {
            uint8_t rep[TDC_USB_STATUS_LEN];
            tdc_usbp_status_report(&s, rep);
            if (tdc_get_le32(rep) != TDC_USB_STATUS_MAGIC || rep[TDC_USB_STATUS_OFF_DFU] != (uint8_t)s.dfu_state)
                abort();
            break;
        }
        case 3: bus_reset(); break;
        case 4: fail_write ^= 1; break;
        default: {
            const uint32_t payload = (p < size ? data[p++] : 0) * 8u;
            const uint8_t b = p < size ? data[p++] : 0;
            full_download(payload, (b & 3u) == 3u ? "otherboard" : BOARD, data + p, size - p);
            break;
        }
        }
        check_state();
    }
    return 0;
}
