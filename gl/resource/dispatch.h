// Compute dispatch by the size of the work rather than by group counts: the group count is the ceiling
// of size / localSize per axis, so every invocation inside `size` exists once; the invocations of the
// last, partial groups beyond `size` run too, and the shader must return early there
// (any(greaterThanEqual(gl_GlobalInvocationID, size))).
#pragma once

#include <stdexcept>

#include <glm/glm.hpp>

namespace bounce::gl {

class Program;

struct DispatchError : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

// ceil(size / localSize) per axis. Throws DispatchError when a size or local size is zero or negative.
glm::ivec3 computeGroupCount(glm::ivec3 size, glm::ivec3 localSize);

// Uses `program` and dispatches computeGroupCount(size, localSize) groups. Throws DispatchError, before
// any GL call that would fail, when a size is zero or negative, when localSize is not the program's
// declared local_size (GL_COMPUTE_WORK_GROUP_SIZE), or when a group count exceeds
// GL_MAX_COMPUTE_WORK_GROUP_COUNT on its axis. The caller still issues the memory barrier it needs.
void dispatchCompute(const Program& program, glm::ivec3 size, glm::ivec3 localSize);

} // namespace bounce::gl
