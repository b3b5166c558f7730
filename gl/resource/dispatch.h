// Compute dispatch by the size of the work rather than by group counts: the group count is the ceiling
// of size / localSize per axis, so every invocation inside `size` exists once; the invocations of the
// last, partial groups beyond `size` run too, and the shader must return early there
// (any(greaterThanEqual(gl_GlobalInvocationID, size))).
#pragma once

#include <cstddef>
#include <stdexcept>

#include <glm/glm.hpp>

namespace bounce::gl {

class Program;

struct DispatchError : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

// ceil(size / localSize) per axis. Throws DispatchError when a size or local size is zero or negative.
glm::ivec3 computeGroupCount(glm::ivec3 size, glm::ivec3 localSize);

// The invocations a dispatch of computeGroupCount(size, localSize) groups runs: the groups times the local
// size, the idle invocations of the partial groups included (what the driver counts, and what a pass declares
// to its timed scope: PassTimers::Scope::expectComputes).
double computeInvocations(glm::ivec3 size, glm::ivec3 localSize);

// Uses `program` and dispatches computeGroupCount(size, localSize) groups. Throws DispatchError, before
// any GL call that would fail, when a size is zero or negative, when localSize is not the program's
// declared local_size (GL_COMPUTE_WORK_GROUP_SIZE), or when a group count exceeds
// GL_MAX_COMPUTE_WORK_GROUP_COUNT on its axis, or when no buffer is bound under the storage name of one of
// the program's blocks (unboundStorage). The caller still issues the memory barrier it needs.
void dispatchCompute(const Program& program, glm::ivec3 size, glm::ivec3 localSize);

// The most work groups dispatchRows puts in one row: the least GL_MAX_COMPUTE_WORK_GROUP_COUNT a driver may
// have on an axis (GL 4.5, Table 23.75).
constexpr std::size_t kMaxRowGroups = 65535;

// Dispatches `groups` work groups of a one-dimensional program (local size localSize x 1 x 1) in rows of at
// most kMaxRowGroups groups, as many rows as it takes, so that a dispatch of millions of groups stays within
// every driver's limits; the shader finds its group with glsl/common/dispatch_rows.glsl's rowGroup() and
// returns past `groups` (the last row is filled up). Nothing when groups is 0. Throws DispatchError as
// dispatchCompute.
void dispatchRows(const Program& program, std::size_t groups, int localSize);

// The invocations dispatchRows(program, groups, localSize) runs: its last row is filled up.
double rowsInvocations(std::size_t groups, int localSize);

} // namespace bounce::gl
