// Placeholder until `bounce render` is implemented.
#include <cstdio>

#include "app/commands.h"

namespace bounce::app {

int cmdRender(const Args&)
{
    std::fputs("bounce render: not available in this build\n", stderr);
    return 1;
}

} // namespace bounce::app
