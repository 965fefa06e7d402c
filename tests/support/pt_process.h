#pragma once
// Runs a program (pt, xvfb-run, Ray's Python) for the tests that drive binaries as a user would:
// in a given working directory, with variables added to or removed from the environment, stdin
// from a file, stdout and stderr captured to files and read back, a timeout, and a callback while
// it runs (to send it a signal mid-render). The command-line, long-render and viewer tests all
// spawn through runProcess.
#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <map>
#include <ostream>
#include <set>
#include <string>
#include <vector>

namespace pt::test {

struct RunOptions {
    std::filesystem::path dir;              // working directory
    std::map<std::string, std::string> env; // added, replacing any inherited value
    // Removed from the inherited environment: by default the test hooks a developer may have set,
    // so that every run sees only what its test sets.
    std::set<std::string> unset = {"PT_VALIDATION", "PT_FAULT"};
    std::filesystem::path stdinFile = "/dev/null";
    std::filesystem::path stdoutFile; // empty: discarded
    std::filesystem::path stderrFile; // empty: dir / ".stderr"
    double timeoutSeconds = 120;      // then killed with SIGKILL, and timedOut set
    // Called every few milliseconds until the program exits, with its pid and the seconds since start.
    std::function<void(pid_t, double)> whileRunning;
};

struct PtRun {
    std::string launchError; // why the program could not be started or waited for ("" when it ran)
    bool signaled = false;
    int signal = 0;
    int status = -1; // exit status when it exited (not killed by a signal, not timed out)
    bool timedOut = false;
    double seconds = 0;           // wall time
    std::string out, err;         // what it wrote to the captured stdout and stderr
    std::string describe() const; // for failure messages

    // Lines of stderr that start with "pt: error: ".
    std::vector<std::string> errorLines() const;
    // The only error line ("" and a test failure when there is not exactly one).
    std::string errorLine() const;
};
std::ostream& operator<<(std::ostream& os, const PtRun& r);

// Runs argv[0] (a path, or a program name looked up on PATH) with the rest of argv as arguments.
PtRun runProcess(const std::vector<std::string>& argv, const RunOptions& options);

// runProcess in `dir` with `env` added to the environment and stderr captured.
PtRun runProgram(const std::filesystem::path& dir, const std::vector<std::string>& argv,
    const std::map<std::string, std::string>& env = {}, const std::function<void(pid_t, double)>& whileRunning = {},
    double timeoutSeconds = 120);

// runProgram of the pt binary (PT_BINARY) with `args`.
PtRun runPt(const std::filesystem::path& dir, const std::vector<std::string>& args,
    const std::map<std::string, std::string>& env = {}, const std::function<void(pid_t, double)>& whileRunning = {},
    double timeoutSeconds = 120);

// The whole content of a file ("" when it cannot be read).
std::string readFile(const std::filesystem::path& path);

// Whether `program` is an executable file in a folder of PATH.
bool onPath(const std::string& program);

} // namespace pt::test
