#include "gl/debug.h"

#include <cstdio>
#include <mutex>
#include <utility>

#include "gl/gl.h"

namespace bounce::gl {

namespace {

// The driver may call back from any thread that has a context current; one lock covers the list and
// stderr, so two messages never interleave.
std::mutex mutex;
std::vector<DebugMessage> errors;

const char* sourceName(GLenum source)
{
    switch (source) {
    case GL_DEBUG_SOURCE_API: return "api";
    case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window-system";
    case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader-compiler";
    case GL_DEBUG_SOURCE_THIRD_PARTY: return "third-party";
    case GL_DEBUG_SOURCE_APPLICATION: return "application";
    case GL_DEBUG_SOURCE_OTHER: return "other";
    default: return "?";
    }
}

const char* typeName(GLenum type)
{
    switch (type) {
    case GL_DEBUG_TYPE_ERROR: return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined-behaviour";
    case GL_DEBUG_TYPE_PORTABILITY: return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
    case GL_DEBUG_TYPE_MARKER: return "marker";
    case GL_DEBUG_TYPE_PUSH_GROUP: return "push-group";
    case GL_DEBUG_TYPE_POP_GROUP: return "pop-group";
    case GL_DEBUG_TYPE_OTHER: return "other";
    default: return "?";
    }
}

const char* severityName(GLenum severity)
{
    switch (severity) {
    case GL_DEBUG_SEVERITY_HIGH: return "high";
    case GL_DEBUG_SEVERITY_MEDIUM: return "medium";
    case GL_DEBUG_SEVERITY_LOW: return "low";
    case GL_DEBUG_SEVERITY_NOTIFICATION: return "notification";
    default: return "?";
    }
}

const char* errorName(GLenum error)
{
    switch (error) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST";
    default: return "unknown GL error";
    }
}

void GLAD_API_PTR onDebugMessage(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                 const GLchar* text, const void*)
{
    const bool counted = type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH;
    // Medium-severity remarks (undefined behaviour, slow paths) are worth seeing but fail nothing; low ones
    // are mostly driver chatter about memory placement.
    if (!counted && severity != GL_DEBUG_SEVERITY_MEDIUM) return;
    const std::string message = length >= 0 ? std::string(text, std::size_t(length)) : std::string(text);
    std::lock_guard lock(mutex);
    std::fprintf(stderr, "GL debug [%s %s, %s severity, id %u]: %s\n", sourceName(source), typeName(type),
                 severityName(severity), id, message.c_str());
    if (counted) errors.push_back({source, type, id, severity, message});
}

} // namespace

void installDebugCallback()
{
    if (!glDebugMessageCallback) return;
    glEnable(GL_DEBUG_OUTPUT);
    // Synchronous: the callback runs inside the offending call, so a breakpoint there names it.
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(onDebugMessage, nullptr);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DEBUG_SEVERITY_NOTIFICATION, 0, nullptr, GL_FALSE);
}

int debugErrorCount()
{
    std::lock_guard lock(mutex);
    return int(errors.size());
}

std::vector<DebugMessage> takeDebugErrors()
{
    std::lock_guard lock(mutex);
    return std::exchange(errors, {});
}

void resetDebugErrors()
{
    std::lock_guard lock(mutex);
    errors.clear();
}

bool checkGlError(const char* where)
{
    bool clean = true;
    // Bounded: a lost context may report an error on every call.
    for (int i = 0; i < 16; ++i) {
        const GLenum error = glGetError();
        if (error == GL_NO_ERROR) break;
        clean = false;
        const std::string text = std::string(errorName(error)) + " (glGetError) at " + where;
        std::lock_guard lock(mutex);
        std::fprintf(stderr, "GL error: %s\n", text.c_str());
        errors.push_back({GL_DEBUG_SOURCE_API, GL_DEBUG_TYPE_ERROR, error, GL_DEBUG_SEVERITY_HIGH, text});
    }
    return clean;
}

void labelObject(unsigned identifier, unsigned name, const std::string& label)
{
    if (!glObjectLabel) return;
    // A label as long as GL_MAX_LABEL_LENGTH is an error; every implementation allows at least 256
    // including the terminator, and debuggers show no more than that anyway.
    const std::size_t length = label.size() < 255 ? label.size() : 255;
    glObjectLabel(identifier, name, GLsizei(length), label.c_str());
}

} // namespace bounce::gl
