/*
 * test_link_file.c - .tdcs stream files: written packet by packet, read
 * back packet by packet (same bytes and fields) and as raw chunks through
 * the decoder (same events as the in-memory stream); truncated and missing
 * files give an error, not a crash.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tdc_cmocka.h"

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "tdc_link_file.h"
#include "link/tdc_link_gen.h"
#include "test_link_util.h"

static lt_rig_t rig_mem, rig_file;
static uint8_t stream[1 << 18], buf[1 << 16];
static uint32_t scratch[32 * 24];

static void test_write_read_decode(void **state)
{
    (void)state;
    tdc_link_gen_opts_t o;
    memset(&o, 0, sizeof o);
    o.stream_id = 11;
    o.info.flags = TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_MOTION;
    o.info.r_num = 1;
    o.info.r_den = 2;
    o.info.width = 31;
    o.info.height = 21;
    o.info.eyes = 2;
    o.fmt = TDC_PIXFMT_YCBCR420;
    o.frames = 5;
    o.seed = 3;
    o.with_stream_header = 1;
    static tdc_link_gen_packet_t pk[64];
    uint32_t npk = 0;
    const size_t n = tdc_link_gen_stream(stream, sizeof stream, &o, (uint8_t *)scratch, sizeof scratch, pk, 64, &npk);
    assert_true(n > 0);

    char path[] = "/tmp/tdc_link_test_XXXXXX";
    const int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    tdc_link_file_t lf;
    assert_int_equal(tdc_link_file_create(&lf, path), 0);
    for (uint32_t i = 0; i < npk; i++) {
        assert_int_equal(tdc_link_file_write(&lf, stream + pk[i].offset, pk[i].size), 0);
    }
    assert_int_equal(lf.packets, npk);
    assert_int_equal(tdc_link_file_close(&lf), 0);

    /* Packet by packet. */
    assert_int_equal(tdc_link_file_open(&lf, path), 0);
    for (uint32_t i = 0; i < npk; i++) {
        tdc_link_header_t f;
        const long got = tdc_link_file_read_packet(&lf, buf, sizeof buf, &f);
        assert_int_equal(got, pk[i].size);
        assert_memory_equal(buf, stream + pk[i].offset, pk[i].size);
        assert_int_equal(f.kind, pk[i].kind);
        assert_int_equal(f.eye, pk[i].eye);
        assert_int_equal(f.frame_index, pk[i].frame);
        assert_int_equal(f.stream_id, 11);
        assert_int_equal(f.payload_len + TDC_LINK_HEADER_BYTES, pk[i].size);
    }
    tdc_link_header_t f;
    assert_int_equal(tdc_link_file_read_packet(&lf, buf, sizeof buf, &f), 0); /* clean end */
    assert_int_equal(tdc_link_file_close(&lf), 0);

    /* Raw chunks through the decoder == the in-memory stream. */
    assert_int_equal(lt_init(&rig_mem, 31, 21, 2), TDC_OK);
    lt_feed(&rig_mem, stream, n, 0, 0);
    assert_int_equal(lt_init(&rig_file, 31, 21, 2), TDC_OK);
    assert_int_equal(tdc_link_file_open(&lf, path), 0);
    long got;
    while ((got = tdc_link_file_read_raw(&lf, buf, 1000)) > 0) {
        lt_feed(&rig_file, buf, (size_t)got, 0, 0);
    }
    assert_int_equal(got, 0);
    assert_int_equal(lf.bytes, n);
    tdc_link_file_close(&lf);
    assert_int_equal(rig_file.nev, rig_mem.nev);
    assert_int_equal(rig_file.nev, npk);
    assert_memory_equal(rig_file.ev, rig_mem.ev, sizeof(tdc_link_event_t) * rig_mem.nev);
    assert_true(lt_hash_all(&rig_file) == lt_hash_all(&rig_mem));

    /* The whole-file check: clean, then with a corrupted byte. */
    tdc_link_file_summary_t sum;
    assert_int_equal(tdc_link_file_check(path, NULL, 0, &sum), 0);
    assert_int_equal(sum.counters.packets_ok, npk);
    assert_int_equal(sum.stream.width, 31);
    assert_int_equal(sum.stream_id, 11);
    assert_int_equal(sum.bytes, n);
    {
        FILE *fp = fopen(path, "r+b");
        assert_non_null(fp);
        fseek(fp, (long)pk[3].offset + 50, SEEK_SET);
        fputc(0x5A ^ stream[pk[3].offset + 50], fp);
        fclose(fp);
    }
    assert_int_equal(tdc_link_file_check(path, NULL, 0, &sum), 1);
    assert_int_equal(sum.counters.errors[TDC_LINK_ERR_CRC], 1);
    assert_int_equal(sum.counters.packets_ok, npk - 1);

    /* Truncated in the middle of a payload: an error, not a crash. */
    assert_int_equal(truncate(path, (off_t)(pk[2].offset + 40)), 0);
    assert_int_equal(tdc_link_file_open(&lf, path), 0);
    assert_int_equal(tdc_link_file_read_packet(&lf, buf, sizeof buf, &f), (long)pk[0].size);
    assert_int_equal(tdc_link_file_read_packet(&lf, buf, sizeof buf, &f), (long)pk[1].size);
    assert_int_equal(tdc_link_file_read_packet(&lf, buf, sizeof buf, &f), -1);
    tdc_link_file_close(&lf);
    /* The whole-file check of the cut file: not clean (issue 19: tdc-linkdump
     * passed a file cut mid-packet with exit 0), the cut packet's 40 bytes. */
    assert_int_equal(tdc_link_file_check(path, NULL, 0, &sum), 1);
    assert_int_equal(sum.truncated_bytes, 40);
    assert_int_equal(sum.counters.packets_ok, 2);
    /* A packet larger than the caller's buffer is refused. */
    assert_int_equal(tdc_link_file_open(&lf, path), 0);
    assert_int_equal(tdc_link_file_read_packet(&lf, buf, 40, &f), -1);
    tdc_link_file_close(&lf);
    unlink(path);
    assert_int_equal(tdc_link_file_open(&lf, "/nonexistent/dir/x.tdcs"), -1);
    assert_int_equal(tdc_link_file_create(&lf, "/nonexistent/dir/x.tdcs"), -1);
    assert_int_equal(tdc_link_file_check("/nonexistent/dir/x.tdcs", NULL, 0, &sum), -2); /* FILE, not INPUT */
    assert_int_equal(tdc_link_file_open(&lf, "."), -1); /* a folder opens on Linux: refused */
    assert_int_equal(tdc_link_file_check(".", NULL, 0, &sum), -2);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_write_read_decode),
)
