// Placeholder until `bounce bench` is implemented.
#include <cstdio>

#include "app/commands.h"

namespace bounce::app {

int cmdBench(const Args&)
{
    std::fputs("bounce bench: not available in this build\n", stderr);
    return 1;
}

} // namespace bounce::app
