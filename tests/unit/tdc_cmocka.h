/*
 * tdc_cmocka.h - the one main() of a cmocka test program in tests/unit:
 *   TDC_TEST_MAIN(cmocka_unit_test(test_a), cmocka_unit_test(test_b), ...)
 * runs the listed tests as one group (group name "tests", no set-up or
 * tear-down) and exits with cmocka's count of failures.  A program that
 * needs a group set-up writes its own main().
 */
#ifndef TDC_CMOCKA_H
#define TDC_CMOCKA_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#define TDC_TEST_MAIN(...)                                       \
    int main(void)                                               \
    {                                                            \
        const struct CMUnitTest tests[] = {__VA_ARGS__};         \
        return cmocka_run_group_tests(tests, NULL, NULL);        \
    }

#endif
