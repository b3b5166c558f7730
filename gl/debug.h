// KHR_debug: every GL error and high-severity message is counted and printed; tests fail on any.
#pragma once

#include <string>
#include <vector>

namespace bounce::gl {

struct DebugMessage {
    unsigned source = 0, type = 0, id = 0, severity = 0;
    std::string text;
};

// Installs the debug callback on the current context (synchronous output, so the message names the call).
void installDebugCallback();
// Errors (GL_DEBUG_TYPE_ERROR) and high-severity messages since the last reset, plus glGetError results
// seen by checkGlError().
int debugErrorCount();
std::vector<DebugMessage> takeDebugErrors();
void resetDebugErrors();
// Polls glGetError(); counts and prints any error with `where`. Returns true if there was none.
bool checkGlError(const char* where);
// Labels a GL object for debuggers (KHR_debug glObjectLabel); a no-op where unsupported.
void labelObject(unsigned identifier, unsigned name, const std::string& label);

} // namespace bounce::gl
