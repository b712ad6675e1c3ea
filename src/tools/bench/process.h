// Child processes for `prism bench suite` and `compare`: wall and CPU time and the child's own
// peak RSS (wait4).
#pragma once

#include <string>
#include <vector>

namespace prism {

struct ChildRun {
    int exitStatus = -1;     // -1: did not start or was killed by a signal
    double wallSeconds = 0;  // spawn to exit
    double cpuSeconds = 0;   // user + system time of the child (all its threads)
    long maxRssKiB = 0;      // ru_maxrss of this child alone
    std::string out, err;    // captured stdout and stderr
};

// Runs argv[0] (looked up on PATH) with the arguments, in workDir when not empty, with stdin
// from stdinFile (default /dev/null). Throws std::runtime_error when it cannot be started.
ChildRun RunChild(const std::vector<std::string> &argv, const std::string &workDir = "",
                  const std::string &stdinFile = "");

// The path of the running executable (/proc/self/exe).
std::string SelfExecutable();
// True when `name` is an executable on PATH.
bool OnPath(const std::string &name);
// stdout of a shell command (popen), "" on failure; trailing newlines removed.
std::string CommandOutput(const std::string &command);

}  // namespace prism
