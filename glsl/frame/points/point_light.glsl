// The outgoing radiance of a diffuse surface point lit directly by the scene's lights through the frame's
// shadow maps (common/lighting.glsl): (c_diff / pi) E, for the point light pass and for any other point a
// gather finds (micro-rendering's ray-cast micro-pixels). Define PUNCTUAL_LIGHTS / AREA_LIGHTS for the
// kinds the scene has; the uniforms are the direct pass's.
#ifndef BOUNCE_POINT_LIGHT_GLSL
#define BOUNCE_POINT_LIGHT_GLSL

#include "common/lighting.glsl"

uniform int punctualLightCount; // lights [0, punctualLightCount): point, spot, directional
uniform int lightCount;         // lights [punctualLightCount, lightCount): emitting triangles

// The points reflect diffusely (micro-rendering §2.2: "when using only diffuse surfaces, we can store the
// reflected radiance inside the point hierarchy"): the BRDF's diffuse lobe alone, seen along the normal.
vec3 pointDirectRadiance(vec3 p, vec3 n, vec3 diffuse)
{
    BrdfParams b;
    b.diffuse = diffuse;
    b.f0 = vec3(0.0);
    b.weight = 0.0;
    b.alpha = 1.0;
    vec3 radiance = vec3(0.0);
    if (max(diffuse.r, max(diffuse.g, diffuse.b)) <= 0.0) return radiance;
#ifdef PUNCTUAL_LIGHTS
    for (int i = 0; i < punctualLightCount; ++i) radiance += directFromPunctual(lights[i], p, n, n, b);
#endif
#ifdef AREA_LIGHTS
    for (int i = punctualLightCount; i < lightCount; ++i) radiance += directFromAreaTriangle(lights[i], p, n, n, b);
#endif
    return radiance;
}

#endif
