#version 450 core
// Display: radiance x 2^exposure, clamped, sRGB-encoded (the PNG writer applies the same curve).
#include "common/bindings.glsl"
layout(binding = UNIT_TONEMAP_RADIANCE) uniform sampler2D radiance;
uniform float exposureStops;
in vec2 vUv;
layout(location = 0) out vec4 outColor;
vec3 srgb(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
void main() { outColor = vec4(srgb(texture(radiance, vUv).rgb * exp2(exposureStops)), 1.0); }
