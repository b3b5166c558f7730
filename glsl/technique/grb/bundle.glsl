// One global ray-bundle (Hermes et al. 2010, Sec. 3, Fig. 4): parallel rays along bundleDir through an
// orthographic view over the scene's bounding sphere, kbufferSize^2 pixels, the grid shifted by a
// sub-pixel jitter per direction. Depth is the distance along bundleDir from the sphere's near side.
#ifndef BOUNCE_GRB_BUNDLE_GLSL
#define BOUNCE_GRB_BUNDLE_GLSL

uniform vec3 bundleDir;   // unit: the rays travel along it, depth grows along it
uniform vec3 bundleRight; // unit, orthogonal to bundleDir: the k-buffer's x axis
uniform vec3 bundleUp;    // unit: its y axis
uniform vec3 bundleCentre;
uniform float bundleRadius;
uniform int kbufferSize;
uniform vec2 bundleJitter; // pixels

float bundleDepth(vec3 p) { return dot(p - bundleCentre, bundleDir) + bundleRadius; }

// Continuous k-buffer pixel coordinates of p (pixel (i, j) covers [i, i+1) x [j, j+1)).
vec2 bundlePixel(vec3 p)
{
    vec3 r = p - bundleCentre;
    return (vec2(dot(r, bundleRight), dot(r, bundleUp)) + bundleRadius) / (2.0 * bundleRadius) * float(kbufferSize) +
           bundleJitter;
}

// The world offset, across the bundle, from p to the centre of its pixel.
vec2 bundleOffsetToPixelCentre(vec3 p, ivec2 px)
{
    return (vec2(px) + 0.5 - bundlePixel(p)) * (2.0 * bundleRadius / float(kbufferSize));
}

#endif
