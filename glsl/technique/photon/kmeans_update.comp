#version 450 core
// k-means, update (section 3.2): each centre becomes its members' mean position and normal, summed over
// its segment of the sorted pixels in order (a segmented reduction: the same sums in every run). An empty
// cluster keeps its centre and drops out (no members: no tree leaf, no sample). A mean normal that
// cancels (members facing opposite ways) keeps the previous one. Clusters kept from the previous frame
// (k < fixedClusters) keep their centres: temporal reuse fixes them (section 3.2).
#include "technique/photon/kmeans_members.glsl"

uniform uint fixedClusters;

void main()
{
    uint k = gl_GlobalInvocationID.x;
    if (k >= clusterCount) return;
    Cluster c = clusters[k];
    uvec2 range = takeMembers(k);
    if (range.y <= range.x) return;
    if (k < fixedClusters) {
        clusters[k].centre.w = float(range.y - range.x);
        return;
    }
    vec3 position = vec3(0.0), normal = vec3(0.0);
    for (uint j = range.x; j < range.y; ++j) {
        GSurface s = gbufferSurface(memberPixel(sortedPixels[j]));
        position += s.position;
        normal += s.normal;
    }
    float count = float(range.y - range.x);
    clusters[k].centre = vec4(position / count, count);
    clusters[k].normal.xyz = meanNormal(normal, count, c.normal.xyz);
}
