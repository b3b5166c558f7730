// Placeholder until `bounce compare` is implemented.
#include <cstdio>

#include "app/commands.h"

namespace bounce::app {

int cmdCompare(const Args&)
{
    std::fputs("bounce compare: not available in this build\n", stderr);
    return 1;
}

} // namespace bounce::app
