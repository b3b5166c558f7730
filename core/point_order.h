// The order of a point cloud that both point-based gatherers build on (no GL here):
//   - micro-rendering (Ritschel et al. 2009, §2.1, "Point Hierarchy Generation"): "determine along which
//     coordinate axis the point list has the largest extent, sort all points along this axis, split the
//     list into two parts with an equal number of points, and recursively process both sub-lists": the
//     order of the list then IS the complete binary tree (leaf j is heap node n + j, the children of node
//     i are 2i and 2i + 1, the root is 1);
//   - importance-driven point projection (Maletz, Wang & Bowers 2011, §4 "Clustering Scene Points"): the
//     first 9 levels of the same kd-tree cut the list into 512 equal clusters, contiguous in this order.
// One order serves both: after medianSplitOrder(positions, L) every run of n / 2^l consecutive points,
// l <= L, is one node of level l.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/surface_points.h"

namespace bounce::core {

// The axis rule of each split: the paper of micro-rendering splits every sub-list along its own longest
// axis; point projection starts with the longest axis and then "repeatedly splits each sub-cluster along a
// different axis" (the next axis in x, y, z order after its parent's).
enum class SplitAxis { Longest, Cycle };

// A permutation of [0, positions.size()): levels of median splits (each sub-list split into halves whose
// sizes differ by at most one: the lower half gets floor(m / 2)), after which every sub-list keeps its
// current order. Deterministic (ties broken by index). levels may exceed log2(n): splits stop at single
// points. Non-finite positions are ordered as if at the origin.
std::vector<std::uint32_t> medianSplitOrder(const std::vector<glm::vec3>& positions, int levels,
                                            SplitAxis rule = SplitAxis::Longest);

// The surface points in that order (positions from evaluateSurfacePoint on `scene`): the order of the
// shared point cloud (gl/frame/points/point_cloud.h).
std::vector<SurfacePoint> orderSurfacePoints(const Scene& scene, const std::vector<SurfacePoint>& points, int levels,
                                             SplitAxis rule = SplitAxis::Longest);

// log2 of a power of two; -1 otherwise.
int exactLog2(std::uint64_t n);

} // namespace bounce::core
