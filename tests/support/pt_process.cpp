#include "support/pt_process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

extern char** environ;

namespace pt::test {

std::string PtRun::describe() const {
    std::ostringstream s;
    s << (signaled ? "killed by signal " + std::to_string(signal) : "exit " + std::to_string(status))
      << (timedOut ? " (timed out)" : "") << "\n--- stderr:\n" << err;
    return s.str();
}

std::filesystem::path freshTestDirectory(const std::string& name) {
    auto dir = std::filesystem::temp_directory_path() / ("pt_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

PtRun runPt(const std::filesystem::path& dir, const std::vector<std::string>& args,
    const std::map<std::string, std::string>& env, const std::function<void(pid_t, double)>& whileRunning,
    double timeoutSeconds) {
    std::vector<std::string> argv = {PT_BINARY};
    argv.insert(argv.end(), args.begin(), args.end());
    return runProgram(dir, argv, env, whileRunning, timeoutSeconds);
}

PtRun runProgram(const std::filesystem::path& dir, const std::vector<std::string>& argStrings0,
    const std::map<std::string, std::string>& env, const std::function<void(pid_t, double)>& whileRunning,
    double timeoutSeconds) {
    std::vector<std::string> argStrings = argStrings0;
    std::vector<char*> argv;
    for (auto& a : argStrings) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> envStrings;
    for (char** e = environ; *e; ++e) {
        const std::string entry = *e;
        const std::string key = entry.substr(0, entry.find('='));
        if (key == "PT_VALIDATION" || key == "PT_FAULT" || env.count(key)) continue;
        envStrings.push_back(entry);
    }
    for (const auto& [k, v] : env) envStrings.push_back(k + "=" + v);
    std::vector<char*> envp;
    for (auto& e : envStrings) envp.push_back(e.data());
    envp.push_back(nullptr);

    const auto errPath = dir / ".stderr";
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
    PtRun r;
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) {
        r.err = std::string("cannot start pt: ") + std::strerror(rc);
        return r;
    }
    const auto start = std::chrono::steady_clock::now();
    int wstatus = 0;
    while (true) {
        const pid_t w = ::waitpid(pid, &wstatus, WNOHANG);
        if (w == pid || (w < 0 && errno != EINTR)) break;
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (seconds > timeoutSeconds) {
            r.timedOut = true;
            ::kill(pid, SIGKILL);
            ::waitpid(pid, &wstatus, 0);
            break;
        }
        if (whileRunning) whileRunning(pid, seconds);
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    r.signaled = WIFSIGNALED(wstatus);
    if (r.signaled) r.signal = WTERMSIG(wstatus);
    if (WIFEXITED(wstatus)) r.status = WEXITSTATUS(wstatus);
    std::ifstream in(errPath);
    std::ostringstream text;
    text << in.rdbuf();
    r.err = text.str();
    return r;
}

} // namespace pt::test
