#include "scene/ceng795/transforms.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace pt::ceng795 {

glm::mat4 translationMatrix(const glm::vec3& d) { return glm::translate(glm::mat4(1.0f), d); }

glm::mat4 scalingMatrix(const glm::vec3& s) { return glm::scale(glm::mat4(1.0f), s); }

glm::mat4 rotationMatrix(float degrees, const glm::vec3& axis) {
    return glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::normalize(axis));
}

glm::mat4 compositeMatrix(const double rowMajor[16]) {
    glm::mat4 m(1.0f);
    // glm indexes m[column][row]; the file lists rows.
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) m[col][row] = static_cast<float>(rowMajor[row * 4 + col]);
    return m;
}

namespace {

bool finiteMatrix(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

// Singular maps flatten geometry and leave normals (inverse transpose) undefined.
bool invertible(const glm::mat4& m) {
    const float det = glm::determinant(glm::mat3(m));
    return std::isfinite(det) && det != 0.0f;
}

glm::mat4 readTranslation(const Context& ctx, pugi::xml_node e) { return translationMatrix(vec3(ctx, e)); }

glm::mat4 readScaling(const Context& ctx, pugi::xml_node e) {
    const glm::vec3 s = vec3(ctx, e);
    if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f) ctx.fail(e, "scale factors must be non-zero");
    return scalingMatrix(s);
}

glm::mat4 readRotation(const Context& ctx, pugi::xml_node e) {
    const std::vector<double> v = numbers(ctx, e);
    if (v.size() != 4) ctx.fail(e, "expected angle and axis (4 numbers), found " + std::to_string(v.size()));
    const glm::vec3 axis(static_cast<float>(v[1]), static_cast<float>(v[2]), static_cast<float>(v[3]));
    const float len = glm::length(axis);
    if (!(len > 0.0f) || !std::isfinite(len)) ctx.fail(e, "rotation axis must be non-zero");
    return rotationMatrix(static_cast<float>(v[0]), axis);
}

glm::mat4 readComposite(const Context& ctx, pugi::xml_node e) {
    const std::vector<double> v = numbers(ctx, e);
    if (v.size() != 16) ctx.fail(e, "expected 16 numbers (a row-major 4x4 matrix), found " + std::to_string(v.size()));
    // Only affine maps keep triangles triangles and spheres quadrics the renderer can handle.
    if (v[12] != 0.0 || v[13] != 0.0 || v[14] != 0.0 || v[15] != 1.0) ctx.fail(e, "last row must be 0 0 0 1");
    return compositeMatrix(v.data());
}

} // namespace

void Transforms::add(const Context& ctx, pugi::xml_node element, char kind, const glm::mat4& m) {
    if (!finiteMatrix(m)) ctx.fail(element, "matrix is not finite");
    if (!invertible(m)) ctx.fail(element, "matrix is singular");
    const long long id = idOf(ctx, element);
    if (!byKind_[kind].emplace(id, m).second) ctx.fail(element, "duplicate id");
}

Transforms Transforms::read(const Context& ctx, pugi::xml_node scene) {
    Transforms t;
    for (pugi::xml_node list : scene.children("Transformations"))
        for (pugi::xml_node e : list.children()) {
            if (e.type() != pugi::node_element) continue;
            const std::string name = e.name();
            if (name == "Translation")
                t.add(ctx, e, 't', readTranslation(ctx, e));
            else if (name == "Scaling")
                t.add(ctx, e, 's', readScaling(ctx, e));
            else if (name == "Rotation")
                t.add(ctx, e, 'r', readRotation(ctx, e));
            else if (name == "Composite")
                t.add(ctx, e, 'c', readComposite(ctx, e));
            else
                ctx.fail(e, "unknown transformation (expected Translation, Scaling, Rotation or Composite)");
        }
    return t;
}

glm::mat4 Transforms::compose(const Context& ctx, pugi::xml_node list) const {
    glm::mat4 m(1.0f);
    if (!list) return m;
    const std::string text = textOf(list);
    for (std::string_view token : tokens(text)) {
        const char kind = token.empty() ? '\0' : static_cast<char>(std::tolower(static_cast<unsigned char>(token[0])));
        if (token.size() < 2 || (kind != 't' && kind != 's' && kind != 'r' && kind != 'c'))
            ctx.fail(list, quote(token) + " is not a transformation reference (t, s, r or c followed by an id)");
        const long long id = toInteger(ctx, list, token.substr(1));
        auto kindIt = byKind_.find(kind);
        auto it = kindIt == byKind_.end() ? std::map<long long, glm::mat4>::const_iterator() : kindIt->second.find(id);
        if (kindIt == byKind_.end() || it == kindIt->second.end())
            ctx.fail(list, "unknown transformation " + quote(token));
        m = it->second * m; // applied after everything to its left
    }
    if (!finiteMatrix(m) || !invertible(m)) ctx.fail(list, "combined transformation is singular or not finite");
    return m;
}

} // namespace pt::ceng795
