#include "scene/ceng795/document.h"

#include "scene/scene_error.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>

namespace pt::ceng795 {

std::filesystem::path Context::resolve(std::string_view relative) const {
    return baseDir_ / std::filesystem::path(std::string(relative));
}

void Context::fail(pugi::xml_node where, const std::string& problem) const {
    const std::string where_ = label(where);
    throw SceneError(file_, where_.empty() ? problem : where_ + ": " + problem);
}

void Context::fail(const std::string& problem) const { throw SceneError(file_, problem); }

void Context::note(const std::string& feature) {
    if (noted_.insert(feature).second) notes_.push_back(feature);
}

std::string printable(std::string_view text) {
    constexpr size_t kMax = 40;
    std::string out;
    for (size_t i = 0; i < text.size() && i < kMax; ++i) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        out += (c >= 32 && c < 127) ? static_cast<char>(c) : '?';
    }
    if (text.size() > kMax) out += "...";
    return out;
}

std::string quote(std::string_view text) { return "'" + printable(text) + "'"; }

std::string formatNumber(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", v);
    return buffer;
}

std::string label(pugi::xml_node node) {
    std::vector<std::string> parts;
    // Stop below the root <Scene>: every element is inside it, so naming it adds nothing.
    for (pugi::xml_node n = node; n && n.type() == pugi::node_element && n.parent().type() == pugi::node_element;
         n = n.parent()) {
        std::string part = printable(n.name());
        if (pugi::xml_attribute id = n.attribute("id")) {
            parts.push_back(part + " id=" + printable(id.value()));
            break;
        }
        parts.push_back(part);
    }
    std::string out;
    for (auto it = parts.rbegin(); it != parts.rend(); ++it) out += (out.empty() ? "" : ": ") + *it;
    return out;
}

std::string textOf(pugi::xml_node node) {
    std::string text;
    for (pugi::xml_node child : node.children())
        if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) {
            text += child.value();
            text += ' ';
        }
    return text;
}

std::vector<std::string_view> tokens(std::string_view text) {
    std::vector<std::string_view> out;
    auto separator = [](char c) {
        return c == ',' || c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
    };
    size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && separator(text[i])) ++i;
        const size_t start = i;
        while (i < text.size() && !separator(text[i])) ++i;
        if (i > start) out.push_back(text.substr(start, i - start));
    }
    return out;
}

double toNumber(const Context& ctx, pugi::xml_node where, std::string_view token) {
    std::string_view t = token;
    if (!t.empty() && t.front() == '+') t.remove_prefix(1); // from_chars rejects a leading '+'
    double value = 0.0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec == std::errc::result_out_of_range) ctx.fail(where, quote(token) + " is out of range");
    if (ec != std::errc() || end != t.data() + t.size()) ctx.fail(where, quote(token) + " is not a number");
    // from_chars accepts "nan" and "inf"; nothing in a scene may be either.
    if (!std::isfinite(value)) ctx.fail(where, quote(token) + " is not a finite number");
    return value;
}

long long toInteger(const Context& ctx, pugi::xml_node where, std::string_view token) {
    std::string_view t = token;
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    long long value = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec == std::errc::result_out_of_range) ctx.fail(where, quote(token) + " is out of range");
    if (ec != std::errc() || end != t.data() + t.size()) ctx.fail(where, quote(token) + " is not an integer");
    return value;
}

std::vector<double> numbers(const Context& ctx, pugi::xml_node node) {
    const std::string text = textOf(node);
    std::vector<double> out;
    for (std::string_view t : tokens(text)) out.push_back(toNumber(ctx, node, t));
    return out;
}

std::vector<long long> integers(const Context& ctx, pugi::xml_node node) {
    const std::string text = textOf(node);
    std::vector<long long> out;
    for (std::string_view t : tokens(text)) out.push_back(toInteger(ctx, node, t));
    return out;
}

namespace {

std::vector<double> exactly(const Context& ctx, pugi::xml_node node, size_t count) {
    std::vector<double> v = numbers(ctx, node);
    if (v.size() != count)
        ctx.fail(node, "expected " + std::to_string(count) + (count == 1 ? " number" : " numbers") + ", found " +
                           std::to_string(v.size()));
    return v;
}

// Finite doubles can still overflow a float.
float toFloat(const Context& ctx, pugi::xml_node node, double v) {
    if (std::fabs(v) > static_cast<double>(std::numeric_limits<float>::max())) ctx.fail(node, "number out of range");
    return static_cast<float>(v);
}

} // namespace

float scalar(const Context& ctx, pugi::xml_node node) { return toFloat(ctx, node, exactly(ctx, node, 1)[0]); }

glm::vec3 vec3(const Context& ctx, pugi::xml_node node) {
    const std::vector<double> v = exactly(ctx, node, 3);
    return glm::vec3(toFloat(ctx, node, v[0]), toFloat(ctx, node, v[1]), toFloat(ctx, node, v[2]));
}

long long integer(const Context& ctx, pugi::xml_node node, long long lo, long long hi) {
    const std::vector<long long> v = integers(ctx, node);
    if (v.size() != 1) ctx.fail(node, "expected one integer, found " + std::to_string(v.size()) + " values");
    if (v[0] < lo || v[0] > hi)
        ctx.fail(
            node, std::to_string(v[0]) + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return v[0];
}

pugi::xml_node required(const Context& ctx, pugi::xml_node parent, const char* child) {
    pugi::xml_node n = parent.child(child);
    if (!n) ctx.fail(parent, std::string("missing <") + child + ">");
    return n;
}

std::optional<float> optionalScalar(const Context& ctx, pugi::xml_node parent, const char* child) {
    pugi::xml_node n = parent.child(child);
    if (!n) return std::nullopt;
    return scalar(ctx, n);
}

std::optional<glm::vec3> optionalVec3(const Context& ctx, pugi::xml_node parent, const char* child) {
    pugi::xml_node n = parent.child(child);
    if (!n) return std::nullopt;
    return vec3(ctx, n);
}

long long idOf(const Context& ctx, pugi::xml_node node) {
    pugi::xml_attribute id = node.attribute("id");
    if (!id) ctx.fail(node, "missing id attribute");
    return toInteger(ctx, node, id.value());
}

std::string idText(pugi::xml_node node, const std::string& fallback) {
    pugi::xml_attribute id = node.attribute("id");
    return id ? printable(id.value()) : fallback;
}

long long integerAttribute(const Context& ctx, pugi::xml_node node, const char* name, long long fallback) {
    pugi::xml_attribute a = node.attribute(name);
    if (!a) return fallback;
    const std::vector<std::string_view> t = tokens(a.value());
    if (t.size() != 1) ctx.fail(node, std::string(name) + " " + quote(a.value()) + " is not an integer");
    return toInteger(ctx, node, t[0]);
}

std::string lowercase(std::string_view s) {
    std::string out(s);
    std::transform(
        out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

bool booleanValue(const Context& ctx, pugi::xml_node where, std::string_view text, const char* what) {
    const std::vector<std::string_view> t = tokens(text);
    const std::string v = t.size() == 1 ? lowercase(t[0]) : std::string();
    if (v == "true" || v == "1") return true;
    if (v == "false" || v == "0") return false;
    ctx.fail(where, std::string(what) + " " + quote(text) + " is not true or false");
}

} // namespace pt::ceng795
