// Running the prism binary as a user does, for the CLI tests.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace prism::test {

struct RunResult {
    int exitCode = -1;  // -1: killed by a signal
    std::string out, err;
    std::string Both() const { return out + err; }  // standard output, then error
};

// Runs the shell command `command` in directory `cwd`, with no standard input.
RunResult RunShell(const std::string &command, const std::filesystem::path &cwd);

// Runs prism with the given arguments (shell-quoted by the caller) in directory `cwd`, with no
// standard input; returns its exit status, standard output and standard error.
// `env` (e.g. "LD_PRELOAD=... NAME=value", shell-quoted by the caller) is set for prism only.
RunResult RunPrism(const std::string &args, const std::filesystem::path &cwd,
                   const std::string &env = "");

// `s` in single quotes for a shell command (s must not hold a single quote).
std::string ShellQuoted(const std::string &s);

// Starts prism with `args` (no shell) in directory `cwd`, its standard error to cwd/`errFile`
// and its standard output to /dev/null, and returns at once with its process id (for tests that
// signal a running render).
pid_t SpawnPrism(const std::filesystem::path &cwd, const std::vector<std::string> &args,
                 const std::string &errFile = "err.txt");

// Waits up to `seconds` for `pid`; kills it (SIGKILL) if it is still running then. Returns its
// wait status, or -1 if it had to be killed.
int WaitOrKill(pid_t pid, int seconds);

}  // namespace prism::test
