#include "gl/resource/dispatch.h"

#include <algorithm>
#include <climits>
#include <string>

#include "gl/gl.h"
#include "gl/resource/program.h"
#include "gl/resource/storage_bindings.h"

namespace bounce::gl {

namespace {

std::string str(glm::ivec3 v)
{
    return std::to_string(v.x) + "x" + std::to_string(v.y) + "x" + std::to_string(v.z);
}

} // namespace

glm::ivec3 computeGroupCount(glm::ivec3 size, glm::ivec3 localSize)
{
    if (glm::any(glm::lessThanEqual(size, glm::ivec3(0))))
        throw DispatchError("compute dispatch of size " + str(size) + ": every axis must be at least 1");
    if (glm::any(glm::lessThanEqual(localSize, glm::ivec3(0))))
        throw DispatchError("compute dispatch with local size " + str(localSize) + ": every axis must be at least 1");
    // (size + local - 1) / local without overflow near INT_MAX.
    return (size - 1) / localSize + 1;
}

double computeInvocations(glm::ivec3 size, glm::ivec3 localSize)
{
    const glm::dvec3 launched = glm::dvec3(computeGroupCount(size, localSize)) * glm::dvec3(localSize);
    return launched.x * launched.y * launched.z;
}

void dispatchCompute(const Program& program, glm::ivec3 size, glm::ivec3 localSize)
{
    const glm::ivec3 groups = computeGroupCount(size, localSize);
    if (!program) throw DispatchError("compute dispatch of size " + str(size) + " with no program");
    glm::ivec3 declared(0);
    glGetProgramiv(program.id(), GL_COMPUTE_WORK_GROUP_SIZE, &declared.x);
    if (declared != localSize)
        throw DispatchError("compute dispatch with local size " + str(localSize) + ", but the program declares " +
                            str(declared));
    for (int axis = 0; axis < 3; ++axis) {
        GLint most = 0;
        glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, GLuint(axis), &most);
        if (groups[axis] > most)
            throw DispatchError("compute dispatch of size " + str(size) + " needs " + str(groups) + " groups of " +
                                str(localSize) + ", more than GL_MAX_COMPUTE_WORK_GROUP_COUNT (" +
                                std::to_string(most) + ") on axis " + std::to_string(axis));
    }
    // A block under whose name no buffer is bound would read nothing at all (storage_bindings.h).
    if (const std::string unbound = unboundStorage(program.storage()); !unbound.empty())
        throw DispatchError("compute dispatch of '" + program.storage().label +
                            "' with no buffer bound under the storage names of " + unbound);
    program.use();
    glDispatchCompute(GLuint(groups.x), GLuint(groups.y), GLuint(groups.z));
}

void dispatchRows(const Program& program, std::size_t groups, int localSize)
{
    if (groups == 0) return;
    const std::size_t row = std::min(groups, kMaxRowGroups), rows = (groups + row - 1) / row;
    if (rows > std::size_t(INT_MAX))
        throw DispatchError("compute dispatch of " + std::to_string(groups) + " groups: too many rows");
    dispatchCompute(program, {int(row) * localSize, int(rows), 1}, {localSize, 1, 1});
}

double rowsInvocations(std::size_t groups, int localSize)
{
    if (groups == 0) return 0.0;
    const std::size_t row = std::min(groups, kMaxRowGroups), rows = (groups + row - 1) / row;
    return double(row) * double(rows) * double(localSize);
}

} // namespace bounce::gl
