/*
 * test_tool - the shared tool convention (common/tdc_tool.c):
 * every exit code has a distinct name, numbers that do not fit are refused
 * (never wrapped: 4294967297 is not 1), nan/inf refused, sizes, CSV fields,
 * lines longer than the buffer reported instead of split, and output files
 * that keep the old contents until committed.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "tdc_cmocka.h"

#include "tdc_tool.h"

static void test_exit_names(void **state)
{
    (void)state;
    for (int i = 0; i < TDC_EXIT_COUNT; i++) {
        assert_string_not_equal(tdc_exit_name(i), "?");
        for (int j = 0; j < i; j++) assert_string_not_equal(tdc_exit_name(i), tdc_exit_name(j));
    }
    assert_string_equal(tdc_exit_name(TDC_EXIT_OK), "OK");
    assert_string_equal(tdc_exit_name(TDC_EXIT_ARGS), "ARGS");
    assert_string_equal(tdc_exit_name(TDC_EXIT_PROTOCOL), "PROTOCOL");
    assert_string_equal(tdc_exit_name(TDC_EXIT_NOMEM), "NOMEM");
    assert_int_equal(TDC_EXIT_PROTOCOL, 12); /* tdc-usb's documented numbers stay */
    assert_string_equal(tdc_exit_name(TDC_EXIT_COUNT), "?");
    assert_string_equal(tdc_exit_name(-1), "?");
}

static void test_u64(void **state)
{
    (void)state;
    uint64_t v = 7;
    assert_int_equal(tdc_parse_u64("0", 0, 10, &v), 0);
    assert_int_equal(v, 0);
    assert_int_equal(tdc_parse_u64("18446744073709551615", 0, UINT64_MAX, &v), 0);
    assert_true(v == UINT64_MAX);
    v = 7;
    assert_int_equal(tdc_parse_u64("18446744073709551616", 0, UINT64_MAX, &v), -1);
    assert_int_equal(v, 7); /* untouched on failure */
    assert_int_equal(tdc_parse_u64("0x1209", 0, 0xFFFF, &v), 0);
    assert_int_equal(v, 0x1209);
    assert_int_equal(tdc_parse_u64("0x10000", 0, 0xFFFF, &v), -1);
    const char *bad[] = {"", "-1", "+1", " 1", "1 ", "1x", "0x", "x1", "1.5", "nan", NULL};
    for (int i = 0; bad[i]; i++) assert_int_equal(tdc_parse_u64(bad[i], 0, UINT64_MAX, &v), -1);
    assert_int_equal(tdc_parse_u64(NULL, 0, 1, &v), -1);
    assert_int_equal(tdc_parse_u64("5", 6, 9, &v), -1); /* below lo */
    assert_int_equal(tdc_parse_u64("9", 0, 5, &v), -1); /* a single digit above hi */
}

static void test_u32_and_int_do_not_wrap(void **state)
{
    (void)state;
    uint32_t u = 0;
    /* the findings of issue 19: --refresh 4294967297 passed as 1 Hz */
    assert_int_equal(tdc_parse_u32("4294967297", 1, 1000, &u), -1);
    assert_int_equal(tdc_parse_u32("4294967295", 0, UINT32_MAX, &u), 0);
    assert_true(u == UINT32_MAX);
    assert_int_equal(tdc_parse_u32("4294967296", 0, UINT32_MAX, &u), -1);
    int i = 0;
    assert_int_equal(tdc_parse_int("-5", -10, 10, &i), 0);
    assert_int_equal(i, -5);
    assert_int_equal(tdc_parse_int("-5", 0, 10, &i), -1);
    assert_int_equal(tdc_parse_int("2147483647", 0, 2147483647, &i), 0);
    assert_int_equal(tdc_parse_int("2147483648", 0, 2147483647, &i), -1);
    assert_int_equal(tdc_parse_int("-2147483648", -2147483647 - 1, 0, &i), 0);
    assert_int_equal(i, -2147483647 - 1);
    assert_int_equal(tdc_parse_int("4294967297", 1, 1000, &i), -1);
    assert_int_equal(tdc_parse_int("--1", -10, 10, &i), -1);
    assert_int_equal(tdc_parse_int("0x10", 0, 100, &i), -1); /* decimal only */
}

static void test_double(void **state)
{
    (void)state;
    double d = 1;
    assert_int_equal(tdc_parse_double("2.5", 0, 10, &d), 0);
    assert_true(d == 2.5);
    const char *bad[] = {"nan", "NaN", "inf", "-inf", "1e999", "", " 1", "1 ", "1,5", "11", NULL};
    for (int i = 0; bad[i]; i++) assert_int_equal(tdc_parse_double(bad[i], 0, 10, &d), -1);
    const char *end;
    assert_int_equal(tdc_parse_double_field("0.25,7", &end, &d), 0);
    assert_true(d == 0.25);
    assert_int_equal(*end, ',');
    assert_int_equal(tdc_parse_double_field("nan,7", &end, &d), -1);
}

static void test_size(void **state)
{
    (void)state;
    unsigned w = 0, h = 0;
    assert_int_equal(tdc_parse_size("160x120", 8192, &w, &h), 0);
    assert_int_equal(w, 160);
    assert_int_equal(h, 120);
    /* issue 19: --size 4294967312x16 passed as 16x16 */
    assert_int_equal(tdc_parse_size("4294967312x16", 8192, &w, &h), -1);
    assert_int_equal(tdc_parse_size("4294967328x24", 8192, &w, &h), -1);
    const char *bad[] = {"0x16", "16x0", "16", "16x", "x16", "16x16x", "-1x4", "16 x16", "8193x1", NULL};
    for (int i = 0; bad[i]; i++) assert_int_equal(tdc_parse_size(bad[i], 8192, &w, &h), -1);
}

static void test_field(void **state)
{
    (void)state;
    const char *end;
    uint64_t v;
    assert_int_equal(tdc_parse_u64_field("255,12", &end, 255, &v), 0);
    assert_int_equal(v, 255);
    assert_int_equal(*end, ',');
    /* issue 19: CSV code 4294967299 */
    assert_int_equal(tdc_parse_u64_field("4294967299,1", &end, 255, &v), -1);
    assert_int_equal(tdc_parse_u64_field("256", &end, 255, &v), -1);
    assert_int_equal(tdc_parse_u64_field(",1", &end, 255, &v), -1);
}

static void test_read_line(void **state)
{
    (void)state;
    FILE *f = tmpfile();
    assert_non_null(f);
    char long_line[700];
    memset(long_line, 'a', sizeof long_line - 1);
    long_line[sizeof long_line - 1] = 0;
    fprintf(f, "width 7\r\n# %s width 9\nlast", long_line);
    rewind(f);
    char buf[512];
    unsigned ln = 0;
    assert_int_equal(tdc_read_line(f, buf, sizeof buf, &ln), 1);
    assert_string_equal(buf, "width 7");
    /* the long comment is one bad line (line 2), not a comment plus "width 9" */
    assert_int_equal(tdc_read_line(f, buf, sizeof buf, &ln), -1);
    assert_int_equal(ln, 2);
    assert_int_equal(tdc_read_line(f, buf, sizeof buf, &ln), 1);
    assert_string_equal(buf, "last");
    assert_int_equal(ln, 3);
    assert_int_equal(tdc_read_line(f, buf, sizeof buf, &ln), 0);
    fclose(f);
}

static void test_out_keeps_old_until_commit(void **state)
{
    (void)state;
    char dir[] = "/tmp/test_tool_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[256], rd[64];
    snprintf(path, sizeof path, "%s/out.txt", dir);
    FILE *f = fopen(path, "w");
    fputs("old", f);
    fclose(f);
    tdc_out_t o;
    assert_int_equal(tdc_out_open(&o, path, "w"), 0);
    fputs("new", o.f);
    tdc_out_abort(&o); /* an error: the old file stays */
    f = fopen(path, "r");
    assert_non_null(fgets(rd, sizeof rd, f));
    fclose(f);
    assert_string_equal(rd, "old");
    assert_int_not_equal(access(o.tmp, F_OK), 0);
    assert_int_equal(tdc_out_open(&o, path, "w"), 0);
    fputs("new", o.f);
    assert_int_equal(tdc_out_commit(&o), 0);
    f = fopen(path, "r");
    assert_non_null(fgets(rd, sizeof rd, f));
    fclose(f);
    assert_string_equal(rd, "new");
    char bad[300];
    snprintf(bad, sizeof bad, "%s/nodir/x", dir);
    assert_int_equal(tdc_out_open(&o, bad, "w"), -1);
    remove(path);
    rmdir(dir);
}

static void test_safe_name(void **state)
{
    (void)state;
    assert_true(tdc_safe_name("room"));
    assert_true(tdc_safe_name("a.b-c_1"));
    const char *bad[] = {"", ".", "..", "../escaped", "a/b", "/abs", "sp ace", "a\\b", NULL};
    for (int i = 0; bad[i]; i++) assert_false(tdc_safe_name(bad[i]));
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_exit_names),
    cmocka_unit_test(test_u64),
    cmocka_unit_test(test_u32_and_int_do_not_wrap),
    cmocka_unit_test(test_double),
    cmocka_unit_test(test_size),
    cmocka_unit_test(test_field),
    cmocka_unit_test(test_read_line),
    cmocka_unit_test(test_out_keeps_old_until_commit),
    cmocka_unit_test(test_safe_name),
)
