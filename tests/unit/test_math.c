/*
 * test_math.c - exhaustive / dense sweeps of the integer math helpers and
 * the gamma tables against double precision.  Asserts the error bounds
 * stated in tdc_math.h and tdc_gamma.h and prints the measured maxima.
 * Also folds every helper's output over its sweep into a checksum
 * (libopus style) so a behaviour change of any helper is visible.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <cmocka.h>

#include "tdc_cmocka.h"

#include "tdc_gamma.h"
#include "tdc_math.h"
#include "tdc_panels.h"

static void test_exp_neg(void **state)
{
    (void)state;
    double max_err = 0.0;
    int32_t prev = 32768;
    /* exhaustive over x < 16 (all 2^20 Q16 values), then sparse to 2^32 */
    for (uint64_t x = 0; x < (1ULL << 32); x += (x < (1u << 20)) ? 1u : 4093u) {
        int32_t got = tdc_exp_neg_q16((uint32_t)x);
        double want = 32768.0 * exp(-(double)x / 65536.0);
        double err = fabs(got - want);
        if (err > max_err) {
            max_err = err;
        }
        assert_true(got <= prev); /* monotone */
        assert_true(got >= 0 && got <= 32768);
        prev = got;
    }
    assert_int_equal(tdc_exp_neg_q16(0), 32768);
    printf("exp_neg_q16: max error %.4f LSB (Q15), bound 0.51\n", max_err);
    assert_true(max_err <= 0.51);
}

static void test_recip(void **state)
{
    (void)state;
    double max_err = 0.0;
    for (uint64_t d = 1ULL << 31; d < (1ULL << 32); d += 65521u) {
        uint32_t got = tdc_recip_norm_q30((uint32_t)d);
        double want = ldexp(1.0, 62) / (double)d;
        double err = fabs(got - want);
        if (err > max_err) {
            max_err = err;
        }
    }
    /* end points */
    assert_int_equal(tdc_recip_norm_q30(0x80000000u), 1u << 31);
    assert_int_equal(tdc_recip_norm_q30_newton(0x80000000u), 1u << 31);
    assert_int_equal(tdc_recip_norm_q30(0xffffffffu), tdc_recip_norm_q30_newton(0xffffffffu));
    /* the three paths agree bit for bit (all 2^31 d were checked once
     * offline when div32 was written): every d on a
     * dense sweep plus 2^22 pseudo-random ones, against the exact formula */
    uint64_t x = 0x243f6a8885a308d3ull;
    uint32_t nchecked = 0;
    for (uint64_t d = 1ULL << 31; d < (1ULL << 32); d += 4099u) {
        for (int j = 0; j < 2; j++) {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            const uint32_t dd = j == 0 ? (uint32_t)d : (uint32_t)(x >> 32) | 0x80000000u;
            const uint32_t exact = (uint32_t)(((1ULL << 62) + (dd >> 1)) / dd);
            if (tdc_recip_norm_q30_newton(dd) != exact || tdc_recip_norm_q30(dd) != exact ||
                tdc_recip_norm_q30_div32(dd) != exact) {
                fail_msg("recip_norm_q30(%u): newton %u, div32 %u, dispatch %u, exact %u", dd,
                         tdc_recip_norm_q30_newton(dd), tdc_recip_norm_q30_div32(dd), tdc_recip_norm_q30(dd), exact);
            }
            nchecked++;
        }
    }
    printf("recip_norm_q30: divide, 32-bit long division and Newton paths equal the exact floor on %u inputs\n",
           nchecked);
    printf("recip_norm_q30: max error %.4f LSB (Q30), bound 1\n", max_err);
    assert_true(max_err <= 1.0);
}

static void test_div_q15(void **state)
{
    (void)state;
    double max_err = 0.0;
    uint32_t s = 12345u;
    for (int i = 0; i < 2000000; i++) {
        s = s * 1664525u + 1013904223u;
        uint32_t den = (s >> (s & 31u)) | 1u;
        s = s * 1664525u + 1013904223u;
        uint32_t num = (uint32_t)(((uint64_t)s * den) >> 32);
        int32_t got = tdc_div_q15(num, den);
        double want = 32768.0 * (double)num / (double)den;
        double err = fabs(got - want);
        if (err > max_err) {
            max_err = err;
        }
    }
    double max30 = 0.0;
    for (int i = 0; i < 2000000; i++) {
        s = s * 1664525u + 1013904223u;
        uint32_t den = (s >> (s & 31u)) | 1u;
        s = s * 1664525u + 1013904223u;
        uint32_t num = (uint32_t)(((uint64_t)s * den) >> 32);
        double err = fabs(tdc_div_q30(num, den) - ldexp((double)num / (double)den, 30));
        if (err > max30) {
            max30 = err;
        }
    }
    printf("div_q30: max error %.4f LSB (Q30), bound 1\n", max30);
    assert_true(max30 <= 1.0);
    assert_int_equal(tdc_div_q30(1, 3), 357913941);
    assert_int_equal(tdc_div_q30(7, 7), 1 << 30);
    assert_int_equal(tdc_div_q30(3, 0), 0);
    assert_int_equal(tdc_div_q15(0, 0), 0);
    assert_int_equal(tdc_div_q15(5, 5), 32768);
    assert_int_equal(tdc_div_q15(1, 2), 16384);
    assert_int_equal(tdc_div_q15(0xffffffffu, 0xffffffffu), 32768);
    printf("div_q15: max error %.4f LSB (Q15), bound 1\n", max_err);
    assert_true(max_err <= 1.0);
}

static void test_isqrt(void **state)
{
    (void)state;
    for (uint64_t x = 0; x < (1u << 22); x++) {
        uint64_t r = tdc_isqrt64(x);
        assert_true(r * r <= x && (r + 1) * (r + 1) > x);
    }
    uint32_t s = 1u;
    for (int i = 0; i < 1000000; i++) {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        uint64_t x = ((uint64_t)s << 32) | (s * 2654435761u);
        uint64_t r = tdc_isqrt64(x);
        assert_true(r * r <= x && (r + 1) * (r + 1) > x);
    }
    assert_int_equal(tdc_isqrt64(UINT64_MAX), 0xffffffffu);
    /* squares and their neighbours at every magnitude, near 2^32 - 1, the
     * start of the top range and random values: Newton and the digit
     * method agree with each other and with the definition */
    uint32_t nchecked = 0;
    for (int k = 0; k < 64; k++) {
        for (int j = -3; j <= 3; j++) {
            const uint64_t n = (1ULL << (k / 2)) + (uint64_t)(int64_t)j * ((k & 1) ? 977u : 1u);
            if (n > 0xffffffffu) {
                continue;
            }
            const uint64_t sq = n * n;
            const uint64_t xs[4] = {sq, sq - 1u, sq + 1u, sq + 2u * n};
            for (int m = 0; m < 4; m++) {
                const uint64_t x = xs[m];
                const uint64_t r = tdc_isqrt64(x);
                if (r != tdc_isqrt64_digits(x) || r * r > x || (r < 0xffffffffu && (r + 1) * (r + 1) <= x)) {
                    fail_msg("isqrt64(%llu) = %llu", (unsigned long long)x, (unsigned long long)r);
                }
                nchecked++;
            }
        }
    }
    uint64_t z = 0x9e3779b97f4a7c15ull;
    for (int i = 0; i < 2000000; i++) {
        z ^= z << 13;
        z ^= z >> 7;
        z ^= z << 17;
        const uint64_t x = i < 100000 ? (0xfffffffbull << 32) + (z >> 31) /* around the top range */
                                      : z >> (z & 63u);
        const uint64_t r = tdc_isqrt64(x);
        if (r != tdc_isqrt64_digits(x) || r * r > x || (r < 0xffffffffu && (r + 1) * (r + 1) <= x)) {
            fail_msg("isqrt64(%llu) = %llu", (unsigned long long)x, (unsigned long long)r);
        }
        nchecked++;
    }
    printf("isqrt64: Newton and digit method exact on %u structured and random inputs (TDC_HW_DIV64 = %d)\n", nchecked,
           TDC_HW_DIV64);
}

/* The Cortex-M long division against the host's divide. */
static void test_udiv64_32(void **state)
{
    (void)state;
    uint64_t z = 0x2545f4914f6cdd1dull;
    uint32_t n = 0;
    for (int i = 0; i < 3000000; i++) {
        z ^= z << 13;
        z ^= z >> 7;
        z ^= z << 17;
        uint32_t v = (uint32_t)(z >> 32) >> (z & 31u);
        if (v == 0u) {
            v = 1u;
        }
        /* u below v 2^32: high word < v; extremes every few draws */
        uint64_t u = ((uint64_t)((uint32_t)z % v) << 32) | (uint32_t)(z >> 17);
        if (i % 7 == 0) {
            u = ((uint64_t)(v - 1u) << 32) | 0xffffffffu; /* largest quotient */
        }
        const uint32_t want = (uint32_t)(u / v);
        if (tdc_udiv64_32_digits(u, v) != want || tdc_udiv64_32(u, v) != want) {
            fail_msg("udiv64_32(%llu, %u) = %u/%u, want %u", (unsigned long long)u, v, tdc_udiv64_32_digits(u, v),
                     tdc_udiv64_32(u, v), want);
        }
        n++;
    }
    printf("udiv64_32: long division equals the host divide on %u pairs\n", n);
}

static void test_shifts(void **state)
{
    (void)state;
    /* asr must be floor division for every sign */
    for (int32_t x = -70000; x <= 70000; x += 7) {
        for (unsigned n = 0; n < 20; n++) {
            int64_t want = (int64_t)floor((double)x / (double)(1 << n));
            assert_int_equal(tdc_asr32(x, n), want);
        }
    }
    assert_int_equal(tdc_asr32(INT32_MIN, 31), -1);
    assert_int_equal(tdc_rshr_round32(-3, 1), -1); /* -1.5 rounds half up to -1 */
    assert_int_equal(tdc_rshr_round32(3, 1), 2);
    assert_int_equal(tdc_sat16(40000), INT16_MAX);
    assert_int_equal(tdc_sat32((int64_t)1 << 40), INT32_MAX);
    assert_int_equal(tdc_abs32(INT32_MIN), INT32_MAX);
    assert_int_equal(tdc_mul_q16_32(65536, -12345), -12345);
    assert_int_equal(tdc_mul_q16_32(-3, 32768), -1); /* -1.5 rounds half up to -1 */
    assert_int_equal(tdc_mul_q16_32(3, 32768), 2);
    assert_int_equal(tdc_mul_q16_32(INT32_MAX, INT32_MAX), INT32_MAX); /* saturates */
    assert_int_equal(tdc_mul_q16_32(INT32_MIN, INT32_MAX), INT32_MIN);
}

/* Gamma tables of every panel: decode exact at codes, interpolation error
 * bounded, encode equal to double round((C-1) L^(1/g)) for every Q24 input
 * in a dense sweep and at every threshold +-1. */
static void check_panel(const tdc_panel_t *p)
{
    const uint32_t maxc = (1u << p->bits) - 1u;
    double max_interp = 0.0;
    uint32_t max_scan = 0;
    for (int ch = 0; ch < 3; ch++) {
        const tdc_gamma_table_t *t = &p->gamma[ch];
        double g = p->gamma_micro[ch] / 1e6;
        for (uint32_t k = 0; k <= maxc; k++) {
            double want = ldexp(pow(k / (double)maxc, g), 24);
            assert_true(fabs(tdc_gamma_decode(t, k) - want) <= 0.5 + 1e-9 * want);
        }
        for (uint32_t gv = 0; gv <= (maxc << 8); gv++) {
            double want = ldexp(pow(gv / 256.0 / maxc, g), 24);
            double err = fabs(tdc_gamma_decode_gval(t, gv) - want) / ldexp(1.0, 24);
            if (err > max_interp) {
                max_interp = err;
            }
        }
        for (int64_t l = -100; l <= (1 << 24) + 100; l += (l < 65536) ? 1 : 97) {
            uint32_t got = tdc_gamma_encode(t, (tdc_lin_t)l, maxc);
            double lc = l < 0 ? 0.0 : (l > (1 << 24) ? 1.0 : ldexp((double)l, -24));
            uint32_t want = (uint32_t)floor(maxc * pow(lc, 1.0 / g) + 0.5);
            if (got != want) {
                fail_msg("%s ch%d encode(%lld) = %u, double says %u", p->name, ch, (long long)l, got, want);
            }
            uint32_t start = t->enc_index[(l < 0 ? 0 : (l > (1 << 24) ? (1 << 24) : l)) >> 12];
            if (got - start > max_scan) {
                max_scan = got - start;
            }
        }
        for (uint32_t k = 1; k <= maxc; k++) {
            uint32_t th = t->enc_thresh[k];
            assert_int_equal(tdc_gamma_encode(t, (tdc_lin_t)th, maxc), k);
            assert_int_equal(tdc_gamma_encode(t, (tdc_lin_t)th - 1, maxc), k - 1);
        }
    }
    /* linear interpolation error of v^g over one code: g(g-1)/8/(C-1)^2,
     * plus the Q24 roundings (table entries and result) */
    double gmax = 0.0;
    for (int ch = 0; ch < 3; ch++) {
        gmax = p->gamma_micro[ch] / 1e6 > gmax ? p->gamma_micro[ch] / 1e6 : gmax;
    }
    const double bound = gmax * (gmax - 1.0) / 8.0 / ((double)maxc * maxc) + ldexp(1.5, -24);
    printf("%s: decode interpolation max error %.3g of full scale (bound %.3g), encode exact, "
           "max forward scan %u codes (bound 8)\n",
           p->name, max_interp, bound, max_scan);
    assert_true(max_interp <= bound);
    assert_true(max_scan <= 8u);
}

static void test_gamma_tables(void **state)
{
    (void)state;
#define CHECK(sym) check_panel(&sym);
    TDC_PANEL_LIST(CHECK)
}

/* Checksum over the helpers' outputs on fixed sweeps (libopus style): any
 * change of a helper's behaviour changes it.  Update deliberately. */
#define TDC_MATH_HELPER_CHECKSUM 0xe8949c654e01efd2ULL
static void test_helper_checksum(void **state)
{
    (void)state;
    uint64_t h = 0xcbf29ce484222325ULL;
#define MIX(v)                 \
    do {                       \
        h ^= (uint32_t)(v);    \
        h *= 0x100000001b3ULL; \
    } while (0)
    for (uint32_t x = 0; x < (1u << 20); x += 3u) {
        MIX(tdc_exp_neg_q16(x));
    }
    for (uint64_t d = 1ULL << 31; d < (1ULL << 32); d += 999983u) {
        MIX(tdc_recip_norm_q30((uint32_t)d));
    }
    for (uint32_t n = 0; n < 70000u; n += 13u) {
        MIX(tdc_div_q15(n, 70000u));
        MIX(tdc_isqrt64((uint64_t)n * n * 977u));
    }
    printf("math helper checksum %016llx (expected %016llx)\n", (unsigned long long)h,
           (unsigned long long)TDC_MATH_HELPER_CHECKSUM);
    assert_true(h == TDC_MATH_HELPER_CHECKSUM);
}

static void test_mean_u8_exhaustive(void **state)
{
    (void)state;
    for (unsigned n = 1; n <= 4; n++)
        for (uint32_t s = 0; s <= 255u * n; s++) assert_int_equal(tdc_mean_u8(s, n), (2 * s + n) / (2 * n));
    assert_int_equal(tdc_mean_u8(10, 0), 0);
    assert_int_equal(tdc_mean_u8(10, 5), 0);
}

static void test_sqrt_q8(void **state)
{
    (void)state;
    double maxerr = 0;
    for (uint32_t d = 0; d < (1u << 20); d++) {
        double e = fabs((double)tdc_sqrt_q8(d) - 256.0 * sqrt((double)d));
        if (e > maxerr) maxerr = e;
    }
    printf("sqrt_q8: max error %.3f (Q8) over all d < 2^20\n", maxerr);
    assert_true(maxerr <= 12.0); /* < 0.05 code value in the clamp edge */
}

static void test_div_small(void **state)
{
    (void)state;
    for (uint32_t n = 1; n <= 8; n++)
        for (uint32_t x = 0; x < (1u << 21); x++)
            if (tdc_div_small(x, n) != x / n) fail_msg("div_small(%u, %u) = %u", x, n, tdc_div_small(x, n));
    assert_int_equal(tdc_div_small((1u << 29) - 1u, 7), ((1u << 29) - 1u) / 7);
    assert_int_equal(tdc_div_small(5, 0), 0);
    assert_int_equal(tdc_div_small(5, 9), 0);
}

/* The random-band hash keeps its constants (the assembly golden vectors and
 * every renderer/controller pair depend on them): known values, and bit 31
 * (the ordering bit) balanced over a frame of tiles. */
static void test_hash3(void **state)
{
    (void)state;
    assert_int_equal(tdc_hash3(0, 0, 0), 0x00000000u);
    assert_int_equal(tdc_hash3(1, 0, 0), 0x11FD02EBu);
    assert_int_equal(tdc_hash3(3, 5, 40), 0xD3B7F9B6u);
    assert_int_equal(tdc_hash3(959, 539, 0xFFFFFFFCu), 0xC5277794u);
    uint32_t ones = 0;
    for (uint32_t ty = 0; ty < 540; ty++)
        for (uint32_t tx = 0; tx < 960; tx++) ones += tdc_hash3(tx, ty, 4) >> 31;
    printf("hash3: bit 31 set in %u of %u tiles\n", ones, 960u * 540u);
    assert_true(ones > 960u * 540u / 2u - 2000u && ones < 960u * 540u / 2u + 2000u);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_shifts),
    cmocka_unit_test(test_exp_neg),
    cmocka_unit_test(test_recip),
    cmocka_unit_test(test_div_q15),
    cmocka_unit_test(test_isqrt),
    cmocka_unit_test(test_udiv64_32),
    cmocka_unit_test(test_gamma_tables),
    cmocka_unit_test(test_helper_checksum),
    cmocka_unit_test(test_mean_u8_exhaustive),
    cmocka_unit_test(test_sqrt_q8),
    cmocka_unit_test(test_div_small),
    cmocka_unit_test(test_hash3),
)
