// Storage names (100-119) and texture units of the global ray-bundles' own buffers and textures, for GLSL
// and C++ alike (gl/technique/grb/bindings.h includes this file); the units are those
// glsl/common/bindings.glsl leaves to techniques. Only #define lines and comments.
#ifndef BOUNCE_GRB_BINDINGS_GLSL
#define BOUNCE_GRB_BINDINGS_GLSL

#define SSBO_GRB_ATLAS_CORNERS 100  // atlas.glsl: three atlas corners (texels) per scene triangle
#define SSBO_GRB_STATS 101          // kbuffer_stats.frag: overflow pixels, largest depth complexity
#define SSBO_GRB_TRIANGLE_CHART 102 // atlas_fill.frag: the chart of every scene triangle
#define UNIT_GRB_POSITION 21        // atlas.glsl: world position, w: material index + 1 (0: empty)
#define UNIT_GRB_NORMAL 22          // atlas.glsl: shading normal, w: the face normal, packed
#define UNIT_GRB_BASE_COLOR 23      // atlas.glsl: base colour (texture included), w: chart + 1
#define UNIT_GRB_SEED 24            // direct_seed.frag: punctual light's diffuse irradiance / pi
#define UNIT_GRB_SENDER_DIRECT 25   // transfer.frag: the sender atlas, light from emitters (sum, count)
#define UNIT_GRB_SENDER_INDIRECT 26 // transfer.frag: the sender atlas, reflected light (sum, count)
#define UNIT_GRB_SENDER_GLOSSY 27   // transfer.frag: the glossy transfer atlas for this direction
#define UNIT_GRB_KBUFFER 28         // kbuffer.glsl: the entries (atlas texel + 1, depth)
#define UNIT_GRB_KBUFFER_COUNT 29   // kbuffer.glsl: fragments per pixel (atomic), overflow (peel)
#define UNIT_GRB_KBUFFER_STENCIL 30 // kbuffer.glsl: the routing stencil (stencil)
#define UNIT_GRB_FINAL_GLOSSY 31    // display.frag: the final glossy bounce at pixels (sum, count)

#endif
