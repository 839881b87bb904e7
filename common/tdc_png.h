/*
 * tdc_png.h - PNG in/out for host programs (libpng).  Images are RGB
 * interleaved, 8 bits (uint8_t) or 16 bits (uint16_t) per channel.
 */
#ifndef TDC_PNG_H
#define TDC_PNG_H

#include <stddef.h>
#include <stdio.h>
#include <stdint.h>

typedef struct {
    int width, height;
    int bits;   /* 8 or 16: bits per channel of `data` */
    void *data; /* width*height*3 samples, malloc'd: free with tdc_png_free */
} tdc_image_t;

/*
 * Reads any PNG (gray, gray+alpha, palette, RGB, RGBA; 1..16 bits) and
 * converts it to RGB with 8 bits (source depth <= 8) or 16 bits per channel;
 * alpha is dropped.  Returns 0, or -1 with a message in err (errlen bytes).
 */
int tdc_png_read(const char *path, tdc_image_t *img, char *err, size_t errlen);

/* Opens path and reads its first bytes (up to 8, *got of them) into sig,
 * for a reader that tells formats apart by them: the file, positioned after
 * them; NULL with one line in err when it cannot be opened or read (a
 * folder opens, and reading it fails with EISDIR). */
FILE *tdc_png_open_sig(const char *path, unsigned char sig[8], size_t *got, char *err, size_t errlen);

/* Writes RGB888 (bits = 8) or RGB16 (bits = 16) rows `stride` samples apart.
 * Returns 0, or -1 with a message in err. */
int tdc_png_write(const char *path, const void *data, int width, int height, int bits, size_t stride_samples, char *err,
                  size_t errlen);

/* Converts a 16-bit image to 8 bits in place (round(v * 255 / 65535)). */
void tdc_png_to8(tdc_image_t *img);

void tdc_png_free(tdc_image_t *img);

#endif
