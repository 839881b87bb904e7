/*
 * tdc_usbproto.c - board side of the tdc USB protocol: descriptors, request
 * dispatch, board info, bulk accounting, status reports and the USB DFU 1.1
 * state machine (docs/usb-protocol.md).  No heap, no float: every buffer is
 * the caller's or a small automatic array of fixed size.
 */
#include "tdc_usbproto.h"

#include <string.h>

/* bmRequestType fields (USB 2.0 §9.3). */
#define REQ_DIR_IN 0x80u
#define REQ_TYPE_MASK 0x60u
#define REQ_TYPE_STANDARD 0x00u
#define REQ_TYPE_CLASS 0x20u
#define REQ_TYPE_VENDOR 0x40u
#define REQ_RECIP_MASK 0x1Fu
#define REQ_RECIP_DEVICE 0x00u
#define REQ_RECIP_INTERFACE 0x01u
#define STD_GET_DESCRIPTOR 0x06u

/* bwPollTimeout the board asks for while manifesting, milliseconds. */
#define DFU_MANIFEST_POLL_MS 10u

/* ---------------------------------------------------------------------
 * Image header checks (shared by host and board).
 * ------------------------------------------------------------------- */
static int board_name_matches(const uint8_t *field, const char *board)
{
    uint32_t i = 0;
    for (; i < TDC_IMAGE_BOARD_LEN && board[i] != '\0'; i++)
        if (field[i] != (uint8_t)board[i]) return 0;
    if (i == TDC_IMAGE_BOARD_LEN) return board[i] == '\0';
    return field[i] == 0u;
}

/* Header fields only; total_len = bytes that follow the start of the header. */
static tdc_status_t image_check_header(const uint8_t hdr[TDC_IMAGE_HEADER_LEN], uint32_t total_len, const char *board,
                                       uint32_t slot_bytes)
{
    if (total_len < TDC_IMAGE_HEADER_LEN) return TDC_ERR_IMAGE_SHORT;
    if (tdc_get_le32(hdr + TDC_IMAGE_OFF_MAGIC) != TDC_IMAGE_MAGIC) return TDC_ERR_IMAGE_MAGIC;
    if (tdc_get_le16(hdr + TDC_IMAGE_OFF_HDR_VERSION) != TDC_IMAGE_HEADER_VERSION ||
        tdc_get_le16(hdr + TDC_IMAGE_OFF_HDR_LEN) != TDC_IMAGE_HEADER_LEN)
        return TDC_ERR_IMAGE_HEADER;
    for (uint32_t i = TDC_IMAGE_OFF_RESERVED; i < TDC_IMAGE_HEADER_LEN; i++)
        if (hdr[i] != 0u) return TDC_ERR_IMAGE_HEADER;
    if (slot_bytes != 0u && total_len > slot_bytes) return TDC_ERR_IMAGE_TOO_BIG;
    if (tdc_get_le32(hdr + TDC_IMAGE_OFF_PAYLOAD_LEN) != total_len - TDC_IMAGE_HEADER_LEN) return TDC_ERR_IMAGE_SIZE;
    if (board != NULL && !board_name_matches(hdr + TDC_IMAGE_OFF_BOARD, board)) return TDC_ERR_IMAGE_BOARD;
    return TDC_OK;
}

tdc_status_t tdc_image_check(const uint8_t *image, uint32_t len, const char *board, uint32_t slot_bytes)
{
    if (image == NULL || len < TDC_IMAGE_HEADER_LEN) return TDC_ERR_IMAGE_SHORT;
    tdc_status_t st = image_check_header(image, len, board, slot_bytes);
    if (st != TDC_OK) return st;
    uint32_t crc = tdc_crc32(image + TDC_IMAGE_HEADER_LEN, len - TDC_IMAGE_HEADER_LEN);
    if (crc != tdc_get_le32(image + TDC_IMAGE_OFF_PAYLOAD_CRC)) return TDC_ERR_IMAGE_CRC;
    return TDC_OK;
}

void tdc_image_make_header(uint8_t hdr[TDC_IMAGE_HEADER_LEN], const uint8_t *payload, uint32_t payload_len,
                           uint32_t fw_version, const char *board)
{
    memset(hdr, 0, TDC_IMAGE_HEADER_LEN);
    tdc_put_le32(hdr + TDC_IMAGE_OFF_MAGIC, TDC_IMAGE_MAGIC);
    tdc_put_le16(hdr + TDC_IMAGE_OFF_HDR_VERSION, (uint16_t)TDC_IMAGE_HEADER_VERSION);
    tdc_put_le16(hdr + TDC_IMAGE_OFF_HDR_LEN, (uint16_t)TDC_IMAGE_HEADER_LEN);
    tdc_put_le32(hdr + TDC_IMAGE_OFF_PAYLOAD_LEN, payload_len);
    tdc_put_le32(hdr + TDC_IMAGE_OFF_PAYLOAD_CRC, tdc_crc32(payload, payload_len));
    tdc_put_le32(hdr + TDC_IMAGE_OFF_FW_VERSION, fw_version);
    for (uint32_t i = 0; board != NULL && i < TDC_IMAGE_BOARD_LEN && board[i] != '\0'; i++)
        hdr[TDC_IMAGE_OFF_BOARD + i] = (uint8_t)board[i];
}

/* DFU suffix CRC: the CRC-32 register (init 0xFFFFFFFF, reflected
 * 0xEDB88320) over every byte before the CRC field, not inverted at the
 * end: what dfu-util and dfu-suffix compute (dfu_file.c). */
tdc_dfu_suffix_status_t tdc_dfu_suffix_check(const uint8_t *file, uint32_t len, uint16_t vid, uint16_t pid,
                                             uint32_t *image_len)
{
    *image_len = len;
    if (file == NULL || len < TDC_DFU_SUFFIX_LEN) return TDC_DFU_SUFFIX_NONE;
    const uint8_t *sx = file + len - TDC_DFU_SUFFIX_LEN;
    if (sx[TDC_DFU_SUFFIX_OFF_SIG] != 'U' || sx[TDC_DFU_SUFFIX_OFF_SIG + 1] != 'F' ||
        sx[TDC_DFU_SUFFIX_OFF_SIG + 2] != 'D' || sx[TDC_DFU_SUFFIX_OFF_LEN] < TDC_DFU_SUFFIX_LEN ||
        sx[TDC_DFU_SUFFIX_OFF_LEN] > len)
        return TDC_DFU_SUFFIX_NONE;
    if (tdc_crc32_update(TDC_CRC32_INIT, file, len - 4u) != tdc_get_le32(sx + TDC_DFU_SUFFIX_OFF_CRC))
        return TDC_DFU_SUFFIX_ERR_CRC;
    const uint16_t fv = tdc_get_le16(sx + TDC_DFU_SUFFIX_OFF_VID);
    const uint16_t fp = tdc_get_le16(sx + TDC_DFU_SUFFIX_OFF_PID);
    if ((fv != 0xFFFFu && fv != vid) || (fp != 0xFFFFu && fp != pid)) return TDC_DFU_SUFFIX_ERR_ID;
    *image_len = len - sx[TDC_DFU_SUFFIX_OFF_LEN];
    return TDC_DFU_SUFFIX_OK;
}

void tdc_dfu_suffix_make(uint8_t out[TDC_DFU_SUFFIX_LEN], const uint8_t *file, uint32_t len, uint16_t vid, uint16_t pid)
{
    tdc_put_le16(out + TDC_DFU_SUFFIX_OFF_BCD_DEVICE, 0xFFFFu);
    tdc_put_le16(out + TDC_DFU_SUFFIX_OFF_PID, pid);
    tdc_put_le16(out + TDC_DFU_SUFFIX_OFF_VID, vid);
    tdc_put_le16(out + TDC_DFU_SUFFIX_OFF_BCD_DFU, 0x0100u);
    out[TDC_DFU_SUFFIX_OFF_SIG] = 'U';
    out[TDC_DFU_SUFFIX_OFF_SIG + 1] = 'F';
    out[TDC_DFU_SUFFIX_OFF_SIG + 2] = 'D';
    out[TDC_DFU_SUFFIX_OFF_LEN] = (uint8_t)TDC_DFU_SUFFIX_LEN;
    uint32_t crc = tdc_crc32_update(TDC_CRC32_INIT, file, len);
    crc = tdc_crc32_update(crc, out, TDC_DFU_SUFFIX_OFF_CRC);
    tdc_put_le32(out + TDC_DFU_SUFFIX_OFF_CRC, crc);
}

const char *tdc_dfu_status_name(tdc_dfu_status_t st)
{
    static const char *const names[] = {"OK",         "errTARGET",       "errFILE",     "errWRITE",
                                        "errERASE",   "errCHECK_ERASED", "errPROG",     "errVERIFY",
                                        "errADDRESS", "errNOTDONE",      "errFIRMWARE", "errVENDOR",
                                        "errUSBR",    "errPOR",          "errUNKNOWN",  "errSTALLEDPKT"};
    return (unsigned)st < sizeof names / sizeof names[0] ? names[st] : "err?";
}

const char *tdc_dfu_state_name(tdc_dfu_state_t st)
{
    static const char *const names[] = {"appIDLE",          "appDETACH",   "dfuIDLE",
                                        "dfuDNLOAD-SYNC",   "dfuDNBUSY",   "dfuDNLOAD-IDLE",
                                        "dfuMANIFEST-SYNC", "dfuMANIFEST", "dfuMANIFEST-WAIT-RESET",
                                        "dfuUPLOAD-IDLE",   "dfuERROR"};
    return (unsigned)st < sizeof names / sizeof names[0] ? names[st] : "dfu?";
}

/* ---------------------------------------------------------------------
 * Descriptors.
 * ------------------------------------------------------------------- */
uint32_t tdc_usbp_device_descriptor(uint8_t out[18])
{
    static const uint8_t dev[18] = {18, 0x01, 0x00, 0x02, /* bLength, DEVICE, bcdUSB 2.00 */
                                    0x00, 0x00, 0x00, 64, /* class per interface, ep0 max packet 64 */
                                    (uint8_t)(TDC_USB_VID & 0xFFu), (uint8_t)(TDC_USB_VID >> 8),
                                    (uint8_t)(TDC_USB_PID & 0xFFu), (uint8_t)(TDC_USB_PID >> 8),
                                    /* bcdDevice = protocol version, 0x0001 (little-endian: low byte first,
         * as every descriptor field: high byte first reads 0x0100) */
                                    (uint8_t)(TDC_USB_PROTO_VERSION & 0xFFu), (uint8_t)(TDC_USB_PROTO_VERSION >> 8), 1,
                                    2, 3, 1}; /* strings, 1 configuration */
    memcpy(out, dev, sizeof dev);
    return (uint32_t)sizeof dev;
}

uint32_t tdc_usbp_config_descriptor(uint8_t out[TDC_USB_CONFIG_DESC_LEN], int high_speed)
{
    const uint8_t mps_lo = high_speed ? 0x00u : 64u, mps_hi = high_speed ? 0x02u : 0x00u;
    const uint8_t cfg[TDC_USB_CONFIG_DESC_LEN] = {
        /* configuration: 2 interfaces, bus powered, 100 mA */
        9, 0x02, (uint8_t)TDC_USB_CONFIG_DESC_LEN, 0, 2, 1, 0, 0x80, 50,
        /* interface 0: vendor streaming, 2 bulk endpoints, string 4 */
        9, 0x04, TDC_USB_IF_STREAM, 0, 2, 0xFF, TDC_USB_STREAM_SUBCLASS, TDC_USB_STREAM_PROTOCOL, 4, 7, 0x05,
        TDC_USB_EP_LINK_OUT, 0x02, mps_lo, mps_hi, 0, 7, 0x05, TDC_USB_EP_STATUS_IN, 0x02, mps_lo, mps_hi, 0,
        /* interface 1: DFU 1.1 in DFU mode, string 5 */
        9, 0x04, TDC_USB_IF_DFU, 0, 0, 0xFE, 0x01, 0x02, 5,
        /* DFU functional: CanDnload|CanUpload|ManifestationTolerant,
         * detach timeout 1000 ms, wTransferSize, bcdDFUVersion 1.1 */
        9, 0x21, 0x07, 0xE8, 0x03, (uint8_t)(TDC_DFU_TRANSFER_SIZE & 0xFFu), (uint8_t)(TDC_DFU_TRANSFER_SIZE >> 8),
        0x10, 0x01};
    memcpy(out, cfg, sizeof cfg);
    return (uint32_t)sizeof cfg;
}

uint32_t tdc_usbp_string_descriptor(const tdc_usbp_t *s, uint8_t index, uint8_t *out, uint32_t cap)
{
    const char *str;
    switch (index) {
    case 0:
        if (cap < 4u) return 0;
        out[0] = 4;
        out[1] = 0x03;
        out[2] = 0x09;
        out[3] = 0x04; /* en-US */
        return 4;
    case 1: str = "tdc project"; break;
    case 2: str = "tdc display controller"; break;
    case 3: str = s->cfg.serial != NULL ? s->cfg.serial : "0"; break;
    case 4: str = "tdc link stream"; break;
    case 5: str = "tdc DFU (A/B slot)"; break;
    default: return 0;
    }
    uint32_t n = 2;
    for (uint32_t i = 0; str[i] != '\0' && n + 2u <= cap && n + 2u <= 64u; i++) {
        out[n] = (uint8_t)str[i]; /* ASCII -> UTF-16LE */
        out[n + 1u] = 0;
        n += 2u;
    }
    if (cap < 2u) return 0;
    out[0] = (uint8_t)n;
    out[1] = 0x03;
    return n;
}

/* ---------------------------------------------------------------------
 * State.
 * ------------------------------------------------------------------- */
tdc_status_t tdc_usbp_init(tdc_usbp_t *s, const tdc_usbp_config_t *cfg)
{
    if (s == NULL || cfg == NULL) return TDC_ERR_ARG;
    memset(s, 0, sizeof *s);
    s->cfg = *cfg;
    s->cnt.rx_crc = TDC_CRC32_INIT;
    s->dfu_state = TDC_DFU_STATE_IDLE;
    s->dfu_status = TDC_DFU_OK;
    return TDC_OK;
}

void tdc_usbp_parse_setup(const uint8_t raw[8], tdc_usbp_setup_t *out)
{
    out->bm_request_type = raw[0];
    out->b_request = raw[1];
    out->w_value = tdc_get_le16(raw + 2);
    out->w_index = tdc_get_le16(raw + 4);
    out->w_length = tdc_get_le16(raw + 6);
}

static void put_name(uint8_t *dst, const char *name)
{
    memset(dst, 0, TDC_USB_INFO_NAME_LEN);
    /* NUL padded; a name of exactly 16 characters fills the field */
    for (uint32_t i = 0; name != NULL && i < TDC_USB_INFO_NAME_LEN && name[i] != '\0'; i++) dst[i] = (uint8_t)name[i];
}

static uint32_t board_info(const tdc_usbp_t *s, uint8_t out[TDC_USB_INFO_LEN])
{
    const tdc_usbp_counters_t *c = &s->cnt;
    memset(out, 0, TDC_USB_INFO_LEN);
    tdc_put_le32(out + TDC_USB_INFO_OFF_MAGIC, TDC_USB_INFO_MAGIC);
    tdc_put_le16(out + TDC_USB_INFO_OFF_PROTO, (uint16_t)TDC_USB_PROTO_VERSION);
    tdc_put_le16(out + TDC_USB_INFO_OFF_LEN, (uint16_t)TDC_USB_INFO_LEN);
    tdc_put_le32(out + TDC_USB_INFO_OFF_FW_VERSION, s->cfg.fw_version);
    put_name(out + TDC_USB_INFO_OFF_BOARD, s->cfg.board_name);
    put_name(out + TDC_USB_INFO_OFF_PANEL, s->cfg.panel_name);
    tdc_put_le16(out + TDC_USB_INFO_OFF_WIDTH, s->cfg.panel_width);
    tdc_put_le16(out + TDC_USB_INFO_OFF_HEIGHT, s->cfg.panel_height);
    tdc_put_le32(out + TDC_USB_INFO_OFF_REFRESH, s->cfg.refresh_mhz);
    tdc_put_le32(out + TDC_USB_INFO_OFF_RX_BUF, s->cfg.rx_buffer_bytes);
    tdc_put_le32(out + TDC_USB_INFO_OFF_MAX_PKT, s->cfg.max_packet_bytes);
    tdc_put_le32(out + TDC_USB_INFO_OFF_SLOT, s->cfg.flash.slot_bytes);
    tdc_put_le32(out + TDC_USB_INFO_OFF_RX_XFERS, c->rx_transfers);
    tdc_put_le32(out + TDC_USB_INFO_OFF_RX_BYTES, (uint32_t)(c->rx_bytes & 0xFFFFFFFFu));
    tdc_put_le32(out + TDC_USB_INFO_OFF_RX_BYTES + 4, (uint32_t)(c->rx_bytes >> 32));
    tdc_put_le32(out + TDC_USB_INFO_OFF_RX_CRC, tdc_crc32_final(c->rx_crc));
    tdc_put_le32(out + TDC_USB_INFO_OFF_LINK_CRC, c->link_crc_errors);
    tdc_put_le32(out + TDC_USB_INFO_OFF_LINK_BAD, c->link_malformed);
    tdc_put_le32(out + TDC_USB_INFO_OFF_OVERRUNS, c->rx_overruns);
    tdc_put_le32(out + TDC_USB_INFO_OFF_DFU_ERRORS, c->dfu_errors);
    tdc_put_le32(out + TDC_USB_INFO_OFF_STALLS, c->stalls);
    tdc_put_le32(out + TDC_USB_INFO_OFF_FRAMES, c->frames_shown);
    return TDC_USB_INFO_LEN;
}

/* Copy an IN reply of n bytes, truncated to wLength and the buffer. */
static tdc_status_t reply_in(const uint8_t *src, uint32_t n, const tdc_usbp_setup_t *setup, uint8_t *reply,
                             uint32_t reply_cap, uint32_t *reply_len)
{
    if (n > setup->w_length) n = setup->w_length;
    if (n > reply_cap) return TDC_ERR_ARG;
    if (n > 0u) /* reply may be NULL with capacity 0 (wLength 0): no memcpy(NULL, .., 0) */
        memcpy(reply, src, n);
    *reply_len = n;
    return TDC_OK;
}

/* ---------------------------------------------------------------------
 * DFU 1.1.
 * ------------------------------------------------------------------- */
static tdc_status_t dfu_fail(tdc_usbp_t *s, tdc_dfu_status_t st)
{
    s->dfu_state = TDC_DFU_STATE_ERROR;
    s->dfu_status = st;
    s->cnt.dfu_errors++;
    return TDC_ERR_STALL;
}

static unsigned inactive_slot(const tdc_usbp_t *s)
{
    return s->dfu_active_slot ^ 1u;
}

static uint32_t slot_base(const tdc_usbp_t *s, unsigned slot)
{
    return slot * s->cfg.flash.slot_bytes;
}

/* Manifestation: the downloaded bytes must form a valid image for this
 * board.  Reads the inactive slot back in 64-byte pieces (CRC while reading). */
static tdc_dfu_status_t dfu_manifest(tdc_usbp_t *s)
{
    uint8_t hdr[TDC_IMAGE_HEADER_LEN];
    const tdc_usbp_flash_t *f = &s->cfg.flash;
    const uint32_t base = slot_base(s, inactive_slot(s));
    if (s->dfu_received < TDC_IMAGE_HEADER_LEN) return TDC_DFU_ERR_NOTDONE;
    if (f->read(f->ctx, base, hdr, TDC_IMAGE_HEADER_LEN) != 0) return TDC_DFU_ERR_VERIFY;
    tdc_status_t st = image_check_header(hdr, s->dfu_received, s->cfg.board_name, f->slot_bytes);
    if (st == TDC_ERR_IMAGE_SIZE) return TDC_DFU_ERR_NOTDONE;
    if (st == TDC_ERR_IMAGE_TOO_BIG) return TDC_DFU_ERR_ADDRESS;
    if (st != TDC_OK) return TDC_DFU_ERR_FILE;
    uint32_t crc = TDC_CRC32_INIT;
    uint8_t chunk[64];
    for (uint32_t off = TDC_IMAGE_HEADER_LEN; off < s->dfu_received;) {
        uint32_t n = s->dfu_received - off;
        if (n > sizeof chunk) n = (uint32_t)sizeof chunk;
        if (f->read(f->ctx, base + off, chunk, n) != 0) return TDC_DFU_ERR_VERIFY;
        crc = tdc_crc32_update(crc, chunk, n);
        off += n;
    }
    if (tdc_crc32_final(crc) != tdc_get_le32(hdr + TDC_IMAGE_OFF_PAYLOAD_CRC)) return TDC_DFU_ERR_VERIFY;
    return TDC_DFU_OK;
}

static tdc_status_t dfu_request(tdc_usbp_t *s, const tdc_usbp_setup_t *setup, const uint8_t *data_out, uint8_t *reply,
                                uint32_t reply_cap, uint32_t *reply_len)
{
    const int dir_in = (setup->bm_request_type & REQ_DIR_IN) != 0u;
    const tdc_usbp_flash_t *f = &s->cfg.flash;

    switch (setup->b_request) {
    case TDC_DFU_DNLOAD:
        if (dir_in) return dfu_fail(s, TDC_DFU_ERR_STALLEDPKT);
        if (s->dfu_state == TDC_DFU_STATE_IDLE) {
            if (setup->w_length == 0u) return dfu_fail(s, TDC_DFU_ERR_NOTDONE);
            s->dfu_received = 0;
            s->dfu_next_block = setup->w_value;
            /* the inactive slot is about to be overwritten: it no longer
             * holds an image to boot or upload; the running slot is untouched */
            s->dfu_slot_image[inactive_slot(s)] = 0;
            s->dfu_pending = 0;
            s->dfu_block_len = 0; /* a block an ABORT left unwritten */
        } else if (s->dfu_state == TDC_DFU_STATE_DNLOAD_IDLE) {
            if (setup->w_length == 0u) {
                s->dfu_state = TDC_DFU_STATE_MANIFEST_SYNC;
                return TDC_OK;
            }
        } else {
            return dfu_fail(s, TDC_DFU_ERR_STALLEDPKT);
        }
        if (setup->w_length > TDC_DFU_TRANSFER_SIZE || data_out == NULL || setup->w_value != s->dfu_next_block)
            return dfu_fail(s, TDC_DFU_ERR_STALLEDPKT);
        if ((uint64_t)s->dfu_received + setup->w_length > f->slot_bytes) return dfu_fail(s, TDC_DFU_ERR_ADDRESS);
        {
            const uint32_t at = slot_base(s, inactive_slot(s)) + s->dfu_received;
            const uint32_t ms = f->busy_ms != NULL ? f->busy_ms(f->ctx, at, setup->w_length) : 0u;
            if (ms != 0u) { /* too slow for the request: written after GETSTATUS */
                memcpy(s->dfu_block, data_out, setup->w_length);
                s->dfu_block_len = setup->w_length;
                s->dfu_block_ms = ms;
            } else if (f->write(f->ctx, at, data_out, setup->w_length) != 0) {
                return dfu_fail(s, TDC_DFU_ERR_WRITE);
            }
        }
        s->dfu_received += setup->w_length;
        s->dfu_next_block = (uint16_t)(s->dfu_next_block + 1u);
        s->dfu_state = TDC_DFU_STATE_DNLOAD_SYNC;
        return TDC_OK;

    case TDC_DFU_GETSTATUS: {
        if (!dir_in || setup->w_length < TDC_DFU_GETSTATUS_LEN) return dfu_fail(s, TDC_DFU_ERR_STALLEDPKT);
        if (reply_cap < TDC_DFU_GETSTATUS_LEN) /* caller error: answer nothing, change nothing */
            return TDC_ERR_ARG;
        uint32_t poll_ms = 0;
        if (s->dfu_state == TDC_DFU_STATE_DNLOAD_SYNC && s->dfu_block_len != 0u) {
            s->dfu_state = TDC_DFU_STATE_DNBUSY; /* DFU 1.1 §6.1.2: the block is written now */
            s->dfu_block_armed = 1;
            poll_ms = s->dfu_block_ms;
        } else if (s->dfu_state == TDC_DFU_STATE_DNLOAD_SYNC) {
            s->dfu_state = TDC_DFU_STATE_DNLOAD_IDLE; /* written within DNLOAD */
        } else if (s->dfu_state == TDC_DFU_STATE_DNBUSY) {
            poll_ms = s->dfu_block_ms; /* asked too early (or a board writing later): wait again */
        } else if (s->dfu_state == TDC_DFU_STATE_MANIFEST_SYNC) {
            tdc_dfu_status_t st = dfu_manifest(s);
            if (st != TDC_DFU_OK) {
                s->dfu_state = TDC_DFU_STATE_ERROR;
                s->dfu_status = st;
                s->cnt.dfu_errors++;
            } else {
                s->dfu_slot_image[inactive_slot(s)] = s->dfu_received;
                s->dfu_pending = 1; /* booted at the next reset (activation) */
                s->dfu_state = TDC_DFU_STATE_MANIFEST;
                poll_ms = DFU_MANIFEST_POLL_MS;
            }
        } else if (s->dfu_state == TDC_DFU_STATE_MANIFEST) {
            s->dfu_state = TDC_DFU_STATE_IDLE; /* manifestation tolerant */
        }
        uint8_t r[TDC_DFU_GETSTATUS_LEN] = {
            (uint8_t)s->dfu_status,   (uint8_t)(poll_ms & 0xFFu), (uint8_t)((poll_ms >> 8) & 0xFFu),
            (uint8_t)(poll_ms >> 16), (uint8_t)s->dfu_state,      0};
        return reply_in(r, TDC_DFU_GETSTATUS_LEN, setup, reply, reply_cap, reply_len);
    }

    case TDC_DFU_CLRSTATUS:
        if (dir_in || s->dfu_state != TDC_DFU_STATE_ERROR) return dfu_fail(s, TDC_DFU_ERR_STALLEDPKT);
        s->dfu_state = TDC_DFU_STATE_IDLE;
        s->dfu_status = TDC_DFU_OK;
        return TDC_OK;

    case TDC_DFU_GETSTATE: {
        if (!dir_in || setup->w_length < 1u) return dfu_fail(s, TDC_DFU_ERR_STALLEDPKT);
        uint8_t st = (uint8_t)s->dfu_state;
        return reply_in(&st, 1, setup, reply, reply_cap, reply_len);
    }

    case TDC_DFU_ABORT:
        if (dir_in) return dfu_fail(s, TDC_DFU_ERR_STALLEDPKT);
        switch (s->dfu_state) {
        case TDC_DFU_STATE_IDLE:
        case TDC_DFU_STATE_DNLOAD_SYNC:
        case TDC_DFU_STATE_DNLOAD_IDLE:
        case TDC_DFU_STATE_MANIFEST_SYNC:
        case TDC_DFU_STATE_UPLOAD_IDLE: s->dfu_state = TDC_DFU_STATE_IDLE; return TDC_OK;
        default: return dfu_fail(s, TDC_DFU_ERR_STALLEDPKT);
        }

    case TDC_DFU_UPLOAD: {
        if (!dir_in || setup->w_length > TDC_DFU_TRANSFER_SIZE) return dfu_fail(s, TDC_DFU_ERR_STALLEDPKT);
        if (s->dfu_state == TDC_DFU_STATE_IDLE) {
            /* the newest good image: the one waiting to be booted, else the
             * running one (a failed download never hides the last good image) */
            const unsigned in = inactive_slot(s);
            s->dfu_upload_slot = (uint8_t)(s->dfu_pending && s->dfu_slot_image[in] ? in : s->dfu_active_slot);
            s->dfu_upload_pos = 0;
        } else if (s->dfu_state != TDC_DFU_STATE_UPLOAD_IDLE) {
            return dfu_fail(s, TDC_DFU_ERR_STALLEDPKT);
        }
        uint32_t n = s->dfu_slot_image[s->dfu_upload_slot] - s->dfu_upload_pos;
        if (n > setup->w_length) n = setup->w_length;
        if (n > reply_cap) return TDC_ERR_ARG;
        if (n > 0u && f->read(f->ctx, slot_base(s, s->dfu_upload_slot) + s->dfu_upload_pos, reply, n) != 0)
            return dfu_fail(s, TDC_DFU_ERR_VERIFY);
        s->dfu_upload_pos += n;
        /* a short frame ends the upload (DFU 1.1 §6.2) */
        s->dfu_state = n < setup->w_length ? TDC_DFU_STATE_IDLE : TDC_DFU_STATE_UPLOAD_IDLE;
        *reply_len = n;
        return TDC_OK;
    }

    case TDC_DFU_DETACH:
        /* DFU 1.1 semantics chosen here (docs/usb-protocol.md): the interface
         * is in DFU mode and manifestation tolerant, so DETACH does not
         * re-enumerate; it is accepted in dfuIDLE and arms the activation,
         * which the next USB reset performs (dfu-util -R: DETACH, then a
         * bus reset).  A reset alone activates too.  Elsewhere: STALL. */
        if (dir_in || s->dfu_state != TDC_DFU_STATE_IDLE) return dfu_fail(s, TDC_DFU_ERR_STALLEDPKT);
        s->detach_pending = 1;
        return TDC_OK;

    default: return dfu_fail(s, TDC_DFU_ERR_STALLEDPKT);
    }
}

int tdc_usbp_dfu_work(tdc_usbp_t *s)
{
    if (s == NULL || !s->dfu_block_armed) return 0;
    const tdc_usbp_flash_t *f = &s->cfg.flash;
    const uint32_t n = s->dfu_block_len;
    s->dfu_block_armed = 0;
    s->dfu_block_len = 0;
    if (s->dfu_state != TDC_DFU_STATE_DNBUSY) return 0; /* a stalled request ended the download */
    if (f->write(f->ctx, slot_base(s, inactive_slot(s)) + s->dfu_received - n, s->dfu_block, n) != 0) {
        (void)dfu_fail(s, TDC_DFU_ERR_WRITE);
    } else {
        s->dfu_state = TDC_DFU_STATE_DNLOAD_SYNC; /* the next GETSTATUS: dfuDNLOAD-IDLE */
    }
    return 1;
}

int tdc_usbp_bus_reset(tdc_usbp_t *s)
{
    if (s == NULL) return 0;
    int switched = 0;
    const unsigned in = inactive_slot(s);
    if (s->dfu_pending && s->dfu_slot_image[in] != 0u) {
        s->dfu_active_slot = (uint8_t)in;
        switched = 1;
    }
    s->dfu_pending = 0;
    s->detach_pending = 0;
    s->dfu_state = TDC_DFU_STATE_IDLE;
    s->dfu_status = TDC_DFU_OK;
    s->dfu_upload_pos = 0;
    s->dfu_received = 0;
    s->dfu_block_len = 0;
    s->dfu_block_armed = 0;
    return switched;
}

uint32_t tdc_usbp_slot_image(const tdc_usbp_t *s, unsigned slot)
{
    return s != NULL && slot < 2u ? s->dfu_slot_image[slot] : 0u;
}

/* ---------------------------------------------------------------------
 * Dispatch.
 * ------------------------------------------------------------------- */
static tdc_status_t control_dispatch(tdc_usbp_t *s, const tdc_usbp_setup_t *setup, const uint8_t *data_out,
                                     uint8_t *reply, uint32_t reply_cap, uint32_t *reply_len)
{
    const uint8_t type = setup->bm_request_type & REQ_TYPE_MASK;
    const uint8_t recip = setup->bm_request_type & REQ_RECIP_MASK;
    const int dir_in = (setup->bm_request_type & REQ_DIR_IN) != 0u;
    const uint8_t iface = (uint8_t)(setup->w_index & 0xFFu);

    if (type == REQ_TYPE_STANDARD && dir_in && setup->b_request == STD_GET_DESCRIPTOR) {
        uint8_t buf[TDC_USB_CONFIG_DESC_LEN + 16u];
        uint32_t n = 0;
        switch (setup->w_value >> 8) {
        case 1: n = tdc_usbp_device_descriptor(buf); break;
        case 2: n = tdc_usbp_config_descriptor(buf, 1); break;
        case 3: n = tdc_usbp_string_descriptor(s, (uint8_t)(setup->w_value & 0xFFu), buf, (uint32_t)sizeof buf); break;
        default: break;
        }
        if (n == 0u) return TDC_ERR_STALL;
        return reply_in(buf, n, setup, reply, reply_cap, reply_len);
    }
    if (type == REQ_TYPE_VENDOR && (recip == REQ_RECIP_INTERFACE || recip == REQ_RECIP_DEVICE) &&
        iface == TDC_USB_IF_STREAM) {
        switch (setup->b_request) {
        case TDC_USB_REQ_BOARD_INFO: {
            if (!dir_in) return TDC_ERR_STALL;
            uint8_t info[TDC_USB_INFO_LEN];
            return reply_in(info, board_info(s, info), setup, reply, reply_cap, reply_len);
        }
        case TDC_USB_REQ_RESET_COUNTERS: {
            if (dir_in) return TDC_ERR_STALL;
            uint32_t stalls = s->cnt.stalls;
            memset(&s->cnt, 0, sizeof s->cnt);
            s->cnt.rx_crc = TDC_CRC32_INIT;
            s->cnt.stalls = stalls; /* stalls are a lifetime count */
            return TDC_OK;
        }
        case TDC_USB_REQ_RESET_BOARD:
            if (dir_in) return TDC_ERR_STALL;
            s->reset_pending = 1;
            return TDC_OK;
        default: return TDC_ERR_STALL;
        }
    }
    if (type == REQ_TYPE_CLASS && recip == REQ_RECIP_INTERFACE && iface == TDC_USB_IF_DFU)
        return dfu_request(s, setup, data_out, reply, reply_cap, reply_len);
    return TDC_ERR_STALL;
}

tdc_status_t tdc_usbp_control(tdc_usbp_t *s, const tdc_usbp_setup_t *setup, const uint8_t *data_out, uint8_t *reply,
                              uint32_t reply_cap, uint32_t *reply_len)
{
    if (s == NULL || setup == NULL || reply_len == NULL || (reply == NULL && reply_cap != 0u)) return TDC_ERR_ARG;
    *reply_len = 0;
    tdc_status_t r = control_dispatch(s, setup, data_out, reply, reply_cap, reply_len);
    if (r == TDC_ERR_STALL) s->cnt.stalls++;
    return r;
}

void tdc_usbp_bulk_out(tdc_usbp_t *s, const uint8_t *data, uint32_t len)
{
    if (s == NULL || (data == NULL && len != 0u)) return;
    s->cnt.rx_transfers++;
    s->cnt.rx_bytes += len;
    s->cnt.rx_crc = tdc_crc32_update(s->cnt.rx_crc, data, len);
    if (s->cfg.sink == NULL) return;
    /* Counters wrap modulo 2^32 (unsigned, defined); hosts compare deltas. */
    tdc_usbp_sink_report_t d = {0, 0, 0, 0};
    s->cfg.sink(s->cfg.sink_ctx, data, len, &d);
    s->cnt.link_crc_errors += d.crc_errors;
    s->cnt.link_malformed += d.malformed;
    s->cnt.rx_overruns += d.overruns;
    s->cnt.frames_shown += d.frames;
}

void tdc_usbp_status_report(tdc_usbp_t *s, uint8_t out[TDC_USB_STATUS_LEN])
{
    const tdc_usbp_counters_t *c = &s->cnt;
    memset(out, 0, TDC_USB_STATUS_LEN);
    tdc_put_le32(out + TDC_USB_STATUS_OFF_MAGIC, TDC_USB_STATUS_MAGIC);
    tdc_put_le32(out + TDC_USB_STATUS_OFF_SEQ, s->status_seq++);
    out[TDC_USB_STATUS_OFF_DFU] = (uint8_t)s->dfu_state;
    out[TDC_USB_STATUS_OFF_DFU + 1] = (uint8_t)s->dfu_status;
    tdc_put_le32(out + TDC_USB_STATUS_OFF_RX_XFERS, c->rx_transfers);
    tdc_put_le32(out + TDC_USB_STATUS_OFF_RX_BYTES, (uint32_t)(c->rx_bytes & 0xFFFFFFFFu));
    tdc_put_le32(out + TDC_USB_STATUS_OFF_ERRORS, c->link_crc_errors + c->link_malformed + c->rx_overruns);
    tdc_put_le32(out + TDC_USB_STATUS_OFF_FRAMES, c->frames_shown);
    tdc_put_le32(out + TDC_USB_STATUS_OFF_RX_CRC, tdc_crc32_final(c->rx_crc));
}

int tdc_usbp_take_reset(tdc_usbp_t *s)
{
    if (s == NULL || !s->reset_pending) return 0;
    s->reset_pending = 0;
    return 1;
}
