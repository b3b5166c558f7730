// The `bounce` subcommands. Each lives in its own file (app/cmd_<name>.cpp) and returns the process
// exit status: 0 success, 1 a failure while running, 2 bad input (unknown option, bad value, a scene
// or image that cannot be read). Bad input throws UsageError, which main() prints and maps to 2.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace bounce::app {

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

using Args = std::vector<std::string>; // the arguments after the subcommand's name

int cmdRender(const Args& args);
int cmdList(const Args& args);
int cmdDemo(const Args& args);
int cmdReference(const Args& args);
int cmdCompare(const Args& args);
int cmdBench(const Args& args);
int cmdRays(const Args& args);
int cmdProbe(const Args& args);

} // namespace bounce::app
