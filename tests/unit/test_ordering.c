/*
 * test_ordering.c - the tile-ordering decision (docs/design.md §4.3, paper eq. 2-5):
 * orderings and jitter tables, angle and fractional-length precision against
 * double, agreement with the double reference decision, paper eq. 4 / eq. 5
 * per band, the hashed diagonal, zero motion, and the per-tile update.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tdc_cmocka.h"
#include <math.h>
#include <stdio.h>
#include "tdc_math.h"
#include <stdlib.h>
#include <string.h>

#include "ref_assemble.h"
#include "tdc_ordering.h"

static void test_pixel_orders(void **st)
{
    (void)st;
    const unsigned hg[4] = {TDC_TILE_TL, TDC_TILE_TR, TDC_TILE_BL, TDC_TILE_BR};
    const unsigned bt[4] = {TDC_TILE_TL, TDC_TILE_BL, TDC_TILE_TR, TDC_TILE_BR};
    for (unsigned k = 0; k < 8; k++) {
        assert_int_equal(tdc_ordering_pixel(TDC_ORDER_HOURGLASS, k), hg[k & 3]);
        assert_int_equal(tdc_ordering_pixel(TDC_ORDER_BOWTIE, k), bt[k & 3]);
    }
    assert_int_equal(TDC_PATTERN_BYTES(5, 3), 1);  /* 3 x 2 tiles */
    assert_int_equal(TDC_PATTERN_BYTES(17, 3), 3); /* 9 x 2 = 18 bits */
}

static void test_jitter(void **st)
{
    (void)st;
    int32_t sx = 0, sy = 0, seen[4][2];
    for (uint32_t f = 0; f < 16; f++) {
        int32_t dx, dy;
        tdc_jitter_offset_q4(f, &dx, &dy);
        /* constant within a cycle, advances once per 4 frames */
        int32_t dx0, dy0;
        tdc_jitter_offset_q4(f & ~3u, &dx0, &dy0);
        assert_int_equal(dx, dx0);
        assert_int_equal(dy, dy0);
        assert_true(dx > -8 && dx < 8 && dy > -8 && dy < 8); /* inside the pixel */
        if ((f & 3u) == 0) {
            seen[f / 4][0] = dx, seen[f / 4][1] = dy;
            sx += dx, sy += dy;
        }
    }
    for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++) assert_false(seen[i][0] == seen[j][0] && seen[i][1] == seen[j][1]);
    /* rotated grid: centred, and each of x and y takes 4 distinct values */
    assert_int_equal(sx, 0);
    assert_int_equal(sy, 0);
    int32_t a, b;
    tdc_jitter_offset_q4(16, &a, &b);
    assert_int_equal(a, seen[0][0]);
}

static void test_angle_table_and_precision(void **st)
{
    (void)st;
    /* Exact table points: t = i/32 -> the entry round(atan(i/32)/(pi/2)*2^16). */
    for (int i = 0; i <= 32; i++) {
        uint32_t want = (uint32_t)lround(atan(i / 32.0) / (M_PI / 2) * 65536.0);
        assert_int_equal(tdc_ordering_angle_q16(32 * 64, i * 64), want);
        assert_int_equal(tdc_ordering_angle_q16(i * 64, 32 * 64), 65536u - want);
    }
    /* Dense sweep against double atan2: |error| <= 2^-13 quarter turns. */
    double maxerr = 0;
    for (int my = -600; my <= 600; my++)
        for (int mx = -600; mx <= 600; mx++) {
            if (!mx && !my) continue;
            double u = atan2(fabs((double)my), fabs((double)mx)) / (M_PI / 2) * 65536.0;
            double e = fabs(tdc_ordering_angle_q16(mx, my) - u);
            if (e > maxerr) maxerr = e;
        }
    printf("ordering: angle max error %.2f Q16 LSB of a quarter turn (%.2e rad), bound 8\n", maxerr,
           maxerr / 65536.0 * M_PI / 2);
    assert_true(maxerr <= 8.0);
}

static void test_frac_len(void **st)
{
    (void)st;
    long exact = 0, total = 0;
    for (int my = -400; my <= 400; my += 1)
        for (int mx = -400; mx <= 400; mx += 3) {
            double l = sqrt((double)mx * mx + (double)my * my) / 16.0;
            double want = floor((l - floor(l)) * 4096.0);
            int32_t got = (int32_t)tdc_ordering_frac_len_q12(mx, my);
            int32_t d = (got - (int32_t)want + 4096) % 4096;
            assert_true(d == 0 || d == 1 || d == 4095);
            exact += d == 0;
            total++;
        }
    /* extremes of the Q4 range */
    assert_int_equal(tdc_ordering_frac_len_q12(-32768, 0), 0);
    assert_int_equal(tdc_ordering_frac_len_q12(32767, 0), 4096 - 256);
    assert_int_equal(tdc_ordering_frac_len_q12(0, -32768), 0);
    printf("ordering: fractional length exact (Q12) in %ld of %ld cases\n", exact, total);
    assert_true(exact * 1000 >= total * 999);
}

/* Distance of the reference band coordinate to a band edge, or to the
 * random-band edge in angle: decisions may differ only that close. */
static int near_boundary(int mx, int my)
{
    double a = atan2(fabs((double)my), fabs((double)mx));
    if (fabs(fabs(a - M_PI / 4) - M_PI / 40) < 1e-4) return 1;
    double l = hypot(mx / 16.0, my / 16.0), lf = l - floor(l), s = 0.5 * a / (M_PI / 2);
    double x = a < M_PI / 4 ? fmod(lf - s + 1.0, 1.0) : fmod(lf + s, 1.0);
    const double eps = 2.0 / 4096; /* l_f floor + shift rounding + angle error */
    return fabs(x - 0.25) < eps || fabs(x - 0.75) < eps || x < eps || x > 1 - eps;
}

static void test_decision_matches_reference(void **st)
{
    (void)st;
    long agree = 0, total = 0, boundary = 0;
    for (int my = -700; my <= 700; my += 1)
        for (int mx = -700; mx <= 700; mx += 1) {
            if (!mx && !my) continue;
            tdc_ordering_t f =
                tdc_ordering_decide(mx, my, TDC_ORDER_HOURGLASS, (uint32_t)mx & 63u, (uint32_t)my & 63u, 8);
            tdc_ordering_t r = tdc_ref_ordering_decide(mx / 16.0, my / 16.0, TDC_ORDER_HOURGLASS, (uint32_t)mx & 63u,
                                                       (uint32_t)my & 63u, 8);
            total++;
            if (f == r) {
                agree++;
            } else {
                if (!near_boundary(mx, my))
                    fail_msg("decision differs from double away from a boundary: m = (%d, %d)/16", mx, my);
                boundary++;
            }
        }
    printf("ordering: fixed vs double decision agree in %ld of %ld vectors (%.4f %%), %ld differ within 2^-11 of a "
           "band edge\n",
           agree, total, 100.0 * agree / total, boundary);
    assert_true(agree * 1000 >= total * 999);
}

/* Paper eq. 4: horizontal motion: hourglass iff l_f in (0.25, 0.75).
 * Paper eq. 5: vertical motion: hourglass iff l_f in [0, 0.25] u [0.75, 1). */
static void test_eq4_eq5_bands(void **st)
{
    (void)st;
    for (int L = 0; L <= 200; L += 7)
        for (int f = 0; f < 16; f++) {
            int32_t v = 16 * L + f;
            if (v == 0) continue;
            double lf = f / 16.0;
            tdc_ordering_t h4 = lf > 0.25 && lf < 0.75 ? TDC_ORDER_HOURGLASS : TDC_ORDER_BOWTIE;
            tdc_ordering_t h5 = lf <= 0.25 || lf >= 0.75 ? TDC_ORDER_HOURGLASS : TDC_ORDER_BOWTIE;
            for (int sgn = -1; sgn <= 1; sgn += 2)
                for (int cur = 0; cur < 2; cur++) {
                    assert_int_equal(tdc_ordering_decide(sgn * v, 0, (tdc_ordering_t)cur, 3, 4, 0), h4);
                    assert_int_equal(tdc_ordering_decide(0, sgn * v, (tdc_ordering_t)cur, 3, 4, 0), h5);
                }
        }
    /* One example per band, spelled out. */
    assert_int_equal(tdc_ordering_decide(16 * 3 + 8, 0, TDC_ORDER_BOWTIE, 0, 0, 0), TDC_ORDER_HOURGLASS); /* 3.5 px */
    assert_int_equal(tdc_ordering_decide(16 * 3 + 2, 0, TDC_ORDER_HOURGLASS, 0, 0, 0), TDC_ORDER_BOWTIE); /* 3.125 */
    assert_int_equal(tdc_ordering_decide(0, 16 * 3 + 8, TDC_ORDER_HOURGLASS, 0, 0, 0), TDC_ORDER_BOWTIE);
    assert_int_equal(tdc_ordering_decide(0, 16 * 3 + 2, TDC_ORDER_BOWTIE, 0, 0, 0), TDC_ORDER_HOURGLASS);
}

static void test_band_moves_with_angle(void **st)
{
    (void)st;
    /* a = 30 deg: band (0.25, 0.75) shifted by +1/6.  |m| = 4.5 px:
     * l_f - s = 0.5 - 0.1667 = 0.333 -> hourglass; |m| = 4.9: 0.733 ->
     * hourglass; |m| = 4.95 (0.783) -> bowtie; |m| = 4.3 (0.133) -> bowtie. */
    const double lens[4] = {4.5, 4.9, 4.97, 4.3};
    const tdc_ordering_t want[4] = {TDC_ORDER_HOURGLASS, TDC_ORDER_HOURGLASS, TDC_ORDER_BOWTIE, TDC_ORDER_BOWTIE};
    for (int i = 0; i < 4; i++) {
        int mx = (int)lround(lens[i] * 16 * cos(M_PI / 6)), my = (int)lround(lens[i] * 16 * sin(M_PI / 6));
        assert_int_equal(tdc_ordering_decide(mx, my, TDC_ORDER_BOWTIE, 0, 0, 0),
                         tdc_ref_ordering_decide(mx / 16.0, my / 16.0, TDC_ORDER_BOWTIE, 0, 0, 0));
        assert_int_equal(tdc_ordering_decide(mx, my, TDC_ORDER_BOWTIE, 0, 0, 0), want[i]);
        /* 60 deg: band shifted by -1/3 (closed ends) */
        assert_int_equal(tdc_ordering_decide(my, mx, TDC_ORDER_BOWTIE, 0, 0, 0),
                         tdc_ref_ordering_decide(my / 16.0, mx / 16.0, TDC_ORDER_BOWTIE, 0, 0, 0));
    }
}

static void test_diagonal_hashed(void **st)
{
    (void)st;
    /* a = 45 deg and just inside / outside gamma = pi/40 (4.5 deg). */
    assert_true(tdc_ordering_in_random_band(100, 100));
    assert_true(tdc_ordering_in_random_band(-100, 90));   /* 42.0 deg */
    assert_true(tdc_ordering_in_random_band(86, -100));   /* 49.3 deg */
    assert_false(tdc_ordering_in_random_band(100, 80));   /* 38.7 deg */
    assert_false(tdc_ordering_in_random_band(80, 100));   /* 51.3 deg */
    assert_false(tdc_ordering_in_random_band(1000, 854)); /* 40.49 deg < 40.5 */
    assert_true(tdc_ordering_in_random_band(1000, 855));  /* 40.53 deg */
    int bowtie = 0, n = 0, changed = 0;
    for (uint32_t ty = 0; ty < 64; ty++)
        for (uint32_t tx = 0; tx < 64; tx++) {
            tdc_ordering_t a = tdc_ordering_decide(37, 37, TDC_ORDER_HOURGLASS, tx, ty, 40);
            tdc_ordering_t b = tdc_ordering_decide(-37, 37, TDC_ORDER_BOWTIE, tx, ty, 40);
            assert_int_equal(a, b); /* reproducible: only (tile, frame) matter */
            assert_int_equal(a, (tdc_hash3(tx, ty, 40) >> 31) ? TDC_ORDER_BOWTIE : TDC_ORDER_HOURGLASS);
            changed += a != tdc_ordering_decide(37, 37, TDC_ORDER_HOURGLASS, tx, ty, 44);
            bowtie += a == TDC_ORDER_BOWTIE;
            n++;
        }
    printf("ordering: diagonal: %d of %d tiles bowtie, %d change at the next cycle\n", bowtie, n, changed);
    assert_true(bowtie > n * 45 / 100 && bowtie < n * 55 / 100);
    assert_true(changed > n * 40 / 100 && changed < n * 60 / 100);
}

static void test_zero_keeps(void **st)
{
    (void)st;
    assert_int_equal(tdc_ordering_decide(0, 0, TDC_ORDER_BOWTIE, 1, 2, 3), TDC_ORDER_BOWTIE);
    assert_int_equal(tdc_ordering_decide(0, 0, TDC_ORDER_HOURGLASS, 1, 2, 3), TDC_ORDER_HOURGLASS);
    /* integer horizontal length: l_f = 0 -> bowtie (eq. 4), not "keep" */
    assert_int_equal(tdc_ordering_decide(16, 0, TDC_ORDER_HOURGLASS, 0, 0, 0), TDC_ORDER_BOWTIE);
}

static void test_update_neighbourhood(void **st)
{
    (void)st;
    enum { W = 13, H = 9 }; /* 7 x 5 tiles, odd sizes */
    int16_t mv[W * H * 2];
    uint8_t bits[TDC_PATTERN_BYTES(W, H) + 1];
    memset(mv, 0, sizeof(mv));
    memset(bits, 0, sizeof(bits));
    bits[sizeof(bits) - 1] = 0xA5;            /* guard */
    bits[TDC_PATTERN_BYTES(W, H) - 1] = 0xF8; /* padding bits set: 35 tiles -> bits 3..7 of byte 4 */
    /* pixel (8, 4) = tile (4, 2): horizontal 3.5 px -> hourglass; a shorter
     * vector (1.0 px, -> bowtie) at pixel (12, 8) = tile (6, 4). */
    mv[(4 * W + 8) * 2] = 56;
    mv[(8 * W + 12) * 2] = 16;
    for (int i = 0; i < 35; i++) tdc_ordering_set(bits, (uint32_t)i, TDC_ORDER_BOWTIE);
    tdc_ordering_update(mv, W, H, bits, 4);
    for (int ty = 0; ty < 5; ty++)
        for (int tx = 0; tx < 7; tx++) {
            tdc_ordering_t want = TDC_ORDER_BOWTIE;
            if (abs(tx - 4) <= 1 && abs(ty - 2) <= 1) want = TDC_ORDER_HOURGLASS; /* longest wins */
            assert_int_equal(tdc_ordering_get(bits, (uint32_t)(ty * 7 + tx)), want);
        }
    assert_int_equal(bits[TDC_PATTERN_BYTES(W, H) - 1] & 0xF8, 0xF8);
    assert_int_equal(bits[sizeof(bits) - 1], 0xA5);
    /* Now the tile (5, 3) also sees (12, 8)? No: tile (5,3) covers pixels 8..13 x 4..9,
     * so it sees both; the longer 3.5 px wins.  Tile (6, 4) sees only 1.0 px. */
    for (int i = 0; i < 35; i++) tdc_ordering_set(bits, (uint32_t)i, TDC_ORDER_HOURGLASS);
    tdc_ordering_update(mv, W, H, bits, 8);
    assert_int_equal(tdc_ordering_get(bits, 4 * 7 + 6), TDC_ORDER_BOWTIE);
    assert_int_equal(tdc_ordering_get(bits, 3 * 7 + 5), TDC_ORDER_HOURGLASS);
    assert_int_equal(tdc_ordering_get(bits, 0), TDC_ORDER_HOURGLASS);
}

/* The straightforward definition: raster scan of the clipped 6x6 block. */
static void naive_update(const int16_t *mv, int w, int h, uint8_t *bits, uint32_t frame)
{
    int tx_n = (w + 1) / 2, ty_n = (h + 1) / 2;
    for (int ty = 0; ty < ty_n; ty++)
        for (int tx = 0; tx < tx_n; tx++) {
            uint32_t best = 0;
            int32_t bx = 0, by = 0;
            for (int y = 2 * ty - 2; y <= 2 * ty + 3; y++)
                for (int x = 2 * tx - 2; x <= 2 * tx + 3; x++) {
                    if (x < 0 || y < 0 || x >= w || y >= h) continue;
                    int32_t dx = mv[(y * w + x) * 2], dy = mv[(y * w + x) * 2 + 1];
                    uint32_t l2 = (uint32_t)(dx * dx) + (uint32_t)(dy * dy);
                    if (l2 > best) best = l2, bx = dx, by = dy;
                }
            uint32_t ti = (uint32_t)(ty * tx_n + tx);
            tdc_ordering_set(
                bits, ti, tdc_ordering_decide(bx, by, tdc_ordering_get(bits, ti), (uint32_t)tx, (uint32_t)ty, frame));
        }
}

/* The optimised update (sliding column maxima, decision memo) against the
 * definition, on random fields full of equal-length ties ((3,4), (4,3),
 * (5,0), (0,-5), ...), at odd and even sizes. */
static void test_update_matches_definition(void **st)
{
    (void)st;
    static const int16_t vals[][2] = {{0, 0},  {3, 4},  {4, 3},   {5, 0},      {0, -5},        {-4, 3},
                                      {56, 0}, {0, 56}, {40, 40}, {-32768, 0}, {32767, 32767}, {18, -7}};
    uint32_t rng = 12345;
    const int sizes[][2] = {{1, 1}, {2, 3}, {7, 5}, {13, 9}, {32, 17}, {41, 40}};
    for (size_t si = 0; si < sizeof(sizes) / sizeof(sizes[0]); si++) {
        int w = sizes[si][0], h = sizes[si][1];
        int16_t *mv = calloc((size_t)w * h * 2, sizeof(int16_t));
        size_t nb = (size_t)TDC_PATTERN_BYTES(w, h);
        uint8_t *a = calloc(nb, 1), *b = calloc(nb, 1);
        for (int rep = 0; rep < 50; rep++) {
            int density = rep % 5; /* 0: sparse motion .. 4: dense */
            for (int i = 0; i < w * h; i++) {
                rng = rng * 1664525u + 1013904223u;
                int pick = (int)((rng >> 8) % 12u);
                if ((int)((rng >> 24) % 5u) > density) pick = 0;
                mv[2 * i] = vals[pick][0], mv[2 * i + 1] = vals[pick][1];
            }
            for (size_t i = 0; i < nb; i++) {
                rng = rng * 1664525u + 1013904223u;
                a[i] = b[i] = (uint8_t)(rng >> 24);
            }
            tdc_ordering_update(mv, w, h, a, (uint32_t)rep * 4u);
            naive_update(mv, w, h, b, (uint32_t)rep * 4u);
            assert_memory_equal(a, b, nb);
        }
        free(mv), free(a), free(b);
    }
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_pixel_orders),
    cmocka_unit_test(test_jitter),
    cmocka_unit_test(test_angle_table_and_precision),
    cmocka_unit_test(test_frac_len),
    cmocka_unit_test(test_decision_matches_reference),
    cmocka_unit_test(test_eq4_eq5_bands),
    cmocka_unit_test(test_band_moves_with_angle),
    cmocka_unit_test(test_diagonal_hashed),
    cmocka_unit_test(test_zero_keeps),
    cmocka_unit_test(test_update_neighbourhood),
    cmocka_unit_test(test_update_matches_definition),
)
