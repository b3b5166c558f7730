// Closed-form form factors from a differential area to a parallel rectangle (Howell's catalogue of
// configuration factors, C-11), for tests that check irradiance from a rectangular emitter.
#pragma once

#include <cmath>

namespace bounce::testing {

// From a point to the rectangle [0, a] x [0, b] of a parallel plane at distance c, one corner straight
// above the point; odd in a and in b, so that any rectangle is a signed sum of four.
inline double cornerFormFactor(double a, double b, double c)
{
    const double ac = std::sqrt(a * a + c * c), bc = std::sqrt(b * b + c * c);
    return (a / ac * std::atan(b / ac) + b / bc * std::atan(a / bc)) / (2.0 * M_PI);
}

// From a point to the rectangle [x0, x1] x [z0, z1] (coordinates relative to the point) of a parallel
// plane at distance h.
inline double rectFormFactor(double x0, double x1, double z0, double z1, double h)
{
    if (x1 <= x0 || z1 <= z0) return 0.0;
    return cornerFormFactor(x1, z1, h) - cornerFormFactor(x0, z1, h) - cornerFormFactor(x1, z0, h) +
           cornerFormFactor(x0, z0, h);
}

} // namespace bounce::testing
