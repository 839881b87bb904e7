/*
 * tdc_sim_heatmap.h - the judge's visible-difference map: where FovVideoVDP
 * (metrics/tdc_fvvdp.h) sees the difference, per pixel, mean over the
 * pooled refreshes of one mode and eye (simulator/tdc_sim_jod.c).
 *
 * Definition (FovVideoVDP's heat map, paper section 3 and the reference's
 * "raw" map): each frame's masked difference D of every band (the sustained
 * channel plus the transient one weighted 0.25, as the pooling weighs them)
 * is collapsed to the image's resolution as a Laplacian pyramid is
 * reconstructed (expand the coarser level, add the band; the baseband
 * carries no D), then put through the JOD regression pixel by pixel:
 * dmap = 10 - JOD(D), the JOD drop the whole view would have if every pixel
 * differed as this one.  0 is no visible difference, 1 about one JOD.
 *
 * Picture (heatmap_<mode>.png): the reference's mean luminance as grey
 * context (log luminance, min..max of the frame -> 15..65 % grey), tinted
 * by dmap: hue green (0) -> yellow (1.5) -> red (3 JOD or more), weight
 * min(1, dmap / 0.5), so differences well below 0.1 JOD leave the context
 * grey and every pixel at 0.5 JOD or more shows its hue alone.  One fixed
 * scale for every mode and run (the reference clamps its map to [0, 1] and
 * would saturate here: a BFI pixel loses 2-3 JOD).  Colours are tdc's own.
 */
#ifndef TDC_SIM_HEATMAP_H
#define TDC_SIM_HEATMAP_H

#include <stddef.h>

typedef struct tdc_sim_heatmap tdc_sim_heatmap_t;

/* A map of w x h pixels for the metric's pyramid at ppd (px/deg of the view
 * centre, tdc_fvvdp_ppd).  NULL when out of memory or the pyramid has no
 * band. */
tdc_sim_heatmap_t *tdc_sim_heatmap_new(int w, int h, double ppd);
/* The band planes, zeroed, for tdc_fvvdp_set_dmap before a frame. */
double *const *tdc_sim_heatmap_bands(tdc_sim_heatmap_t *hm);
/* After that frame: collapses its bands into the pixel map and adds it (and
 * ref_y, the reference's luminance in cd/m^2, the context) to the means. */
void tdc_sim_heatmap_add(tdc_sim_heatmap_t *hm, const float *ref_y);
/* Frames added so far. */
int tdc_sim_heatmap_frames(const tdc_sim_heatmap_t *hm);
/* The mean map (w x h, JOD drop per pixel; NULL before any frame). */
const double *tdc_sim_heatmap_map(const tdc_sim_heatmap_t *hm);
/* The picture as an 8-bit RGB PNG at path.  0, or -1 with the reason in
 * err. */
int tdc_sim_heatmap_write(const tdc_sim_heatmap_t *hm, const char *path, char *err, size_t errlen);
void tdc_sim_heatmap_free(tdc_sim_heatmap_t *hm);

#endif
