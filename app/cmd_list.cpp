// Placeholder until `bounce list` is implemented.
#include <cstdio>

#include "app/commands.h"

namespace bounce::app {

int cmdList(const Args&)
{
    std::fputs("bounce list: not available in this build\n", stderr);
    return 1;
}

} // namespace bounce::app
