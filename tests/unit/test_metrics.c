/*
 * test_metrics.c - PSNR and SSIM against scikit-image on a few image pairs
 * (via /usr/bin/python3, Debian python3-skimage), and properties of FLIP.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "metrics/tdc_metrics.h"

static uint32_t rng = 12345u;
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return (double)(rng >> 8) / 16777216.0;
}

typedef struct {
    int w, h;
    double *a, *b;
} pair_t;

/* Four pairs: noise vs noisier, gradient vs blocky, checker vs shifted,
 * smooth vs contrast-reduced; odd sizes included. */
static void make_pairs(pair_t *p, int n)
{
    static const int sizes[4][2] = {{40, 32}, {37, 29}, {64, 48}, {23, 31}};
    for (int k = 0; k < n; k++) {
        int w = sizes[k][0], h = sizes[k][1];
        p[k].w = w;
        p[k].h = h;
        p[k].a = malloc(sizeof(double) * 3 * w * h);
        p[k].b = malloc(sizeof(double) * 3 * w * h);
        for (int y = 0; y < h; y++) {
            for (int x = 0; x < w; x++) {
                for (int c = 0; c < 3; c++) {
                    size_t i = 3 * ((size_t)y * w + x) + c;
                    double a, b;
                    switch (k) {
                    case 0:
                        a = urand();
                        b = fmin(1.0, fmax(0.0, a + 0.1 * (urand() - 0.5)));
                        break;
                    case 1:
                        a = (double)(x + y + c) / (w + h + 2);
                        b = (double)((x / 4) * 4 + (y / 4) * 4 + c) / (w + h + 2);
                        break;
                    case 2:
                        a = ((x / 3 + y / 3) & 1) ? 0.9 : 0.1;
                        b = (((x + 1) / 3 + y / 3) & 1) ? 0.9 : 0.1;
                        break;
                    default:
                        a = 0.5 + 0.4 * sin(x * 0.3 + c) * cos(y * 0.2);
                        b = 0.5 + 0.3 * sin(x * 0.3 + c) * cos(y * 0.2) + 0.02 * urand();
                        break;
                    }
                    p[k].a[i] = a;
                    p[k].b[i] = b;
                }
            }
        }
    }
}

static void test_psnr_ssim_vs_skimage(void **state)
{
    (void)state;
    pair_t p[4];
    make_pairs(p, 4);
    char dir[] = "/tmp/tdc_metrics_XXXXXX";
    assert_non_null(mkdtemp(dir));
    for (int k = 0; k < 4; k++) {
        char path[256];
        snprintf(path, sizeof(path), "%s/p%d.bin", dir, k);
        FILE *f = fopen(path, "wb");
        assert_non_null(f);
        size_t n = 3 * (size_t)p[k].w * p[k].h;
        assert_int_equal(fwrite(p[k].a, sizeof(double), n, f), n);
        assert_int_equal(fwrite(p[k].b, sizeof(double), n, f), n);
        fclose(f);
    }
    char cmd[2048];
    snprintf(cmd, sizeof(cmd),
             "/usr/bin/python3 -c \""
             "import numpy as np, sys\n"
             "from skimage.metrics import structural_similarity as ssim, peak_signal_noise_ratio as psnr\n"
             "for k, (w, h) in enumerate([(40,32),(37,29),(64,48),(23,31)]):\n"
             "    d = np.fromfile('%s/p%%d.bin' %% k, dtype=np.float64).reshape(2, h, w, 3)\n"
             "    print('%%.12f %%.12f' %% (psnr(d[0], d[1], data_range=1.0), ssim(d[0], d[1], data_range=1.0, "
             "channel_axis=2, gaussian_weights=True, sigma=1.5, use_sample_covariance=False)))\n"
             "\"",
             dir);
    FILE *py = popen(cmd, "r");
    assert_non_null(py);
    for (int k = 0; k < 4; k++) {
        double ps, ss;
        assert_int_equal(fscanf(py, "%lf %lf", &ps, &ss), 2);
        size_t n = 3 * (size_t)p[k].w * p[k].h;
        double mps = tdc_psnr(p[k].a, p[k].b, n, 1.0);
        double mss = tdc_ssim(p[k].a, p[k].b, p[k].w, p[k].h, 1.0);
        printf("pair %d (%dx%d): PSNR ours %.9f skimage %.9f | SSIM ours %.9f skimage %.9f\n", k, p[k].w, p[k].h,
               mps, ps, mss, ss);
        assert_true(fabs(mps - ps) < 1e-6);
        assert_true(fabs(mss - ss) < 1e-6);
        free(p[k].a);
        free(p[k].b);
    }
    assert_int_equal(pclose(py), 0);
    char rm[300];
    snprintf(rm, sizeof(rm), "rm -rf %s", dir);
    assert_int_equal(system(rm), 0);
}

static void test_psnr_identical_capped(void **state)
{
    (void)state;
    double a[12] = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 0.0, 0.5};
    assert_true(tdc_psnr(a, a, 12, 1.0) == TDC_PSNR_CAP);
}

static void fill(double *img, int w, int h, double noise, uint32_t seed)
{
    rng = seed;
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            double base = ((x / 4 + y / 4) & 1) ? 0.7 : 0.2;
            for (int c = 0; c < 3; c++) {
                double v = base + noise * (urand() - 0.5);
                img[3 * ((size_t)y * w + x) + c] = v < 0 ? 0 : (v > 1 ? 1 : v);
            }
        }
    }
}

static void test_flip_properties(void **state)
{
    (void)state;
    const int w = 48, h = 40;
    double *ref = malloc(sizeof(double) * 3 * w * h), *t1 = malloc(sizeof(double) * 3 * w * h);
    double *t2 = malloc(sizeof(double) * 3 * w * h), *map = malloc(sizeof(double) * w * h);
    fill(ref, w, h, 0.0, 1);
    /* identical images: zero error everywhere */
    assert_true(fabs(tdc_flip(ref, ref, w, h, TDC_FLIP_DEFAULT_PPD, map)) < 1e-12);
    /* more noise -> more error; every pixel in [0, 1] */
    fill(t1, w, h, 0.1, 7);
    fill(t2, w, h, 0.5, 7);
    double f1 = tdc_flip(ref, t1, w, h, TDC_FLIP_DEFAULT_PPD, map);
    double f2 = tdc_flip(ref, t2, w, h, TDC_FLIP_DEFAULT_PPD, map);
    printf("FLIP noise 0.1: %.4f, noise 0.5: %.4f\n", f1, f2);
    assert_true(f1 > 0.0 && f1 < f2 && f2 <= 1.0);
    for (int i = 0; i < w * h; i++) {
        assert_true(map[i] >= 0.0 && map[i] <= 1.0);
    }
    /* pure green vs pure blue is the maximal colour difference: ~1 */
    for (int i = 0; i < w * h; i++) {
        t1[3 * i] = 0;
        t1[3 * i + 1] = 1;
        t1[3 * i + 2] = 0;
        t2[3 * i] = 0;
        t2[3 * i + 1] = 0;
        t2[3 * i + 2] = 1;
    }
    double fgb = tdc_flip(t1, t2, w, h, TDC_FLIP_DEFAULT_PPD, map);
    printf("FLIP green vs blue: %.6f\n", fgb);
    assert_true(fgb > 0.99 && fgb <= 1.0);
    /* black vs white, flat: large; a 1-level difference: tiny */
    for (int i = 0; i < 3 * w * h; i++) {
        t1[i] = 0.5;
        t2[i] = 0.5 + 1.0 / 255.0;
    }
    double small = tdc_flip(t1, t2, w, h, TDC_FLIP_DEFAULT_PPD, NULL);
    printf("FLIP 1/255 offset: %.6f\n", small);
    assert_true(small > 0.0 && small < 0.05);
    free(ref);
    free(t1);
    free(t2);
    free(map);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_psnr_ssim_vs_skimage),
        cmocka_unit_test(test_psnr_identical_capped),
        cmocka_unit_test(test_flip_properties),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
