#include "support/process.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "support/temp_dir.h"

namespace prism::test {

RunResult RunShell(const std::string &command, const std::filesystem::path &cwd) {
    std::filesystem::path outFile = cwd / "stdout.txt", errFile = cwd / "stderr.txt";
    std::string cmd = "cd " + ShellQuoted(cwd.string()) + " && " + command + " >" +
                      ShellQuoted(outFile.string()) + " 2>" + ShellQuoted(errFile.string()) +
                      " </dev/null";
    int status = std::system(cmd.c_str());
    RunResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = ReadFile(outFile);
    r.err = ReadFile(errFile);
    std::filesystem::remove(outFile);
    std::filesystem::remove(errFile);
    return r;
}

RunResult RunPrism(const std::string &args, const std::filesystem::path &cwd,
                   const std::string &env) {
    return RunShell(env + " " + ShellQuoted(PRISM_BINARY) + " " + args, cwd);
}

std::string ShellQuoted(const std::string &s) {
    std::string q = "'";
    q += s;
    q += "'";
    return q;
}

pid_t SpawnPrism(const std::filesystem::path &cwd, const std::vector<std::string> &args,
                 const std::string &errFile) {
    pid_t pid = fork();
    if (pid == 0) {
        if (chdir(cwd.c_str()) != 0) _exit(126);
        if (!std::freopen(errFile.c_str(), "w", stderr) || !std::freopen("/dev/null", "w", stdout))
            _exit(126);
        std::vector<char *> argv{const_cast<char *>(PRISM_BINARY)};
        for (const std::string &a : args) argv.push_back(const_cast<char *>(a.c_str()));
        argv.push_back(nullptr);
        execv(PRISM_BINARY, argv.data());
        _exit(127);
    }
    return pid;
}

int WaitOrKill(pid_t pid, int seconds) {
    int status = 0;
    for (int i = 0; i < seconds * 50; ++i) {
        if (waitpid(pid, &status, WNOHANG) == pid) return status;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    return -1;
}

}  // namespace prism::test
