/* tdc_png.c - PNG in/out through libpng (see tdc_png.h). */
#include "tdc_png.h"

#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* libpng's own messages would be a second line beside the tool's one
 * (docs/tools.md): errors only longjmp, warnings are dropped. */
static void png_quiet_error(png_structp png, png_const_charp msg)
{
    (void)msg;
    png_longjmp(png, 1);
}

static void png_quiet_warning(png_structp png, png_const_charp msg)
{
    (void)png, (void)msg;
}

FILE *tdc_png_open_sig(const char *path, unsigned char sig[8], size_t *got, char *err, size_t errlen)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return NULL;
    }
    *got = fread(sig, 1, 8, f);
    if (*got != 8 && ferror(f)) {
        snprintf(err, errlen, "%s: cannot read: %s", path, strerror(errno));
        fclose(f);
        return NULL;
    }
    return f;
}

int tdc_png_read(const char *path, tdc_image_t *img, char *err, size_t errlen)
{
    memset(img, 0, sizeof *img);
    unsigned char sig[8];
    size_t got;
    FILE *f = tdc_png_open_sig(path, sig, &got, err, errlen);
    if (!f) {
        return -1;
    }
    if (got != 8 || png_sig_cmp(sig, 0, 8)) {
        snprintf(err, errlen, "%s: not a PNG file", path);
        fclose(f);
        return -1;
    }
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, png_quiet_error, png_quiet_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    /* volatile: they change between setjmp and a longjmp from libpng, so the
     * error path must see their current values (issue 19: it freed the
     * stale NULLs and leaked the buffers of a truncated PNG). */
    png_bytep *volatile rows = NULL;
    void *volatile data = NULL;
    if (!png || !info) {
        snprintf(err, errlen, "%s: out of memory", path);
        fclose(f);
        return -1;
    }
    if (setjmp(png_jmpbuf(png))) {
        snprintf(err, errlen, "%s: corrupt or truncated PNG", path);
        png_destroy_read_struct(&png, &info, NULL);
        free(rows);
        free(data);
        fclose(f);
        return -1;
    }
    png_init_io(png, f);
    png_set_sig_bytes(png, 8);
    png_read_info(png, info);
    int w = (int)png_get_image_width(png, info), h = (int)png_get_image_height(png, info);
    int depth = png_get_bit_depth(png, info), ct = png_get_color_type(png, info);
    if (w <= 0 || h <= 0 || w > 16384 || h > 16384) {
        snprintf(err, errlen, "%s: unsupported size %dx%d (1..16384)", path, w, h);
        png_destroy_read_struct(&png, &info, NULL);
        fclose(f);
        return -1;
    }
    /* A header may claim any size; the file must be able to hold it.
     * Deflate compresses at most 1032:1, so the filtered rows (one filter
     * byte each) cannot exceed 1032 x the file's size: a 69-byte file
     * claiming 16384 x 16384 x 48 bits is refused before 1.6 GB are
     * allocated (issue 19). */
    {
        const uint64_t raw = (uint64_t)h * ((uint64_t)png_get_rowbytes(png, info) + 1u);
        long here = ftell(f);
        uint64_t fsize = 0;
        if (here >= 0 && fseek(f, 0, SEEK_END) == 0) {
            long end = ftell(f);
            fsize = end > 0 ? (uint64_t)end : 0;
            fseek(f, here, SEEK_SET);
        }
        if (fsize && raw > fsize * 1032u + 4096u) {
            snprintf(err, errlen,
                     "%s: header claims %dx%d at %d bits (%llu bytes of rows) but the file has only %llu bytes", path,
                     w, h, depth, (unsigned long long)raw, (unsigned long long)fsize);
            png_destroy_read_struct(&png, &info, NULL);
            fclose(f);
            return -1;
        }
    }
    if (ct == PNG_COLOR_TYPE_PALETTE) {
        png_set_palette_to_rgb(png);
    }
    if (ct == PNG_COLOR_TYPE_GRAY || ct == PNG_COLOR_TYPE_GRAY_ALPHA) {
        if (depth < 8) {
            png_set_expand_gray_1_2_4_to_8(png);
        }
        png_set_gray_to_rgb(png);
    }
    if (png_get_valid(png, info, PNG_INFO_tRNS)) {
        png_set_tRNS_to_alpha(png);
    }
    png_set_strip_alpha(png);
    if (depth == 16) {
        png_set_swap(png); /* host (little-endian) order for uint16_t */
    }
    png_read_update_info(png, info);
    int bits = depth == 16 ? 16 : 8;
    size_t rowbytes = png_get_rowbytes(png, info);
    if (rowbytes != (size_t)w * 3u * (size_t)(bits / 8)) {
        snprintf(err, errlen, "%s: unexpected row layout", path);
        png_destroy_read_struct(&png, &info, NULL);
        fclose(f);
        return -1;
    }
    data = malloc(rowbytes * (size_t)h);
    rows = malloc(sizeof(png_bytep) * (size_t)h);
    if (!data || !rows) {
        snprintf(err, errlen, "%s: out of memory", path);
        png_destroy_read_struct(&png, &info, NULL);
        free(data);
        free(rows);
        fclose(f);
        return -1;
    }
    for (int y = 0; y < h; y++) {
        rows[y] = (png_bytep)data + rowbytes * (size_t)y;
    }
    png_read_image(png, rows);
    png_read_end(png, NULL);
    png_destroy_read_struct(&png, &info, NULL);
    free(rows);
    rows = NULL;
    fclose(f);
    img->width = w;
    img->height = h;
    img->bits = bits;
    img->data = data;
    return 0;
}

int tdc_png_write(const char *path, const void *data, int width, int height, int bits, size_t stride_samples, char *err,
                  size_t errlen)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot create: %s", path, strerror(errno));
        return -1;
    }
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info || setjmp(png_jmpbuf(png))) {
        snprintf(err, errlen, "%s: write failed", path);
        png_destroy_write_struct(&png, &info);
        fclose(f);
        return -1;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, bits, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, 3);
    png_write_info(png, info);
    if (bits == 16) {
        png_set_swap(png);
    }
    size_t bps = (size_t)bits / 8u;
    for (int y = 0; y < height; y++) {
        png_write_row(png, (png_const_bytep)data + (size_t)y * stride_samples * bps);
    }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    if (fclose(f) != 0) {
        snprintf(err, errlen, "%s: write failed: %s", path, strerror(errno));
        return -1;
    }
    return 0;
}

void tdc_png_to8(tdc_image_t *img)
{
    if (img->bits != 16) {
        return;
    }
    const uint16_t *s = img->data;
    uint8_t *d = img->data;
    size_t n = (size_t)img->width * (size_t)img->height * 3u;
    for (size_t i = 0; i < n; i++) {
        d[i] = (uint8_t)(((uint32_t)s[i] * 255u + 32767u) / 65535u);
    }
    img->bits = 8;
}

void tdc_png_free(tdc_image_t *img)
{
    free(img->data);
    img->data = NULL;
}
