/*
 * tdc_usb_run.c - what the umockdev tests share (tdc_usb_run.h): running a
 * program (tdc-usb, dfu-util, lsusb) against the emulated boards of the
 * current testbed with a deadline, checking its exit code and output,
 * fixtures with zero, one or two boards, files and reference CRCs.
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

#include "tdc_usb_run.h"


extern char **environ;


char tmpdir[] = "/tmp/tdc-usb-test-XXXXXX";

static double mono_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void slurp(const char *path, char *dst, size_t cap)
{
    FILE *f = fopen(path, "rb");
    size_t n = f != NULL ? fread(dst, 1, cap - 1, f) : 0;
    dst[n] = '\0';
    if (f != NULL) fclose(f);
}

/* Runs prog (tdc-usb, or a standard client: dfu-util, lsusb) with the
 * given arguments inside the current testbed; stdin from in_path (NULL:
 * /dev/null). */
void run_prog_in(run_t *r, const char *prog, const char *const *args, const char *in_path)
{
    const char *argv[32];
    int n = 0;
    argv[n++] = prog;
    for (int i = 0; args[i] != NULL && n < 31; i++) argv[n++] = args[i];
    argv[n] = NULL;

    /* Environment prepared before fork: the umockdev worker thread makes
     * this process multi-threaded, so the child only calls dup2/execve. */
    static char preload[] = "LD_PRELOAD=libumockdev-preload.so.0";
    /* An ASan tdc-usb must accept a preload library ahead of its runtime. */
    static char asan[] = "ASAN_OPTIONS=verify_asan_link_order=0:detect_leaks=1";
    char *envp[256];
    int ne = 0;
    for (char **e = environ; *e != NULL && ne < 250; e++)
        if (strncmp(*e, "LD_PRELOAD=", 11) != 0 && strncmp(*e, "ASAN_OPTIONS=", 13) != 0) envp[ne++] = *e;
    envp[ne++] = preload;
    envp[ne++] = asan;
    envp[ne] = NULL;

    char out_path[128], err_path[128];
    snprintf(out_path, sizeof out_path, "%s/stdout", tmpdir);
    snprintf(err_path, sizeof err_path, "%s/stderr", tmpdir);
    int fo = open(out_path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    int fe = open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    int fi = open(in_path != NULL ? in_path : "/dev/null", O_RDONLY);
    assert_true(fo >= 0 && fe >= 0 && fi >= 0);

    double t0 = mono_s();
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        dup2(fi, 0);
        dup2(fo, 1);
        dup2(fe, 2);
        execve(argv[0], (char *const *)argv, envp);
        _exit(127);
    }
    close(fo);
    close(fe);
    close(fi);
    int st = 0;
    r->status = -1;
    for (;;) {
        pid_t w = waitpid(pid, &st, WNOHANG);
        if (w == pid) {
            r->status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
            break;
        }
        if (mono_s() - t0 > CHILD_DEADLINE_S) {
            kill(pid, SIGKILL);
            waitpid(pid, &st, 0);
            r->status = -1;
            break;
        }
        struct timespec ts = {0, 5000000};
        nanosleep(&ts, NULL);
    }
    r->secs = mono_s() - t0;
    slurp(out_path, r->out, sizeof r->out);
    slurp(err_path, r->err, sizeof r->err);
    printf("  $ %s", strrchr(prog, '/') != NULL ? strrchr(prog, '/') + 1 : prog);
    for (int i = 1; argv[i] != NULL; i++) printf(" %s", argv[i]);
    printf("  -> exit %d in %.2f s\n", r->status, r->secs);
    if (r->err[0] != '\0') printf("    stderr: %s", r->err);
}

void run_tool_in(run_t *r, const char *const *args, const char *in_path)
{
    run_prog_in(r, TDC_USB_BIN, args, in_path);
}

void run_tool(run_t *r, const char *const *args)
{
    run_tool_in(r, args, NULL);
}

void expect(const run_t *r, int status, const char *in_out, const char *in_err)
{
    if (r->status != status || (in_out != NULL && strstr(r->out, in_out) == NULL) ||
        (in_err != NULL && strstr(r->err, in_err) == NULL)) {
        print_error("expected exit %d, stdout with '%s', stderr with '%s'\n"
                    "got exit %d\n--- stdout\n%s--- stderr\n%s",
                    status, in_out != NULL ? in_out : "", in_err != NULL ? in_err : "", r->status, r->out, r->err);
        fail();
    }
    assert_true(r->secs < CHILD_DEADLINE_S);
}

/* Reference CRC-32 (table-driven, written from the IEEE 802.3 definition),
 * independent of the firmware's bitwise one. */
uint32_t ref_crc32(const uint8_t *p, size_t n)
{
    static uint32_t table[256];
    if (table[1] == 0)
        for (uint32_t i = 0; i < 256; i++) {
            uint32_t c = i;
            for (int k = 0; k < 8; k++) c = c & 1 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            table[i] = c;
        }
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; i++) c = table[(c ^ p[i]) & 0xFFu] ^ (c >> 8);
    return ~c;
}

void write_file(const char *path, const uint8_t *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

uint8_t *random_bytes(size_t n, uint32_t seed)
{
    uint8_t *p = malloc(n);
    assert_non_null(p);
    for (size_t i = 0; i < n; i++) {
        seed = seed * 1664525u + 1013904223u;
        p[i] = (uint8_t)(seed >> 24);
    }
    return p;
}

/* ------------------------------------------------------------------ */

int setup_none(void **state)
{
    fixture_t *f = calloc(1, sizeof *f);
    f->tb = umockdev_testbed_new();
    *state = f;
    return f->tb != NULL ? 0 : -1;
}

int setup_one(void **state)
{
    if (setup_none(state) != 0) return -1;
    fixture_t *f = *state;
    f->board[0] = emul_board_add(f->tb, 1, 2, "TDC-A", SLOT_BYTES);
    return f->board[0] != NULL ? 0 : -1;
}

int setup_two(void **state)
{
    if (setup_one(state) != 0) return -1;
    fixture_t *f = *state;
    f->board[1] = emul_board_add(f->tb, 1, 3, "TDC-B", SLOT_BYTES);
    return f->board[1] != NULL ? 0 : -1;
}

int teardown(void **state)
{
    fixture_t *f = *state;
    for (int i = 0; i < 2; i++) emul_board_free(f->board[i]);
    g_object_unref(f->tb);
    free(f);
    return 0;
}

void tmp_path(char *out, size_t cap, const char *name)
{
    snprintf(out, cap, "%s/%s", tmpdir, name);
}

void check_busy_erase(const fixture_t *f, void (*flash)(run_t *r, const char *img_path), const char *want_out)
{
    char img_path[128];
    tmp_path(img_path, sizeof img_path, "busy.img");
    size_t len;
    uint8_t *img = make_image("emul", 9000, img_path, &len);
    emul_board_set_erase(f->board[0], 40, 4096);
    run_t r;
    flash(&r, img_path);
    expect(&r, 0, want_out, NULL);
    emul_board_stats_t st;
    emul_board_stats(f->board[0], &st);
    assert_int_equal(st.image_bytes, len);
    assert_int_equal(st.slot_crc, ref_crc32(img, len));
    assert_int_equal(st.busy_replies, 3);
    assert_int_equal(st.early_polls, 0);
    free(img);
}

/* Builds an image with tdc-usb mkimage; returns its bytes (caller frees). */
uint8_t *make_image(const char *board, size_t payload, const char *img_path, size_t *len)
{
    uint8_t *p = random_bytes(payload, 99);
    char bin[128];
    tmp_path(bin, sizeof bin, "fw.bin");
    write_file(bin, p, payload);
    free(p);
    run_t r;
    run_tool(&r, (const char *[]){"mkimage", "--board", board, "--fw-version", "1.2.3", bin, img_path, NULL});
    expect(&r, 0, "CRC-32", NULL);
    FILE *f = fopen(img_path, "rb");
    assert_non_null(f);
    uint8_t *img = malloc(payload + TDC_IMAGE_HEADER_LEN);
    *len = fread(img, 1, payload + TDC_IMAGE_HEADER_LEN, f);
    fclose(f);
    assert_int_equal(*len, payload + TDC_IMAGE_HEADER_LEN);
    return img;
}
