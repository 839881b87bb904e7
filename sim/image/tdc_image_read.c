/* tdc_image_read.c - PNG (libpng, via tdc_png) or JPEG (libjpeg) input. */
#include "image/tdc_image_read.h"

#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <jpeglib.h>

typedef struct {
    struct jpeg_error_mgr mgr;
    jmp_buf jb;
    char msg[JMSG_LENGTH_MAX];
    int warnings;
} jpeg_err_t;

static void jpeg_on_error(j_common_ptr c)
{
    jpeg_err_t *e = (jpeg_err_t *)c->err;
    (*c->err->format_message)(c, e->msg);
    longjmp(e->jb, 1);
}

/* Warnings (level -1) include "Premature end of JPEG file", after which
 * libjpeg pads the image: kept as an error by the caller. */
static void jpeg_on_message(j_common_ptr c, int level)
{
    jpeg_err_t *e = (jpeg_err_t *)c->err;
    if (level < 0 && e->warnings++ == 0) {
        (*c->err->format_message)(c, e->msg);
    }
}

static int read_jpeg(FILE *f, const char *path, tdc_image_t *img, char *err, size_t errlen)
{
    struct jpeg_decompress_struct d;
    jpeg_err_t e;
    memset(&e, 0, sizeof e);
    unsigned char *volatile data = NULL;
    d.err = jpeg_std_error(&e.mgr);
    e.mgr.error_exit = jpeg_on_error;
    e.mgr.emit_message = jpeg_on_message;
    if (setjmp(e.jb)) {
        snprintf(err, errlen, "%s: corrupt JPEG: %s", path, e.msg);
        jpeg_destroy_decompress(&d);
        free(data);
        return -1;
    }
    jpeg_create_decompress(&d);
    jpeg_stdio_src(&d, f);
    jpeg_read_header(&d, TRUE);
    d.out_color_space = JCS_RGB; /* gray and YCbCr converted by libjpeg; CMYK refused below */
    jpeg_start_decompress(&d);
    int w = (int)d.output_width, h = (int)d.output_height;
    if (w <= 0 || h <= 0 || w > 16384 || h > 16384 || d.output_components != 3) {
        snprintf(err, errlen, "%s: unsupported JPEG %dx%d with %d components (1..16384, RGB or gray)", path, w, h,
                 d.output_components);
        jpeg_destroy_decompress(&d);
        return -1;
    }
    data = malloc((size_t)w * h * 3);
    if (!data) {
        snprintf(err, errlen, "%s: out of memory for %dx%d", path, w, h);
        jpeg_destroy_decompress(&d);
        return -1;
    }
    while (d.output_scanline < d.output_height) {
        JSAMPROW row = data + (size_t)d.output_scanline * w * 3;
        jpeg_read_scanlines(&d, &row, 1);
    }
    jpeg_finish_decompress(&d);
    jpeg_destroy_decompress(&d);
    if (e.warnings) {
        snprintf(err, errlen, "%s: corrupt JPEG: %s", path, e.msg);
        free(data);
        return -1;
    }
    img->width = w;
    img->height = h;
    img->bits = 8;
    img->data = data;
    return 0;
}

int tdc_image_read(const char *path, tdc_image_t *img, char *err, size_t errlen)
{
    memset(img, 0, sizeof *img);
    unsigned char sig[8];
    size_t n;
    FILE *f = tdc_png_open_sig(path, sig, &n, err, errlen);
    if (!f) {
        return -1;
    }
    if (n == 0) {
        snprintf(err, errlen, "%s: empty file", path);
        fclose(f);
        return -1;
    }
    if (n >= 3 && sig[0] == 0xFF && sig[1] == 0xD8 && sig[2] == 0xFF) {
        rewind(f);
        int rc = read_jpeg(f, path, img, err, errlen);
        fclose(f);
        return rc;
    }
    fclose(f);
    static const unsigned char png_sig[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    if (n == 8 && memcmp(sig, png_sig, 8) == 0) {
        return tdc_png_read(path, img, err, errlen);
    }
    snprintf(err, errlen, "%s: not a PNG or JPEG file", path);
    return -1;
}
