/*
 * test_image_source.c - the photograph source (sim/image): the exact
 * area-sampled ground truth against an independent polygon-clipping
 * reference, closed-form cases (constant image, aligned texels, 2x2 box
 * means), nearest-texel samples, exact motion vectors, PNG/JPEG reading
 * and every bad-input path.
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

#include "tdc_cmocka.h"
#include <jpeglib.h>

#include "image/tdc_image_read.h"
#include "image/tdc_image_source.h"
#include "tdc_png.h"

static uint32_t rng = 12345u;
static double urand(void)
{
    rng = rng * 1664525u + 1013904223u;
    return (double)(rng >> 8) / 16777216.0;
}

static tdc_scene_params_t screen(int w, int h, double speed, double angle)
{
    const tdc_scene_params_t p = {.width = w, .height = h, .speed = speed, .angle_deg = angle, .pursuit = 1};
    return p;
}

/* A constant image is a constant frame under any pan, zoom and rotation,
 * also many mirror periods away from the image. */
static void test_constant_image(void **state)
{
    (void)state;
    enum { IW = 13, IH = 7, W = 24, H = 18 };
    static double img[IW * IH * 3], gt[W * H * 3];
    for (int i = 0; i < IW * IH; i++) {
        img[3 * i] = 0.37;
        img[3 * i + 1] = 0.5;
        img[3 * i + 2] = 0.01;
    }
    for (int trial = 0; trial < 20; trial++) {
        tdc_scene_params_t p = screen(W, H, 400.0 * urand(), 360.0 * urand());
        tdc_image_motion_t m;
        tdc_image_motion_default(&m);
        m.zoom = 0.2 + 3.0 * urand();
        m.zoom_rate = urand() - 0.5;
        m.rotate_dps = 200.0 * (urand() - 0.5);
        char err[256];
        tdc_source_t *s = tdc_image_source_from_linear(img, IW, IH, &p, &m, err, sizeof err);
        assert_non_null(s);
        double t = 3.0 * urand();
        s->ground_truth(s, t, urand() - 0.5, urand() - 0.5, gt);
        for (int i = 0; i < W * H; i++) {
            assert_true(fabs(gt[3 * i] - 0.37) < 1e-11);
            assert_true(fabs(gt[3 * i + 1] - 0.5) < 1e-11);
            assert_true(fabs(gt[3 * i + 2] - 0.01) < 1e-11);
        }
        s->destroy(s);
    }
}

/* Closed forms: zoom 1 aligned -> the texels themselves (mirrored beyond
 * the image); zoom 1/2 -> the mean of each 2x2 texel block. */
static void test_aligned_and_box_means(void **state)
{
    (void)state;
    enum { IW = 8, IH = 6, W = 12, H = 8 };
    static double img[IW * IH * 3], gt[W * H * 3];
    for (int i = 0; i < IW * IH * 3; i++) {
        img[i] = urand();
    }
    char err[256];
    tdc_scene_params_t p = screen(W, H, 0.0, 0.0);
    tdc_image_motion_t m;
    tdc_image_motion_default(&m);
    m.cx = 0.5 * W; /* screen pixel (x, y) = texel (x, y) */
    m.cy = 0.5 * H;
    tdc_source_t *s = tdc_image_source_from_linear(img, IW, IH, &p, &m, err, sizeof err);
    assert_non_null(s);
    s->ground_truth(s, 0.0, 0.0, 0.0, gt);
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            int mx = x < IW ? x : 2 * IW - 1 - x, my = y < IH ? y : 2 * IH - 1 - y; /* mirror */
            for (int k = 0; k < 3; k++) {
                assert_true(fabs(gt[3 * (y * W + x) + k] - img[3 * (my * IW + mx) + k]) < 1e-12);
            }
        }
    }
    s->destroy(s);
    m.zoom = 0.5; /* one screen pixel covers 2x2 texels */
    m.cx = 0.5 * W * 2.0;
    m.cy = 0.5 * H * 2.0;
    tdc_scene_params_t p2 = screen(IW / 2, IH / 2, 0.0, 0.0);
    m.cx = IW / 2.0;
    m.cy = IH / 2.0;
    s = tdc_image_source_from_linear(img, IW, IH, &p2, &m, err, sizeof err);
    assert_non_null(s);
    s->ground_truth(s, 0.0, 0.0, 0.0, gt);
    for (int y = 0; y < IH / 2; y++) {
        for (int x = 0; x < IW / 2; x++) {
            for (int k = 0; k < 3; k++) {
                double e =
                    0.25 * (img[3 * ((2 * y) * IW + 2 * x) + k] + img[3 * ((2 * y) * IW + 2 * x + 1) + k] +
                            img[3 * ((2 * y + 1) * IW + 2 * x) + k] + img[3 * ((2 * y + 1) * IW + 2 * x + 1) + k]);
                assert_true(fabs(gt[3 * (y * (IW / 2) + x) + k] - e) < 1e-12);
            }
        }
    }
    s->destroy(s);
}

/* Independent reference: area of the pixel's preimage quad clipped against
 * each texel square (Sutherland-Hodgman), weighted by the mirrored texel. */
static int clip(const double *in, int n, int axis, double v, int keep_above, double *out)
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        const double *a = in + 2 * i, *b = in + 2 * ((i + 1) % n);
        int ia = keep_above ? a[axis] >= v : a[axis] <= v, ib = keep_above ? b[axis] >= v : b[axis] <= v;
        if (ia) {
            out[2 * m] = a[0];
            out[2 * m + 1] = a[1];
            m++;
        }
        if (ia != ib) {
            double f = (v - a[axis]) / (b[axis] - a[axis]);
            out[2 * m] = a[0] + f * (b[0] - a[0]);
            out[2 * m + 1] = a[1] + f * (b[1] - a[1]);
            m++;
        }
    }
    return m;
}

static double poly_area(const double *p, int n)
{
    double a = 0;
    for (int i = 0; i < n; i++) {
        const double *u = p + 2 * i, *v = p + 2 * ((i + 1) % n);
        a += u[0] * v[1] - v[0] * u[1];
    }
    return 0.5 * a;
}

static int mir(int i, int n)
{
    int p = 2 * n, r = ((i % p) + p) % p;
    return r < n ? r : p - 1 - r;
}

static void test_exact_against_clipping(void **state)
{
    (void)state;
    enum { IW = 7, IH = 5, W = 9, H = 7 };
    static double img[IW * IH * 3], gt[W * H * 3];
    for (int i = 0; i < IW * IH * 3; i++) {
        img[i] = urand();
    }
    double worst = 0.0;
    for (int trial = 0; trial < 12; trial++) {
        tdc_scene_params_t p = screen(W, H, 300.0 * urand(), 360.0 * urand());
        tdc_image_motion_t m;
        tdc_image_motion_default(&m);
        m.zoom = 0.3 + 2.5 * urand();
        m.zoom_rate = 0.6 * (urand() - 0.5);
        m.rotate_dps = 90.0 * (urand() - 0.5);
        char err[256];
        tdc_source_t *s = tdc_image_source_from_linear(img, IW, IH, &p, &m, err, sizeof err);
        assert_non_null(s);
        double t = urand(), ox = urand() - 0.5, oy = urand() - 0.5;
        s->ground_truth(s, t, ox, oy, gt);
        double A[4], b[2];
        tdc_image_source_map(s, t, A, b);
        for (int y = 0; y < H; y++) {
            for (int x = 0; x < W; x++) {
                double quad[8], lo[2] = {1e30, 1e30}, hi[2] = {-1e30, -1e30};
                static const int cx[4] = {0, 1, 1, 0}, cy[4] = {0, 0, 1, 1};
                for (int c = 0; c < 4; c++) {
                    double px = x + ox + cx[c], py = y + oy + cy[c];
                    quad[2 * c] = A[0] * px + A[1] * py + b[0];
                    quad[2 * c + 1] = A[2] * px + A[3] * py + b[1];
                    for (int d = 0; d < 2; d++) {
                        lo[d] = fmin(lo[d], quad[2 * c + d]);
                        hi[d] = fmax(hi[d], quad[2 * c + d]);
                    }
                }
                double area = fabs(poly_area(quad, 4)), acc[3] = {0, 0, 0};
                for (int j = (int)floor(lo[1]); j <= (int)floor(hi[1]); j++) {
                    for (int i = (int)floor(lo[0]); i <= (int)floor(hi[0]); i++) {
                        double b1[32], b2[32];
                        int n = clip(quad, 4, 0, i, 1, b1);
                        n = clip(b1, n, 0, i + 1, 0, b2);
                        n = clip(b2, n, 1, j, 1, b1);
                        n = clip(b1, n, 1, j + 1, 0, b2);
                        double a = n >= 3 ? fabs(poly_area(b2, n)) : 0.0;
                        const double *tx = img + 3 * (mir(j, IH) * IW + mir(i, IW));
                        for (int k = 0; k < 3; k++) {
                            acc[k] += a * tx[k];
                        }
                    }
                }
                for (int k = 0; k < 3; k++) {
                    worst = fmax(worst, fabs(gt[3 * (y * W + x) + k] - acc[k] / area));
                }
            }
        }
        s->destroy(s);
    }
    printf("ground truth vs polygon clipping: max |diff| %.3g\n", worst);
    assert_true(worst < 1e-10);
}

/* Samples are the nearest texel; MVs bring each sample back to the same
 * image point one frame earlier (exact up to the Q4 rounding). */
static void test_samples_and_mvs(void **state)
{
    (void)state;
    enum { IW = 16, IH = 12, W = 20, H = 14 };
    static double img[IW * IH * 3];
    for (int i = 0; i < IW * IH * 3; i++) {
        img[i] = urand();
    }
    char err[256];
    tdc_scene_params_t p = screen(W, H, 120.0, 30.0);
    tdc_image_motion_t m;
    tdc_image_motion_default(&m);
    m.zoom = 1.7;
    m.zoom_rate = 0.4;
    m.rotate_dps = 25.0;
    tdc_source_t *s = tdc_image_source_from_linear(img, IW, IH, &p, &m, err, sizeof err);
    assert_non_null(s);
    s->gamma[0] = s->gamma[1] = s->gamma[2] = 1.0;
    double xy[2 * W * H];
    uint8_t rgb[3 * W * H];
    int16_t mv[2 * W * H];
    for (int i = 0; i < W * H; i++) {
        xy[2 * i] = i % W + 0.5;
        xy[2 * i + 1] = i / W + 0.5;
    }
    double t = 0.3, dt = 1.0 / 90.0;
    s->samples(s, t, W * H, xy, 1, rgb, mv, dt, TDC_MV_SURFACE);
    double A[4], b[2], Ap[4], bp[2];
    tdc_image_source_map(s, t, A, b);
    tdc_image_source_map(s, t - dt, Ap, bp);
    for (int i = 0; i < W * H; i++) {
        double x = xy[2 * i], y = xy[2 * i + 1];
        double qx = A[0] * x + A[1] * y + b[0], qy = A[2] * x + A[3] * y + b[1];
        int tx = mir((int)floor(qx), IW), ty = mir((int)floor(qy), IH);
        for (int k = 0; k < 3; k++) {
            int e = (int)floor(255.0 * img[3 * (ty * IW + tx) + k] + 0.5);
            assert_int_equal(rgb[3 * i + k], e);
        }
        double px = x + mv[2 * i] / 16.0, py = y + mv[2 * i + 1] / 16.0;
        double q2x = Ap[0] * px + Ap[1] * py + bp[0], q2y = Ap[2] * px + Ap[3] * py + bp[1];
        /* Q4 rounding: <= 1/32 px per axis, times the texels per pixel */
        assert_true(hypot(q2x - qx, q2y - qy) <=
                    (1.0 / 32.0) * sqrt(2.0) / (m.zoom * exp(m.zoom_rate * (t - dt))) + 1e-9);
    }
    /* pursuit: velocity of the content at the screen centre, by differences */
    double v[2], c0x = 0.5 * W, c0y = 0.5 * H, h = 1e-5;
    s->pursuit(s, t, v);
    tdc_image_source_map(s, t, A, b);
    double qx = A[0] * c0x + A[1] * c0y + b[0], qy = A[2] * c0x + A[3] * c0y + b[1];
    tdc_image_source_map(s, t + h, Ap, bp);
    qx -= bp[0];
    qy -= bp[1];
    double id = 1.0 / (Ap[0] * Ap[3] - Ap[1] * Ap[2]);
    double nx = (Ap[3] * qx - Ap[1] * qy) * id, ny = (-Ap[2] * qx + Ap[0] * qy) * id;
    assert_true(fabs((nx - c0x) / h - v[0]) < 1e-3 && fabs((ny - c0y) / h - v[1]) < 1e-3);
    assert_false(s->rigid); /* zoom + rotation: several ground-truth instants */
    s->destroy(s);
}

static void write_jpeg(const char *path, const uint8_t *rgb, int w, int h)
{
    struct jpeg_compress_struct c;
    struct jpeg_error_mgr e;
    c.err = jpeg_std_error(&e);
    jpeg_create_compress(&c);
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    jpeg_stdio_dest(&c, f);
    c.image_width = (JDIMENSION)w;
    c.image_height = (JDIMENSION)h;
    c.input_components = 3;
    c.in_color_space = JCS_RGB;
    jpeg_set_defaults(&c);
    jpeg_set_quality(&c, 100, TRUE);
    jpeg_start_compress(&c, TRUE);
    for (int y = 0; y < h; y++) {
        JSAMPROW r = (JSAMPROW)(rgb + (size_t)y * w * 3);
        jpeg_write_scanlines(&c, &r, 1);
    }
    jpeg_finish_compress(&c);
    jpeg_destroy_compress(&c);
    fclose(f);
}

/* PNG (8 and 16 bit) and JPEG round trips; every bad input named. */
static void test_read_and_bad_input(void **state)
{
    (void)state;
    char dir[] = "/tmp/tdc_image_testXXXXXX";
    assert_non_null(mkdtemp(dir));
    char png8[256], png16[256], jpg[256], trunc[256], empty[256], junk[256];
    snprintf(png8, sizeof png8, "%s/a.png", dir);
    snprintf(png16, sizeof png16, "%s/b.png", dir);
    snprintf(jpg, sizeof jpg, "%s/c.jpg", dir);
    snprintf(trunc, sizeof trunc, "%s/d.jpg", dir);
    snprintf(empty, sizeof empty, "%s/e.png", dir);
    snprintf(junk, sizeof junk, "%s/f.jpg", dir);
    enum { IW = 40, IH = 24 };
    static uint8_t rgb[IW * IH * 3];
    static uint16_t rgb16[IW * IH * 3];
    for (int i = 0; i < IW * IH * 3; i++) {
        rgb[i] = (uint8_t)((i * 7) & 255);
        rgb16[i] = (uint16_t)(i * 331u);
    }
    char err[512];
    for (int i = 0; i < IW * IH * 3; i++) {
        rgb[i] = (uint8_t)(128 + 60 * sin(i * 0.01)); /* smooth: JPEG q100 keeps it within a few codes */
    }
    assert_int_equal(tdc_png_write(png8, rgb, IW, IH, 8, IW * 3, err, sizeof err), 0);
    assert_int_equal(tdc_png_write(png16, rgb16, IW, IH, 16, IW * 3, err, sizeof err), 0);
    write_jpeg(jpg, rgb, IW, IH);
    tdc_image_t im;
    assert_int_equal(tdc_image_read(png8, &im, err, sizeof err), 0);
    assert_int_equal(im.bits, 8);
    assert_memory_equal(im.data, rgb, sizeof rgb);
    tdc_png_free(&im);
    assert_int_equal(tdc_image_read(png16, &im, err, sizeof err), 0);
    assert_int_equal(im.bits, 16);
    assert_memory_equal(im.data, rgb16, sizeof rgb16);
    tdc_png_free(&im);
    assert_int_equal(tdc_image_read(jpg, &im, err, sizeof err), 0);
    assert_int_equal(im.width, IW);
    assert_int_equal(im.height, IH);
    int worst = 0;
    for (int i = 0; i < IW * IH * 3; i++) {
        int d = abs((int)((uint8_t *)im.data)[i] - rgb[i]);
        worst = d > worst ? d : worst;
    }
    assert_true(worst <= 6);
    tdc_png_free(&im);
    /* a JPEG cut in half: an error, not a grey-padded image */
    FILE *f = fopen(jpg, "rb"), *g = fopen(trunc, "wb");
    uint8_t buf[65536];
    size_t n = fread(buf, 1, sizeof buf, f);
    fwrite(buf, 1, n / 2, g);
    fclose(f);
    fclose(g);
    g = fopen(empty, "wb");
    fclose(g);
    g = fopen(junk, "wb");
    fputs("\xFF\xD8\xFFgarbage that is no JPEG", g);
    fclose(g);
    const char *bad[] = {trunc, empty, junk, "/nonexistent/x.png"};
    const char *what[] = {"corrupt JPEG", "empty file", "corrupt JPEG", "cannot open"};
    tdc_scene_params_t p = screen(16, 16, 0, 0);
    for (int i = 0; i < 4; i++) {
        err[0] = 0;
        assert_null(tdc_image_source_open(bad[i], &p, NULL, err, sizeof err));
        printf("%s -> %s\n", bad[i], err);
        assert_non_null(strstr(err, bad[i]));
        assert_non_null(strstr(err, what[i]));
        assert_null(strchr(err, '\n'));
    }
    /* zero sizes and motion out of range */
    double px[3] = {0.5, 0.5, 0.5};
    assert_null(tdc_image_source_from_linear(px, 0, 1, &p, NULL, err, sizeof err));
    assert_non_null(strstr(err, "image size 0x1"));
    tdc_scene_params_t p0 = screen(0, 16, 0, 0);
    assert_null(tdc_image_source_from_linear(px, 1, 1, &p0, NULL, err, sizeof err));
    tdc_image_motion_t m;
    tdc_image_motion_default(&m);
    m.zoom = 0.0;
    assert_null(tdc_image_source_from_linear(px, 1, 1, &p, &m, err, sizeof err));
    assert_non_null(strstr(err, "zoom 0"));
    tdc_source_t *s = tdc_image_source_open(png16, &p, NULL, err, sizeof err);
    assert_non_null(s);
    s->destroy(s);
    const char *files[] = {png8, png16, jpg, trunc, empty, junk};
    for (int i = 0; i < 6; i++) {
        unlink(files[i]);
    }
    rmdir(dir);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_constant_image),         cmocka_unit_test(test_aligned_and_box_means),
    cmocka_unit_test(test_exact_against_clipping), cmocka_unit_test(test_samples_and_mvs),
    cmocka_unit_test(test_read_and_bad_input),
)
