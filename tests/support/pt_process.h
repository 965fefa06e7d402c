#pragma once
// Runs the pt binary for the command-line tests of long and distributed renders: in a given
// working directory, with extra environment variables, stderr captured, and a callback while it
// runs (to send it a signal mid-render).
#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace pt::test {

struct PtRun {
    bool signaled = false;
    int signal = 0;
    int status = -1; // exit status when !signaled
    bool timedOut = false;
    std::string err;
    std::string describe() const; // for failure messages
};

// Runs argv[0] (a path) with `args`; `whileRunning(pid, seconds)` is called every few
// milliseconds until it exits.
PtRun runProgram(const std::filesystem::path& dir, const std::vector<std::string>& argv,
    const std::map<std::string, std::string>& env = {},
    const std::function<void(pid_t, double)>& whileRunning = {}, double timeoutSeconds = 120);

// `whileRunning(pid, seconds)` is called every few milliseconds until pt exits.
PtRun runPt(const std::filesystem::path& dir, const std::vector<std::string>& args,
    const std::map<std::string, std::string>& env = {},
    const std::function<void(pid_t, double)>& whileRunning = {}, double timeoutSeconds = 120);

// A fresh empty directory for one test, under the system temporary directory.
std::filesystem::path freshTestDirectory(const std::string& name);

} // namespace pt::test
