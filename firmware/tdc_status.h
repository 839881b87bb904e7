/*
 * tdc_status.h - the one status vocabulary of the firmware.
 *
 * Every fallible firmware function returns a tdc_status_t: the stages (TRM,
 * tile assembly, LCD inverse, link decoder init), the USB protocol and the
 * firmware-image checks.  TDC_OK is 0, every error is negative, and no two
 * subsystems share a value, so a code printed anywhere names one cause.
 * tdc_status_name() gives the enumerator's own name ("TDC_ERR_STATE", the
 * libusb_error_name() convention: greppable), tdc_status_text() one line
 * saying what went wrong (what the tools print after the name).
 *
 * Deliberately not in this enum:
 *   - tdc_link_err_t (tdc_link.h): the reason a link packet was rejected.
 *     It is not a return value but a dense, positive counter index (one
 *     counter per reason, 0 = none) carried in a decoder event.
 *   - tdc_dfu_status_t (tdc_usbproto.h): USB DFU 1.1 bStatus values, fixed
 *     by the DFU specification and sent on the wire.
 *
 * TDC_MUST_CHECK marks every function returning a status: ignoring one is a
 * compile error under the project's -Werror (GCC/clang warn_unused_result;
 * GCC does not accept a (void) cast as handling it, which is the point).
 */
#ifndef TDC_STATUS_H
#define TDC_STATUS_H

#if defined(__GNUC__) || defined(__clang__)
#define TDC_MUST_CHECK __attribute__((warn_unused_result))
#else
#define TDC_MUST_CHECK
#endif

typedef enum {
    TDC_OK = 0,

    /* Stages (-1 .. -19). */
    TDC_ERR_ARG = -1,         /* null pointer or out-of-range argument */
    TDC_ERR_SIZE = -2,        /* dimensions exceed the compiled buffers, or the arena is too small */
    TDC_ERR_REFRESH_LOW = -3, /* TRM requested below the minimum refresh */
    TDC_ERR_STATE = -4,       /* call out of sequence (e.g. reduced before full) */
    TDC_ERR_RATIO = -5,       /* reduction ratio outside [1/4, 1] */
    TDC_ERR_PANEL = -6,       /* panel profile lacks what the stage needs */
    TDC_ERR_FRAME = -7,       /* tile assembly: ingest/assemble for a frame out of sequence */
    TDC_ERR_LAYER = -8,       /* layered assembly: a layer the stage does not keep, or its size disagrees */

    /* USB protocol (-20 .. -29). */
    TDC_ERR_STALL = -20, /* request refused: the endpoint is stalled (counted) */

    /* Firmware images (-30 .. -39): tdc_image_check(). */
    TDC_ERR_IMAGE_SHORT = -30,  /* fewer bytes than an image header */
    TDC_ERR_IMAGE_MAGIC = -31,  /* not a tdc image */
    TDC_ERR_IMAGE_HEADER = -32, /* unknown header version or length */
    TDC_ERR_IMAGE_SIZE = -33,   /* header payload length != bytes present */
    TDC_ERR_IMAGE_CRC = -34,    /* payload CRC mismatch */
    TDC_ERR_IMAGE_BOARD = -35,  /* built for another board */
    TDC_ERR_IMAGE_TOO_BIG = -36 /* does not fit the flash slot */
} tdc_status_t;

/* "TDC_ERR_STATE"; "TDC_ERR_?" for a value outside the enum. */
const char *tdc_status_name(tdc_status_t st);

/* One line without a trailing period: "call out of sequence". */
const char *tdc_status_text(tdc_status_t st);

#endif /* TDC_STATUS_H */
