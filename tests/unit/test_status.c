/*
 * test_status.c - the one status vocabulary (firmware/tdc_status.h): every
 * code has its own name and text, names are the enumerators' spelling, no
 * two codes share a name or a text, and a value outside the enum is named
 * as unknown rather than as some other code.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "tdc_cmocka.h"

#include "tdc_status.h"

/* Every code, as the enum spells it (kept by hand: the test is that the
 * functions agree with this list). */
#define S(x)  \
    {         \
        x, #x \
    }
static const struct {
    tdc_status_t st;
    const char *name;
} codes[] = {
    S(TDC_OK),
    S(TDC_ERR_ARG),
    S(TDC_ERR_SIZE),
    S(TDC_ERR_REFRESH_LOW),
    S(TDC_ERR_STATE),
    S(TDC_ERR_RATIO),
    S(TDC_ERR_PANEL),
    S(TDC_ERR_FRAME),
    S(TDC_ERR_LAYER),
    S(TDC_ERR_STALL),
    S(TDC_ERR_IMAGE_SHORT),
    S(TDC_ERR_IMAGE_MAGIC),
    S(TDC_ERR_IMAGE_HEADER),
    S(TDC_ERR_IMAGE_SIZE),
    S(TDC_ERR_IMAGE_CRC),
    S(TDC_ERR_IMAGE_BOARD),
    S(TDC_ERR_IMAGE_TOO_BIG),
};
#undef S
#define NCODES (sizeof codes / sizeof codes[0])

static void test_names_are_the_enumerators(void **state)
{
    (void)state;
    for (size_t i = 0; i < NCODES; i++) {
        assert_string_equal(tdc_status_name(codes[i].st), codes[i].name);
        assert_true(codes[i].st == TDC_OK ? codes[i].st == 0 : codes[i].st < 0);
    }
}

static void test_codes_names_texts_distinct(void **state)
{
    (void)state;
    for (size_t i = 0; i < NCODES; i++) {
        const char *t = tdc_status_text(codes[i].st);
        assert_true(strlen(t) > 1u);
        assert_string_not_equal(t, "unknown status");
        assert_true(t[strlen(t) - 1u] != '.' && t[strlen(t) - 1u] != '\n'); /* one line, no period */
        for (size_t j = 0; j < i; j++) {
            assert_int_not_equal(codes[i].st, codes[j].st);
            assert_string_not_equal(tdc_status_name(codes[i].st), tdc_status_name(codes[j].st));
            assert_string_not_equal(t, tdc_status_text(codes[j].st));
        }
    }
}

/* Every int in the range the enum uses is either one of the codes or named
 * unknown: no value aliases another code's name. */
static void test_unknown_values(void **state)
{
    (void)state;
    size_t known = 0;
    for (int v = -200; v <= 200; v++) {
        const char *n = tdc_status_name((tdc_status_t)v);
        int listed = 0;
        for (size_t i = 0; i < NCODES; i++) {
            listed |= (int)codes[i].st == v;
        }
        if (listed) {
            known++;
        } else {
            assert_string_equal(n, "TDC_ERR_?");
            assert_string_equal(tdc_status_text((tdc_status_t)v), "unknown status");
        }
    }
    assert_int_equal(known, NCODES);
}

/* The image texts are what tdc-usb prints and tests/usb, tests/vm match. */
static void test_image_texts_stable(void **state)
{
    (void)state;
    assert_string_equal(tdc_status_text(TDC_ERR_IMAGE_BOARD), "image was built for another board");
    assert_string_equal(tdc_status_text(TDC_ERR_IMAGE_TOO_BIG), "image larger than the board's flash slot");
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_names_are_the_enumerators),
    cmocka_unit_test(test_codes_names_texts_distinct),
    cmocka_unit_test(test_unknown_values),
    cmocka_unit_test(test_image_texts_stable),
)
