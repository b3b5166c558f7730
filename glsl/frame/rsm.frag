#version 450 core
// Reflective shadow map texel (layout in common/rsm.glsl): world position, normal, light-space
// depth, and the flux the texel's surface reflects, rho_j Phi_j, with Phi_j the flux the light sends
// through the texel's solid angle omega_t.
// Units: spot/point intensity I is in W/sr, so Phi_t = I(omega) omega_t with omega_t in steradians. The
// paper's Eq. 2, I_j = I omega_j / (4 pi), reads I as the light's total intensity normalised over the
// sphere; ours is already per steradian, so no 4 pi appears. Directional lights: Phi_t = E A_perp, with E
// in W/m^2 and A_perp the texel's area perpendicular to the light. Area lights: their emitting mesh is a
// cosine-lobe point emitter at its centroid, I(omega) = sum_k L_k A_k max(N_k . omega, 0) (a departure:
// the paper has only spot lights).
#include "common/brdf.glsl"
#include "common/scene.glsl"
#include "common/base_color.glsl"

in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;
flat in uint vMaterial;

layout(binding = UNIT_RSM_SOLID_ANGLES) uniform sampler2DArray texelSolidAngles; // exact omega_t per texel, one layer per view

uniform int lightIndex;        // spot, point, directional: frameLight(lightIndex)
uniform int areaFirst;         // area emitter: its triangles are frameLight(areaFirst .. areaFirst + areaCount - 1)
uniform int areaCount;
uniform vec3 viewOrigin;
uniform vec3 viewDirection;    // orthographic: the direction light travels
uniform int orthographic;
uniform float orthoTexelArea;  // m^2, perpendicular to the light
uniform int exactSolidAngle;   // 1: texelSolidAngles, 0: Eq. 4 (every texel omega_frustum / size^2)
uniform int viewLayer;
uniform float equalSolidAngle;

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outFlux;
layout(location = 3) out vec2 outDepthRange;
layout(location = 4) out vec4 outNormalMin;
layout(location = 5) out vec4 outNormalMax;

// Intensity (W/sr) the light sends along unit direction w; irradiance (W/m^2) for directional lights.
vec3 lightIntensity(vec3 w)
{
    if (areaCount > 0) {
        vec3 sum = vec3(0.0);
        for (int i = areaFirst; i < areaFirst + areaCount; ++i) {
            Light t = frameLight(i);
            int first = t.shadow.z;
            vec3 a = lightPolygon(first), b = lightPolygon(first + 1), c = lightPolygon(first + 2);
            float area = 0.5 * length(cross(b - a, c - a));
            sum += t.intensity * area * max(dot(t.direction, w), 0.0);
        }
        return sum;
    }
    Light l = frameLight(lightIndex);
    int type = l.type;
    if (type == kLightSpot) return l.intensity * spotWeight(l, dot(w, l.direction));
    return l.intensity;
}

void main()
{
    Material m = materials[vMaterial];
    vec3 n = normalize(vNormal);
    vec4 texel = baseColorTexel(m, vUv);
#ifdef ALPHA_MASK
    if (alphaCutOut(m, texel.a)) discard; // light passes through the hole: no texel, no VPL
#endif
    vec3 baseColor = m.baseColorMetallic.rgb * texel.rgb;
    vec3 rho = baseColor * (1.0 - m.baseColorMetallic.a); // the diffuse colour, as in the G-buffer
    bool reflects = true;
    if (!gl_FrontFacing) {
        if (m.flags.y != 0) n = -n;
        else reflects = false; // the back of a one-sided surface is black
    }

    vec3 toLight;
    float depth, omega, texelArea;
    vec3 incident; // Phi_t, the flux reaching the texel's surface (W)
    if (orthographic != 0) {
        toLight = -viewDirection;
        depth = dot(vPosition - viewOrigin, viewDirection);
        omega = 0.0;
        texelArea = orthoTexelArea;
        incident = lightIntensity(viewDirection) * orthoTexelArea;
    } else {
        vec3 d = vPosition - viewOrigin;
        depth = length(d);
        toLight = -d / max(depth, 1e-30);
        omega = exactSolidAngle != 0 ? texelFetch(texelSolidAngles, ivec3(ivec2(gl_FragCoord.xy), viewLayer), 0).r : equalSolidAngle;
        texelArea = omega * depth * depth; // Eq. 3
        incident = lightIntensity(-toLight) * omega;
    }
    // Surfaces facing away from the light reflect nothing.
    if (dot(n, toLight) <= 0.0) reflects = false;
    vec3 reflected = reflects ? rho * incident : vec3(0.0);
    bool lit = max(reflected.r, max(reflected.g, reflected.b)) > 0.0;

    outPosition = vec4(vPosition, 1.0);
    outNormal = vec4(n, lit ? texelArea : 0.0);
    outFlux = vec4(reflected, lit ? omega : 0.0);
    outDepthRange = vec2(depth);
    outNormalMin = vec4(n, 0.0);
    outNormalMax = vec4(n, 0.0);
}
