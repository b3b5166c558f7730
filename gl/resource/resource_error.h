// A GL resource that cannot be had: a size over the driver's limits, GL_OUT_OF_MEMORY, an incomplete
// framebuffer. The message says what was asked for and the limit; the CLI turns it into exit status 2
// with the parameter that lowers it (app/main.cpp).
#pragma once

#include <stdexcept>
#include <string>

namespace bounce::gl {

struct ResourceError : std::runtime_error {
    ResourceError(const std::string& label, const std::string& what) : std::runtime_error(what), label(label) {}
    std::string label; // the resource's label ("shadow.depth", "gbuffer.position"...)
};

} // namespace bounce::gl
