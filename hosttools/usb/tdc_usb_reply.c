/*
 * tdc_usb_reply.c - parsing of board replies for tdc-usb (tdc_usb_reply.h).
 */
#include "tdc_usb_reply.h"

#include <string.h>

int tdc_usb_parse_info(const uint8_t *raw, int got, board_info_t *bi)
{
    if (raw == NULL || got < (int)TDC_USB_INFO_LEN ||
        tdc_get_le32(raw + TDC_USB_INFO_OFF_MAGIC) != TDC_USB_INFO_MAGIC ||
        tdc_get_le16(raw + TDC_USB_INFO_OFF_PROTO) != TDC_USB_PROTO_VERSION)
        return -1;
    memset(bi, 0, sizeof *bi);
    bi->fw_version = tdc_get_le32(raw + TDC_USB_INFO_OFF_FW_VERSION);
    memcpy(bi->board, raw + TDC_USB_INFO_OFF_BOARD, TDC_USB_INFO_NAME_LEN);
    memcpy(bi->panel, raw + TDC_USB_INFO_OFF_PANEL, TDC_USB_INFO_NAME_LEN);
    bi->width = tdc_get_le16(raw + TDC_USB_INFO_OFF_WIDTH);
    bi->height = tdc_get_le16(raw + TDC_USB_INFO_OFF_HEIGHT);
    bi->refresh_mhz = tdc_get_le32(raw + TDC_USB_INFO_OFF_REFRESH);
    bi->rx_buf = tdc_get_le32(raw + TDC_USB_INFO_OFF_RX_BUF);
    bi->max_pkt = tdc_get_le32(raw + TDC_USB_INFO_OFF_MAX_PKT);
    bi->slot = tdc_get_le32(raw + TDC_USB_INFO_OFF_SLOT);
    bi->rx_xfers = tdc_get_le32(raw + TDC_USB_INFO_OFF_RX_XFERS);
    bi->rx_bytes = (uint64_t)tdc_get_le32(raw + TDC_USB_INFO_OFF_RX_BYTES) |
                   ((uint64_t)tdc_get_le32(raw + TDC_USB_INFO_OFF_RX_BYTES + 4) << 32);
    bi->rx_crc = tdc_get_le32(raw + TDC_USB_INFO_OFF_RX_CRC);
    bi->link_crc = tdc_get_le32(raw + TDC_USB_INFO_OFF_LINK_CRC);
    bi->link_bad = tdc_get_le32(raw + TDC_USB_INFO_OFF_LINK_BAD);
    bi->overruns = tdc_get_le32(raw + TDC_USB_INFO_OFF_OVERRUNS);
    bi->dfu_errors = tdc_get_le32(raw + TDC_USB_INFO_OFF_DFU_ERRORS);
    bi->stalls = tdc_get_le32(raw + TDC_USB_INFO_OFF_STALLS);
    bi->frames = tdc_get_le32(raw + TDC_USB_INFO_OFF_FRAMES);
    return 0;
}

uint16_t tdc_usb_dfu_transfer_size(const uint8_t *x, int len, uint16_t dflt)
{
    uint16_t size = dflt;
    /* each descriptor: bLength >= 2 and inside the buffer (a 7-byte DFU 1.0
     * descriptor at the end counts: the old loop wanted 9 bytes left) */
    for (int k = 0; x != NULL && k + 2 <= len && x[k] >= 2 && k + x[k] <= len; k += x[k])
        if (x[k + 1] == 0x21 && x[k] >= 7) size = (uint16_t)(x[k + 5] | (x[k + 6] << 8));
    return size >= 64 && size <= 4096 ? size : dflt;
}

int tdc_usb_string_decode(const uint8_t *buf, int r, char *out, int cap)
{
    if (cap < 1) return -1;
    out[0] = '\0';
    if (buf == NULL || r < 2 || buf[1] != 0x03 || buf[0] > r || buf[0] < 2) return -1;
    int n = 0;
    for (int i = 2; i + 1 < buf[0] && n + 1 < cap; i += 2)
        out[n++] = buf[i + 1] == 0 && buf[i] >= 0x20 && buf[i] < 0x7F ? (char)buf[i] : '?';
    out[n] = '\0';
    return n;
}

int tdc_usb_parse_status(const uint8_t *st, int got, tdc_usb_status_t *out)
{
    if (st == NULL || got < (int)TDC_USB_STATUS_LEN || tdc_get_le32(st) != TDC_USB_STATUS_MAGIC) return -1;
    out->seq = tdc_get_le32(st + TDC_USB_STATUS_OFF_SEQ);
    out->errors = tdc_get_le32(st + TDC_USB_STATUS_OFF_ERRORS);
    out->frames = tdc_get_le32(st + TDC_USB_STATUS_OFF_FRAMES);
    out->dfu_state = st[TDC_USB_STATUS_OFF_DFU];
    out->dfu_status = st[TDC_USB_STATUS_OFF_DFU + 1];
    return 0;
}
