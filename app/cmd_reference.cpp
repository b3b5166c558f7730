// Placeholder until `bounce reference` is implemented.
#include <cstdio>

#include "app/commands.h"

namespace bounce::app {

int cmdReference(const Args&)
{
    std::fputs("bounce reference: not available in this build\n", stderr);
    return 1;
}

} // namespace bounce::app
