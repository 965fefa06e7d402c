#pragma once
// `pt view --script FILE`: timed inputs for tests and benchmarks, one command per line
// ('#' starts a comment). The format is documented in README.md ("Viewer").
#include <filesystem>
#include <string>
#include <vector>

namespace pt::viewer {

struct ScriptCommand {
    int line = 0;
    std::string name;              // e.g. "orbit"
    std::vector<std::string> args; // as written
    std::vector<double> numbers;   // args parsed as numbers where the command takes numbers
    std::string where() const;     // "line N"
};

// Parses and checks every command up front (unknown names, wrong argument counts or values),
// so a bad script fails before the window opens. Throws std::runtime_error("FILE:LINE: ...").
std::vector<ScriptCommand> parseScript(const std::string& text, const std::string& source);
std::vector<ScriptCommand> loadScript(const std::filesystem::path& path);

} // namespace pt::viewer
