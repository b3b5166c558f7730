// Error figures written again in the app tests, apart from core/metrics.h, so that a test of the figures
// the commands report does not check them against themselves.
#pragma once

#include <cmath>
#include <cstddef>

#include "core/image.h"

namespace bounce::testing {

// sqrt(mean (a - r)^2) / mean(r) over every value, in double: the relative RMSE.
inline double relativeRmseOf(const core::Image& a, const core::Image& r)
{
    double se = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
        se += (double(a.rgb[i]) - r.rgb[i]) * (double(a.rgb[i]) - r.rgb[i]);
        sum += r.rgb[i];
    }
    return std::sqrt(se / double(a.rgb.size())) / (sum / double(a.rgb.size()));
}

} // namespace bounce::testing
