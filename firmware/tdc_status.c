/*
 * tdc_status.c - names and one-line texts of tdc_status_t (tdc_status.h).
 * One switch per function, no default: -Wall (-Wswitch) fails the build
 * when a code is added to the enum without its name and text here.
 */
#include "tdc_status.h"

const char *tdc_status_name(tdc_status_t st)
{
    switch (st) {
    case TDC_OK: return "TDC_OK";
    case TDC_ERR_ARG: return "TDC_ERR_ARG";
    case TDC_ERR_SIZE: return "TDC_ERR_SIZE";
    case TDC_ERR_REFRESH_LOW: return "TDC_ERR_REFRESH_LOW";
    case TDC_ERR_STATE: return "TDC_ERR_STATE";
    case TDC_ERR_RATIO: return "TDC_ERR_RATIO";
    case TDC_ERR_PANEL: return "TDC_ERR_PANEL";
    case TDC_ERR_FRAME: return "TDC_ERR_FRAME";
    case TDC_ERR_LAYER: return "TDC_ERR_LAYER";
    case TDC_ERR_STALL: return "TDC_ERR_STALL";
    case TDC_ERR_IMAGE_SHORT: return "TDC_ERR_IMAGE_SHORT";
    case TDC_ERR_IMAGE_MAGIC: return "TDC_ERR_IMAGE_MAGIC";
    case TDC_ERR_IMAGE_HEADER: return "TDC_ERR_IMAGE_HEADER";
    case TDC_ERR_IMAGE_SIZE: return "TDC_ERR_IMAGE_SIZE";
    case TDC_ERR_IMAGE_CRC: return "TDC_ERR_IMAGE_CRC";
    case TDC_ERR_IMAGE_BOARD: return "TDC_ERR_IMAGE_BOARD";
    case TDC_ERR_IMAGE_TOO_BIG: return "TDC_ERR_IMAGE_TOO_BIG";
    }
    return "TDC_ERR_?";
}

const char *tdc_status_text(tdc_status_t st)
{
    switch (st) {
    case TDC_OK: return "ok";
    case TDC_ERR_ARG: return "null pointer or out-of-range argument";
    case TDC_ERR_SIZE: return "dimensions exceed the compiled buffers or the arena is too small";
    case TDC_ERR_REFRESH_LOW: return "refresh rate below the minimum for reduced frames";
    case TDC_ERR_STATE: return "call out of sequence";
    case TDC_ERR_RATIO: return "reduction ratio outside [1/4, 1]";
    case TDC_ERR_PANEL: return "panel profile lacks what the stage needs";
    case TDC_ERR_FRAME: return "frame out of sequence";
    case TDC_ERR_LAYER: return "layer not kept by the stage or of another size";
    case TDC_ERR_STALL: return "request refused (endpoint stalled)";
    /* The image texts are what tdc-usb prints (tests/usb, tests/vm match them). */
    case TDC_ERR_IMAGE_SHORT: return "shorter than the 48-byte image header";
    case TDC_ERR_IMAGE_MAGIC: return "not a tdc firmware image (bad magic)";
    case TDC_ERR_IMAGE_HEADER: return "unknown image header version or length";
    case TDC_ERR_IMAGE_SIZE: return "image size does not match the header's payload length";
    case TDC_ERR_IMAGE_CRC: return "payload CRC-32 does not match the header";
    case TDC_ERR_IMAGE_BOARD: return "image was built for another board";
    case TDC_ERR_IMAGE_TOO_BIG: return "image larger than the board's flash slot";
    }
    return "unknown status";
}
