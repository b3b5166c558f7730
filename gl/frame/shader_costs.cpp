#include "gl/frame/shader_costs.h"

#include "gl/frame/frame.h"

namespace bounce::gl {

PassCost shadowLookupCost(const Frame& frame)
{
    const int r = frame.sampler().stillIndex() > 0 ? 0 : frame.settings().pcfRadius;
    const double texels = 4.0 * (r + 1) * (r + 1);
    PassCost c;
    c.flops = 75 + 3.5 * texels;
    c.fetches = texels;
    c.bytesRead = texels * 4;
    c.uniformWords = 24;
    return c;
}

PassCost directLightsCost(const FrameSettings& settings, double punctual, double area)
{
    const double taps =
        double((2 * settings.pcfRadius + 1) * (2 * settings.pcfRadius + 1)) * (settings.pcfLinear ? 4.0 : 1.0);
    PassCost c;
    c.flops = punctual * (60 + 10 * taps) + area * (250 + 10 * taps);
    c.fetches = (punctual + area) * taps;
    c.bytesRead = (punctual + area) * taps * 4;
    return c;
}

} // namespace bounce::gl
