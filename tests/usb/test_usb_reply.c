/*
 * test_usb_reply.c - tdc-usb's parsing of board replies
 * (hosttools/usb/tdc_usb_reply.c) on exact byte strings, including the
 * cases the fuzz target (tests/fuzz/fuzz_usbreply.c) is built around.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <string.h>

#include "tdc_usb_reply.h"

static void test_transfer_size(void **state)
{
    (void)state;
    static const uint8_t dfu11[] = {9, 0x21, 7, 0xE8, 3, 0x00, 0x04, 0x10, 0x01};
    assert_int_equal(tdc_usb_dfu_transfer_size(dfu11, sizeof dfu11, 1024), 1024);
    static const uint8_t dfu11_2k[] = {9, 0x21, 7, 0xE8, 3, 0x00, 0x08, 0x10, 0x01};
    assert_int_equal(tdc_usb_dfu_transfer_size(dfu11_2k, sizeof dfu11_2k, 1024), 2048);
    /* a DFU 1.0 functional descriptor (7 bytes) last in the list: found (the
     * old scan wanted 9 bytes left and skipped it) */
    static const uint8_t dfu10_last[] = {5, 0x24, 0, 1, 2, 7, 0x21, 3, 0xE8, 3, 0x00, 0x02};
    assert_int_equal(tdc_usb_dfu_transfer_size(dfu10_last, sizeof dfu10_last, 1024), 512);
    /* a descriptor whose bLength runs past the buffer is not read */
    static const uint8_t overrun[] = {9, 0x21, 7, 0xE8, 3, 0x00, 0x02};
    assert_int_equal(tdc_usb_dfu_transfer_size(overrun, sizeof overrun, 1024), 1024);
    static const uint8_t zero_len[] = {0, 0x21, 7, 0xE8, 3, 0x00, 0x02, 0, 0};
    assert_int_equal(tdc_usb_dfu_transfer_size(zero_len, sizeof zero_len, 1024), 1024);
    static const uint8_t tiny[] = {9, 0x21, 7, 0xE8, 3, 0x10, 0x00, 0x10, 0x01}; /* 16: out of range */
    assert_int_equal(tdc_usb_dfu_transfer_size(tiny, sizeof tiny, 1024), 1024);
    assert_int_equal(tdc_usb_dfu_transfer_size(NULL, 0, 1024), 1024);
}

static void test_info_and_strings(void **state)
{
    (void)state;
    uint8_t raw[TDC_USB_INFO_LEN] = {0};
    tdc_put_le32(raw, TDC_USB_INFO_MAGIC);
    tdc_put_le16(raw + TDC_USB_INFO_OFF_PROTO, TDC_USB_PROTO_VERSION);
    memcpy(raw + TDC_USB_INFO_OFF_BOARD, "stm32h747i-disco", 16); /* fills the field: no NUL */
    tdc_put_le32(raw + TDC_USB_INFO_OFF_FW_VERSION, 0x020001u);
    board_info_t bi;
    assert_int_equal(tdc_usb_parse_info(raw, sizeof raw, &bi), 0);
    assert_string_equal(bi.board, "stm32h747i-disco");
    assert_int_equal(bi.fw_version, 0x020001u);
    assert_int_equal(tdc_usb_parse_info(raw, sizeof raw - 1, &bi), -1);
    raw[0] ^= 1u;
    assert_int_equal(tdc_usb_parse_info(raw, sizeof raw, &bi), -1);
    char s[8];
    static const uint8_t str[] = {12, 3, 'T', 0, 'D', 0, 'C', 0, 0xE9, 0, '-', 0x04};
    assert_int_equal(tdc_usb_string_decode(str, sizeof str, s, sizeof s), 5);
    assert_string_equal(s, "TDC??");
    assert_int_equal(tdc_usb_string_decode(str, sizeof str, s, 3), 2); /* truncated to the buffer */
    assert_string_equal(s, "TD");
    assert_int_equal(tdc_usb_string_decode(str, 5, s, sizeof s), -1); /* bLength past what arrived */
    static const uint8_t notstr[] = {4, 2, 'x', 0};
    assert_int_equal(tdc_usb_string_decode(notstr, 4, s, sizeof s), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_transfer_size), cmocka_unit_test(test_info_and_strings)};
    return cmocka_run_group_tests_name("tdc-usb reply parsing", tests, NULL, NULL);
}
