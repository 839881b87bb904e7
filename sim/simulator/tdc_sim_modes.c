/* tdc_sim_modes.c - the mode table and which parts of the data path exist. */
#include <string.h>

#include "simulator/tdc_sim.h"
#include "tdc_sim_features.h"

static const tdc_mode_desc_t k_modes[] = {
    {"full", TDC_MODE_FULL, 1, 1, 0, 0, 0, "every refresh rendered at full resolution (reference cost)"},
    {"half", TDC_MODE_HALF, 1, 1, 0, 0, 0, "half frame rate, each frame shown twice"},
    {"interlace", TDC_MODE_INTERLACE, 1, 1, 0, 0, 0, "odd/even rows on alternate refreshes, missing rows black"},
    {"bfi", TDC_MODE_BFI, 1, 1, 0, 0, 0, "half rate, black frame inserted every other refresh"},
    {"ncsfi", TDC_MODE_NCSFI, 1, 2, 0, 0, 0,
     "half rate; sharpened + blurred frame pair from one frame, residual always added"},
    {"trm50", TDC_MODE_TRM, 1, 2, 0, 0, 0, "TRM, every other frame at r = 1/2"},
    {"trm40", TDC_MODE_TRM, 2, 5, 0, 0, 0, "TRM, every other frame at r = 0.4"},
    {"trm25", TDC_MODE_TRM, 1, 4, 0, 0, 0, "TRM, every other frame at r = 1/4"},
    {"asw", TDC_MODE_ASW, 1, 1, 0, 0, 0, "half rate, in-between frame warped by motion vectors (ASW style)"},
    {"asm-hourglass", TDC_MODE_ASM, 1, 1, 0, 0, 0, "tile-ordered assembly, hourglass only"},
    {"asm-bowtie", TDC_MODE_ASM, 1, 1, 0, 1, 0, "tile-ordered assembly, bowtie only"},
    {"asm-adaptive", TDC_MODE_ASM, 1, 1, 0, -1, 0, "tile-ordered assembly, adaptive orderings"},
    {"asm-hourglass-smv", TDC_MODE_ASM, 1, 1, 0, 0, 1, "assembly, hourglass, shadow + dual MVs"},
    {"asm-bowtie-smv", TDC_MODE_ASM, 1, 1, 0, 1, 1, "assembly, bowtie, shadow + dual MVs"},
    {"asm-adaptive-smv", TDC_MODE_ASM, 1, 1, 0, -1, 1, "assembly, adaptive, shadow + dual MVs"},
    {"full60", TDC_MODE_FULL, 1, 1, 60, 0, 0, "full frames at 60 Hz"},
    {"taa60", TDC_MODE_TAA, 1, 1, 60, 0, 0, "60 Hz, jittered 1 spp with TAA (reprojection, clamp, blend 0.1)"},
};

const tdc_mode_desc_t *tdc_sim_modes(int *n)
{
    *n = (int)(sizeof(k_modes) / sizeof(k_modes[0]));
    return k_modes;
}

const tdc_mode_desc_t *tdc_sim_mode_find(const char *name)
{
    int n;
    const tdc_mode_desc_t *m = tdc_sim_modes(&n);
    for (int i = 0; i < n; i++) {
        if (strcmp(m[i].name, name) == 0) {
            return &m[i];
        }
    }
    return NULL;
}

void tdc_sim_parts(tdc_sim_parts_t *p)
{
    p->trm = TDC_SIM_HAVE_TRM;
    p->link = TDC_SIM_HAVE_LINK;
    p->assemble = TDC_SIM_HAVE_ASM;
    p->lcd_fw = TDC_SIM_HAVE_LCD_FW;
    p->lcd_phys = TDC_SIM_HAVE_LCD_PHYS;
}

void tdc_sim_default_config(tdc_sim_config_t *c)
{
    memset(c, 0, sizeof(*c));
    c->scene.kind = TDC_SCENE_PAN;
    c->scene.speed = -1.0;
    c->scene.pursuit = 1;
    c->scene.cut_time = -1.0;
    c->width = 160;
    c->height = 120;
    c->refresh_hz = 90;
    c->duration_s = 0.5;
    c->panel = TDC_PANEL_SIM_OLED;
    c->lcd_mode = 1; /* TDC_LCD_MODE_EXACT, as before the mode was selectable */
    c->lcd_bits = 8;
    c->backlight = -1;
    c->strobe_duty = 0.3;
    c->strobe_phase = 0.7;
    c->persistence = -1.0;
    c->pursuit_gain = 1.0;
    c->metric_every = 1;
    c->flip_ppd = 67.0206;
    c->progress = 1;
    c->strip_at = -1;
    c->seed = 1;
}
