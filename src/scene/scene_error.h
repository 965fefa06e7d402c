#pragma once
#include <stdexcept>
#include <string>

namespace pt {

// A problem with an input file. what() is one line: "<file>: <problem>".
class SceneError : public std::runtime_error {
public:
    SceneError(const std::string& file, const std::string& problem) : std::runtime_error(file + ": " + problem) {}
};

} // namespace pt
