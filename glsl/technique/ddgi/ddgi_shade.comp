#version 450 core
// Every pixel's indirect light from the probes (Majercik et al. 2019, section 5.2): the irradiance of the
// eight probes around its surface (probes.glsl, ddgiIrradiance) reflected by the diffuse lobe, c_diff / pi
// times what the glossy interface lets through on the way out (toward the eye) and, on the way in, its
// mean over directions (the probes keep no direction of their light). DDGI carries diffuse
// interreflection only: no glossy lobe reflects the probes' light.
#define DDGI_SHADING
#include "common/gbuffer.glsl"
#include "technique/ddgi/probes.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform writeonly image2D indirectOut;

uniform ivec2 viewport;
uniform vec3 cameraPosition;

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, viewport))) return;
    vec3 radiance = vec3(0.0);
    GSurface s = gbufferSurface(px);
    BrdfParams b = gbufferBrdf(px);
    if (s.geometry && max(b.diffuse.r, max(b.diffuse.g, b.diffuse.b)) > 0.0) {
        vec3 wo = normalize(cameraPosition - s.position);
        radiance = b.diffuse / kPi * ddgiIrradiance(s.position, s.normal, wo) *
                   brdfTransmission(b, max(dot(s.normal, wo), 0.0)) * brdfMeanTransmission(b);
    }
    imageStore(indirectOut, px, vec4(radiance, 1.0));
}
