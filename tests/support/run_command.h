// Runs a command line through the shell and collects what it prints: the command-line tools' tests
// (tests/tools, tests/render) run the real binaries this way.
#pragma once

#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace supermodal::test
{

struct CommandOutcome {
    int status = -1;    ///< Exit status; −1 if the command did not exit normally (or did not start).
    std::string output; ///< Its stdout (append " 2>&1" to the command line for stderr too).
};

inline CommandOutcome run_command(const std::string& command_line)
{
    CommandOutcome o;
    FILE* pipe = ::popen(command_line.c_str(), "r");
    if (pipe == nullptr)
        return o;
    char buf[4096];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0)
        o.output.append(buf, n);
    const int raw = ::pclose(pipe);
    o.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    return o;
}

} // namespace supermodal::test
