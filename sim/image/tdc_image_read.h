/*
 * tdc_image_read.h - reads a photograph (PNG through libpng, JPEG through
 * libjpeg) into RGB with 8 or 16 bits per channel, chosen by the file's
 * magic bytes, not its name.
 */
#ifndef TDC_IMAGE_READ_H
#define TDC_IMAGE_READ_H

#include <stddef.h>

#include "tdc_png.h"

/* Returns 0, or -1 with one line in err naming the file and what failed:
 * cannot open, empty, not PNG/JPEG, corrupt or truncated (any libjpeg
 * warning counts: a truncated JPEG is not silently padded with grey),
 * size 0 or above 16384 per side.  Free with tdc_png_free(). */
int tdc_image_read(const char *path, tdc_image_t *img, char *err, size_t errlen);

#endif
