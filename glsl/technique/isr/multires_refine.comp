#version 450 core
// Multiresolution splatting [NW09], the refinement that §3.2.1 replaces with one stencil pass (technique
// multires-splat, for the paper's Table 1): one dispatch per level, coarsest first. The first takes every
// patch of the coarsest level (CoarseImageSampling); each later one takes the list the previous one wrote.
// A patch with a discontinuity is replaced by its four children (SubdivideIntoFour, appended to the next
// level's list); a patch without one stays: it is a valid multiresolution fragment, the same set the
// stencil pass selects (common/multires.glsl). A valid fragment is counted, marked in the
// illumination buffer's alpha exactly as the stencil pass marks it (for the upsampling), and, unless it
// reflects nothing, appended to the splat list: the vertex array every VPL's splat draws.
#include "technique/isr/bindings.glsl"
#include "common/multires.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_ISR_FRAGMENT_COUNTS) buffer FragmentCounts { uint fragmentCounts[]; };
layout(std430, binding = SSBO_ISR_WORK_IN) readonly buffer WorkIn { uint workIn[]; };   // patches x | y << 16
layout(std430, binding = SSBO_ISR_WORK_OUT) writeonly buffer WorkOut { uint workOut[]; };
layout(std430, binding = SSBO_ISR_REFINE_COUNTS) buffer RefineCounts { uint nextCount; uint splatCount; };
// One vertex per valid fragment: the patch's mean position and unit normal, its texel in the flattened buffer.
struct SplatVertex {
    vec4 positionTexelX;
    vec4 normalTexelY;
};
layout(std430, binding = SSBO_ISR_SPLAT_VERTICES) writeonly buffer SplatVertices { SplatVertex splatVertices[]; };
layout(rgba32f, binding = 0) uniform writeonly image2D marksOut; // the illumination buffer (cleared)

uniform int level;   // the level of this dispatch's patches
uniform int inCount; // patches in workIn; -1: every patch of the level (the first, coarsest dispatch)

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    ivec2 t;
    if (inCount < 0) {
        if (i >= levelSize[level].x * levelSize[level].y) return;
        t = ivec2(i % levelSize[level].x, i / levelSize[level].x);
    } else {
        if (i >= inCount) return;
        t = ivec2(workIn[i] & 0xffffu, workIn[i] >> 16);
    }
    float state = patchState(level, t);
    if (state == kPatchEmpty) return;
    if (state == kPatchDiscontinuous) {
        for (int k = 0; k < 4; ++k) {
            ivec2 c = 2 * t + ivec2(k & 1, k >> 1);
            if (levelContains(level - 1, c)) workOut[atomicAdd(nextCount, 1u)] = uint(c.x) | uint(c.y) << 16;
        }
        return;
    }
    atomicAdd(fragmentCounts[level], 1u);
    ivec2 a = levelOrigin[level] + t;
    imageStore(marksOut, a, vec4(0.0, 0.0, 0.0, 1.0 + float(sameSurfaceNeighbours(level, t))));
    MultiresPatch p = loadPatch(level, t);
    float len = length(p.normal);
    if (len > 0.0 && max(p.diffuse.r, max(p.diffuse.g, p.diffuse.b)) > 0.0) // as the gather: black reflects nothing
        splatVertices[atomicAdd(splatCount, 1u)] = SplatVertex(vec4(p.position, float(a.x)), vec4(p.normal / len, float(a.y)));
}
