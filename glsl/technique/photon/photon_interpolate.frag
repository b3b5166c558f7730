#version 450 core
// The interpolation of the samples' irradiance to every pixel (photon_interpolate.glsl) as a full-screen
// triangle into the frame's indirect target.
#include "technique/photon/photon_interpolate.glsl"

layout(location = 0) out vec4 outRadiance;

void main() { outRadiance = interpolatedRadiance(ivec2(gl_FragCoord.xy)); }
