/*
 * tdc_link_file.h - .tdcs stream files: the link byte stream exactly as it
 * goes over the wire (packets back to back, normally starting with a STREAM
 * packet), so a file can be fed to the decoder or sent to a board verbatim.
 * The renderer and the simulator write them, hosttools and tests read them.
 *
 * Reading walks packet by packet and checks magic and header CRC; it does
 * not skip garbage (use the firmware decoder for damaged streams).
 */
#ifndef TDC_LINK_FILE_H
#define TDC_LINK_FILE_H

#include <stdint.h>
#include <stdio.h>

#include "tdc_link_encode.h"

typedef struct {
    FILE *f;
    int writing;
    uint64_t bytes;   /* bytes written / read so far */
    uint32_t packets; /* packets written / read */
    char path[256];
    char err[256]; /* why the last call failed (no path: the caller prints the message line) */
} tdc_link_file_t;

/* Open for writing (truncates) / reading.  0 on success, -1 with the reason
 * in lf->err otherwise (a folder is refused for reading: EISDIR).  Nothing
 * here prints; the program prints one line with the reason. */
int tdc_link_file_create(tdc_link_file_t *lf, const char *path);
int tdc_link_file_open(tdc_link_file_t *lf, const char *path);

/* Appends n bytes (one or more complete packets).  0 / -1 (lf->err). */
int tdc_link_file_write(tdc_link_file_t *lf, const uint8_t *packet, size_t n);

/* Reads the next packet into buf (cap bytes): returns its total size,
 * 0 at a clean end of file, -1 on a truncated/invalid packet or if it does
 * not fit (reason in lf->err).  *hdr: the unpacked header. */
long tdc_link_file_read_packet(tdc_link_file_t *lf, uint8_t *buf, size_t cap, tdc_link_header_t *hdr);

/* Reads up to cap raw bytes (for feeding a decoder in chunks); returns the
 * count, 0 at end of file, -1 on error. */
long tdc_link_file_read_raw(tdc_link_file_t *lf, uint8_t *buf, size_t cap);

/* Flushes and closes; 0 / -1 (a write error surfaces here too). */
int tdc_link_file_close(tdc_link_file_t *lf);

/* Result of tdc_link_file_check(). */
typedef struct {
    tdc_link_stream_info_t stream; /* first stream header of the file */
    uint16_t stream_id;
    tdc_link_counters_t counters; /* of a decoder fed the whole file */
    uint64_t bytes;
    uint32_t truncated_bytes; /* bytes of an unfinished packet (or garbage) at the end of the file */
    char err[256];            /* why, when tdc_link_file_check() returned -1 or -2 */
} tdc_link_file_summary_t;

/* Decodes a whole .tdcs file with the firmware decoder, sized from the
 * file's first STREAM packet (buffers on the heap: host only).  Logs every
 * error event (and with verbose every accepted packet) to log (may be NULL).
 * Returns 0 if the stream decoded without an error event, 1 if there were
 * errors or the file ends inside a packet (truncated_bytes), -1 if it does
 * not start with a valid STREAM packet or its size is not supported (a
 * malformed input), -2 if the file cannot be opened or read (reason in
 * sum->err for both). */
int tdc_link_file_check(const char *path, FILE *log, int verbose, tdc_link_file_summary_t *sum);

#endif /* TDC_LINK_FILE_H */
