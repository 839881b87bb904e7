/* tdc_sim_modes.c - the mode families, the run defaults and which parts of the data path exist. */
#include <string.h>

#include "ref_fov.h" /* TDC_FOV_LOD_*, TDC_FOV_JITTER_* */
#include "simulator/tdc_sim.h"
#include "simulator/tdc_sim_mode.h"

/* The mode families, in the order --list and 'all' show them.  A new
 * family is one file (tdc_sim_mode.h) and one line here. */
static const tdc_sim_family_t *const k_families[] = {
    &tdc_sim_family_plain,
    &tdc_sim_family_trm,
    &tdc_sim_family_warp,
    &tdc_sim_family_asm,
    &tdc_sim_family_layers,
    &tdc_sim_family_fov,
    &tdc_sim_family_fovtrm,
};

#define MAX_MODES 64

const tdc_mode_desc_t *const *tdc_sim_modes(int *n)
{
    static const tdc_mode_desc_t *all[MAX_MODES];
    static int count = -1;
    if (count < 0) {
        int k = 0;
        for (size_t f = 0; f < sizeof(k_families) / sizeof(k_families[0]); f++) {
            for (int i = 0; i < k_families[f]->nmodes && k < MAX_MODES; i++) {
                all[k++] = &k_families[f]->modes[i];
            }
        }
        count = k;
    }
    *n = count;
    return all;
}

const tdc_mode_desc_t *tdc_sim_mode_find(const char *name)
{
    int n;
    const tdc_mode_desc_t *const *m = tdc_sim_modes(&n);
    for (int i = 0; i < n; i++) {
        if (strcmp(m[i]->name, name) == 0) {
            return m[i];
        }
    }
    return NULL;
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
    c->gaze = 0; /* TDC_GAZE_PURSUIT */
    c->gaze_at_x = c->gaze_at_y = -1.0;
    c->fov_alpha = 4.0;
    c->fov_delta = 0.555;
    c->fov_disk = 0.12443;
    c->fov_lod = TDC_FOV_LOD_FOOTPRINT;
    c->fov_jitter = TDC_FOV_JITTER_PIXEL;
}
