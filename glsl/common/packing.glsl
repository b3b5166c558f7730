// Packings shared by the frame and the families.
#ifndef BOUNCE_PACKING_GLSL
#define BOUNCE_PACKING_GLSL

// A unit vector as two numbers in [-1, 1] (octahedral map; 2 x 16-bit snorm keeps it to about 1e-4 rad).
vec2 octEncode(vec3 n)
{
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    vec2 e = n.xy;
    if (n.z < 0.0) e = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return e;
}
vec3 octDecode(vec2 e)
{
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return normalize(n);
}
uint packUnitVector(vec3 n) { return packSnorm2x16(octEncode(n)); }
vec3 unpackUnitVector(uint v) { return octDecode(unpackSnorm2x16(v)); }

#endif
