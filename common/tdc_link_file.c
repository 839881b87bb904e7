/* tdc_link_file.c - .tdcs stream files (see tdc_link_file.h). */
#include "tdc_link_file.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* The reason of the last failure, for the caller's one message line. */
#define LF_ERR(lf, ...) snprintf((lf)->err, sizeof (lf)->err, __VA_ARGS__)

static int open_mode(tdc_link_file_t *lf, const char *path, const char *mode, int writing)
{
    memset(lf, 0, sizeof *lf);
    snprintf(lf->path, sizeof lf->path, "%s", path);
    lf->f = fopen(path, mode);
    struct stat st; /* a folder opens for reading on Linux; every read then fails */
    if (lf->f && !writing && fstat(fileno(lf->f), &st) == 0 && S_ISDIR(st.st_mode)) {
        fclose(lf->f);
        lf->f = NULL;
        errno = EISDIR;
    }
    if (!lf->f) {
        LF_ERR(lf, "cannot open for %s: %s", writing ? "writing" : "reading", strerror(errno));
        return -1;
    }
    lf->writing = writing;
    return 0;
}

int tdc_link_file_create(tdc_link_file_t *lf, const char *path)
{
    return open_mode(lf, path, "wb", 1);
}

int tdc_link_file_open(tdc_link_file_t *lf, const char *path)
{
    return open_mode(lf, path, "rb", 0);
}

int tdc_link_file_write(tdc_link_file_t *lf, const uint8_t *packet, size_t n)
{
    if (!lf->f || !lf->writing) {
        return -1;
    }
    if (fwrite(packet, 1, n, lf->f) != n) {
        LF_ERR(lf, "write failed: %s", strerror(errno));
        return -1;
    }
    lf->bytes += n;
    lf->packets++;
    return 0;
}

long tdc_link_file_read_packet(tdc_link_file_t *lf, uint8_t *buf, size_t cap, tdc_link_header_t *hdr)
{
    if (!lf->f || lf->writing || cap < TDC_LINK_HEADER_BYTES) {
        return -1;
    }
    size_t got = fread(buf, 1, TDC_LINK_HEADER_BYTES, lf->f);
    if (got == 0 && feof(lf->f)) {
        return 0;
    }
    if (got != TDC_LINK_HEADER_BYTES) {
        LF_ERR(lf, "truncated header at byte %llu", (unsigned long long)lf->bytes);
        return -1;
    }
    const tdc_link_err_t e = tdc_link_header_unpack(buf, hdr);
    if (e != TDC_LINK_OK) {
        LF_ERR(lf, "bad %s at byte %llu", e == TDC_LINK_ERR_MAGIC ? "magic" : "header CRC", (unsigned long long)lf->bytes);
        return -1;
    }
    if ((size_t)hdr->payload_len > cap - TDC_LINK_HEADER_BYTES) {
        LF_ERR(lf, "packet of %u payload bytes at byte %llu does not fit %zu", (unsigned)hdr->payload_len,
               (unsigned long long)lf->bytes, cap);
        return -1;
    }
    if (fread(buf + TDC_LINK_HEADER_BYTES, 1, hdr->payload_len, lf->f) != hdr->payload_len) {
        LF_ERR(lf, "truncated payload at byte %llu", (unsigned long long)lf->bytes);
        return -1;
    }
    const long total = (long)(TDC_LINK_HEADER_BYTES + hdr->payload_len);
    lf->bytes += (uint64_t)total;
    lf->packets++;
    return total;
}

long tdc_link_file_read_raw(tdc_link_file_t *lf, uint8_t *buf, size_t cap)
{
    if (!lf->f || lf->writing) {
        return -1;
    }
    size_t got = fread(buf, 1, cap, lf->f);
    if (got == 0 && ferror(lf->f)) {
        LF_ERR(lf, "read failed: %s", strerror(errno));
        return -1;
    }
    lf->bytes += got;
    return (long)got;
}

int tdc_link_file_close(tdc_link_file_t *lf)
{
    if (!lf->f) {
        return -1;
    }
    int rc = 0;
    if (lf->writing && fflush(lf->f) != 0) {
        LF_ERR(lf, "flush failed: %s", strerror(errno));
        rc = -1;
    }
    if (fclose(lf->f) != 0) {
        if (rc == 0) { /* else the flush's reason stands */
            LF_ERR(lf, "close failed: %s", strerror(errno));
        }
        rc = -1;
    }
    lf->f = NULL;
    return rc;
}

int tdc_link_file_check(const char *path, FILE *log, int verbose, tdc_link_file_summary_t *sum)
{
    memset(sum, 0, sizeof *sum);
    tdc_link_file_t lf;
    if (tdc_link_file_open(&lf, path) < 0) {
        snprintf(sum->err, sizeof sum->err, "%s", lf.err);
        return -2;
    }
    uint8_t first[TDC_LINK_HEADER_BYTES + TDC_LINK_STREAM_HEADER_BYTES];
    tdc_link_header_t f;
    if (fread(first, 1, sizeof first, lf.f) != sizeof first || tdc_link_header_unpack(first, &f) != TDC_LINK_OK ||
        f.kind != TDC_LINK_KIND_STREAM || f.payload_len != TDC_LINK_STREAM_HEADER_BYTES) {
        snprintf(sum->err, sizeof sum->err, "not a .tdcs stream: %s",
                 ferror(lf.f) ? strerror(errno) : "it does not start with a valid STREAM packet");
        tdc_link_file_close(&lf);
        return -1;
    }
    tdc_link_stream_info_t in;
    tdc_link_stream_unpack(first + TDC_LINK_HEADER_BYTES, &in);
    sum->stream = in;
    sum->stream_id = f.stream_id;
    rewind(lf.f);
    if (in.width == 0 || in.height == 0 || in.eyes < 1 || in.eyes > 2 ||
        (uint32_t)in.width * in.height > TDC_LINK_MAX_PIXELS || in.width > TDC_LINK_MAX_WIDTH ||
        in.height > TDC_LINK_MAX_HEIGHT) {
        snprintf(sum->err, sizeof sum->err, "stream size %ux%u x %u eyes is not supported", in.width, in.height,
                 in.eyes);
        tdc_link_file_close(&lf);
        return -1;
    }
    const size_t w = in.width, h = in.height;
    tdc_link_buffers_t b;
    memset(&b, 0, sizeof b);
    b.staging_bytes = TDC_LINK_STAGING_BYTES(w, h);
    if ((in.flags & TDC_LINK_STREAM_LAYERS) && TDC_LINK_STAGING_LAYERS_BYTES(w, h) > b.staging_bytes)
        b.staging_bytes = TDC_LINK_STAGING_LAYERS_BYTES(w, h); /* layered subframes: up to 7 B/px */
    tdc_layer_frame_t lay[2];
    memset(lay, 0, sizeof lay);
    b.full_stride = (uint32_t)(w * 3u);
    b.reduced_bytes = TDC_LINK_FRAME_BYTES(w, h);
    uint8_t *mem[16 + 2 * (2 * TDC_LAYER_MAX + 1)];
    size_t nmem = 0;
#define TDCS_ALLOC(dst, type, bytes)     \
    do {                                 \
        mem[nmem] = calloc(1, (bytes));  \
        (dst) = (type)(void *)mem[nmem]; \
        nmem++;                          \
    } while (0)
    TDCS_ALLOC(b.staging, uint8_t *, b.staging_bytes);
    for (unsigned e = 0; e < in.eyes; e++) {
        TDCS_ALLOC(b.full[e], uint8_t *, TDC_LINK_FRAME_BYTES(w, h));
        TDCS_ALLOC(b.reduced[e], uint8_t *, TDC_LINK_FRAME_BYTES(w, h));
        TDCS_ALLOC(b.subframe[e], uint8_t *, TDC_LINK_SUBFRAME_BYTES(w, h));
        TDCS_ALLOC(b.motion[e], int16_t *, TDC_LINK_MOTION_COUNT(w, h) * 2u);
        TDCS_ALLOC(b.sample_motion[e], int16_t *, TDC_LINK_SAMPLE_MOTION_COUNT(w, h) * 2u);
        TDCS_ALLOC(b.pattern[e], uint8_t *, TDC_PATTERN_BYTES(w, h));
        if (in.flags & TDC_LINK_STREAM_LAYERS) { /* every layer type and the falloff plane */
            for (uint32_t t = 1; t <= TDC_LAYER_MAX; t++) {
                TDCS_ALLOC(lay[e].value[t - 1], uint8_t *, TDC_TILE_COUNT(w, h) * tdc_layer_value_bytes(t));
                TDCS_ALLOC(lay[e].mv[t - 1], int16_t *, TDC_TILE_COUNT(w, h) * 2u * sizeof(int16_t));
            }
            TDCS_ALLOC(lay[e].falloff, uint16_t *, TDC_TILE_COUNT(w, h) * sizeof(uint16_t));
            b.layers[e] = &lay[e];
        }
    }
#undef TDCS_ALLOC
    static uint8_t chunk[65536];
    int rc = 0;
    for (size_t i = 0; i < nmem; i++) {
        if (!mem[i]) {
            rc = -1;
        }
    }
    tdc_link_decoder_t *dec = rc == 0 ? calloc(1, sizeof *dec) : NULL;
    tdc_link_config_t cfg = {in.width, in.height, in.eyes};
    if (!dec || tdc_link_decoder_init(dec, &cfg, &b) != TDC_OK) {
        snprintf(sum->err, sizeof sum->err, "out of memory for a %ux%u decoder", in.width, in.height);
        rc = -1;
    }
    long got = 0;
    while (rc == 0 && (got = tdc_link_file_read_raw(&lf, chunk, sizeof chunk)) > 0) {
        size_t pos = 0;
        while (pos < (size_t)got || dec->ev_count) {
            tdc_link_event_t ev;
            pos += tdc_link_feed(dec, chunk + pos, (size_t)got - pos, &ev);
            if (ev.type == TDC_LINK_EV_ERROR && log) {
                fprintf(log, "error %-15s frame %u kind %s eye %u detail %u (at byte ~%llu)\n",
                        tdc_link_err_name((tdc_link_err_t)ev.error), ev.frame_index, tdc_link_kind_name(ev.kind),
                        ev.eye, ev.detail, (unsigned long long)(dec->cnt.bytes_in));
            } else if (ev.type == TDC_LINK_EV_PACKET && log && verbose) {
                fprintf(log, "packet %-8s frame %u eye %u %ux%u format %u flags %u payload %u\n",
                        tdc_link_kind_name(ev.kind), ev.frame_index, ev.eye, ev.width, ev.height, ev.format, ev.flags,
                        ev.detail);
            }
        }
    }
    if (got < 0) {
        snprintf(sum->err, sizeof sum->err, "%s", lf.err);
        rc = -2;
    }
    if (rc == 0 && dec) {
        /* End of file: a packet begun but not finished (a truncated file), or
         * bytes after the last packet, would only be reported by the next
         * packet's resync, which never comes; report them here (issue 19:
         * a file cut mid-packet passed as clean). */
        const uint64_t before = dec->cnt.garbage_bytes;
        tdc_link_decoder_resync(dec);
        const uint64_t cut = dec->cnt.garbage_bytes - before;
        if (dec->garbage_run) {
            if (log) {
                fprintf(log, "error %-15s %u bytes at the end of the file (%s)\n", cut ? "TRUNCATED" : "GARBAGE",
                        dec->garbage_run, cut ? "it ends inside a packet" : "after the last packet");
            }
            sum->truncated_bytes = dec->garbage_run;
            rc = 1;
        }
    }
    if (dec) {
        sum->counters = dec->cnt;
        sum->bytes = dec->cnt.bytes_in;
        if (rc == 0) {
            for (int e = 1; e < TDC_LINK_ERR_COUNT; e++) {
                rc |= dec->cnt.errors[e] != 0;
            }
        }
    }
    free(dec);
    for (size_t i = 0; i < nmem; i++) {
        free(mem[i]);
    }
    tdc_link_file_close(&lf);
    return rc;
}
