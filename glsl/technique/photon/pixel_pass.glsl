// What the photon family's passes that add light at every pixel share (photon_caustic.comp,
// photon_glossy.comp; one invocation per pixel): the pixel's shading point from the G-buffer, and the
// addition to the indirect light that the interpolation (photon_interpolate.*) wrote before them.
#ifndef BOUNCE_PHOTON_PIXEL_PASS_GLSL
#define BOUNCE_PHOTON_PIXEL_PASS_GLSL

#include "common/gbuffer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform image2D target;

uniform ivec2 viewport;
uniform vec3 cameraPosition;

// A pixel's shading point: its surface point x, shading normal n, the unit direction wo towards the
// camera, and its BRDF.
struct PixelPoint {
    ivec2 q;
    vec3 x, n, wo;
    BrdfParams b;
};

// This invocation's pixel; false outside the viewport and on the background, where nothing is added.
bool loadPixelPoint(out PixelPoint s)
{
    s.q = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(s.q, viewport))) return false;
    GSurface g = gbufferSurface(s.q);
    if (!g.geometry) return false;
    s.b = gbufferBrdf(s.q);
    s.x = g.position;
    s.n = g.normal;
    s.wo = normalize(cameraPosition - s.x);
    return true;
}

// Adds radiance to pixel q's indirect light.
void addToPixel(ivec2 q, vec3 radiance)
{
    vec4 before = imageLoad(target, q);
    imageStore(target, q, vec4(before.rgb + radiance, before.a));
}

#endif
