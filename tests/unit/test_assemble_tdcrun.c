/*
 * test_assemble_tdcrun.c - `tdc-run assemble` end to end: it writes a
 * synthetic stream (PNG + .mv files), assembles it with a dropped subframe
 * and an odd size, and its PNG frames must equal, byte for byte, the
 * firmware stage run in-process on the same files' contents; bad input gives
 * exit 1 with a message, bad usage exit 2.  TDC_RUN_PATH is set by
 * mk/assemble.mk.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tdc_tool.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "ref_assemble.h"
#include "tdc_assemble.h"
#include "tdc_png.h"

#ifndef TDC_RUN_PATH
#define TDC_RUN_PATH "build/gcc-O2/bin/tdc-run"
#endif

static char g_dir[256];

static int run(const char *cmd)
{
    char full[8192];
    snprintf(full, sizeof(full), "%.4000s > %.256s/log.txt 2>&1", cmd, g_dir);
    int st = system(full);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static int log_contains(const char *s)
{
    char path[512], buf[8192];
    snprintf(path, sizeof(path), "%s/log.txt", g_dir);
    FILE *f = fopen(path, "r");
    if (!f) return 0;
    size_t n = fread(buf, 1, sizeof(buf) - 1, f);
    fclose(f);
    buf[n] = 0;
    return strstr(buf, s) != NULL;
}

static void test_stream_roundtrip(void **state)
{
    (void)state;
    const int W = 45, H = 29, N = 14, DROP = 6;
    char cmd[4096];
    snprintf(cmd, sizeof(cmd), "%s assemble --write-stream pan -o %s/in --size %dx%d --count %d --velocity -1.75,0.6",
             TDC_RUN_PATH, g_dir, W, H, N);
    assert_int_equal(run(cmd), 0);
    int len = snprintf(cmd, sizeof(cmd), "%s assemble -q -o %s/out --size %dx%d", TDC_RUN_PATH, g_dir, W, H);
    for (int f = 0; f < N; f++)
        len += f == DROP ? snprintf(cmd + len, sizeof(cmd) - (size_t)len, " -")
                         : snprintf(cmd + len, sizeof(cmd) - (size_t)len, " %s/in/sub_%05d.png", g_dir, f);
    assert_int_equal(run(cmd), 0);

    /* In-process: the same stream from the generator (same seed) through the stage. */
    tdc_scene_t sc;
    assert_int_equal(tdc_scene_init(&sc, TDC_SCENE_PAN, W, H, -28, 10, 1), 0);
    tdc_asm_config_t cfg = {W, H};
    size_t n = tdc_asm_get_size(&cfg);
    void *arena = aligned_alloc(TDC_ARENA_ALIGN, TDC_ARENA_ROUND(n));
    tdc_asm_t st;
    assert_int_equal(tdc_asm_init(&st, &cfg, arena, n), TDC_OK);
    size_t tiles = (size_t)((W + 1) / 2) * ((H + 1) / 2);
    uint8_t *smp = malloc(tiles * 3), *bits = malloc(tiles / 8 + 1);
    int16_t *mv = malloc(tiles * 4);
    for (int f = 0; f < N; f++) {
        tdc_scene_subframe(&sc, (uint32_t)f, smp, mv, bits);
        if (f != DROP) assert_int_equal(tdc_asm_ingest(&st, (uint32_t)f, smp, mv, (f & 3) == 0 ? bits : NULL), TDC_OK);
        assert_int_equal(tdc_asm_assemble(&st, (uint32_t)f), TDC_OK);
        char path[512], err[256];
        tdc_image_t img;
        snprintf(path, sizeof(path), "%s/out/frame_%05d.png", g_dir, f);
        assert_int_equal(tdc_png_read(path, &img, err, sizeof(err)), 0);
        assert_int_equal(img.width, W);
        assert_int_equal(img.height, H);
        assert_memory_equal(img.data, tdc_asm_output(&st, NULL), (size_t)W * H * 3);
        tdc_png_free(&img);
    }
    assert_int_equal(st.stats.subframes_missing, 1);
    free(smp), free(bits), free(mv), free(arena);
    tdc_scene_free(&sc);
}

static void test_bad_input(void **state)
{
    (void)state;
    char cmd[4096];
    /* no such file: FILE (exit codes: common/tdc_tool.h, docs/tools.md) */
    snprintf(cmd, sizeof(cmd), "%s assemble -o %s/o2 %s/nope.png", TDC_RUN_PATH, g_dir, g_dir);
    assert_int_equal(run(cmd), TDC_EXIT_FILE);
    /* size does not match the subframes */
    snprintf(cmd, sizeof(cmd), "%s assemble -o %s/o2 --size 10x10 %s/in/sub_00000.png", TDC_RUN_PATH, g_dir, g_dir);
    assert_int_equal(run(cmd), TDC_EXIT_INPUT);
    assert_true(log_contains("needs 5x5 subframes"));
    /* truncated and corrupted motion files */
    snprintf(cmd, sizeof(cmd),
             "cp %s/in/sub_00001.png %s/in/cut.png && head -c 30 %s/in/sub_00001.mv > %s/in/cut.mv && "
             "cp %s/in/sub_00001.png %s/in/bad.png && printf 'XXXXXXXXXXXXXXXXXXXX' > %s/in/bad.mv",
             g_dir, g_dir, g_dir, g_dir, g_dir, g_dir, g_dir);
    assert_int_equal(system(cmd), 0);
    snprintf(cmd, sizeof(cmd), "%s assemble -o %s/o2 %s/in/cut.png", TDC_RUN_PATH, g_dir, g_dir);
    assert_int_equal(run(cmd), TDC_EXIT_INPUT);
    assert_true(log_contains("truncated"));
    snprintf(cmd, sizeof(cmd), "%s assemble -o %s/o2 %s/in/bad.png", TDC_RUN_PATH, g_dir, g_dir);
    assert_int_equal(run(cmd), TDC_EXIT_INPUT);
    assert_true(log_contains("not a motion-vector file"));
    /* usage errors */
    snprintf(cmd, sizeof(cmd), "%s assemble --frobnicate", TDC_RUN_PATH);
    assert_int_equal(run(cmd), TDC_EXIT_ARGS);
    assert_true(log_contains("tdc-run: assemble: unknown option '--frobnicate'"));
    snprintf(cmd, sizeof(cmd), "%s assemble -o %s/o3", TDC_RUN_PATH, g_dir);
    assert_int_equal(run(cmd), TDC_EXIT_ARGS);
    /* numbers that do not fit are refused, not wrapped (issue 19) */
    snprintf(cmd, sizeof(cmd), "%s assemble --write-stream pan -o %s/o4 --count 4294967297", TDC_RUN_PATH, g_dir);
    assert_int_equal(run(cmd), TDC_EXIT_ARGS);
    snprintf(cmd, sizeof(cmd), "%s assemble --write-stream pan -o %s/o4 --size 4294967312x16", TDC_RUN_PATH, g_dir);
    assert_int_equal(run(cmd), TDC_EXIT_ARGS);
    snprintf(cmd, sizeof(cmd), "%s assemble --write-stream pan -o %s/o4 --velocity nan,1", TDC_RUN_PATH, g_dir);
    assert_int_equal(run(cmd), TDC_EXIT_ARGS);
    snprintf(cmd, sizeof(cmd), "%s assemble --help", TDC_RUN_PATH);
    assert_int_equal(run(cmd), 0);
    /* the help is printed as it is, not through printf: no literal %% */
    assert_false(log_contains("%%"));
    assert_true(log_contains("i % 4 == 0"));
    assert_true(log_contains("SUBFRAME.mv"));
}

int main(void)
{
    snprintf(g_dir, sizeof(g_dir), "/tmp/tdc_asm_run.XXXXXX");
    if (!mkdtemp(g_dir)) return 1;
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_stream_roundtrip), cmocka_unit_test(test_bad_input)};
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    char cmd[512];
    snprintf(cmd, sizeof(cmd), "rm -rf %s", g_dir);
    if (system(cmd) != 0) rc = rc ? rc : 0;
    return rc;
}
