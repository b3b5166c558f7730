#version 450 core
// Multiresolution splatting [NW09]: one VPL's light at one patch, added to the flattened buffer (rgb; the
// alpha channel keeps the refinement's marks).
flat in vec3 vLight;

layout(location = 0) out vec4 outIllumination;

void main() { outIllumination = vec4(vLight, 0.0); }
