// Running the prism binary from the CLI tests of tests/app.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace prism::test {

struct RunResult {
    int exitCode = -1;  // -1: killed by a signal
    std::string out, err;
};

// An empty folder `<gtest temp>/prism_<prefix>_<name>` (removed first if it exists).
inline std::filesystem::path FreshTempDir(const std::string &prefix, const std::string &name) {
    std::filesystem::path d =
        std::filesystem::path(::testing::TempDir()) / ("prism_" + prefix + "_" + name);
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    return d;
}

inline std::string ReadFile(const std::filesystem::path &p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Runs prism with the given arguments (shell-quoted by the caller) in directory `cwd`, with no
// standard input; returns its exit status, standard output and standard error.
// `env` (e.g. "LD_PRELOAD=... NAME=value", shell-quoted by the caller) is set for prism only.
inline RunResult RunPrism(const std::string &args, const std::filesystem::path &cwd,
                          const std::string &env = "") {
    std::filesystem::path outFile = cwd / "stdout.txt", errFile = cwd / "stderr.txt";
    std::string cmd = "cd '" + cwd.string() + "' && " + env + " '" + std::string(PRISM_BINARY) +
                      "' " + args + " >'" + outFile.string() + "' 2>'" + errFile.string() +
                      "' </dev/null";
    int status = std::system(cmd.c_str());
    RunResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = ReadFile(outFile);
    r.err = ReadFile(errFile);
    std::filesystem::remove(outFile);
    std::filesystem::remove(errFile);
    return r;
}

}  // namespace prism::test
