/*
 * test_usb_emul.c - tdc-usb against emulated boards (umockdev).
 *
 * Each test builds a fresh umockdev testbed with zero, one or two emulated
 * boards (tests/usb/tdc_usb_emul.c: the firmware's own protocol code behind
 * an emulated usbdevfs), then runs the real tdc-usb binary as a child with
 * LD_PRELOAD=libumockdev-preload.so.0, so the program, libusb and its Linux
 * backend are all unmodified.  A child that runs longer than CHILD_DEADLINE_S
 * is killed and the test fails: "no hang" is asserted, not hoped for.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "link/tdc_link_gen.h"
#include "tdc_link_encode.h"
#include "tdc_usb_emul.h"

#include "tdc_usb_run.h"

/* ------------------------------------------------------------------ */
static void test_no_device(void **state)
{
    (void)state;
    run_t r;
    run_tool(&r, (const char *[]){"list", NULL});
    expect(&r, 2, NULL, "no tdc board");
    run_tool(&r, (const char *[]){"info", NULL});
    expect(&r, 2, NULL, "no tdc board");
    run_tool(&r, (const char *[]){"--serial", "NOPE", "info", NULL});
    expect(&r, 2, NULL, "matching --bus/--address/--serial");
    /* local inputs are checked first: a bad file is named even without a board */
    run_tool(&r, (const char *[]){"stream", "/nonexistent/x.tdcs", NULL});
    expect(&r, 7, NULL, "cannot open /nonexistent/x.tdcs");
    char path[128];
    tmp_path(path, sizeof path, "garbage.img");
    write_file(path, (const uint8_t *)"not an image at all, but longer than the 48 header bytes", 56);
    run_tool(&r, (const char *[]){"flash", path, NULL});
    expect(&r, 8, NULL, "not a tdc firmware image");
}

static void test_list_and_info(void **state)
{
    (void)state;
    run_t r;
    run_tool(&r, (const char *[]){"list", NULL});
    expect(&r, 0, "bus 001 address 002 serial TDC-A board emul panel htc-vive fw 0.1.0", NULL);
    run_tool(&r, (const char *[]){"info", NULL});
    expect(&r, 0, "panel: htc-vive 2160x1200 @ 90.000 Hz", NULL);
    assert_non_null(strstr(r.out, "flash slot 65536 bytes"));
    assert_non_null(strstr(r.out, "link rx 16384 bytes"));
    assert_non_null(strstr(r.out, "serial TDC-A"));
}

static void test_two_devices(void **state)
{
    (void)state;
    run_t r;
    run_tool(&r, (const char *[]){"list", NULL});
    expect(&r, 0, "serial TDC-B", NULL);
    assert_non_null(strstr(r.out, "serial TDC-A"));
    run_tool(&r, (const char *[]){"info", NULL});
    expect(&r, 3, NULL, "2 tdc boards match");
    assert_non_null(strstr(r.err, "--serial"));
    run_tool(&r, (const char *[]){"--serial", "TDC-B", "info", NULL});
    expect(&r, 0, "address 003 serial TDC-B", NULL);
    run_tool(&r, (const char *[]){"--bus", "1", "--address", "2", "info", NULL});
    expect(&r, 0, "address 002 serial TDC-A", NULL);
    run_tool(&r, (const char *[]){"--bus", "1", "info", NULL});
    expect(&r, 3, NULL, "2 tdc boards match");
}

/* Writes n bytes to <tmpdir>/<name> and sends them with tdc-usb stream in
 * transfers of `chunk` bytes. */
static void stream_bytes(run_t *r, const char *name, const uint8_t *data, size_t n, const char *chunk)
{
    char path[128];
    tmp_path(path, sizeof path, name);
    write_file(path, data, n);
    run_tool(r, (const char *[]){"stream", "--chunk", chunk, path, NULL});
}

static void test_stream(void **state)
{
    fixture_t *f = *state;
    const size_t n = 200003; /* not a multiple of the chunk: the last transfer is short */
    uint8_t *data = random_bytes(n, 42);
    char path[128];
    tmp_path(path, sizeof path, "stream.tdcs");
    run_t r;
    stream_bytes(&r, "stream.tdcs", data, n, "8192");
    expect(&r, 0, "board received all 200003 bytes", NULL);
    assert_non_null(strstr(r.out, "MB/s"));
    assert_non_null(strstr(r.out, "link_crc_errors 0"));
    emul_board_stats_t st;
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.rx_bytes, n);
    assert_int_equal(st.rx_transfers, (n + 8191) / 8192);
    assert_int_equal(st.rx_crc, tdc_crc32(data, n));
    /* the same bytes from stdin (a live producer such as tdc-sim), with
     * the progress bar forced on (stderr is not a terminal here) */
    run_tool_in(&r, (const char *[]){"stream", "--progress", "--chunk", "8192", "-", NULL}, path);
    expect(&r, 0, "board received all 200003 bytes", "stream 200003 bytes");
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.rx_crc, tdc_crc32(data, n));
    run_tool(&r, (const char *[]){"stream", "--progress", path, NULL});
    expect(&r, 0, "board received all 200003 bytes", "100.0%");
    free(data);
}

/* A real link stream (sim/link generator) into a board whose sink is the
 * firmware's link decoder: its verdicts become the counters tdc-usb prints. */
static void test_stream_link_decoder(void **state)
{
    fixture_t *f = *state;
    enum { W = 32, H = 24, FRAMES = 12 };
    assert_int_equal(emul_board_attach_link_decoder(f->board[0], W, H), 0);
    tdc_link_gen_opts_t o;
    tdc_link_gen_opts_plain(&o, 7, W, H, 1, 90, TDC_PIXFMT_RGB888, FRAMES, 5);
    static uint8_t stream[64 * 1024], scratch[TDC_LINK_GEN_SCRATCH_BYTES(W, H)];
    tdc_link_gen_packet_t pk[64];
    uint32_t npk = 0;
    size_t n = tdc_link_gen_stream(stream, sizeof stream, &o, scratch, sizeof scratch, pk, 64, &npk);
    assert_true(n > 0 && npk == FRAMES + 1);
    run_t r;
    stream_bytes(&r, "gen.tdcs", stream, n, "1000");
    expect(&r, 0, "link_crc_errors 0 link_malformed 0", NULL);
    assert_non_null(strstr(r.out, "frames 12"));
    /* A new stream (new id: the board keeps its sequence state across
     * transfers, like a real decoder) with one flipped payload bit in frame
     * packet 5: one CRC error, one frame lost, the rest shown. */
    o.stream_id = 8;
    assert_int_equal(tdc_link_gen_stream(stream, sizeof stream, &o, scratch, sizeof scratch, pk, 64, &npk), n);
    stream[pk[5].offset + TDC_LINK_HEADER_BYTES + 17] ^= 0x04u;
    stream_bytes(&r, "gen.tdcs", stream, n, "1000");
    expect(&r, 0, "link_crc_errors 1 link_malformed 0", NULL);
    assert_non_null(strstr(r.out, "frames 11"));
}

/* A foveated stream (issue 14) needs nothing of tdc-usb: it sends the
 * bytes, the board's decoder takes FOVEATED packets (kernel log-polar and
 * log-rectilinear, with and without vectors) like any other kind and
 * refuses a bad foveation header by name (counted as malformed). */
static void test_stream_foveated(void **state)
{
    fixture_t *f = *state;
    enum { W = 32, H = 24, FRAMES = 6 };
    assert_int_equal(emul_board_attach_link_decoder(f->board[0], W, H), 0);
    tdc_link_stream_info_t in;
    memset(&in, 0, sizeof in);
    in.flags = TDC_LINK_STREAM_FOVEATED;
    in.r_num = in.r_den = 1;
    in.width = W;
    in.height = H;
    in.eyes = 1;
    in.refresh_hz = 90;
    tdc_link_encoder_t enc;
    tdc_link_encoder_init(&enc, 9, &in);
    static uint8_t stream[64 * 1024], samples[W * H * 6];
    static int16_t mv[W * H * 2];
    for (size_t i = 0; i < sizeof samples; i++) {
        samples[i] = (uint8_t)(i * 7u);
    }
    size_t n = tdc_link_encode_stream(&enc, stream, sizeof stream), spoiled = 0;
    for (uint32_t fr = 0; fr < FRAMES; fr++) {
        tdc_fov_params_t p;
        memset(&p, 0, sizeof p);
        p.gaze_x_q8 = (int32_t)(fr * 3u + 10u) * 256;
        p.gaze_y_q8 = 12 * 256;
        p.alpha_q8 = (fr & 1u) ? 256u : 1024u;
        p.disk_q15 = 4077;
        p.lp_w = tdc_fov_lp_size(18187, W);
        p.lp_h = tdc_fov_lp_size(18187, H);
        if (fr & 1u) { /* log-rectilinear */
            p.transform = TDC_FOV_LOG_RECT;
            p.lr_k_q4[0] = p.lr_k_q4[1] = 8 * 16;
        }
        const size_t at = n;
        n += tdc_link_encode_foveated(&enc, stream + n, sizeof stream - n, 0, fr, &p, 18187, samples,
                                      (fr % 3u) ? mv : NULL, NULL);
        assert_true(n > at);
        if (fr == 4) { /* alpha 9.0, both CRCs recomputed: only the foveation check refuses it */
            tdc_link_header_t hh;
            assert_int_equal(tdc_link_header_unpack(stream + at, &hh), TDC_LINK_OK);
            stream[at + TDC_LINK_HEADER_BYTES + 9] = 9;
            hh.payload_crc = tdc_crc32(stream + at + TDC_LINK_HEADER_BYTES, hh.payload_len);
            tdc_link_header_pack(stream + at, &hh);
            spoiled = 1;
        }
    }
    assert_int_equal(spoiled, 1);
    run_t r;
    stream_bytes(&r, "fov.tdcs", stream, n, "1000");
    expect(&r, 0, "link_crc_errors 0 link_malformed 1", NULL);
    assert_non_null(strstr(r.out, "frames 5"));
}

static void stream_fault(fixture_t *f, emul_fault_t fault, uint32_t after, int code, const char *msg)
{
    uint8_t *data = random_bytes(100000, 3);
    char path[128];
    tmp_path(path, sizeof path, "fault.tdcs");
    write_file(path, data, 100000);
    free(data);
    emul_board_set_fault(f->board[0], fault, after);
    run_t r;
    run_tool(&r, (const char *[]){"--timeout", "300", "stream", "--chunk", "4096", path, NULL});
    expect(&r, code, NULL, msg);
    assert_non_null(strstr(r.err, "stopped after"));
    assert_true(r.secs < 10.0);
}

static void test_stream_stall(void **state)
{
    stream_fault(*state, EMUL_FAULT_STALL_BULK, 3, 4, "LIBUSB_ERROR_PIPE");
}

static void test_stream_timeout(void **state)
{
    stream_fault(*state, EMUL_FAULT_HANG_BULK, 3, 5, "LIBUSB_ERROR_TIMEOUT");
}

static void test_stream_unplug(void **state)
{
    stream_fault(*state, EMUL_FAULT_UNPLUG, 3, 6, "LIBUSB_ERROR_NO_DEVICE");
}

static void test_stream_missing_file(void **state)
{
    (void)state;
    run_t r;
    run_tool(&r, (const char *[]){"stream", "/nonexistent/file.tdcs", NULL});
    expect(&r, 7, NULL, "cannot open /nonexistent/file.tdcs");
}

static void test_info_stall_and_timeout(void **state)
{
    fixture_t *f = *state;
    run_t r;
    emul_board_set_fault(f->board[0], EMUL_FAULT_STALL_INFO, 0);
    run_tool(&r, (const char *[]){"info", NULL});
    expect(&r, 4, NULL, "board-info request failed: LIBUSB_ERROR_PIPE");
    emul_board_set_fault(f->board[0], EMUL_FAULT_HANG_INFO, 0);
    run_tool(&r, (const char *[]){"--timeout", "250", "info", NULL});
    expect(&r, 5, NULL, "failed after 250 ms: LIBUSB_ERROR_TIMEOUT");
}

static void test_flash(void **state)
{
    fixture_t *f = *state;
    char img_path[128];
    tmp_path(img_path, sizeof img_path, "fw.img");
    size_t len;
    uint8_t *img = make_image("emul", 5000, img_path, &len);
    run_t r;
    run_tool(&r, (const char *[]){"flash", img_path, NULL});
    expect(&r, 0, "verified 5048 bytes read back", NULL);
    assert_non_null(strstr(r.out, "board reset requested"));
    emul_board_stats_t st;
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.image_bytes, len);
    assert_int_equal(st.slot_crc, tdc_crc32(img, len));
    assert_int_equal(st.reset_requested, 1);
    assert_int_equal(st.dfu_state, TDC_DFU_STATE_IDLE);
    free(img);
}

/* A board whose flash erases slowly: tdc-usb flash waits out each
 * bwPollTimeout of a dfuDNBUSY answer instead of polling early. */
static void flash_no_reset(run_t *r, const char *img_path)
{
    run_tool(r, (const char *[]){"flash", "--no-reset", img_path, NULL});
}

static void test_flash_busy_erase(void **state)
{
    check_busy_erase(*state, flash_no_reset, "verified 9048 bytes read back");
}

static void test_flash_bad_images(void **state)
{
    fixture_t *f = *state;
    char img_path[128], bad_path[128];
    tmp_path(img_path, sizeof img_path, "fw.img");
    tmp_path(bad_path, sizeof bad_path, "bad.img");
    size_t len;
    uint8_t *img = make_image("emul", 3000, img_path, &len);
    run_t r;

    img[TDC_IMAGE_HEADER_LEN + 1000] ^= 0x01u; /* one flipped payload bit */
    write_file(bad_path, img, len);
    run_tool(&r, (const char *[]){"flash", bad_path, NULL});
    expect(&r, 8, NULL, "payload CRC-32 does not match the header");
    img[TDC_IMAGE_HEADER_LEN + 1000] ^= 0x01u;

    write_file(bad_path, img, len - 100); /* truncated */
    run_tool(&r, (const char *[]){"flash", bad_path, NULL});
    expect(&r, 8, NULL, "image size does not match the header's payload length");

    write_file(bad_path, img + 4, len - 4); /* no header */
    run_tool(&r, (const char *[]){"flash", bad_path, NULL});
    expect(&r, 8, NULL, "not a tdc firmware image");

    emul_board_stats_t st;
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.image_bytes, 0); /* nothing reached the board */
    assert_int_equal(st.dfu_state, TDC_DFU_STATE_IDLE);
    free(img);

    img = make_image("otherboard", 3000, img_path, &len);
    run_tool(&r, (const char *[]){"flash", img_path, NULL});
    expect(&r, 9, NULL, "image was built for another board");
    free(img);

    img = make_image("emul", SLOT_BYTES, img_path, &len); /* header makes it 48 bytes too big */
    run_tool(&r, (const char *[]){"flash", img_path, NULL});
    expect(&r, 9, NULL, "larger than the board's flash slot");
    free(img);
}

static void test_flash_board_rejects(void **state)
{
    fixture_t *f = *state;
    char img_path[128];
    tmp_path(img_path, sizeof img_path, "fw.img");
    size_t len;
    uint8_t *img = make_image("emul", 4000, img_path, &len);
    emul_board_set_fault(f->board[0], EMUL_FAULT_CORRUPT_FLASH, 2100); /* a bad flash cell */
    run_t r;
    run_tool(&r, (const char *[]){"flash", img_path, NULL});
    expect(&r, 10, NULL, "DFU status errVERIFY");
    emul_board_stats_t st;
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.image_bytes, 0);
    assert_int_equal(st.reset_requested, 0);
    assert_int_equal(st.dfu_state, TDC_DFU_STATE_ERROR);
    /* The next flash clears the error state first and succeeds. */
    emul_board_set_fault(f->board[0], EMUL_FAULT_NONE, 0);
    run_tool(&r, (const char *[]){"flash", "--no-reset", img_path, NULL});
    expect(&r, 0, "verified 4048 bytes", NULL);
    free(img);
}

static void test_args(void **state)
{
    (void)state;
    run_t r;
    run_tool(&r, (const char *[]){"frobnicate", NULL});
    expect(&r, 1, NULL, "unknown command 'frobnicate'");
    run_tool(&r, (const char *[]){"--timeout", "x", "info", NULL});
    expect(&r, 1, NULL, "bad value for --timeout");
    run_tool(&r, (const char *[]){"--help", NULL});
    expect(&r, 0, "exit codes:", NULL);
}

int main(void)
{
    if (mkdtemp(tmpdir) == NULL) {
        perror("mkdtemp");
        return 1;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_args, setup_none, teardown),
        cmocka_unit_test_setup_teardown(test_no_device, setup_none, teardown),
        cmocka_unit_test_setup_teardown(test_list_and_info, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_two_devices, setup_two, teardown),
        cmocka_unit_test_setup_teardown(test_stream, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_stream_link_decoder, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_stream_foveated, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_stream_stall, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_stream_timeout, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_stream_unplug, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_stream_missing_file, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_info_stall_and_timeout, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_flash, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_flash_busy_erase, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_flash_bad_images, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_flash_board_rejects, setup_one, teardown),
    };
    int failed = cmocka_run_group_tests_name("tdc-usb against emulated boards (umockdev)", tests, NULL, NULL);
    char cmd[160];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", tmpdir);
    return failed != 0;
}
