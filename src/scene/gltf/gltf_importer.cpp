// The glTF importer's run (gltf_importer.h): the settings carried in the scene's extras, the node
// hierarchy walked from the scene's roots (each node's transform, then its mesh, camera and
// light), and the note of extensions the scene uses that are not supported.
#include "scene/gltf/gltf_importer.h"

#include "scene/memory_estimate.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <set>

namespace pt::gltf {

Scene GltfImporter::run() {
    scene_.source = file_;
    readHints();
    convertMaterials();
    readMaterialVariants();
    std::vector<int> roots = rootNodes();
    // A mesh one node places is copied into world space, one several nodes place is kept once:
    // refuse a scene whose triangles cannot fit before reading them.
    placements_ = placementsPerMesh(roots);
    uint64_t triangles = 0;
    for (size_t m = 0; m < placements_.size(); ++m)
        if (placements_[m] > 0) triangles += meshTriangleCount(static_cast<int>(m));
    requireMemoryForTriangles(file_, triangles, "each mesh once");
    std::vector<bool> onPath(model_.nodes.size(), false);
    for (int root : roots) visitNode(root, glm::mat4(1.0f), onPath, 0);
    if (scene_.triangleCount() == 0) fail("no renderable geometry (the scene has no triangle primitives)");
    noteUnsupportedExtensions();
    std::vector<std::string> notes;
    for (const auto& [what, count] : unsupportedCounts_)
        notes.push_back(count > 1 ? what + " (x" + std::to_string(count) + ")" : what);
    scene_.unsupported = notes;
    return std::move(scene_);
}

// ---- settings carried in scenes[].extras (width, height, max_depth) ----
void GltfImporter::readHints() {
    int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (sceneIndex >= static_cast<int>(model_.scenes.size())) return;
    const tinygltf::Value& extras = model_.scenes[sceneIndex].extras;
    if (!extras.IsObject()) return;
    // extras are free-form: a value of another type may mean something else to another tool, so it
    // is ignored, with a note; a fractional one is rounded down, also with a note.
    auto intHint = [&](const char* key, std::optional<int>& out, int lo, int hi) {
        if (!extras.Has(key)) return;
        const tinygltf::Value& v = extras.Get(key);
        if (!v.IsNumber()) {
            unsupported(std::string("scene extras: ") + key + " that is not a number (ignored)");
            return;
        }
        double d = v.GetNumberAsDouble();
        if (!(d >= lo && d <= hi))
            fail(std::string("scene extras: ") + key + " " + std::to_string(d) + " is out of range");
        out = static_cast<int>(d);
        if (double(*out) != d)
            unsupported(std::string("scene extras: ") + key + " " + formatNumber(d) + " is not an integer (" +
                        std::to_string(*out) + " assumed)");
    };
    intHint("width", scene_.hints.width, 1, 1 << 16);
    intHint("height", scene_.hints.height, 1, 1 << 16);
    intHint("max_depth", scene_.hints.maxDepth, 1, 1 << 16);
}

// ---- node hierarchy ----
std::vector<int> GltfImporter::rootNodes() {
    std::vector<int> roots;
    if (!model_.scenes.empty()) {
        int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
        // The spec leaves the choice to the application when `scene` is absent.
        if (model_.defaultScene < 0 && model_.scenes.size() > 1)
            unsupported("no default scene among " + std::to_string(model_.scenes.size()) + " (scene 0 assumed)");
        if (s >= static_cast<int>(model_.scenes.size())) fail("default scene " + std::to_string(s) + " does not exist");
        roots = model_.scenes[s].nodes;
    } else {
        // No scene: every node that is nobody's child is a root.
        std::vector<bool> isChild(model_.nodes.size(), false);
        for (const auto& n : model_.nodes)
            for (int c : n.children)
                if (c >= 0 && c < static_cast<int>(isChild.size())) isChild[c] = true;
        for (size_t i = 0; i < model_.nodes.size(); ++i)
            if (!isChild[i]) roots.push_back(static_cast<int>(i));
        if (roots.empty() && !model_.nodes.empty()) fail("node hierarchy is cyclic (every node is a child)");
    }
    return roots;
}

glm::mat4 GltfImporter::localTransform(const tinygltf::Node& node, int index) {
    glm::mat4 m(1.0f);
    if (node.matrix.size() == 16) {
        for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = static_cast<float>(node.matrix[i]);
    } else {
        glm::vec3 t(0.0f), s(1.0f);
        glm::quat r(1.0f, 0.0f, 0.0f, 0.0f);
        if (node.translation.size() == 3) t = glm::vec3(node.translation[0], node.translation[1], node.translation[2]);
        if (node.scale.size() == 3) s = glm::vec3(node.scale[0], node.scale[1], node.scale[2]);
        if (node.rotation.size() == 4)
            r = glm::normalize(glm::quat(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2])));
        m = glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(r) * glm::scale(glm::mat4(1.0f), s);
    }
    for (int i = 0; i < 16; ++i)
        if (!std::isfinite(glm::value_ptr(m)[i])) fail("node " + std::to_string(index) + ": transform is not finite");
    return m;
}

void GltfImporter::visitNode(int index, const glm::mat4& parent, std::vector<bool>& onPath, int depth) {
    if (index < 0 || index >= static_cast<int>(model_.nodes.size()))
        fail("node index " + std::to_string(index) + " out of range");
    if (onPath[index]) fail("node hierarchy is cyclic (node " + std::to_string(index) + " is its own ancestor)");
    if (depth > kMaxNodeDepth) fail("node hierarchy deeper than " + std::to_string(kMaxNodeDepth));
    if (visited_.size() != model_.nodes.size()) visited_.assign(model_.nodes.size(), false);
    if (visited_[index] && ++repeatedVisits_ > kMaxRepeatedNodeVisits)
        fail("node " + std::to_string(index) + " is shared by several parents: the hierarchy expands to more than " +
             std::to_string(kMaxRepeatedNodeVisits) + " extra node instances");
    visited_[index] = true;
    const tinygltf::Node& node = model_.nodes[index];
    glm::mat4 world = parent * localTransform(node, index);
    for (int i = 0; i < 16; ++i)
        if (!std::isfinite(glm::value_ptr(world)[i]))
            fail("node " + std::to_string(index) + ": world transform overflows");
    if (node.mesh >= 0) {
        if (node.mesh >= static_cast<int>(model_.meshes.size()))
            fail("node " + std::to_string(index) + ": mesh index out of range");
        placeMesh(node.mesh, world, index);
    }
    if (node.camera >= 0) addCamera(node.camera, world);
    if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end())
        addLight(it->second, index, world);
    onPath[index] = true;
    for (int child : node.children) visitNode(child, world, onPath, depth + 1);
    onPath[index] = false;
}

// ---- KHR_materials_variants ----
// The scene's variant names (root extension), and the index of the one asked for.
void GltfImporter::readMaterialVariants() {
    if (auto it = model_.extensions.find("KHR_materials_variants"); it != model_.extensions.end()) {
        const tinygltf::Value& ext = it->second;
        if (!ext.IsObject() || !ext.Has("variants") || !ext.Get("variants").IsArray())
            fail("KHR_materials_variants: no variants array");
        const tinygltf::Value& variants = ext.Get("variants");
        for (size_t i = 0; i < variants.ArrayLen(); ++i) {
            const tinygltf::Value& v = variants.Get(static_cast<int>(i));
            if (!v.IsObject() || !v.Has("name") || !v.Get("name").IsString())
                fail("KHR_materials_variants: variant " + std::to_string(i) + " has no name");
            scene_.materialVariants.push_back(v.Get("name").Get<std::string>());
        }
    }
    if (variant_.empty()) return;
    const auto& names = scene_.materialVariants;
    const auto found = std::find(names.begin(), names.end(), variant_);
    if (found == names.end()) {
        std::string list;
        for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
        fail("no material variant '" + variant_ + "' (" +
             (names.empty() ? std::string("the scene has none") : "the scene's: " + list) + ")");
    }
    variantIndex_ = static_cast<int>(found - names.begin());
    scene_.variant = variant_;
}

// A primitive's material: the chosen variant's mapping where the primitive has one, else its own.
int GltfImporter::primitiveMaterial(const tinygltf::Primitive& prim, const std::string& label) const {
    if (variantIndex_ < 0) return prim.material;
    auto it = prim.extensions.find("KHR_materials_variants");
    if (it == prim.extensions.end()) return prim.material;
    const tinygltf::Value& ext = it->second;
    if (!ext.IsObject() || !ext.Has("mappings") || !ext.Get("mappings").IsArray())
        fail(label + ": KHR_materials_variants without a mappings array");
    const tinygltf::Value& mappings = ext.Get("mappings");
    for (size_t m = 0; m < mappings.ArrayLen(); ++m) {
        const tinygltf::Value& mapping = mappings.Get(static_cast<int>(m));
        if (!mapping.IsObject() || !mapping.Has("variants") || !mapping.Get("variants").IsArray() ||
            !mapping.Has("material") || !mapping.Get("material").IsInt())
            fail(label + ": KHR_materials_variants mapping " + std::to_string(m) + " needs variants and a material");
        const tinygltf::Value& variants = mapping.Get("variants");
        for (size_t v = 0; v < variants.ArrayLen(); ++v) {
            const tinygltf::Value& index = variants.Get(static_cast<int>(v));
            if (index.IsInt() && index.GetNumberAsInt() == variantIndex_) {
                const int material = mapping.Get("material").GetNumberAsInt();
                if (material < 0)
                    fail(label + ": KHR_materials_variants mapping to material " + std::to_string(material));
                return material;
            }
        }
    }
    return prim.material;
}

void GltfImporter::noteUnsupportedExtensions() {
    static const std::set<std::string> supported = {"KHR_materials_emissive_strength", "KHR_materials_ior",
        "KHR_materials_specular", "KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_variants",
        "KHR_materials_diffuse_transmission", "KHR_materials_clearcoat", "KHR_materials_sheen",
        "KHR_materials_iridescence", "KHR_materials_anisotropy", "KHR_materials_dispersion",
        "KHR_materials_pbrSpecularGlossiness", "KHR_materials_unlit", "KHR_lights_punctual", "KHR_texture_transform"};
    for (const auto& e : model_.extensionsUsed)
        if (!supported.count(e)) unsupported("extension " + e);
}

} // namespace pt::gltf
