/*
 * test_usb_clients.c - the emulated board (tests/usb/tdc_usb_emul.c: the
 * firmware's protocol code behind umockdev's usbdevfs) against Debian's
 * own clients, dfu-util 0.11 and lsusb, run unmodified as a user would.
 * Every dfu-util run is judged by the board's state afterwards (running
 * slot, its image CRC, firmware version, DFU state), not only by the exit
 * code: dfu-util exits 0 after some failures.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tdc_usb_run.h"

#define DFU_UTIL "/usr/bin/dfu-util"
#define LSUSB "/usr/bin/lsusb"
#define DFU_SUFFIX "/usr/bin/dfu-suffix"

static uint8_t *read_all(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long sz = ftell(f);
    rewind(f);
    uint8_t *p = malloc((size_t)sz + 1);
    assert_non_null(p);
    *n = fread(p, 1, (size_t)sz, f);
    fclose(f);
    return p;
}

/* The descriptors the emulation serves are exactly the firmware's: the
 * sysfs copy libusb reads (the kernel's cache of them) byte for byte, and
 * what lsusb -v decodes from it (bcdDevice, the DFU functional descriptor). */
static void test_descriptors_lsusb(void **state)
{
    fixture_t *f = *state;
    uint8_t fw[18 + TDC_USB_CONFIG_DESC_LEN];
    tdc_usbp_device_descriptor(fw);
    tdc_usbp_config_descriptor(fw + 18, 1);
    char path[512];
    gchar *sys = umockdev_testbed_get_sys_dir(f->tb); /* transfer full */
    snprintf(path, sizeof path, "%s/devices/pci0000:00/0000:00:14.0/usb1/1-2/descriptors", sys);
    g_free(sys);
    size_t n;
    uint8_t *served = read_all(path, &n);
    assert_int_equal(n, sizeof fw); /* 68: it was 67 (hex one byte short, issue 19) */
    assert_memory_equal(served, fw, sizeof fw);
    free(served);

    run_t r;
    run_prog_in(&r, LSUSB, (const char *[]){"-v", "-d", "1209:0001", NULL}, NULL);
    expect(&r, 0, NULL, NULL);
    /* lsusb aligns with runs of blanks: compare with each run squeezed to one */
    char *o = r.out, *w = r.out;
    for (; *o != '\0'; o++)
        if (!((*o == ' ' || *o == '\t') && w > r.out && w[-1] == ' ')) *w++ = *o == '\t' ? ' ' : *o;
    *w = '\0';
    static const char *const want[] = {"bcdDevice 0.01",
                                       "idVendor 0x1209",
                                       "idProduct 0x0001",
                                       "bInterfaceClass 254 Application Specific Interface",
                                       "bInterfaceSubClass 1 Device Firmware Update",
                                       "Device Firmware Upgrade Interface Descriptor:",
                                       "bDescriptorType 33",
                                       "bmAttributes 7",
                                       "Will Not Detach",
                                       "Manifestation Tolerant",
                                       "Upload Supported",
                                       "Download Supported",
                                       "wDetachTimeout 1000 milliseconds",
                                       "wTransferSize 1024 bytes",
                                       "bcdDFUVersion 1.10",
                                       NULL};
    for (int i = 0; want[i] != NULL; i++) {
        if (strstr(r.out, want[i]) == NULL) {
            fprintf(stderr, "lsusb -v has no '%s':\n%s", want[i], r.out);
            fail();
        }
    }
    assert_string_equal(r.err, ""); /* no "short config descriptor", no failed status read */
    assert_null(strstr(r.out, "Couldn't"));
}

static void test_dfu_list(void **state)
{
    (void)state;
    run_t r;
    run_prog_in(&r, DFU_UTIL, (const char *[]){"-l", NULL}, NULL);
    expect(&r, 0, "Found DFU: [1209:0001] ver=0001", NULL);
    assert_non_null(strstr(r.out, "name=\"tdc DFU (A/B slot)\", serial=\"TDC-A\""));
}

/* Flashes img_path with the plain command a user types; returns the run. */
static void dfu_flash(run_t *r, const char *img_path, int reset)
{
    if (reset)
        run_prog_in(r, DFU_UTIL, (const char *[]){"-d", "1209:0001", "-a", "0", "-D", img_path, "-R", NULL}, NULL);
    else
        run_prog_in(r, DFU_UTIL, (const char *[]){"-d", "1209:0001", "-a", "0", "-D", img_path, NULL}, NULL);
}

static void dfu_upload(const char *back_path, uint8_t **data, size_t *n)
{
    unlink(back_path);
    run_t r;
    run_prog_in(&r, DFU_UTIL, (const char *[]){"-d", "1209:0001", "-a", "0", "-U", back_path, NULL}, NULL);
    expect(&r, 0, "Upload done", NULL);
    *data = read_all(back_path, n);
}

/* The done-when of issue 19: `dfu-util -d 1209:0001 -a 0 -D image -R`
 * flashes, reads back and activates the board; then every bad case leaves
 * the running image alone. */
static void test_dfu_flash_activate_and_failures(void **state)
{
    fixture_t *f = *state;
    char img[256], back[256], path[256];
    tmp_path(img, sizeof img, "good.img");
    tmp_path(back, sizeof back, "back.bin");
    size_t len;
    uint8_t *good = make_image("emul", 5000, img, &len); /* with a DFU suffix */
    emul_board_stats_t st;
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.active_slot, 0);
    assert_int_equal(st.fw_version, 0x000100u);

    run_t r;
    dfu_flash(&r, img, 1);
    expect(&r, 0, "Download done.", NULL);
    assert_null(strstr(r.err, "Invalid DFU suffix")); /* the suffix is standard */
    assert_null(strstr(r.err, "Transfer size must be specified"));
    assert_non_null(strstr(r.out, "DFU mode device DFU version 0110"));
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.active_slot, 1); /* activated by -R: DETACH + USB reset */
    assert_int_equal(st.activations, 1);
    assert_int_equal(st.active_bytes, len);
    assert_int_equal(st.active_crc, ref_crc32(good, len)); /* the suffix never reached the board */
    assert_int_equal(st.fw_version, 0x010203u);
    assert_int_equal(st.dfu_state, TDC_DFU_STATE_IDLE);
    run_tool(&r, (const char *[]){"info", NULL});
    expect(&r, 0, "firmware: 1.2.3", NULL);

    /* read back with dfu-util -U: exactly the image (header + payload) */
    uint8_t *up;
    size_t upn;
    dfu_upload(back, &up, &upn);
    assert_int_equal(upn, len);
    assert_memory_equal(up, good, len);
    free(up);

    /* an image for another board: refused at manifestation (errFILE) */
    size_t olen;
    tmp_path(path, sizeof path, "other.img");
    uint8_t *other = make_image("otherboard", 3000, path, &olen);
    dfu_flash(&r, path, 1);
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.active_slot, 1);
    assert_int_equal(st.active_crc, ref_crc32(good, len));
    assert_int_equal(st.activations, 1);
    assert_int_equal(st.fw_version, 0x010203u);
    free(other);

    /* a raw binary (no tdc header, no suffix) */
    uint8_t *raw = random_bytes(4000, 5);
    tmp_path(path, sizeof path, "raw.bin");
    write_file(path, raw, 4000);
    free(raw);
    dfu_flash(&r, path, 0);
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.dfu_state, TDC_DFU_STATE_ERROR);
    assert_int_equal(st.dfu_status, TDC_DFU_ERR_FILE);
    assert_int_equal(st.active_slot, 1);
    assert_int_equal(st.active_crc, ref_crc32(good, len));
    /* the last good image can still be read back (dfu-util clears the error first) */
    dfu_upload(back, &up, &upn);
    assert_int_equal(upn, len);
    assert_memory_equal(up, good, len);
    free(up);

    /* an oversized image: larger than the slot, refused (errADDRESS) while downloading */
    uint8_t *big = random_bytes(SLOT_BYTES + 4096, 6);
    tmp_path(path, sizeof path, "big.bin");
    write_file(path, big, SLOT_BYTES + 4096);
    free(big);
    dfu_flash(&r, path, 1);
    assert_int_not_equal(r.status, 0);
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.active_slot, 1);
    assert_int_equal(st.active_crc, ref_crc32(good, len));
    assert_int_equal(st.activations, 1);

    /* an interrupted download: the 3rd DNLOAD block is lost on the wire */
    size_t nlen;
    tmp_path(path, sizeof path, "new.img");
    free(good);
    good = NULL;
    uint8_t *newer = make_image("emul", 6000, path, &nlen);
    emul_board_set_fault(f->board[0], EMUL_FAULT_STALL_DNLOAD, 2);
    dfu_flash(&r, path, 1);
    assert_int_not_equal(r.status, 0);
    emul_board_set_fault(f->board[0], EMUL_FAULT_NONE, 0);
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.active_slot, 1); /* the half-written slot is never booted */
    assert_int_equal(st.fw_version, 0x010203u);
    /* ... and recovery: the same command again */
    dfu_flash(&r, path, 1);
    expect(&r, 0, "Download done.", NULL);
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.active_slot, 0);
    assert_int_equal(st.active_bytes, nlen);
    assert_int_equal(st.active_crc, ref_crc32(newer, nlen));
    assert_int_equal(st.activations, 2);
    assert_int_equal(st.dfu_state, TDC_DFU_STATE_IDLE);
    free(newer);
}

/* A board whose flash erases slowly (dfuDNBUSY with bwPollTimeout for
 * each block starting a 4 KiB erase unit): dfu-util waits each timeout
 * out, as tdc-usb flash does (test_usb_emul), and the image lands. */
static void dfu_flash_no_reset(run_t *r, const char *img_path)
{
    dfu_flash(r, img_path, 0);
}

static void test_dfu_busy_erase(void **state)
{
    check_busy_erase(*state, dfu_flash_no_reset, "Download done.");
}

/* Detach/reset on their own: dfu-util -e (DETACH) and a USB reset without a
 * new image change nothing; after a plain download (no -R) the new image
 * waits, and the next USB reset boots it. */
static void test_dfu_detach_reset(void **state)
{
    fixture_t *f = *state;
    char img[256];
    tmp_path(img, sizeof img, "d.img");
    size_t len;
    uint8_t *good = make_image("emul", 2000, img, &len);
    run_t r;
    run_prog_in(&r, DFU_UTIL, (const char *[]){"-d", "1209:0001", "-e", NULL}, NULL);
    emul_board_stats_t st;
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.active_slot, 0);
    assert_int_equal(st.activations, 0);
    assert_int_equal(st.dfu_state, TDC_DFU_STATE_IDLE);
    dfu_flash(&r, img, 0);
    expect(&r, 0, "Download done.", NULL);
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.active_slot, 0);
    assert_int_equal(st.pending, 1);
    assert_int_equal(st.image_bytes, len); /* uploads return the new image already */
    run_prog_in(&r, DFU_UTIL, (const char *[]){"-d", "1209:0001", "-a", "0", "-e", "-R", NULL}, NULL);
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.active_slot, 1);
    assert_int_equal(st.active_crc, ref_crc32(good, len));
    assert_int_equal(st.fw_version, 0x010203u);
    free(good);
}

/* The suffix tdc-usb mkimage writes is the standard one: dfu-suffix checks
 * it, and a suffix added by dfu-suffix to a bare image is accepted by
 * tdc-usb flash (it was refused, exit 8: issue 19). */
static void test_suffix_interop(void **state)
{
    fixture_t *f = *state;
    char img[256], bare[256];
    tmp_path(img, sizeof img, "s.img");
    tmp_path(bare, sizeof bare, "bare.img");
    size_t len;
    uint8_t *good = make_image("emul", 3000, img, &len);
    run_t r;
    run_prog_in(&r, DFU_SUFFIX, (const char *[]){"-c", img, NULL}, NULL);
    expect(&r, 0, "Vendor ID:\t0x1209", NULL);
    assert_non_null(strstr(r.out, "Product ID:\t0x0001"));
    write_file(bare, good, len); /* header + payload, no suffix */
    run_prog_in(&r, DFU_SUFFIX, (const char *[]){"-a", bare, "-v", "1209", "-p", "0001", NULL}, NULL);
    expect(&r, 0, NULL, NULL);
    run_tool(&r, (const char *[]){"flash", bare, NULL});
    expect(&r, 0, "verified 3048 bytes read back", NULL);
    emul_board_stats_t st;
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.active_crc, ref_crc32(good, len));
    assert_int_equal(st.active_slot, 1);
    /* a suffix for another device is refused before the board is touched */
    run_prog_in(&r, DFU_SUFFIX, (const char *[]){"-D", bare, NULL}, NULL);
    run_prog_in(&r, DFU_SUFFIX, (const char *[]){"-a", bare, "-v", "1209", "-p", "0002", NULL}, NULL);
    run_tool(&r, (const char *[]){"flash", bare, NULL});
    expect(&r, 9, NULL, "DFU suffix is for USB 1209:0002");
    /* mkimage refuses a board name that does not fit the header */
    run_tool(&r, (const char *[]){"mkimage", "--board", "stm32h747i-disco-rev2", img, img, NULL});
    expect(&r, 1, NULL, "does not fit the image header's 16 characters");
    free(good);
}

int main(void)
{
    if (mkdtemp(tmpdir) == NULL) {
        perror("mkdtemp");
        return 1;
    }
    if (access(DFU_UTIL, X_OK) != 0 || access(LSUSB, X_OK) != 0 || access(DFU_SUFFIX, X_OK) != 0) {
        fprintf(stderr, "test_usb_clients: dfu-util and lsusb are missing: make deps installs them "
                        "(DEPS_PKGS: dfu-util usbutils)\n");
        return 1;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_descriptors_lsusb, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_dfu_list, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_dfu_flash_activate_and_failures, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_dfu_busy_erase, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_dfu_detach_reset, setup_one, teardown),
        cmocka_unit_test_setup_teardown(test_suffix_interop, setup_one, teardown),
    };
    int failed = cmocka_run_group_tests_name("dfu-util and lsusb against the emulated board", tests, NULL, NULL);
    char cmd[160];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", tmpdir);
    return failed != 0;
}
