#version 450 core
// Each pixel keeps the line of the bounding edge nearest its centre (edges.geom): the depth test on
// gl_FragDepth, the distance scaled, keeps the least. An edge behind the plane of what the G-buffer sees at
// the pixel (by more than 1% of its eye depth) is hidden there and writes nothing; an edge of the visible
// surface itself, or in front of it (a silhouette over the background), does. The plane, not the depth: the
// pixel beside an edge of a surface seen at a grazing angle lies far nearer than the edge.
#include "common/gbuffer.glsl"

in vec3 gWorld;
flat in vec3 gLine;

layout(location = 0) out vec4 outEdge; // the edge's unit normal out of its triangle, the signed distance, 1

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    if (gbufferHasGeometry(px)) {
        vec3 seen = gbufferPosition(px), n = gbufferNormal(px);
        if (dot(n, seen - gbufferCamera.origin.xyz) > 0.0) n = -n; // towards the camera
        if (dot(n, gWorld - seen) < -0.01 * gbufferEyeDepth(px)) discard;
    }
    float s = dot(gLine, vec3(gl_FragCoord.xy, 1.0));
    gl_FragDepth = min(abs(s) * 0.25, 1.0);
    outEdge = vec4(-gLine.xy, s, 1.0);
}
