#pragma once
// <Materials> of the course format mapped onto the renderer's four material types.
#include "scene/ceng795/document.h"
#include "scene/scene.h"

#include <map>

namespace pt::ceng795 {

class MaterialTable {
public:
    // Reads every <Material> into `out` (in file order) and remembers its index.
    static MaterialTable read(const Context& ctx, pugi::xml_node scene, std::vector<Material>& out);

    // The scene index of the material an object's <Material>id</Material> names; marks it used.
    uint32_t lookup(const Context& ctx, pugi::xml_node reference);

    // Passes on the approximations made for the materials objects use: course files often
    // carry unused leftovers, which should not produce warnings.
    void noteUsed(Context& ctx) const;

private:
    std::map<long long, uint32_t> indexById_;
    std::vector<std::vector<std::string>> notes_; // per material
    std::vector<bool> used_;
};

// One course <Material> element as a scene Material (exposed for tests); approximations made
// are appended to `notes`.
// `brdfs` maps each <BRDFs> child's id to its element.
Material convertMaterial(const Context& ctx, pugi::xml_node element, const std::map<long long, pugi::xml_node>& brdfs,
    std::vector<std::string>& notes);

// A copy of materials[base] that emits `radiance`, for LightMesh and LightSphere: the course
// gives each object light a (black) material plus its own Radiance. Returns the new index.
uint32_t addEmissiveCopy(
    std::vector<Material>& materials, uint32_t base, const glm::vec3& radiance, const std::string& name);

} // namespace pt::ceng795
