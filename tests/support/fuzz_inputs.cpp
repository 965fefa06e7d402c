#include "support/fuzz_inputs.h"

#include "scene/ceng795/loader.h"
#include "scene/gltf/gltf_loader.h"
#include "scene/ceng795/ply_reader.h"
#include "scene/scene_error.h"
#include "image/texture_image.h"
#include "support/load_contract.h"

#include <cmath>
#include <stdexcept>

namespace pt::test {
namespace {

// The name errors must start with; no real file has it, so a message cannot pass by naming another.
constexpr const char* kDisplayName = "fuzz-input";

// A PLY mesh must be consistent as it is; a point cloud (no faces) is a valid PLY file.
std::string plyContract(std::string_view bytes) {
    try {
        const PlyMesh ply = parsePly(bytes, kDisplayName);
        if (ply.positions.empty() && ply.triangles.empty()) return "";
        Scene scene;
        scene.materials.emplace_back();
        Mesh& mesh = scene.meshes.emplace_back();
        mesh.name = kDisplayName;
        mesh.positions = ply.positions;
        mesh.normals = ply.normals;
        mesh.uvs = ply.uvs;
        mesh.triangles = ply.triangles;
        for (const glm::vec3& n : ply.normals)
            if (!std::isfinite(n.x + n.y + n.z)) return "accepted a non-finite normal";
        const std::string p = sceneInconsistency(scene);
        return p.empty() ? "" : "accepted an inconsistent mesh: " + p;
    } catch (const SceneError& e) {
        return messageProblem(e.what(), kDisplayName);
    } catch (const std::exception& e) {
        return std::string("an exception other than SceneError escaped the PLY reader: ") + e.what();
    }
}

// Image decoding reports std::runtime_error "<source>: <problem>" (texture_image.h).
std::string textureContract(std::string_view bytes) {
    try {
        const TextureImage image =
            decodeTextureImage(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), kDisplayName);
        const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
        if (image.width <= 0 || image.height <= 0 || image.width > kMaxTextureSide || image.height > kMaxTextureSide)
            return "accepted an image of " + std::to_string(image.width) + "x" + std::to_string(image.height);
        if (image.rgba8.size() != pixels && image.rgbaF.size() != pixels)
            return "pixel count differs from the image size";
        return "";
    } catch (const std::runtime_error& e) {
        return messageProblem(e.what(), kDisplayName);
    } catch (const std::exception& e) {
        return std::string("an exception other than std::runtime_error escaped the image decoder: ") + e.what();
    }
}

} // namespace

const char* fuzzTargetName(FuzzTarget target) {
    switch (target) {
    case FuzzTarget::Gltf: return "gltf";
    case FuzzTarget::Ceng795: return "ceng795";
    case FuzzTarget::Ply: return "ply";
    case FuzzTarget::TextureImage: return "texture_image";
    }
    return "?";
}

std::vector<FuzzTarget> allFuzzTargets() {
    return {FuzzTarget::Gltf, FuzzTarget::Ceng795, FuzzTarget::Ply, FuzzTarget::TextureImage};
}

std::string fuzzOneInput(FuzzTarget target, std::string_view bytes, const std::filesystem::path& dataDir) {
    switch (target) {
    case FuzzTarget::Gltf:
        return checkLoadContract(kDisplayName, [&] { return loadGltfMemory(bytes, kDisplayName, dataDir); });
    case FuzzTarget::Ceng795:
        return checkLoadContract(kDisplayName, [&] { return loadCeng795Text(bytes, kDisplayName, dataDir); });
    case FuzzTarget::Ply: return plyContract(bytes);
    case FuzzTarget::TextureImage: return textureContract(bytes);
    }
    return "unknown fuzz target";
}

} // namespace pt::test
