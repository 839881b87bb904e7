/*
 * tdc_render_cones.h - incident radiance in 6 cones per pixel (Zeng et al.,
 * temporally reliable motion vectors, §4.3, eqs. 9-11): the renderer's
 * option `indirect` records each pixel's diffuse indirect sample into the
 * cones of its hemisphere, and a consumer reuses the previous pixel's cones
 * (found with the dual MV) cone by cone, weighted by the solid angle two
 * cones share, then re-shades.  Host reference code, double precision.
 *
 * Layout: 6 cones of equal solid angle pi/3 (half-angle acos(5/6) =
 * 33.56 deg, §4.3: "6 slightly overlapping cones with equal solid angles
 * pi/3"), one along the normal and five at 60 deg from it, 72 deg apart in
 * azimuth, in a tangent frame that depends only on the normal (so the cones
 * of two pixels with the same normal are the same world-space cones).
 * Neighbouring cones overlap by a few degrees; near the horizon between two
 * ring cones there are gaps, and a sample there goes to the nearest cone.
 *
 * Eqs. 9-10 print the apex angle pi/6, which as a half-angle gives cones of
 * 0.842 sr, not the pi/3 of §4.3 and eq. 11; the overlap below takes the
 * half-angle as a parameter (checked against Monte Carlo for both).  Eq. 11
 * as printed, f_r sum L_k pi/3, is the integral of L without the cosine of
 * the incident angle: twice the diffuse radiance under a uniform sky.
 * tdc_cones_shade weights each cone by its cosine-weighted solid angle
 * instead, normalised so that a uniform sky gives albedo * L (test).
 */
#ifndef TDC_RENDER_CONES_H
#define TDC_RENDER_CONES_H

#define TDC_CONES 6

/* cos of the half-angle of a cone of solid angle pi/3: 1 - 1/6 */
#define TDC_CONE_COS_HALF (5.0 / 6.0)

/* Cone axes of the hemisphere around the unit normal n (world space). */
void tdc_cones_axes(const double n[3], double axes[TDC_CONES][3]);

/* Eqs. 9-10: solid angle shared by two cones of half-angle `half` whose
 * axes are `alpha` apart (Mazonka 2012), 0 for alpha >= 2 half. */
double tdc_cones_overlap(double alpha, double half);

/* The same for pi/3 cones as a share of one cone's solid angle, from the
 * cosine of the angle between the axes (a table of the formula, linear
 * interpolation; what tdc_cones_reuse uses). */
double tdc_cones_overlap_share(double cos_alpha);

/* Records one incident sample (unit direction d, radiance L) into every
 * cone containing d (the nearest one if none): cone_L accumulates L,
 * cone_w counts.  Returns the number of cones that took it. */
int tdc_cones_record(const double axes[TDC_CONES][3], const double d[3], const double L[3],
                     double cone_L[TDC_CONES][3], double cone_w[TDC_CONES]);

/* Temporal reuse (§4.3): each current cone j takes the previous pixel's
 * cones k (axes pa, mean radiance pL, weights pw) weighted by the overlap
 * of cone j and cone k (eqs. 9-10) times pw_k, and blends that history
 * with its own sample mean: L_j = (a w_j L_j + (1 - a) h_j H_j) / (a w_j +
 * (1 - a) h_j), h_j the history's weight relative to the cone's own solid
 * angle.  cL / cw: the current cones' mean radiance and weight, updated in
 * place (cw becomes the blended weight).  a: the current frame's share. */
void tdc_cones_reuse(const double ca[TDC_CONES][3], double cL[TDC_CONES][3], double cw[TDC_CONES],
                     const double pa[TDC_CONES][3], const double pL[TDC_CONES][3], const double pw[TDC_CONES],
                     double a);

/* Re-shading (eq. 11 with the cosine): diffuse radiance albedo / pi *
 * sum_k L_k C_k, C_k the cosine-weighted solid angle of cone k, scaled so
 * that the C_k sum to pi.  Cones with weight 0 are left out and the rest
 * rescaled. */
void tdc_cones_shade(const double albedo[3], const double L[TDC_CONES][3], const double w[TDC_CONES],
                     double out[3]);

#endif
