#include "gl/frame/shader_costs.h"

#include "gl/frame/frame.h"

namespace bounce::gl {

PassCost shadowLookupCost(const Frame& frame)
{
    const int r = frame.sampler().sampleIndex() > 0 ? 0 : frame.settings().pcfRadius;
    const double texels = 4.0 * (r + 1) * (r + 1);
    PassCost c;
    c.flops = 75 + 3.5 * texels;
    c.fetches = texels;
    c.bytesRead = texels * 4;
    c.uniformWords = 24;
    return c;
}

PassCost directLightsCost(const Frame& frame, double punctual, double area)
{
    const PassCost shadow = shadowLookupCost(frame);
    PassCost c;
    c.flops = punctual * (60 + shadow.flops) + area * (250 + shadow.flops);
    c.fetches = (punctual + area) * shadow.fetches;
    c.bytesRead = (punctual + area) * shadow.bytesRead;
    c.uniformWords = punctual * (16 + shadow.uniformWords) + area * (16 + 12 + shadow.uniformWords);
    return c;
}

} // namespace bounce::gl
