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

#define SLOT 4096u

static uint8_t slot[SLOT];
static int fail_write;

static int fw(void *ctx, uint32_t off, const uint8_t *d, uint32_t n)
{
    (void)ctx;
    if (fail_write || off + n > SLOT)
        return -1;
    memcpy(slot + off, d, n);
    return 0;
}

static int fr(void *ctx, uint32_t off, uint8_t *d, uint32_t n)
{
    (void)ctx;
    if (off + n > SLOT)
        return -1;
    memcpy(d, slot + off, n);
    return 0;
}

static tdc_usbp_t s;

static int setup(void **state)
{
    (void)state;
    memset(slot, 0xFF, sizeof slot);
    fail_write = 0;
    tdc_usbp_config_t cfg = {.board_name = "testboard", .panel_name = "htc-vive", .serial = "S1",
                             .fw_version = 0x010203u, .panel_width = 2160, .panel_height = 1200,
                             .refresh_mhz = 90000u, .rx_buffer_bytes = 8192u,
                             .max_packet_bytes = 8192u, .flash = {fw, fr, NULL, SLOT}};
    return tdc_usbp_init(&s, &cfg) == TDC_OK ? 0 : -1;
}

static uint8_t reply[TDC_DFU_TRANSFER_SIZE];
static uint32_t rlen;

static tdc_status_t req(uint8_t type, uint8_t r, uint16_t value, uint16_t index,
                             uint16_t len, const uint8_t *data)
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
    for (uint32_t i = 0; i < payload; i++)
        image[TDC_IMAGE_HEADER_LEN + i] = (uint8_t)(i * 7u + 3u);
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
    if (*state == TDC_DFU_STATE_MANIFEST)
        getstatus(status, state);
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
    assert_int_equal(tdc_get_le16(c + 18 + 4), 512);            /* HS bulk OUT */
    tdc_usbp_config_descriptor(c, 0);
    assert_int_equal(tdc_get_le16(c + 18 + 4), 64);             /* FS bulk OUT */
    assert_int_equal(tdc_get_le16(c + 41 + 5), TDC_DFU_TRANSFER_SIZE); /* wTransferSize */
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
    for (int i = 0; i < 100; i++)
        data[i] = (uint8_t)i;
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
    assert_int_equal(tdc_get_le32(reply + TDC_USB_INFO_OFF_RX_CRC), tdc_usbp_crc32(both, 140));
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
    assert_memory_equal(slot, image, len);
    /* upload in 1000-byte frames: 1000, 1000, 1000, 32 (short: ends) */
    uint8_t back[SLOT];
    uint32_t got = 0;
    for (uint16_t b = 0;; b++) {
        assert_int_equal(req(DFU_IN, TDC_DFU_UPLOAD, b, 1, 1000, NULL), TDC_OK);
        memcpy(back + got, reply, rlen);
        got += rlen;
        if (rlen < 1000)
            break;
        assert_int_equal(dfu_state(), TDC_DFU_STATE_UPLOAD_IDLE);
    }
    assert_int_equal(got, len);
    assert_memory_equal(back, image, len);
    assert_int_equal(dfu_state(), TDC_DFU_STATE_IDLE);
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
    assert_int_equal(req(DFU_OUT, TDC_DFU_DETACH, 1000, 1, 0, NULL), TDC_ERR_STALL);
    req(DFU_OUT, TDC_DFU_CLRSTATUS, 0, 1, 0, NULL);

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
    assert_int_equal(tdc_image_check(image, 31, NULL, 0), TDC_ERR_IMAGE_SHORT);
    assert_int_equal(tdc_image_check(image, len - 1, NULL, 0), TDC_ERR_IMAGE_SIZE);
    assert_int_equal(tdc_image_check(image, len, "testboar", 0), TDC_ERR_IMAGE_BOARD);
    assert_int_equal(tdc_image_check(image, len, "testboardX", 0), TDC_ERR_IMAGE_BOARD);
    assert_int_equal(tdc_image_check(image, len, "testboard", len - 1), TDC_ERR_IMAGE_TOO_BIG);
    image[40] ^= 0x80u;
    assert_int_equal(tdc_image_check(image, len, NULL, 0), TDC_ERR_IMAGE_CRC);
    image[40] ^= 0x80u;
    image[4] = 2; /* header version */
    assert_int_equal(tdc_image_check(image, len, NULL, 0), TDC_ERR_IMAGE_HEADER);
    image[0] = 'X';
    assert_int_equal(tdc_image_check(image, len, NULL, 0), TDC_ERR_IMAGE_MAGIC);
    /* a 12-character board name fills the field with no NUL */
    len = make_image(10, "twelve-chars");
    assert_int_equal(tdc_image_check(image, len, "twelve-chars", 0), TDC_OK);
    assert_int_equal(tdc_image_check(image, len, "twelve-chars!", 0), TDC_ERR_IMAGE_BOARD);
    assert_string_equal(tdc_dfu_status_name(TDC_DFU_ERR_VERIFY), "errVERIFY");
    assert_string_equal(tdc_dfu_state_name(TDC_DFU_STATE_ERROR), "dfuERROR");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_descriptors, setup),
        cmocka_unit_test_setup(test_board_info_and_counters, setup),
        cmocka_unit_test_setup(test_dfu_download_upload, setup),
        cmocka_unit_test_setup(test_dfu_rejects, setup),
        cmocka_unit_test_setup(test_image_check, setup),
    };
    return cmocka_run_group_tests_name("board USB protocol (tdc_usbproto)", tests, NULL, NULL);
}
