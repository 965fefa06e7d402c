#pragma once
#include <stdexcept>
#include <string>

namespace pt {

// A problem with an input file. what() is one line: "<file>: <problem>".
// The problem text often quotes the file (names, paths, tokens), so it is made safe to print
// here, once for every loader: control characters become '?' (a hostile file must not be able to
// break the line or drive the terminal) and its length is bounded.
class SceneError : public std::runtime_error {
public:
    SceneError(const std::string& file, const std::string& problem)
        : std::runtime_error(file + ": " + printable(problem)) {}

private:
    static std::string printable(std::string text) {
        constexpr size_t kMaxLength = 600;
        if (text.size() > kMaxLength) text = text.substr(0, kMaxLength) + "...";
        for (char& c : text)
            if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
        return text;
    }
};

} // namespace pt
