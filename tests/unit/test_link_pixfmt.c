/*
 * test_link_pixfmt.c - CRC-32 tables against their definition, and the
 * fixed-point pixel-format conversions against the double-precision
 * reference (sim/link/tdc_pixfmt_ref.c): max abs error in output LSB and
 * the share within 1 LSB, over every input.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tdc_cmocka.h"

#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "tdc_link_encode.h"
#include "link/tdc_pixfmt_ref.h"
#include "tdc_crc32.h"
#include "tdc_pixfmt.h"

static void test_crc32_tables_and_check_value(void **state)
{
    (void)state;
    uint32_t t0[256];
    for (uint32_t k = 0; k < 256; k++) {
        /* The definition (checked by the check value below) */
        const uint32_t c = tdc_crc32_shift8(k);
        t0[k] = c;
        assert_int_equal(tdc_crc32_table_entry(0, k), c);
    }
    /* Entries of the published zlib/PNG table (independent of the code). */
    assert_int_equal(t0[1], 0x77073096u);
    assert_int_equal(t0[128], 0xEDB88320u);
    assert_int_equal(t0[255], 0x2D02EF8Du);
    for (unsigned j = 1; j < 8; j++) {
        for (uint32_t k = 0; k < 256; k++) {
            const uint32_t prev = tdc_crc32_table_entry(j - 1, k);
            assert_int_equal(tdc_crc32_table_entry(j, k), (prev >> 8) ^ t0[prev & 0xFFu]);
        }
    }
    const uint8_t check[] = "123456789";
    assert_int_equal(tdc_crc32(check, 9), 0xCBF43926u);
    assert_int_equal(tdc_crc32_bitwise(check, 9), 0xCBF43926u);
    assert_int_equal(tdc_crc32(check, 0), 0);
    /* Any length and split agrees with the bit-at-a-time definition. */
    static uint8_t buf[1000];
    uint32_t s = 12345;
    for (size_t i = 0; i < sizeof buf; i++) {
        s = s * 1103515245u + 12345u;
        buf[i] = (uint8_t)(s >> 16);
    }
    for (size_t n = 0; n < 200; n += 1) {
        const uint32_t want = tdc_crc32_bitwise(buf + (n % 7), n);
        assert_int_equal(tdc_crc32(buf + (n % 7), n), want);
        for (size_t cut = 0; cut <= n; cut += 13) {
            uint32_t c = tdc_crc32_update(TDC_CRC32_INIT, buf + (n % 7), cut);
            c = tdc_crc32_update(c, buf + (n % 7) + cut, n - cut);
            assert_int_equal(tdc_crc32_final(c), want);
        }
    }
}

static int rint_clamp(double v)
{
    v = v < 0.0 ? 0.0 : (v > 255.0 ? 255.0 : v);
    return (int)floor(v + 0.5);
}

/* Every (Y, Cb, Cr): fixed point vs the BT.709 double reference. */
static void test_ycbcr_to_rgb_vs_reference(void **state)
{
    (void)state;
    uint64_t n = 0, exact = 0, within1 = 0;
    int maxerr = 0;
    double max_abs_unrounded = 0.0;
    for (int y = 0; y < 256; y++) {
        for (int cb = 0; cb < 256; cb++) {
            for (int cr = 0; cr < 256; cr++) {
                uint8_t fx[3];
                double ref[3];
                tdc_pixfmt_ycbcr_to_rgb((uint8_t)y, (uint8_t)cb, (uint8_t)cr, fx);
                tdc_pixfmt_ref_ycbcr_to_rgb(y, cb, cr, ref);
                for (int c = 0; c < 3; c++) {
                    const int e = fx[c] - rint_clamp(ref[c]);
                    const int ae = e < 0 ? -e : e;
                    maxerr = ae > maxerr ? ae : maxerr;
                    exact += ae == 0;
                    within1 += ae <= 1;
                    const double r = ref[c] < 0 ? 0 : (ref[c] > 255 ? 255 : ref[c]);
                    const double u = fabs(fx[c] - r);
                    max_abs_unrounded = u > max_abs_unrounded ? u : max_abs_unrounded;
                    n++;
                }
            }
        }
    }
    printf("ycbcr420->rgb888 fixed vs double (%llu channel values): max |err| %d LSB vs rounded reference, "
           "%.5f %% exact, %.5f %% within 1 LSB; max |fixed - exact| %.4f LSB\n",
           (unsigned long long)n, maxerr, 100.0 * (double)exact / (double)n, 100.0 * (double)within1 / (double)n,
           max_abs_unrounded);
    assert_true(maxerr <= 1);
    assert_true((double)exact / (double)n >= 0.999);
    assert_true(max_abs_unrounded < 0.51);
}

/* The 4:2:0 unpacker (one offset per chroma sample) equals the per-pixel
 * conversion for every (Y, Cb, Cr). */
static void test_ycbcr420_unpack_equals_pointwise(void **state)
{
    (void)state;
    uint64_t mismatches = 0;
    for (int cb = 0; cb < 256; cb++) {
        for (int cr = 0; cr < 256; cr++) {
            for (int y = 0; y < 256; y++) {
                /* 2 x 1 image: luma y and 255 - y sharing one chroma sample. */
                const uint8_t in[4] = {(uint8_t)y, (uint8_t)(255 - y), (uint8_t)cb, (uint8_t)cr};
                uint8_t out[6], want[6];
                tdc_pixfmt_unpack_ycbcr420(in, 2, 1, out, 6);
                tdc_pixfmt_ycbcr_to_rgb((uint8_t)y, (uint8_t)cb, (uint8_t)cr, want);
                tdc_pixfmt_ycbcr_to_rgb((uint8_t)(255 - y), (uint8_t)cb, (uint8_t)cr, want + 3);
                mismatches += memcmp(out, want, 6) != 0;
            }
        }
    }
    assert_int_equal(mismatches, 0);
}

static void test_rgb30_and_rgb565_vs_reference(void **state)
{
    (void)state;
    /* 10 -> 8 bits is round(v * 255 / 1023) exactly. */
    for (uint32_t v = 0; v < 1024; v++) {
        assert_int_equal(tdc_pixfmt_u10_to_u8(v), (int)floor(v * 255.0 / 1023.0 + 0.5));
    }
    /* 8 -> 10 -> 8 through the packer is lossless. */
    uint8_t rgb[256 * 3], packed[256 * 4], back[256 * 3];
    for (int i = 0; i < 256; i++) {
        rgb[3 * i] = (uint8_t)i;
        rgb[3 * i + 1] = (uint8_t)(255 - i);
        rgb[3 * i + 2] = (uint8_t)(i * 7);
    }
    tdc_pixfmt_pack(TDC_PIXFMT_RGB30, rgb, 256, 1, 256 * 3, packed);
    tdc_pixfmt_unpack_rgb30(packed, 256, 1, back, 256 * 3);
    assert_memory_equal(rgb, back, sizeof rgb);
    /* RGB565 bit replication vs round(v * 255 / 31 or 63): within 1 LSB. */
    int max5 = 0, max6 = 0;
    for (uint32_t v = 0; v < 65536; v += 1) {
        uint8_t p[2] = {(uint8_t)v, (uint8_t)(v >> 8)}, o[3];
        tdc_pixfmt_unpack_rgb565(p, 1, 1, o, 3);
        const int r = (int)floor((v >> 11) * 255.0 / 31.0 + 0.5), g = (int)floor(((v >> 5) & 63) * 255.0 / 63.0 + 0.5),
                  b = (int)floor((v & 31) * 255.0 / 31.0 + 0.5);
        max5 = fmax(max5, fmax(abs(o[0] - r), abs(o[2] - b)));
        max6 = fmax(max6, abs(o[1] - g));
    }
    printf("rgb565 bit replication vs round(v*255/max): max |err| %d LSB (5-bit), %d LSB (6-bit)\n", max5, max6);
    assert_true(max5 <= 1 && max6 <= 1);
}

/* Encoder colour conversion (integer) vs the double reference. */
static void test_rgb_to_ycbcr_vs_reference(void **state)
{
    (void)state;
    int maxerr = 0, maxrt = 0;
    uint64_t n = 0, within1 = 0;
    for (int r = 0; r < 256; r += 3) {
        for (int g = 0; g < 256; g += 3) {
            for (int b = 0; b < 256; b += 3) {
                uint8_t ycc[3], back[3];
                double ref[3];
                tdc_pixfmt_rgb_to_ycbcr(r, g, b, ycc);
                tdc_pixfmt_ref_rgb_to_ycbcr(r, g, b, ref);
                for (int c = 0; c < 3; c++) {
                    const int e = abs(ycc[c] - rint_clamp(ref[c]));
                    maxerr = e > maxerr ? e : maxerr;
                    within1 += e <= 1;
                    n++;
                }
                /* Flat colour through encode + decode (a 2x2 block of it). */
                tdc_pixfmt_ycbcr_to_rgb(ycc[0], ycc[1], ycc[2], back);
                const int rt = (int)fmax(abs(back[0] - r), fmax(abs(back[1] - g), abs(back[2] - b)));
                maxrt = rt > maxrt ? rt : maxrt;
            }
        }
    }
    printf("rgb->ycbcr integer vs double: max |err| %d LSB, %.4f %% within 1 LSB; flat-colour round trip "
           "rgb->ycbcr->rgb max |err| %d LSB (8-bit YCbCr quantisation)\n",
           maxerr, 100.0 * (double)within1 / (double)n, maxrt);
    assert_true(maxerr <= 1);
    assert_true(maxrt <= 2);
}

/* Payload sizes at odd dimensions. */
static void test_payload_sizes(void **state)
{
    (void)state;
    assert_int_equal(tdc_pixfmt_payload_bytes(TDC_PIXFMT_RGB888, 3, 5), 45);
    assert_int_equal(tdc_pixfmt_payload_bytes(TDC_PIXFMT_RGB565, 3, 5), 30);
    assert_int_equal(tdc_pixfmt_payload_bytes(TDC_PIXFMT_RGB30, 3, 5), 60);
    assert_int_equal(tdc_pixfmt_payload_bytes(TDC_PIXFMT_YCBCR420, 3, 5), 15 + 2 * 2 * 3);
    assert_int_equal(tdc_pixfmt_payload_bytes(TDC_PIXFMT_YCBCR420, 1, 1), 3);
    assert_int_equal(tdc_pixfmt_payload_bytes(TDC_PIXFMT_NONE, 3, 5), 0);
    assert_int_equal(tdc_pixfmt_payload_bytes((tdc_pixfmt_t)9, 3, 5), 0);
    assert_false(tdc_pixfmt_valid(0));
    assert_false(tdc_pixfmt_valid(TDC_PIXFMT_COUNT));
    assert_true(tdc_pixfmt_valid(TDC_PIXFMT_YCBCR420));
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_crc32_tables_and_check_value),     cmocka_unit_test(test_ycbcr_to_rgb_vs_reference),
    cmocka_unit_test(test_ycbcr420_unpack_equals_pointwise), cmocka_unit_test(test_rgb30_and_rgb565_vs_reference),
    cmocka_unit_test(test_rgb_to_ycbcr_vs_reference),        cmocka_unit_test(test_payload_sizes),
)
