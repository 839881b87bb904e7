/*
 * test_usbproto.c - the board side of the USB protocol driven request by
 * request (firmware/tdc_usbproto.c): descriptors, board info, DFU 1.1
 * state machine including every rejected sequence, image checks.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "tdc_usbproto.h"
#include "tdc_usbp_vive.h"

#define SLOT 4096u

static uint8_t slot[2 * SLOT]; /* A/B: slot k at k * SLOT */
static int fail_write;

static int fw(void *ctx, uint32_t off, const uint8_t *d, uint32_t n)
{
    (void)ctx;
    if (fail_write || off + n > 2 * SLOT) return -1;
    memcpy(slot + off, d, n);
    return 0;
}

static int fr(void *ctx, uint32_t off, uint8_t *d, uint32_t n)
{
    (void)ctx;
    if (off + n > 2 * SLOT) return -1;
    memcpy(d, slot + off, n);
    return 0;
}

/* A flash whose erase unit is 2048 bytes: a block starting one is slow. */
#define ERASE_UNIT 2048u
#define ERASE_MS 1234u
static uint32_t fbusy(void *ctx, uint32_t off, uint32_t n)
{
    (void)ctx;
    (void)n;
    return off % ERASE_UNIT == 0u ? ERASE_MS : 0u;
}

static tdc_usbp_t s;
static uint32_t (*busy_hook)(void *, uint32_t, uint32_t);

static int setup(void **state)
{
    (void)state;
    memset(slot, 0xFF, sizeof slot);
    fail_write = 0;
    const tdc_usbp_config_t cfg =
        tdc_usbp_vive_config("testboard", "S1", 0x010203u, 8192u, (tdc_usbp_flash_t){fw, fr, NULL, SLOT, busy_hook});
    return tdc_usbp_init(&s, &cfg) == TDC_OK ? 0 : -1;
}

static int setup_busy(void **state)
{
    busy_hook = fbusy;
    int r = setup(state);
    busy_hook = NULL;
    return r;
}

static uint8_t reply[TDC_DFU_TRANSFER_SIZE];
static uint32_t rlen;

static tdc_status_t req(uint8_t type, uint8_t r, uint16_t value, uint16_t index, uint16_t len, const uint8_t *data)
{
    tdc_usbp_setup_t st = {type, r, value, index, len};
    return tdc_usbp_control(&s, &st, data, reply, sizeof reply, &rlen);
}

#define DFU_OUT 0x21u
#define DFU_IN 0xA1u

static uint8_t dfu_state(void)
{
    assert_int_equal(req(DFU_IN, TDC_DFU_GETSTATE, 0, 1, 1, NULL), TDC_OK);
    assert_int_equal(rlen, 1);
    return reply[0];
}

static void getstatus(uint8_t *status, uint8_t *state)
{
    assert_int_equal(req(DFU_IN, TDC_DFU_GETSTATUS, 0, 1, 6, NULL), TDC_OK);
    assert_int_equal(rlen, 6);
    *status = reply[0];
    *state = reply[4];
}

static uint8_t image[SLOT];
static uint32_t make_image(uint32_t payload, const char *board)
{
    for (uint32_t i = 0; i < payload; i++) image[TDC_IMAGE_HEADER_LEN + i] = (uint8_t)(i * 7u + 3u);
    tdc_image_make_header(image, image + TDC_IMAGE_HEADER_LEN, payload, 0x010203u, board);
    return payload + TDC_IMAGE_HEADER_LEN;
}

/* Downloads len bytes of image in blocks of bs; returns final status. */
static void download(uint32_t len, uint32_t bs, uint8_t *status, uint8_t *state)
{
    uint16_t block = 0;
    for (uint32_t off = 0; off < len; off += bs, block++) {
        uint16_t n = (uint16_t)(len - off < bs ? len - off : bs);
        assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, block, 1, n, image + off), TDC_OK);
        getstatus(status, state);
        assert_int_equal(*state, TDC_DFU_STATE_DNLOAD_IDLE);
    }
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, block, 1, 0, NULL), TDC_OK);
    assert_int_equal(dfu_state(), TDC_DFU_STATE_MANIFEST_SYNC);
    getstatus(status, state);
    if (*state == TDC_DFU_STATE_MANIFEST) getstatus(status, state);
}

static void test_descriptors(void **state)
{
    (void)state;
    uint8_t d[18], c[TDC_USB_CONFIG_DESC_LEN];
    assert_int_equal(tdc_usbp_device_descriptor(d), 18);
    assert_int_equal(tdc_get_le16(d + 8), 0x1209);
    assert_int_equal(tdc_get_le16(d + 10), 0x0001);
    assert_int_equal(tdc_usbp_config_descriptor(c, 1), TDC_USB_CONFIG_DESC_LEN);
    assert_int_equal(tdc_get_le16(c + 2), TDC_USB_CONFIG_DESC_LEN);
    /* walk: every descriptor's length adds up to the total */
    uint32_t off = 0, n = 0;
    while (off < TDC_USB_CONFIG_DESC_LEN) {
        assert_true(c[off] >= 2);
        off += c[off];
        n++;
    }
    assert_int_equal(off, TDC_USB_CONFIG_DESC_LEN);
    assert_int_equal(n, 6);
    assert_int_equal(tdc_get_le16(c + 18 + 4), 512); /* HS bulk OUT */
    tdc_usbp_config_descriptor(c, 0);
    assert_int_equal(tdc_get_le16(c + 18 + 4), 64);                    /* FS bulk OUT */
    assert_int_equal(tdc_get_le16(c + 41 + 5), TDC_DFU_TRANSFER_SIZE); /* wTransferSize */
    /* the whole DFU functional descriptor (DFU 1.1 table 4.2) */
    assert_memory_equal(c + 41, ((uint8_t[]){9, 0x21, 0x07, 0xE8, 0x03, 0x00, 0x04, 0x10, 0x01}), 9);
    /* bcdDevice as documented: 0x0001 (it read 0x0100, issue 19) */
    assert_int_equal(tdc_get_le16(d + 12), 0x0001);
    /* string: serial as UTF-16LE, and through GET_DESCRIPTOR with wLength truncation */
    assert_int_equal(req(0x80, 6, 0x0303, 0x0409, 255, NULL), TDC_OK);
    assert_int_equal(rlen, 6);
    assert_memory_equal(reply, ((uint8_t[]){6, 3, 'S', 0, '1', 0}), 6);
    assert_int_equal(req(0x80, 6, 0x0200, 0, 9, NULL), TDC_OK);
    assert_int_equal(rlen, 9);
    assert_int_equal(req(0x80, 6, 0x0309, 0, 255, NULL), TDC_ERR_STALL); /* no string 9 */
}

static void test_board_info_and_counters(void **state)
{
    (void)state;
    uint8_t data[100];
    for (int i = 0; i < 100; i++) data[i] = (uint8_t)i;
    tdc_usbp_bulk_out(&s, data, 100);
    tdc_usbp_bulk_out(&s, data, 40);
    assert_int_equal(req(0xC1, TDC_USB_REQ_BOARD_INFO, 0, 0, 255, NULL), TDC_OK);
    assert_int_equal(rlen, TDC_USB_INFO_LEN);
    assert_int_equal(tdc_get_le32(reply), TDC_USB_INFO_MAGIC);
    assert_string_equal((const char *)reply + TDC_USB_INFO_OFF_BOARD, "testboard");
    assert_int_equal(tdc_get_le32(reply + TDC_USB_INFO_OFF_FW_VERSION), 0x010203u);
    assert_int_equal(tdc_get_le32(reply + TDC_USB_INFO_OFF_SLOT), SLOT);
    assert_int_equal(tdc_get_le32(reply + TDC_USB_INFO_OFF_RX_XFERS), 2);
    assert_int_equal(tdc_get_le32(reply + TDC_USB_INFO_OFF_RX_BYTES), 140);
    uint8_t both[140];
    memcpy(both, data, 100);
    memcpy(both + 100, data, 40);
    assert_int_equal(tdc_get_le32(reply + TDC_USB_INFO_OFF_RX_CRC), tdc_crc32(both, 140));
    /* short wLength truncates; wrong direction and unknown requests stall and count */
    assert_int_equal(req(0xC1, TDC_USB_REQ_BOARD_INFO, 0, 0, 8, NULL), TDC_OK);
    assert_int_equal(rlen, 8);
    assert_int_equal(req(0x41, TDC_USB_REQ_BOARD_INFO, 0, 0, 0, NULL), TDC_ERR_STALL);
    assert_int_equal(req(0xC1, 0x7F, 0, 0, 8, NULL), TDC_ERR_STALL);
    assert_int_equal(req(0xC1, TDC_USB_REQ_BOARD_INFO, 0, 5, 8, NULL), TDC_ERR_STALL); /* other interface */
    assert_int_equal(req(0x41, TDC_USB_REQ_RESET_COUNTERS, 0, 0, 0, NULL), TDC_OK);
    assert_int_equal(req(0xC1, TDC_USB_REQ_BOARD_INFO, 0, 0, 255, NULL), TDC_OK);
    assert_int_equal(tdc_get_le32(reply + TDC_USB_INFO_OFF_RX_BYTES), 0);
    assert_int_equal(tdc_get_le32(reply + TDC_USB_INFO_OFF_RX_CRC), 0); /* CRC of nothing */
    assert_int_equal(tdc_get_le32(reply + TDC_USB_INFO_OFF_STALLS), 3); /* kept */
    uint8_t st[TDC_USB_STATUS_LEN];
    tdc_usbp_status_report(&s, st);
    tdc_usbp_status_report(&s, st);
    assert_int_equal(tdc_get_le32(st), TDC_USB_STATUS_MAGIC);
    assert_int_equal(tdc_get_le32(st + TDC_USB_STATUS_OFF_SEQ), 1);
    assert_int_equal(st[TDC_USB_STATUS_OFF_DFU], TDC_DFU_STATE_IDLE);
    assert_int_equal(tdc_usbp_take_reset(&s), 0);
    assert_int_equal(req(0x41, TDC_USB_REQ_RESET_BOARD, 0, 0, 0, NULL), TDC_OK);
    assert_int_equal(tdc_usbp_take_reset(&s), 1);
    assert_int_equal(tdc_usbp_take_reset(&s), 0);
}

static void test_dfu_download_upload(void **state)
{
    (void)state;
    uint32_t len = make_image(3000, "testboard");
    uint8_t status, st;
    download(len, 1024, &status, &st);
    assert_int_equal(status, TDC_DFU_OK);
    assert_int_equal(st, TDC_DFU_STATE_IDLE);
    assert_memory_equal(slot + SLOT, image, len); /* into the slot that is not running */
    assert_int_equal(tdc_usbp_slot_image(&s, 1), len);
    assert_int_equal(tdc_usbp_slot_image(&s, 0), 0);
    /* upload in 1000-byte frames: 1000, 1000, 1000, 48 (short: ends) */
    uint8_t back[SLOT];
    uint32_t got = 0;
    for (uint16_t b = 0;; b++) {
        assert_int_equal(req(DFU_IN, TDC_DFU_UPLOAD, b, 1, 1000, NULL), TDC_OK);
        memcpy(back + got, reply, rlen);
        got += rlen;
        if (rlen < 1000) break;
        assert_int_equal(dfu_state(), TDC_DFU_STATE_UPLOAD_IDLE);
    }
    assert_int_equal(got, len);
    assert_memory_equal(back, image, len);
    assert_int_equal(dfu_state(), TDC_DFU_STATE_IDLE);
}

static uint32_t poll_timeout(void)
{
    return reply[1] | (uint32_t)reply[2] << 8 | (uint32_t)reply[3] << 16;
}

/* A block the board's flash cannot write within the request (busy_ms):
 * dfuDNBUSY with its poll timeout, written by tdc_usbp_dfu_work() after
 * the reply; other blocks as before. */
static void test_dfu_busy(void **state)
{
    (void)state;
    uint32_t len = make_image(3000, "testboard"); /* blocks at 0, 1024, 2048 (slow), 3072 */
    uint8_t status, st;
    for (uint16_t blk = 0; blk * 1024u < len; blk++) {
        const uint32_t off = blk * 1024u, n = len - off < 1024u ? len - off : 1024u;
        const int slow = (SLOT + off) % ERASE_UNIT == 0u;
        assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, blk, 1, (uint16_t)n, image + off), TDC_OK);
        getstatus(&status, &st);
        assert_int_equal(status, TDC_DFU_OK);
        if (slow) {
            assert_int_equal(st, TDC_DFU_STATE_DNBUSY);
            assert_int_equal(poll_timeout(), ERASE_MS);
            assert_int_equal(slot[SLOT + off], 0xFF); /* not written before the reply */
            getstatus(&status, &st);                  /* polled too early: still busy */
            assert_int_equal(st, TDC_DFU_STATE_DNBUSY);
            assert_int_equal(poll_timeout(), ERASE_MS);
            assert_int_equal(tdc_usbp_dfu_work(&s), 1);
            assert_memory_equal(slot + SLOT + off, image + off, n);
            assert_int_equal(dfu_state(), TDC_DFU_STATE_DNLOAD_SYNC);
            getstatus(&status, &st);
        }
        assert_int_equal(st, TDC_DFU_STATE_DNLOAD_IDLE);
        assert_int_equal(poll_timeout(), 0);
        assert_int_equal(tdc_usbp_dfu_work(&s), 0); /* nothing waiting */
    }
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, 3, 1, 0, NULL), TDC_OK);
    getstatus(&status, &st);
    if (st == TDC_DFU_STATE_MANIFEST) getstatus(&status, &st);
    assert_int_equal(status, TDC_DFU_OK);
    assert_int_equal(tdc_usbp_slot_image(&s, 1), len);
    assert_memory_equal(slot + SLOT, image, len);

    /* the deferred write fails: dfuERROR/errWRITE at the next GETSTATUS */
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, 0, 1, 1024, image), TDC_OK);
    getstatus(&status, &st);
    assert_int_equal(st, TDC_DFU_STATE_DNBUSY);
    fail_write = 1;
    assert_int_equal(tdc_usbp_dfu_work(&s), 1);
    getstatus(&status, &st);
    assert_int_equal(st, TDC_DFU_STATE_ERROR);
    assert_int_equal(status, TDC_DFU_ERR_WRITE);
    fail_write = 0;

    /* a request stalled while busy ends the download: the block is dropped */
    assert_int_equal(req(DFU_OUT, TDC_DFU_CLRSTATUS, 0, 1, 0, NULL), TDC_OK);
    memset(slot + SLOT, 0xFF, SLOT);
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, 0, 1, 1024, image), TDC_OK);
    getstatus(&status, &st);
    assert_int_equal(st, TDC_DFU_STATE_DNBUSY);
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, 1, 1, 1024, image + 1024), TDC_ERR_STALL);
    assert_int_equal(tdc_usbp_dfu_work(&s), 0);
    assert_int_equal(slot[SLOT], 0xFF);
    assert_int_equal(dfu_state(), TDC_DFU_STATE_ERROR);
}

static void test_dfu_rejects(void **state)
{
    (void)state;
    uint8_t status, st;
    uint32_t len = make_image(2000, "testboard");

    /* block out of sequence */
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, 0, 1, 1024, image), TDC_OK);
    getstatus(&status, &st);
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, 2, 1, 1024, image + 1024), TDC_ERR_STALL);
    getstatus(&status, &st);
    assert_int_equal(st, TDC_DFU_STATE_ERROR);
    assert_int_equal(status, TDC_DFU_ERR_STALLEDPKT);
    /* in dfuERROR everything but GETSTATUS/GETSTATE/CLRSTATUS stalls */
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, 0, 1, 16, image), TDC_ERR_STALL);
    assert_int_equal(req(DFU_OUT, TDC_DFU_ABORT, 0, 1, 0, NULL), TDC_ERR_STALL);
    assert_int_equal(req(DFU_OUT, TDC_DFU_CLRSTATUS, 0, 1, 0, NULL), TDC_OK);
    assert_int_equal(dfu_state(), TDC_DFU_STATE_IDLE);
    /* CLRSTATUS outside dfuERROR is a protocol error */
    assert_int_equal(req(DFU_OUT, TDC_DFU_CLRSTATUS, 0, 1, 0, NULL), TDC_ERR_STALL);
    req(DFU_OUT, TDC_DFU_CLRSTATUS, 0, 1, 0, NULL);

    /* zero-length DNLOAD in dfuIDLE: nothing to manifest */
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, 0, 1, 0, NULL), TDC_ERR_STALL);
    getstatus(&status, &st);
    assert_int_equal(status, TDC_DFU_ERR_NOTDONE);
    req(DFU_OUT, TDC_DFU_CLRSTATUS, 0, 1, 0, NULL);

    /* block larger than wTransferSize; DETACH in DFU mode */
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, 0, 1, TDC_DFU_TRANSFER_SIZE + 1, image), TDC_ERR_STALL);
    req(DFU_OUT, TDC_DFU_CLRSTATUS, 0, 1, 0, NULL);
    /* DETACH: accepted in dfuIDLE (arms activation), a protocol error elsewhere */
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, 0, 1, 0, NULL), TDC_ERR_STALL);
    assert_int_equal(req(DFU_OUT, TDC_DFU_DETACH, 1000, 1, 0, NULL), TDC_ERR_STALL); /* in dfuERROR */
    req(DFU_OUT, TDC_DFU_CLRSTATUS, 0, 1, 0, NULL);
    assert_int_equal(req(DFU_OUT, TDC_DFU_DETACH, 1000, 1, 0, NULL), TDC_OK);
    assert_int_equal(dfu_state(), TDC_DFU_STATE_IDLE);
    assert_int_equal(tdc_usbp_bus_reset(&s), 0); /* nothing manifested: no switch */

    /* ABORT mid-download returns to dfuIDLE; the slot holds no checked image */
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, 0, 1, 1024, image), TDC_OK);
    getstatus(&status, &st);
    assert_int_equal(req(DFU_OUT, TDC_DFU_ABORT, 0, 1, 0, NULL), TDC_OK);
    assert_int_equal(dfu_state(), TDC_DFU_STATE_IDLE);
    assert_int_equal(req(DFU_IN, TDC_DFU_UPLOAD, 0, 1, 1000, NULL), TDC_OK);
    assert_int_equal(rlen, 0);

    /* truncated image (header says 2000 payload bytes): errNOTDONE */
    download(len - 100, 1024, &status, &st);
    assert_int_equal(st, TDC_DFU_STATE_ERROR);
    assert_int_equal(status, TDC_DFU_ERR_NOTDONE);
    req(DFU_OUT, TDC_DFU_CLRSTATUS, 0, 1, 0, NULL);
    /* corrupted payload: errVERIFY */
    image[500] ^= 1u;
    download(len, 1024, &status, &st);
    assert_int_equal(status, TDC_DFU_ERR_VERIFY);
    req(DFU_OUT, TDC_DFU_CLRSTATUS, 0, 1, 0, NULL);
    image[500] ^= 1u;
    /* another board's image: errFILE */
    len = make_image(2000, "otherboard");
    download(len, 1024, &status, &st);
    assert_int_equal(status, TDC_DFU_ERR_FILE);
    req(DFU_OUT, TDC_DFU_CLRSTATUS, 0, 1, 0, NULL);
    /* more bytes than the slot: errADDRESS on the block that overflows */
    len = make_image(2000, "testboard");
    uint16_t b = 0;
    for (uint32_t off = 0; off < SLOT; off += 1024, b++) {
        assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, b, 1, 1024, image), TDC_OK);
        getstatus(&status, &st);
    }
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, b, 1, 1024, image), TDC_ERR_STALL);
    getstatus(&status, &st);
    assert_int_equal(status, TDC_DFU_ERR_ADDRESS);
    req(DFU_OUT, TDC_DFU_CLRSTATUS, 0, 1, 0, NULL);
    /* flash write failure: errWRITE */
    fail_write = 1;
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, 0, 1, 64, image), TDC_ERR_STALL);
    getstatus(&status, &st);
    assert_int_equal(status, TDC_DFU_ERR_WRITE);
    fail_write = 0;
    req(DFU_OUT, TDC_DFU_CLRSTATUS, 0, 1, 0, NULL);
    /* and after all that, a good image still goes through */
    len = make_image(2000, "testboard");
    download(len, 512, &status, &st);
    assert_int_equal(status, TDC_DFU_OK);
    assert_int_equal(st, TDC_DFU_STATE_IDLE);
}

static void test_image_check(void **state)
{
    (void)state;
    uint32_t len = make_image(100, "testboard");
    assert_int_equal(tdc_image_check(image, len, "testboard", SLOT), TDC_OK);
    assert_int_equal(tdc_image_check(image, len, NULL, 0), TDC_OK);
    assert_int_equal(tdc_image_check(image, TDC_IMAGE_HEADER_LEN - 1, NULL, 0), TDC_ERR_IMAGE_SHORT);
    assert_int_equal(tdc_image_check(image, len - 1, NULL, 0), TDC_ERR_IMAGE_SIZE);
    assert_int_equal(tdc_image_check(image, len, "testboar", 0), TDC_ERR_IMAGE_BOARD);
    assert_int_equal(tdc_image_check(image, len, "testboardX", 0), TDC_ERR_IMAGE_BOARD);
    assert_int_equal(tdc_image_check(image, len, "testboard", len - 1), TDC_ERR_IMAGE_TOO_BIG);
    image[TDC_IMAGE_HEADER_LEN + 8] ^= 0x80u;
    assert_int_equal(tdc_image_check(image, len, NULL, 0), TDC_ERR_IMAGE_CRC);
    image[TDC_IMAGE_HEADER_LEN + 8] ^= 0x80u;
    image[TDC_IMAGE_OFF_RESERVED + 3] = 1; /* reserved bytes must be zero */
    assert_int_equal(tdc_image_check(image, len, NULL, 0), TDC_ERR_IMAGE_HEADER);
    image[TDC_IMAGE_OFF_RESERVED + 3] = 0;
    image[4] = 1; /* header version 1 (12-character board field) is not accepted */
    assert_int_equal(tdc_image_check(image, len, NULL, 0), TDC_ERR_IMAGE_HEADER);
    image[0] = 'X';
    assert_int_equal(tdc_image_check(image, len, NULL, 0), TDC_ERR_IMAGE_MAGIC);
    /* the longest board name, 16 characters, fills the field with no NUL (issue 19:
     * with 12 no image could ever pass the check for this board) */
    len = make_image(10, "stm32h747i-disco");
    assert_int_equal(tdc_image_check(image, len, "stm32h747i-disco", 0), TDC_OK);
    assert_int_equal(tdc_image_check(image, len, "stm32h747i-disco!", 0), TDC_ERR_IMAGE_BOARD);
    assert_int_equal(tdc_image_check(image, len, "stm32h747i-disc", 0), TDC_ERR_IMAGE_BOARD);
    assert_string_equal(tdc_dfu_status_name(TDC_DFU_ERR_VERIFY), "errVERIFY");
    assert_string_equal(tdc_dfu_state_name(TDC_DFU_STATE_ERROR), "dfuERROR");
}

/* Found by fuzzing the device side (issue 19): BOARD_INFO with wLength 0
 * and a NULL reply buffer of capacity 0 (the API allows it) must not
 * memcpy(NULL, .., 0) (UBSan in the ASan build); GETSTATUS with a reply
 * buffer under 6 bytes is the caller's error and must not advance state. */
static void test_corner_cases(void **state)
{
    (void)state;
    tdc_usbp_setup_t info = {0xC1, TDC_USB_REQ_BOARD_INFO, 0, 0, 0};
    uint32_t n = 99;
    assert_int_equal(tdc_usbp_control(&s, &info, NULL, NULL, 0, &n), TDC_OK);
    assert_int_equal(n, 0);
    make_image(100, "testboard");
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, 0, 1, 64, image), TDC_OK);
    assert_int_equal(dfu_state(), TDC_DFU_STATE_DNLOAD_SYNC);
    tdc_usbp_setup_t gs = {DFU_IN, TDC_DFU_GETSTATUS, 0, 1, 6};
    uint8_t small[4];
    assert_int_equal(tdc_usbp_control(&s, &gs, NULL, small, sizeof small, &n), TDC_ERR_ARG);
    assert_int_equal(dfu_state(), TDC_DFU_STATE_DNLOAD_SYNC); /* not advanced */
    assert_int_equal(tdc_usbp_control(&s, &gs, NULL, NULL, 0, &n), TDC_ERR_ARG);
    assert_int_equal(dfu_state(), TDC_DFU_STATE_DNLOAD_SYNC);
    uint8_t status, st;
    getstatus(&status, &st);
    assert_int_equal(st, TDC_DFU_STATE_DNLOAD_IDLE);
}

static uint32_t upload_all(uint8_t *back)
{
    uint32_t got = 0;
    for (uint16_t b = 0;; b++) {
        assert_int_equal(req(DFU_IN, TDC_DFU_UPLOAD, b, 1, 1024, NULL), TDC_OK);
        memcpy(back + got, reply, rlen);
        got += rlen;
        if (rlen < 1024) return got;
    }
}

/* A/B activation and "a failed download never destroys the last good image". */
static void test_activation(void **state)
{
    (void)state;
    uint8_t status, st, back[2 * SLOT];
    uint8_t good[SLOT];
    uint32_t len = make_image(1500, "testboard");
    memcpy(good, image, len);
    download(len, 1024, &status, &st);
    assert_int_equal(status, TDC_DFU_OK);
    /* DETACH (dfu-util -R) then the bus reset: slot 1 runs */
    assert_int_equal(req(DFU_OUT, TDC_DFU_DETACH, 1000, 1, 0, NULL), TDC_OK);
    assert_int_equal(tdc_usbp_bus_reset(&s), 1);
    assert_int_equal(s.dfu_active_slot, 1);
    assert_int_equal(tdc_usbp_bus_reset(&s), 0); /* a second reset changes nothing */
    /* a raw binary (no header) goes to slot 0 and is rejected at manifestation */
    for (uint32_t i = 0; i < 2000; i++) image[i] = (uint8_t)(i * 13u);
    download(2000, 1024, &status, &st);
    assert_int_equal(st, TDC_DFU_STATE_ERROR);
    assert_int_equal(status, TDC_DFU_ERR_FILE);
    assert_int_equal(req(DFU_OUT, TDC_DFU_CLRSTATUS, 0, 1, 0, NULL), TDC_OK);
    /* the running image is intact and still what an upload returns */
    assert_memory_equal(slot + SLOT, good, len);
    assert_int_equal(upload_all(back), len);
    assert_memory_equal(back, good, len);
    /* a reset now does not boot the rejected bytes */
    assert_int_equal(tdc_usbp_bus_reset(&s), 0);
    assert_int_equal(s.dfu_active_slot, 1);
    /* an interrupted download (ABORT half way), then recovery */
    len = make_image(3000, "testboard");
    assert_int_equal(req(DFU_OUT, TDC_DFU_DNLOAD, 0, 1, 1024, image), TDC_OK);
    getstatus(&status, &st);
    assert_int_equal(req(DFU_OUT, TDC_DFU_ABORT, 0, 1, 0, NULL), TDC_OK);
    assert_int_equal(upload_all(back), 1500 + TDC_IMAGE_HEADER_LEN); /* still the good one */
    download(len, 1024, &status, &st);
    assert_int_equal(status, TDC_DFU_OK);
    assert_int_equal(upload_all(back), len); /* the new one, waiting for activation */
    assert_memory_equal(back, image, len);
    /* RESET_BOARD: the board resets itself and calls bus_reset */
    assert_int_equal(req(0x41, TDC_USB_REQ_RESET_BOARD, 0, 0, 0, NULL), TDC_OK);
    assert_int_equal(tdc_usbp_take_reset(&s), 1);
    assert_int_equal(tdc_usbp_bus_reset(&s), 1);
    assert_int_equal(s.dfu_active_slot, 0);
    assert_memory_equal(slot, image, len);
}

/* The standard DFU suffix: what dfu-suffix writes, checked and stripped. */
static void test_dfu_suffix(void **state)
{
    (void)state;
    uint32_t len = make_image(200, "testboard"), il = 0;
    assert_int_equal(tdc_dfu_suffix_check(image, len, 0x1209, 0x0001, &il), TDC_DFU_SUFFIX_NONE);
    assert_int_equal(il, len);
    tdc_dfu_suffix_make(image + len, image, len, 0x1209, 0x0001);
    assert_memory_equal(image + len + 6, ((uint8_t[]){0x00, 0x01, 'U', 'F', 'D', 16}), 6);
    assert_int_equal(tdc_dfu_suffix_check(image, len + 16, 0x1209, 0x0001, &il), TDC_DFU_SUFFIX_OK);
    assert_int_equal(il, len);
    assert_int_equal(tdc_dfu_suffix_check(image, len + 16, 0x1209, 0x0002, &il), TDC_DFU_SUFFIX_ERR_ID);
    image[100] ^= 1u;
    assert_int_equal(tdc_dfu_suffix_check(image, len + 16, 0x1209, 0x0001, &il), TDC_DFU_SUFFIX_ERR_CRC);
    image[100] ^= 1u;
    assert_int_equal(tdc_dfu_suffix_check(NULL, 0, 0, 0, &il), TDC_DFU_SUFFIX_NONE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_descriptors, setup),
        cmocka_unit_test_setup(test_board_info_and_counters, setup),
        cmocka_unit_test_setup(test_dfu_download_upload, setup),
        cmocka_unit_test_setup(test_dfu_busy, setup_busy),
        cmocka_unit_test_setup(test_dfu_rejects, setup),
        cmocka_unit_test_setup(test_image_check, setup),
        cmocka_unit_test_setup(test_corner_cases, setup),
        cmocka_unit_test_setup(test_activation, setup),
        cmocka_unit_test_setup(test_dfu_suffix, setup),
    };
    return cmocka_run_group_tests_name("board USB protocol (tdc_usbproto)", tests, NULL, NULL);
}
