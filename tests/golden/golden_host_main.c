/* golden_host_main.c - host runner: prints every stage's golden lines.
 * Usage: tdc_golden [stage]   (no argument: all stages) */
#include <stdio.h>
#include <string.h>

#include "golden.h"
#include "golden_list.h"

static void write_stdout(tdc_golden_ctx_t *ctx, const char *line)
{
    (void)ctx;
    fputs(line, stdout);
}

#define DECLARE(stage) void tdc_golden_##stage(tdc_golden_ctx_t *ctx);
TDC_GOLDEN_LIST(DECLARE)

int main(int argc, char **argv)
{
    tdc_golden_ctx_t ctx = {write_stdout, NULL, 0};
    int ran = 0;
#define RUN(stage)                              \
    if (argc < 2 || !strcmp(argv[1], #stage)) { \
        tdc_golden_##stage(&ctx);               \
        ran++;                                  \
    }
    TDC_GOLDEN_LIST(RUN)
    if (!ran) {
        fprintf(stderr, "tdc_golden: unknown stage '%s'\n", argc > 1 ? argv[1] : "");
        return 2;
    }
    return 0;
}
