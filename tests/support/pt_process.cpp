#include "support/pt_process.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

extern char** environ;

namespace pt::test {

std::string PtRun::describe() const {
    std::ostringstream s;
    s << *this;
    return s.str();
}

std::ostream& operator<<(std::ostream& os, const PtRun& r) {
    if (!r.launchError.empty()) os << r.launchError << "\n";
    os << (r.signaled ? "killed by signal " + std::to_string(r.signal) : "exit " + std::to_string(r.status))
       << (r.timedOut ? " (timed out)" : "") << " after " << r.seconds << " s\n--- stderr:\n"
       << r.err;
    if (!r.out.empty()) os << "--- stdout:\n" << r.out;
    return os;
}

std::vector<std::string> PtRun::errorLines() const {
    std::vector<std::string> lines;
    std::istringstream s(err);
    for (std::string line; std::getline(s, line);)
        if (line.rfind("pt: error: ", 0) == 0) lines.push_back(line);
    return lines;
}

std::string PtRun::errorLine() const {
    const auto lines = errorLines();
    EXPECT_EQ(lines.size(), 1u) << "expected exactly one 'pt: error: ' line in stderr:\n" << err;
    return lines.size() == 1 ? lines[0] : std::string();
}

std::string readFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

bool onPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::istringstream dirs(path ? path : "");
    for (std::string d; std::getline(dirs, d, ':');)
        if (!d.empty() && ::access((std::filesystem::path(d) / program).c_str(), X_OK) == 0) return true;
    return false;
}

PtRun runProcess(const std::vector<std::string>& argStrings0, const RunOptions& options) {
    std::vector<std::string> argStrings = argStrings0;
    std::vector<char*> argv;
    for (auto& a : argStrings) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> envStrings;
    for (char** e = environ; *e; ++e) {
        const std::string entry = *e;
        const std::string key = entry.substr(0, entry.find('='));
        if (options.unset.count(key) || options.env.count(key)) continue;
        envStrings.push_back(entry);
    }
    for (const auto& [k, v] : options.env) envStrings.push_back(k + "=" + v);
    std::vector<char*> envp;
    for (auto& e : envStrings) envp.push_back(e.data());
    envp.push_back(nullptr);

    const std::filesystem::path outPath = options.stdoutFile.empty() ? "/dev/null" : options.stdoutFile;
    const std::filesystem::path errPath = options.stderrFile.empty() ? options.dir / ".stderr" : options.stderrFile;
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, options.stdinFile.c_str(), O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addchdir_np(&actions, options.dir.c_str());
    PtRun r;
    const auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    pid_t pid = -1;
    // posix_spawnp looks a bare name up on PATH; a path (PT_BINARY, a Python) is used as it is.
    const int rc = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) {
        r.launchError = "cannot start " + argStrings[0] + ": " + std::strerror(rc);
        return r;
    }
    int wstatus = 0;
    while (true) {
        const pid_t w = ::waitpid(pid, &wstatus, WNOHANG);
        if (w == pid) break;
        if (w < 0 && errno != EINTR) {
            r.launchError = std::string("waitpid: ") + std::strerror(errno);
            r.seconds = elapsed();
            return r;
        }
        const double seconds = elapsed();
        if (seconds > options.timeoutSeconds) {
            r.timedOut = true;
            ::kill(pid, SIGKILL);
            ::waitpid(pid, &wstatus, 0);
            break;
        }
        if (options.whileRunning) options.whileRunning(pid, seconds);
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    r.seconds = elapsed();
    r.signaled = WIFSIGNALED(wstatus);
    if (r.signaled) r.signal = WTERMSIG(wstatus);
    if (WIFEXITED(wstatus)) r.status = WEXITSTATUS(wstatus);
    if (!options.stdoutFile.empty()) r.out = readFile(outPath);
    r.err = readFile(errPath);
    return r;
}

PtRun runProgram(const std::filesystem::path& dir, const std::vector<std::string>& argv,
    const std::map<std::string, std::string>& env, const std::function<void(pid_t, double)>& whileRunning,
    double timeoutSeconds) {
    RunOptions options;
    options.dir = dir;
    options.env = env;
    options.whileRunning = whileRunning;
    options.timeoutSeconds = timeoutSeconds;
    return runProcess(argv, options);
}

PtRun runPt(const std::filesystem::path& dir, const std::vector<std::string>& args,
    const std::map<std::string, std::string>& env, const std::function<void(pid_t, double)>& whileRunning,
    double timeoutSeconds) {
    std::vector<std::string> argv = {PT_BINARY};
    argv.insert(argv.end(), args.begin(), args.end());
    return runProgram(dir, argv, env, whileRunning, timeoutSeconds);
}

} // namespace pt::test
