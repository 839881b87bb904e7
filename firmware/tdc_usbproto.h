/*
 * tdc_usbproto.h - the board side of the tdc USB protocol (docs/usb-protocol.md).
 *
 * What lives here: the descriptors, the parsing of SETUP packets, the vendor
 * requests of the streaming interface (board info, counters, reset), the
 * bulk OUT accounting of link packets, the bulk IN status report, and the
 * USB DFU 1.1 state machine of the flashing interface with its image checks.
 * What does not: the USB device controller driver.  A board's USB stack (or
 * the FunctionFS gadget of `make test-vm`, or the umockdev emulation of the
 * tests) calls tdc_usbp_control() for every SETUP it does not handle itself,
 * tdc_usbp_bulk_out() for every bulk OUT transfer and
 * tdc_usbp_status_report() to fill the bulk IN endpoint.
 *
 * Firmware rules: no heap, no float, caller-owned state (tdc_usbp_t), every
 * multi-byte field is serialised explicitly little-endian (tdc_bytes.h's
 * tdc_get/put_le*, no struct punning), so the bytes on the wire do not
 * depend on the compiler or CPU; CRC-32 is the link's (tdc_crc32.h).
 */
#ifndef TDC_USBPROTO_H
#define TDC_USBPROTO_H

#include <stdint.h>
#include <stddef.h>

#include "tdc_crc32.h" /* CRC-32 of images and of the received bytes */
#include "tdc_status.h"
#include "tdc_bytes.h"

/* pid.codes open-source VID with its *test* PID 0x0001: for development and
 * CI only.  A shipped board must get its own PID from pid.codes. */
#define TDC_USB_VID 0x1209u
#define TDC_USB_PID 0x0001u

#define TDC_USB_PROTO_VERSION 1u

/* Interfaces and endpoints of configuration 1. */
#define TDC_USB_IF_STREAM 0u          /* vendor class 0xFF, subclass 'T', protocol 1 */
#define TDC_USB_IF_DFU 1u             /* DFU 1.1, DFU mode (0xFE/0x01/0x02) */
#define TDC_USB_EP_LINK_OUT 0x01u     /* bulk OUT: link packets, host -> board */
#define TDC_USB_EP_STATUS_IN 0x81u    /* bulk IN: status reports, board -> host */
#define TDC_USB_STREAM_SUBCLASS 0x54u /* 'T' */
#define TDC_USB_STREAM_PROTOCOL 0x01u

/* Vendor requests on the streaming interface (wIndex = TDC_USB_IF_STREAM). */
#define TDC_USB_REQ_BOARD_INFO 0x01u     /* IN  (0xC1): tdc board info, TDC_USB_INFO_LEN bytes */
#define TDC_USB_REQ_RESET_COUNTERS 0x02u /* OUT (0x41), no data */
#define TDC_USB_REQ_RESET_BOARD 0x03u    /* OUT (0x41), no data; board resets after the status stage */

/* Board info reply layout (little-endian, offsets in bytes). */
#define TDC_USB_INFO_MAGIC 0x42434454u /* "TDCB" */
#define TDC_USB_INFO_LEN 104u
#define TDC_USB_INFO_NAME_LEN 16u
enum {
    TDC_USB_INFO_OFF_MAGIC = 0,       /* u32 */
    TDC_USB_INFO_OFF_PROTO = 4,       /* u16 protocol version */
    TDC_USB_INFO_OFF_LEN = 6,         /* u16 length of this reply */
    TDC_USB_INFO_OFF_FW_VERSION = 8,  /* u32 major<<16 | minor<<8 | patch */
    TDC_USB_INFO_OFF_BOARD = 12,      /* char[16], NUL padded */
    TDC_USB_INFO_OFF_PANEL = 28,      /* char[16], NUL padded */
    TDC_USB_INFO_OFF_WIDTH = 44,      /* u16 panel width, pixels */
    TDC_USB_INFO_OFF_HEIGHT = 46,     /* u16 panel height, pixels */
    TDC_USB_INFO_OFF_REFRESH = 48,    /* u32 refresh, millihertz */
    TDC_USB_INFO_OFF_RX_BUF = 52,     /* u32 link receive buffer, bytes */
    TDC_USB_INFO_OFF_MAX_PKT = 56,    /* u32 largest link packet, bytes */
    TDC_USB_INFO_OFF_SLOT = 60,       /* u32 DFU flash slot, bytes */
    TDC_USB_INFO_OFF_RX_XFERS = 64,   /* u32 bulk OUT transfers received */
    TDC_USB_INFO_OFF_RX_BYTES = 68,   /* u64 bytes received (lo, hi) */
    TDC_USB_INFO_OFF_RX_CRC = 76,     /* u32 CRC-32 of every byte received since counter reset */
    TDC_USB_INFO_OFF_LINK_CRC = 80,   /* u32 link packets failing their CRC */
    TDC_USB_INFO_OFF_LINK_BAD = 84,   /* u32 malformed link packets */
    TDC_USB_INFO_OFF_OVERRUNS = 88,   /* u32 transfers dropped, receive buffer full */
    TDC_USB_INFO_OFF_DFU_ERRORS = 92, /* u32 DFU requests that ended in dfuERROR */
    TDC_USB_INFO_OFF_STALLS = 96,     /* u32 requests answered with STALL */
    TDC_USB_INFO_OFF_FRAMES = 100     /* u32 frames shown */
};

/* Bulk IN status report (little-endian). */
#define TDC_USB_STATUS_MAGIC 0x53434454u /* "TDCS" */
#define TDC_USB_STATUS_LEN 32u
enum {
    TDC_USB_STATUS_OFF_MAGIC = 0,     /* u32 */
    TDC_USB_STATUS_OFF_SEQ = 4,       /* u32 report sequence number */
    TDC_USB_STATUS_OFF_DFU = 8,       /* u8 DFU state, u8 DFU status, u16 reserved */
    TDC_USB_STATUS_OFF_RX_XFERS = 12, /* u32 */
    TDC_USB_STATUS_OFF_RX_BYTES = 16, /* u32 low 32 bits */
    TDC_USB_STATUS_OFF_ERRORS = 20,   /* u32 sum of link CRC, malformed, overrun */
    TDC_USB_STATUS_OFF_FRAMES = 24,   /* u32 frames shown */
    TDC_USB_STATUS_OFF_RX_CRC = 28    /* u32 running CRC-32 of received bytes */
};

/* USB DFU 1.1 (DFU_1.1.pdf): requests, states and status codes. */
enum {
    TDC_DFU_DETACH = 0,
    TDC_DFU_DNLOAD = 1,
    TDC_DFU_UPLOAD = 2,
    TDC_DFU_GETSTATUS = 3,
    TDC_DFU_CLRSTATUS = 4,
    TDC_DFU_GETSTATE = 5,
    TDC_DFU_ABORT = 6
};
typedef enum {
    TDC_DFU_STATE_APP_IDLE = 0,
    TDC_DFU_STATE_APP_DETACH = 1,
    TDC_DFU_STATE_IDLE = 2,
    TDC_DFU_STATE_DNLOAD_SYNC = 3,
    TDC_DFU_STATE_DNBUSY = 4,
    TDC_DFU_STATE_DNLOAD_IDLE = 5,
    TDC_DFU_STATE_MANIFEST_SYNC = 6,
    TDC_DFU_STATE_MANIFEST = 7,
    TDC_DFU_STATE_MANIFEST_WAIT_RESET = 8,
    TDC_DFU_STATE_UPLOAD_IDLE = 9,
    TDC_DFU_STATE_ERROR = 10
} tdc_dfu_state_t;
typedef enum {
    TDC_DFU_OK = 0x00,
    TDC_DFU_ERR_TARGET = 0x01,
    TDC_DFU_ERR_FILE = 0x02,
    TDC_DFU_ERR_WRITE = 0x03,
    TDC_DFU_ERR_ERASE = 0x04,
    TDC_DFU_ERR_CHECK_ERASED = 0x05,
    TDC_DFU_ERR_PROG = 0x06,
    TDC_DFU_ERR_VERIFY = 0x07,
    TDC_DFU_ERR_ADDRESS = 0x08,
    TDC_DFU_ERR_NOTDONE = 0x09,
    TDC_DFU_ERR_FIRMWARE = 0x0A,
    TDC_DFU_ERR_VENDOR = 0x0B,
    TDC_DFU_ERR_USBR = 0x0C,
    TDC_DFU_ERR_POR = 0x0D,
    TDC_DFU_ERR_UNKNOWN = 0x0E,
    TDC_DFU_ERR_STALLEDPKT = 0x0F
} tdc_dfu_status_t;
#define TDC_DFU_TRANSFER_SIZE 1024u /* wTransferSize of the DFU functional descriptor */
#define TDC_DFU_GETSTATUS_LEN 6u

/* tdc firmware image = 48-byte header + payload (what DFU downloads).
 * Header version 2: the board field holds 16 characters, the longest board
 * name (stm32h747i-disco) and the BOARD_INFO name field; version 1 had 12,
 * too few to name that board. */
#define TDC_IMAGE_MAGIC 0x46434454u /* "TDCF" */
#define TDC_IMAGE_HEADER_VERSION 2u
#define TDC_IMAGE_HEADER_LEN 48u
#define TDC_IMAGE_BOARD_LEN 16u /* = TDC_USB_INFO_NAME_LEN; NUL padded, not terminated at 16 */
enum {
    TDC_IMAGE_OFF_MAGIC = 0,        /* u32 */
    TDC_IMAGE_OFF_HDR_VERSION = 4,  /* u16 = 2 */
    TDC_IMAGE_OFF_HDR_LEN = 6,      /* u16 = 48 */
    TDC_IMAGE_OFF_PAYLOAD_LEN = 8,  /* u32 payload bytes after the header */
    TDC_IMAGE_OFF_PAYLOAD_CRC = 12, /* u32 CRC-32 (IEEE 802.3) of the payload */
    TDC_IMAGE_OFF_FW_VERSION = 16,  /* u32 */
    TDC_IMAGE_OFF_BOARD = 20,       /* char[16] target board name, NUL padded */
    TDC_IMAGE_OFF_RESERVED = 36     /* 12 bytes, zero */
};

/* Standard DFU file suffix (DFU 1.1 appendix B; what dfu-suffix writes and
 * dfu-util strips before downloading): 16 bytes at the end of a file. */
#define TDC_DFU_SUFFIX_LEN 16u
enum {
    TDC_DFU_SUFFIX_OFF_BCD_DEVICE = 0, /* u16, 0xFFFF = any */
    TDC_DFU_SUFFIX_OFF_PID = 2,        /* u16, 0xFFFF = any */
    TDC_DFU_SUFFIX_OFF_VID = 4,        /* u16, 0xFFFF = any */
    TDC_DFU_SUFFIX_OFF_BCD_DFU = 6,    /* u16 0x0100 */
    TDC_DFU_SUFFIX_OFF_SIG = 8,        /* "UFD" */
    TDC_DFU_SUFFIX_OFF_LEN = 11,       /* u8 16 */
    TDC_DFU_SUFFIX_OFF_CRC = 12        /* u32: CRC-32 register over the file before it, not inverted */
};
typedef enum {
    TDC_DFU_SUFFIX_NONE = 0,     /* no suffix: the whole file is the image */
    TDC_DFU_SUFFIX_OK = 1,       /* a valid suffix for vid:pid; the image is the bytes before it */
    TDC_DFU_SUFFIX_ERR_CRC = -1, /* a suffix whose CRC does not match the file */
    TDC_DFU_SUFFIX_ERR_ID = -2   /* a suffix for another USB device */
} tdc_dfu_suffix_status_t;
/* Looks for a suffix at the end of file (len bytes); *image_len gets the
 * bytes before it (len when there is none). */
tdc_dfu_suffix_status_t tdc_dfu_suffix_check(const uint8_t *file, uint32_t len, uint16_t vid, uint16_t pid,
                                             uint32_t *image_len);
/* Writes the 16-byte suffix for file[0..len) (bcdDevice any). */
void tdc_dfu_suffix_make(uint8_t out[TDC_DFU_SUFFIX_LEN], const uint8_t *file, uint32_t len, uint16_t vid,
                         uint16_t pid);


/* Results: tdc_status_t (tdc_status.h).  tdc_image_check() returns TDC_OK
 * or a TDC_ERR_IMAGE_* code; a control request TDC_OK (handled; for IN
 * requests *reply_len bytes are the data stage), TDC_ERR_STALL (protocol
 * error: stall the endpoint, counted) or TDC_ERR_ARG (caller error: null
 * pointer, reply buffer too small). */

/* What the board's link decoder found in one received transfer: counts
 * added to the board counters (a transfer may close several packets). */
typedef struct {
    uint32_t crc_errors; /* packets (or headers) failing their CRC */
    uint32_t malformed;  /* other rejected packets or discarded garbage */
    uint32_t overruns;   /* bytes dropped because the receive buffer was full */
    uint32_t frames;     /* frames completed (shown) */
} tdc_usbp_sink_report_t;

/* The DFU target: an A/B flash region behind two calls so the same state
 * machine drives internal flash on a board, RAM in the emulation and a file
 * in the gadget.  The region holds two slots of slot_bytes each, slot k at
 * offset k * slot_bytes (2 * slot_bytes in all); a download always goes to
 * the slot that is not running.  Both return 0 on success, non-zero on a
 * hardware failure. */
typedef struct {
    int (*write)(void *ctx, uint32_t offset, const uint8_t *data, uint32_t len);
    int (*read)(void *ctx, uint32_t offset, uint8_t *data, uint32_t len);
    void *ctx;
    uint32_t slot_bytes;
    /* Milliseconds a write(offset, len) may take, or 0 when it completes
     * within the DNLOAD request (RAM, a file, word programming).  NULL:
     * always 0.  Non-zero defers the write: GETSTATUS answers dfuDNBUSY
     * with this bwPollTimeout, the board runs tdc_usbp_dfu_work() after
     * the reply, and the host's next GETSTATUS finds dfuDNLOAD-SYNC. */
    uint32_t (*busy_ms)(void *ctx, uint32_t offset, uint32_t len);
} tdc_usbp_flash_t;

/* Called with each bulk OUT transfer; *delta arrives zeroed. */
typedef void (*tdc_usbp_sink_fn)(void *ctx, const uint8_t *data, uint32_t len, tdc_usbp_sink_report_t *delta);

typedef struct {
    const char *board_name; /* <= 16 chars (TDC_IMAGE_BOARD_LEN), also the image's target */
    const char *panel_name;
    const char *serial;  /* iSerialNumber, ASCII, <= 31 chars */
    uint32_t fw_version; /* major<<16 | minor<<8 | patch */
    uint16_t panel_width, panel_height;
    uint32_t refresh_mhz;
    uint32_t rx_buffer_bytes;
    uint32_t max_packet_bytes;
    tdc_usbp_flash_t flash;
    tdc_usbp_sink_fn sink; /* may be NULL: bytes are only counted */
    void *sink_ctx;
} tdc_usbp_config_t;

typedef struct {
    uint32_t rx_transfers;
    uint64_t rx_bytes;
    uint32_t rx_crc; /* running CRC-32 register (pre-inverted) */
    uint32_t link_crc_errors, link_malformed, rx_overruns;
    uint32_t dfu_errors, stalls;
    uint32_t frames_shown;
} tdc_usbp_counters_t;

typedef struct {
    tdc_usbp_config_t cfg;
    tdc_usbp_counters_t cnt;
    uint32_t status_seq;
    /* DFU */
    tdc_dfu_state_t dfu_state;
    tdc_dfu_status_t dfu_status;
    uint16_t dfu_next_block;
    uint32_t dfu_received;      /* bytes written to the inactive slot in this download */
    uint32_t dfu_slot_image[2]; /* bytes of the checked image each slot holds (0: none / destroyed) */
    uint8_t dfu_active_slot;    /* the slot the board runs */
    uint8_t dfu_pending;        /* the inactive slot holds a manifested image: boot it at the next reset */
    uint8_t dfu_upload_slot;    /* slot an upload in progress reads */
    uint8_t detach_pending;     /* DFU_DETACH acknowledged: reset (activate) within wDetachTimeOut */
    uint32_t dfu_upload_pos;
    uint32_t dfu_block_len;  /* a deferred block waits in dfu_block (busy_ms != 0) */
    uint32_t dfu_block_ms;   /* its bwPollTimeout */
    uint8_t dfu_block_armed; /* GETSTATUS answered dfuDNBUSY: tdc_usbp_dfu_work() writes it */
    uint8_t dfu_block[TDC_DFU_TRANSFER_SIZE];
    uint8_t reset_pending; /* RESET_BOARD acknowledged: reset after the status stage */
} tdc_usbp_t;

typedef struct {
    uint8_t bm_request_type, b_request;
    uint16_t w_value, w_index, w_length;
} tdc_usbp_setup_t;

/* State lifecycle. */
TDC_MUST_CHECK
tdc_status_t tdc_usbp_init(tdc_usbp_t *s, const tdc_usbp_config_t *cfg);

/* SETUP packet: 8 raw bytes -> fields (little-endian). */
void tdc_usbp_parse_setup(const uint8_t raw[8], tdc_usbp_setup_t *out);

/* One control request.  data_out: the OUT data stage (w_length bytes, may be
 * NULL when w_length is 0).  reply: buffer for the IN data stage, capacity
 * reply_cap; *reply_len gets the bytes to send (<= w_length).  Handles the
 * standard GET_DESCRIPTOR requests too (for stacks that forward them). */
TDC_MUST_CHECK
tdc_status_t tdc_usbp_control(tdc_usbp_t *s, const tdc_usbp_setup_t *setup, const uint8_t *data_out, uint8_t *reply,
                              uint32_t reply_cap, uint32_t *reply_len);

/* One bulk OUT transfer of link packets. */
void tdc_usbp_bulk_out(tdc_usbp_t *s, const uint8_t *data, uint32_t len);

/* Fill the bulk IN endpoint: TDC_USB_STATUS_LEN bytes into out. */
void tdc_usbp_status_report(tdc_usbp_t *s, uint8_t out[TDC_USB_STATUS_LEN]);

/* Returns 1 once after RESET_BOARD (or DFU_DETACH) was acknowledged: the
 * board then resets itself (and calls tdc_usbp_bus_reset() as it restarts). */
int tdc_usbp_take_reset(tdc_usbp_t *s);

/* Runs a download block deferred as dfuDNBUSY (tdc_usbp_flash_t.busy_ms),
 * once GETSTATUS's reply is on its way: the write, then dfuDNLOAD-SYNC, or
 * dfuERROR/errWRITE.  Returns 1 if it wrote (or failed), 0 if nothing was
 * waiting.  Boards whose busy_ms is NULL need not call it. */
int tdc_usbp_dfu_work(tdc_usbp_t *s);

/* A USB bus reset (or the board's own reset after RESET_BOARD/DETACH).
 * Activation (DFU 1.1 manifestation-tolerant, docs/usb-protocol.md): when
 * the inactive slot holds a manifested image, it becomes the running slot.
 * DFU state returns to dfuIDLE/OK either way.  Returns 1 if the slot
 * switched (the board then runs the new image), 0 if not. */
int tdc_usbp_bus_reset(tdc_usbp_t *s);
/* The image the board runs or will upload: slot index and its bytes (0 if
 * that slot holds no checked image). */
uint32_t tdc_usbp_slot_image(const tdc_usbp_t *s, unsigned slot);

/* Descriptors (high speed: bulk max packet 512; full speed: 64). */
uint32_t tdc_usbp_device_descriptor(uint8_t out[18]);
#define TDC_USB_CONFIG_DESC_LEN 50u
uint32_t tdc_usbp_config_descriptor(uint8_t out[TDC_USB_CONFIG_DESC_LEN], int high_speed);
/* String descriptor index 0..5 -> bytes in out (cap bytes), 0 if none. */
uint32_t tdc_usbp_string_descriptor(const tdc_usbp_t *s, uint8_t index, uint8_t *out, uint32_t cap);

/* Image checks shared by the board (manifest) and the host (before download).
 * image/len: header + payload as it would be downloaded.  board may be NULL
 * (no board check); slot_bytes 0 = no size limit. */
TDC_MUST_CHECK
tdc_status_t tdc_image_check(const uint8_t *image, uint32_t len, const char *board, uint32_t slot_bytes);
/* Write a header for payload (payload_len bytes) into hdr. */
void tdc_image_make_header(uint8_t hdr[TDC_IMAGE_HEADER_LEN], const uint8_t *payload, uint32_t payload_len,
                           uint32_t fw_version, const char *board);
const char *tdc_dfu_status_name(tdc_dfu_status_t st);
const char *tdc_dfu_state_name(tdc_dfu_state_t st);

#endif
