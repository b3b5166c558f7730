// Placeholder until `bounce demo` is implemented.
#include <cstdio>

#include "app/commands.h"

namespace bounce::app {

int cmdDemo(const Args&)
{
    std::fputs("bounce demo: not available in this build\n", stderr);
    return 1;
}

} // namespace bounce::app
