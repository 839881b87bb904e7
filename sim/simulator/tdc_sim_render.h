/*
 * tdc_sim_render.h - the Embree companion renderer (render, tdc-render)
 * as a simulator source.  Full frames (1 primary ray per pixel centre, Whitted
 * shading), motion vectors and supersampled ground truth come from the
 * renderer; the eye pursues the motion at the image centre (renderer probe).
 * Scene time t maps to renderer frame floor(t * clock_hz) of a scene whose
 * fps is set to the run clock.
 */
#ifndef TDC_SIM_RENDER_H
#define TDC_SIM_RENDER_H

#include <stddef.h>

#include "render/tdc_render.h" /* TDC_FOV_LOD_* (header only: no Embree needed) */
#include "simulator/tdc_sim_scene.h"

/* name: a built-in renderer scene (discs text panorama room mirror fence
 * bigmesh glossy blocker) or a scene file path.  NULL with a message in err if
 * the scene does not load.  eye_x: this eye's camera
 * offset along the camera's right vector in scene units (stereo: +-IPD/2). */
tdc_source_t *tdc_sim_render_source(const char *name, int w, int h, int clock_hz, int gt_samples, int threads,
                                    double eye_x, char *err, size_t errlen);
/* Before the first frame: time 0 of the run is the scene's frame start_frame
 * (a multiple of 4, so the subframe cycle stays aligned), reflected MVs
 * at mirror hits on (1, the default) or off (primary MVs, TDRT Fig. 6 left),
 * and the renderer's seed (tdc-sim -S: every random number of the renderer,
 * i.e. glossy and area-light samples and the ground truth's stratification). */
void tdc_sim_render_options(tdc_source_t *s, long start_frame, int reflect_mv, int fov_lod, uint32_t seed);

#endif
