#version 450 core
// Multiresolution splatting [NW09] (technique multires-splat): the list of valid fragments drawn as points,
// one instance per VPL of the bound block of the VPL cache, each point the light of that VPL at that
// patch (Eqs. 1 and 5 without the receiver's rho_i, as the gather writes it) scattered to the patch's texel
// of the flattened multiresolution buffer and added there by blending.
#include "technique/isr/vpl.glsl"

layout(location = 0) in vec4 positionTexelX; // technique/isr/multires_refine.comp: SplatVertex
layout(location = 1) in vec4 normalTexelY;

uniform vec2 bufferSize; // the flattened buffer, texels

flat out vec3 vLight;

void main()
{
    vLight = vplContribution(vplBlock[gl_InstanceID], positionTexelX.xyz, normalTexelY.xyz, vec3(1.0));
    vec2 texel = vec2(positionTexelX.w, normalTexelY.w) + 0.5;
    gl_Position = vec4(texel / bufferSize * 2.0 - 1.0, 0.0, 1.0); // a one-pixel point covers that texel
}
