/* test_png.c - PNG in/out: 8- and 16-bit round trips, 16->8 rounding, bad files. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

#include "tdc_png.h"

static void test_round_trips(void **state)
{
    (void)state;
    char path[] = "/tmp/tdc_png_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    char err[256];
    enum { W = 7, H = 5 };
    uint16_t px16[W * H * 3];
    uint8_t px8[W * H * 3];
    for (int i = 0; i < W * H * 3; i++) {
        px16[i] = (uint16_t)(i * 1543u + 17u);
        px8[i] = (uint8_t)(i * 37u);
    }
    assert_int_equal(tdc_png_write(path, px16, W, H, 16, W * 3, err, sizeof err), 0);
    tdc_image_t img;
    assert_int_equal(tdc_png_read(path, &img, err, sizeof err), 0);
    assert_int_equal(img.bits, 16);
    assert_int_equal(img.width, W);
    assert_memory_equal(img.data, px16, sizeof px16);
    tdc_png_to8(&img);
    for (int i = 0; i < W * H * 3; i++) {
        assert_int_equal(((uint8_t *)img.data)[i], (px16[i] * 255u + 32767u) / 65535u);
    }
    tdc_png_free(&img);
    assert_int_equal(tdc_png_write(path, px8, W, H, 8, W * 3, err, sizeof err), 0);
    assert_int_equal(tdc_png_read(path, &img, err, sizeof err), 0);
    assert_int_equal(img.bits, 8);
    assert_memory_equal(img.data, px8, sizeof px8);
    tdc_png_free(&img);
    /* truncated file: clear error, no crash */
    FILE *f = fopen(path, "r+");
    assert_non_null(f);
    assert_int_equal(ftruncate(fileno(f), 40), 0);
    fclose(f);
    assert_int_equal(tdc_png_read(path, &img, err, sizeof err), -1);
    assert_non_null(strstr(err, "corrupt or truncated"));
    unlink(path);
    assert_int_equal(tdc_png_read(path, &img, err, sizeof err), -1);
    assert_non_null(strstr(err, "cannot open"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_round_trips)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
