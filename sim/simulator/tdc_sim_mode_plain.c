/*
 * tdc_sim_mode_plain.c - the plain modes: every refresh at full resolution,
 * half rate (each frame shown twice), half rate with black frames, and
 * interlaced fields (missing rows black, TRM §6).  No firmware stage beyond
 * the link decoder.
 */
#include <stdlib.h>
#include <string.h>

#include "simulator/tdc_sim_mode.h"

enum { PLAIN_FULL, PLAIN_HALF, PLAIN_BFI, PLAIN_INTERLACE };

#define F &tdc_sim_family_plain
static const tdc_mode_desc_t k_modes[] = {
    {"full", F, PLAIN_FULL, 0, 1, 1, 0, 0, 0, "every refresh rendered at full resolution (reference cost)"},
    {"half", F, PLAIN_HALF, 0, 1, 1, 0, 0, 0, "half frame rate, each frame shown twice"},
    {"interlace", F, PLAIN_INTERLACE, 0, 1, 1, 0, 0, 0, "odd/even rows on alternate refreshes, missing rows black"},
    {"bfi", F, PLAIN_BFI, 0, 1, 1, 0, 0, 0, "half rate, black frame inserted every other refresh"},
    {"full60", F, PLAIN_FULL, 0, 1, 1, 60, 0, 0, "full frames at 60 Hz"},
};
#undef F

static int plain_init(sim_mode_t *m, const tdc_sim_setup_t *s)
{
    (void)s;
    if (m->d->variant == PLAIN_INTERLACE) {
        m->fam = calloc(m->npx * 3, 1); /* the field's rows as traced */
        return m->fam ? 0 : -1;
    }
    return 0;
}

static int plain_frame(sim_mode_t *m, tdc_source_t *src, double t, int spp, uint32_t lf)
{
    int even = (lf & 1u) == 0u;
    if (m->d->variant == PLAIN_INTERLACE) {
        tdc_sim_render_rows(m, src, t, spp, (int)(lf & 1u), m->fam);
        tdc_sim_link_count_raw(m->link, (size_t)m->w * ((m->h + 1 - (int)(lf & 1u)) / 2) * 3);
        memcpy(m->wanted, m->render, m->npx * 3);
        return 0;
    }
    if (!even && m->d->variant != PLAIN_FULL) {
        if (m->d->variant == PLAIN_BFI) {
            memset(m->wanted, 0, m->npx * 3); /* the controller inserts black */
        }                                     /* HALF: the controller repeats the last frame */
        return 0;
    }
    tdc_sim_render_full(m, src, t, spp, 0, 0, NULL, 0, TDC_MV_SURFACE);
    return tdc_sim_send_full(m, lf, m->render);
}

static void plain_free(sim_mode_t *m)
{
    free(m->fam);
    m->fam = NULL;
}

const tdc_sim_family_t tdc_sim_family_plain = {
    "plain", k_modes, (int)(sizeof(k_modes) / sizeof(k_modes[0])), plain_init, plain_frame, NULL, plain_free,
};
