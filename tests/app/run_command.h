// Running shell commands and the bounce binary (BOUNCE_BINARY) from the app tests.
#pragma once

#include <cstdio>
#include <string>

#include <sys/wait.h>

namespace bounce::testing {

struct CommandRun {
    int status = -1;    // the exit status, -1 when the command did not exit
    std::string output; // stdout and stderr together
};

// Runs a shell command line, its stderr with its stdout.
inline CommandRun runShell(const std::string& command)
{
    CommandRun r;
    FILE* p = popen((command + " 2>&1").c_str(), "r");
    if (!p) return r;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, p)) r.output += buf;
    const int s = pclose(p);
    r.status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
    return r;
}

// `bounce ARGS` after `prefix` (another command, e.g. "env -u DISPLAY ", or variables, "NAME=value "), with
// new GL storage poisoned (gl/resource/allocations.h), as in the GL suite.
inline CommandRun runBounce(const std::string& args, const std::string& prefix = "")
{
    return runShell("BOUNCE_POISON_STORAGE=1 " + prefix + std::string(BOUNCE_BINARY) + " " + args);
}

} // namespace bounce::testing
