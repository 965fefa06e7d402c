#pragma once
// The course format's named transformations (HW2): <Translation>, <Scaling>, <Rotation> and
// <Composite> under the scene's <Transformations>, referred to by objects as "t1 r2 s1 c1".
#include "scene/ceng795/document.h"

#include <glm/glm.hpp>

#include <map>

namespace pt::ceng795 {

class Transforms {
public:
    // Reads the scene-level <Transformations> element (absent: an empty table).
    static Transforms read(const Context& ctx, pugi::xml_node scene);

    // An object's <Transformations> list, applied left to right: "r1 t1 s2" means first r1, then
    // t1, then s2, so M = S2 · T1 · R1 (column vectors). An absent list is the identity.
    glm::mat4 compose(const Context& ctx, pugi::xml_node list) const;

private:
    void add(const Context& ctx, pugi::xml_node element, char kind, const glm::mat4& m);

    std::map<char, std::map<long long, glm::mat4>> byKind_; // 't', 's', 'r', 'c' -> id -> matrix
};

// The individual matrices, exposed for tests.
glm::mat4 translationMatrix(const glm::vec3& d);
glm::mat4 scalingMatrix(const glm::vec3& s);
glm::mat4 rotationMatrix(float degrees, const glm::vec3& axis); // counter-clockwise about axis
glm::mat4 compositeMatrix(const double rowMajor[16]);

} // namespace pt::ceng795
