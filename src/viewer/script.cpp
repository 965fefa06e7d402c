#include "viewer/script.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace pt::viewer {
namespace {

// Name -> (number of numeric arguments, or -1 for the command's own check).
const std::map<std::string, int>& numericArity() {
    static const std::map<std::string, int> m = {
        {"wait", 1},
        {"wait-spp", 1},
        {"orbit", 2},
        {"pan", 2},
        {"dolly", 1},
        {"look", 2},
        {"move", 3},
        {"resize", 2},
        {"exposure", 1},
        {"max-depth", 1},
        {"clamp", 1},
        {"stats", 0},
        {"report", 0},
        {"print-camera", 0},
        {"quit", 0},
        {"reset-view", 0},
    };
    return m;
}

const std::map<std::string, std::vector<std::string>>& wordArguments() {
    static const std::map<std::string, std::vector<std::string>> m = {
        {"toggle", {"nee", "mis", "rr", "sampling", "fly", "integrator", "light-tree"}},
        {"view", {"none", "albedo", "normal", "depth", "bvh", "nan"}},
        {"tonemap", {"srgb", "photographic", "aces"}},
    };
    return m;
}

} // namespace

std::string ScriptCommand::where() const { return "line " + std::to_string(line); }

std::vector<ScriptCommand> parseScript(const std::string& text, const std::string& source) {
    std::vector<ScriptCommand> commands;
    std::istringstream in(text);
    std::string raw;
    for (int lineNumber = 1; std::getline(in, raw); ++lineNumber) {
        if (auto hash = raw.find('#'); hash != std::string::npos) raw.erase(hash);
        std::istringstream tokens(raw);
        ScriptCommand c;
        c.line = lineNumber;
        if (!(tokens >> c.name)) continue;
        for (std::string t; tokens >> t;) c.args.push_back(t);
        auto fail = [&](const std::string& problem) {
            throw std::runtime_error(source + ":" + std::to_string(lineNumber) + ": " + c.name + ": " + problem);
        };
        // repeat N COMMAND...: COMMAND on each of the next N frames.
        if (c.name == "repeat") {
            if (c.args.size() < 2) fail("expected a count and a command");
            std::string rest;
            for (size_t i = 1; i < c.args.size(); ++i) rest += c.args[i] + " ";
            std::vector<ScriptCommand> inner = parseScript(rest, source + ":" + std::to_string(lineNumber));
            if (inner.size() != 1 || inner[0].name == "repeat" || inner[0].name.rfind("wait", 0) == 0)
                fail("repeats one command that is not a wait or a repeat");
        }
        const auto& arity = numericArity();
        const auto& words = wordArguments();
        if (auto a = arity.find(c.name); a != arity.end()) {
            if (static_cast<int>(c.args.size()) != a->second)
                fail("expected " + std::to_string(a->second) + " number(s), got " + std::to_string(c.args.size()));
        } else if (auto w = words.find(c.name); w != words.end()) {
            if (c.args.size() != 1) fail("expected one of its words");
            bool known = false;
            for (const auto& option : w->second) known |= option == c.args[0];
            if (!known) fail("unknown argument '" + c.args[0] + "'");
        } else if (c.name == "save" || c.name == "screenshot" || c.name == "key") {
            if (c.args.size() != 1) fail("expected one argument");
        } else if (c.name != "repeat") {
            fail("unknown command (see README.md, \"Viewer\")");
        }
        const size_t numericCount = c.name == "repeat" ? 1 : (arity.count(c.name) ? c.args.size() : 0);
        for (size_t i = 0; i < numericCount; ++i) {
            char* end = nullptr;
            const double v = std::strtod(c.args[i].c_str(), &end);
            if (end == c.args[i].c_str() || *end != '\0' || !std::isfinite(v))
                fail("'" + c.args[i] + "' is not a number");
            c.numbers.push_back(v);
        }
        if ((c.name == "wait" || c.name == "wait-spp" || c.name == "repeat") &&
            (c.numbers[0] < 0 || c.numbers[0] > 1e7))
            fail("count out of range");
        if (c.name == "resize" &&
            (c.numbers[0] < 1 || c.numbers[1] < 1 || c.numbers[0] > 16384 || c.numbers[1] > 16384))
            fail("size out of range");
        commands.push_back(std::move(c));
    }
    return commands;
}

std::vector<ScriptCommand> loadScript(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path.string() + ": cannot open the script");
    std::ostringstream text;
    text << in.rdbuf();
    return parseScript(text.str(), path.string());
}

} // namespace pt::viewer
