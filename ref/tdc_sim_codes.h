/*
 * tdc_sim_codes.h - what every simulator source does with a sample: panel
 * drive code from linear light, Q4 motion vector, the stratified grid of
 * spp rays (shared by the procedural scenes and the photograph source).
 * In ref/ because the references encode their outputs the same way
 * (ref_fov_lr.c): below both the references and the simulator.
 */
#ifndef TDC_SIM_CODES_H
#define TDC_SIM_CODES_H

#include <math.h>
#include <stdint.h>

/* Drive code of linear light lin under panel gamma: round(255 lin^(1/gamma)), lin clamped to [0, 1]. */
static inline uint8_t tdc_sim_encode_code(double lin, double gamma)
{
    lin = lin < 0.0 ? 0.0 : (lin > 1.0 ? 1.0 : lin);
    double c = 255.0 * pow(lin, 1.0 / gamma) + 0.5;
    return (uint8_t)(c >= 255.0 ? 255 : (int)c);
}

/* A displacement in pixels as a Q4 motion vector component, saturated to +-32767. */
static inline int16_t tdc_sim_mv_q4(double d)
{
    double q = floor(d * 16.0 + 0.5);
    return (int16_t)(q > 32767.0 ? 32767 : (q < -32767.0 ? -32767 : q));
}

/* Side g of the g x g stratified grid used for spp rays per pixel (g^2 <= spp). */
static inline int tdc_sim_spp_grid(int spp)
{
    int g = 1;
    while ((g + 1) * (g + 1) <= spp) {
        g++;
    }
    return g;
}

#endif
