/* tdc_link_file.c - .tdcs stream files (see tdc_link_file.h). */
#include "link/tdc_link_file.h"

#include <errno.h>
#include <string.h>

static int open_mode(tdc_link_file_t *lf, const char *path, const char *mode, int writing)
{
    memset(lf, 0, sizeof *lf);
    snprintf(lf->path, sizeof lf->path, "%s", path);
    lf->f = fopen(path, mode);
    if (!lf->f) {
        fprintf(stderr, "tdcs: cannot open '%s' for %s: %s\n", path, writing ? "writing" : "reading", strerror(errno));
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
        fprintf(stderr, "tdcs: write to '%s' failed: %s\n", lf->path, strerror(errno));
        return -1;
    }
    lf->bytes += n;
    lf->packets++;
    return 0;
}

long tdc_link_file_read_packet(tdc_link_file_t *lf, uint8_t *buf, size_t cap, tdc_link_header_fields_t *fields,
                               uint32_t *payload_len)
{
    if (!lf->f || lf->writing || cap < TDC_LINK_HEADER_BYTES) {
        return -1;
    }
    size_t got = fread(buf, 1, TDC_LINK_HEADER_BYTES, lf->f);
    if (got == 0 && feof(lf->f)) {
        return 0;
    }
    if (got != TDC_LINK_HEADER_BYTES) {
        fprintf(stderr, "tdcs: '%s': truncated header at byte %llu\n", lf->path, (unsigned long long)lf->bytes);
        return -1;
    }
    uint32_t crc;
    if (!tdc_link_parse_header(buf, fields, payload_len, &crc)) {
        fprintf(stderr, "tdcs: '%s': bad magic or header CRC at byte %llu\n", lf->path, (unsigned long long)lf->bytes);
        return -1;
    }
    if ((size_t)*payload_len > cap - TDC_LINK_HEADER_BYTES) {
        fprintf(stderr, "tdcs: '%s': packet of %u payload bytes at byte %llu does not fit %zu\n", lf->path,
                (unsigned)*payload_len, (unsigned long long)lf->bytes, cap);
        return -1;
    }
    if (fread(buf + TDC_LINK_HEADER_BYTES, 1, *payload_len, lf->f) != *payload_len) {
        fprintf(stderr, "tdcs: '%s': truncated payload at byte %llu\n", lf->path, (unsigned long long)lf->bytes);
        return -1;
    }
    const long total = (long)(TDC_LINK_HEADER_BYTES + *payload_len);
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
        fprintf(stderr, "tdcs: read from '%s' failed: %s\n", lf->path, strerror(errno));
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
        fprintf(stderr, "tdcs: flush of '%s' failed: %s\n", lf->path, strerror(errno));
        rc = -1;
    }
    if (fclose(lf->f) != 0) {
        fprintf(stderr, "tdcs: close of '%s' failed: %s\n", lf->path, strerror(errno));
        rc = -1;
    }
    lf->f = NULL;
    return rc;
}
