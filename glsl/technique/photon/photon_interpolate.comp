#version 450 core
// The interpolation of the samples' irradiance to every pixel (photon_interpolate.glsl) as a compute pass,
// one invocation per pixel, into the frame's indirect texture.
#include "technique/photon/photon_interpolate.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform writeonly image2D target;

void main()
{
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(q, viewport))) return;
    imageStore(target, q, interpolatedRadiance(q));
}
