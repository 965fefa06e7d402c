#pragma once
// Shared by the parts of the CENG795 loader: where errors and "not supported" notes go, and how
// numbers are read from element text.
#include <glm/glm.hpp>
#include <pugixml.hpp>

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace pt::ceng795 {

// One loading run: the file being read (for messages), its directory (for relative paths), and
// the features it uses that the scene model does not represent.
class Context {
public:
    Context(std::string file, std::filesystem::path baseDir) : file_(std::move(file)), baseDir_(std::move(baseDir)) {}

    const std::string& file() const { return file_; }
    // Relative paths in the course format are relative to the XML file's directory.
    std::filesystem::path resolve(std::string_view relative) const;

    // Throws SceneError "<file>: <element label>: <problem>".
    [[noreturn]] void fail(pugi::xml_node where, const std::string& problem) const;
    [[noreturn]] void fail(const std::string& problem) const;

    // Records a feature used but not modelled, or a value the file lacks and the loader filled in
    // (such notes say "(... assumed)" and are shown in a warning of their own); each distinct note
    // once, in first-seen order.
    void note(const std::string& feature);
    const std::vector<std::string>& notes() const { return notes_; }

private:
    std::string file_;
    std::filesystem::path baseDir_;
    std::vector<std::string> notes_;
    std::set<std::string> noted_;
};

// "Mesh id=3", "Mesh id=3: Faces", "Camera id=1: Gaze", "MaxRecursionDepth": the element and
// its ancestors up to the nearest one with an id (ids are what a user can search the file for).
std::string label(pugi::xml_node node);

// A value from the file, shortened and made printable, for a one-line message; quote() adds
// single quotes around it.
std::string printable(std::string_view text);
std::string quote(std::string_view text);
// A number for a message, shortest form ("0.18", "512", "1e-06").
std::string formatNumber(double v);

// All text content of an element (comments may split it into several pieces).
std::string textOf(pugi::xml_node node);

// Splits on whitespace and commas: a few student-converted course files write "1, 2, 3".
std::vector<std::string_view> tokens(std::string_view text);

double toNumber(const Context& ctx, pugi::xml_node where, std::string_view token);
long long toInteger(const Context& ctx, pugi::xml_node where, std::string_view token);

// Every token of the element's text as a finite number / an integer.
std::vector<double> numbers(const Context& ctx, pugi::xml_node node);
std::vector<long long> integers(const Context& ctx, pugi::xml_node node);

// Exactly one / three numbers.
float scalar(const Context& ctx, pugi::xml_node node);
glm::vec3 vec3(const Context& ctx, pugi::xml_node node);
// One integer in [lo, hi].
long long integer(const Context& ctx, pugi::xml_node node, long long lo, long long hi);

pugi::xml_node required(const Context& ctx, pugi::xml_node parent, const char* child);
std::optional<float> optionalScalar(const Context& ctx, pugi::xml_node parent, const char* child);
std::optional<glm::vec3> optionalVec3(const Context& ctx, pugi::xml_node parent, const char* child);

// The required integer id attribute of an element that others refer to.
long long idOf(const Context& ctx, pugi::xml_node node);
// The id attribute as written, or `fallback` when absent (for names only).
std::string idText(pugi::xml_node node, const std::string& fallback);

long long integerAttribute(const Context& ctx, pugi::xml_node node, const char* name, long long fallback);
// "true"/"false" (also "1"/"0"), case-insensitive.
bool booleanValue(const Context& ctx, pugi::xml_node where, std::string_view text, const char* what);

std::string lowercase(std::string_view s);

} // namespace pt::ceng795
