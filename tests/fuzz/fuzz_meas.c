/*
 * fuzz_meas.c - libFuzzer target of the LCD measurement reader
 * (common/tdc_meas.c) and, for inputs it accepts as transition
 * files, the stateful-table fit's checks (tdc_calib_trans.c): any input must
 * be parsed or refused with a message, never crash, leak or hang.
 * Seeds: tests/fuzz/corpus-meas (pairs and transition files, good and bad).
 * Properties checked beyond the sanitizers: a refusal always has a message;
 * an accepted file has rows whose fields are in the documented ranges.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "../../hosttools/calib/tdc_calib_trans.h"
#include "tdc_meas.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static tdc_st_fits_t fits;
    char err[512];
    err[0] = 0;
    tdc_meas_t m;
    if (tdc_meas_parse((const char *)data, size, "fuzz", &m, err, sizeof err) != 0) {
        if (!err[0]) {
            abort(); /* a refusal without a message */
        }
    } else {
        for (size_t i = 0; i < m.nrows; i++) {
            const tdc_meas_row_t *r = &m.rows[i];
            if (r->rate < 1 || r->rate > 1000 || r->ch < 0 || r->ch > 2 || r->a < 0 || r->a > 1023 || r->b < 0 ||
                r->b > 1023 || !(r->lum == r->lum) || !(r->end == r->end)) {
                abort();
            }
        }
        if (m.kind == TDC_MEAS_TRANSITIONS) {
            err[0] = 0;
            if (tdc_st_fit(&m, "fuzz", 17, (int)(size & 1u), NULL, &fits, err, sizeof err) != 0 && !err[0]) {
                abort();
            }
        }
    }
    tdc_meas_free(&m);
    return 0;
}
