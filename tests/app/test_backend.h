// The backend the app tests render with: OSMesa (Mesa's llvmpipe, as the GL suite) unless
// BOUNCE_TEST_BACKEND names another. A GPU machine carries only its vendor's EGL and no OSMesa, so
// scripts/device-check.sh runs both suites there with BOUNCE_TEST_BACKEND=egl.
#pragma once

#include <cstdlib>
#include <string>

namespace bounce::testing {

inline std::string testBackend()
{
    const char* name = std::getenv("BOUNCE_TEST_BACKEND");
    return name && *name ? name : "osmesa";
}

} // namespace bounce::testing
