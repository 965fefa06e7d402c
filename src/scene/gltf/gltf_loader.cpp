#include "scene/gltf/gltf_loader.h"

#include "scene/scene_error.h"
#include "image/texture_image.h"

#include <tiny_gltf.h>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace pt {
namespace {

constexpr int kMaxNodeDepth = 1024;
// A node may be the child of several parents (glTF forbids it, files do it anyway), so a small
// file can describe an exponential number of instances: 40 nodes that each list the next one
// twice make 2^40. A tree visits each node once, whatever its size; repeat visits are bounded,
// and so are the vertices and triangles all instances add up to.
constexpr size_t kMaxRepeatedNodeVisits = size_t(1) << 12;
constexpr size_t kMaxInstanced = size_t(1) << 27; // vertices, and triangles

// Images decoded as tinygltf reads them (from data URIs, files or buffer views), with our own
// decoder: one code path and one set of size limits for every image, and the error names the
// image. Indexed like the model's images; an image no texture uses is decoded all the same.
struct DecodedImages {
    std::vector<std::optional<TextureImage>> images;
};

bool decodeImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
    const unsigned char* bytes, int size, void* user) {
    auto* decoded = static_cast<DecodedImages*>(user);
    const std::string name = "image " + std::to_string(index) + (image->uri.empty() || image->uri.rfind("data:", 0) == 0 ? "" : " '" + image->uri + "'");
    try {
        if (index < 0) throw std::runtime_error(name + ": bad index");
        if (decoded->images.size() <= static_cast<size_t>(index)) decoded->images.resize(index + 1);
        decoded->images[index] = decodeTextureImage(bytes, size < 0 ? 0 : static_cast<size_t>(size), name);
    } catch (const std::exception& e) {
        if (err) *err += e.what();
        return false;
    }
    image->width = decoded->images[index]->width;
    image->height = decoded->images[index]->height;
    return true;
}

// ---- file access for external buffers and images ----
// tinygltf's own callbacks trust the file: a URI naming a directory made its ReadWholeFile ask for
// 2^63 bytes (found by fuzzing), a device such as /dev/zero has no end, and its path expansion
// runs wordexp() on the URI. Ours take the path as written (relative to the scene's folder),
// read regular files only and bound their size.
constexpr uint64_t kMaxExternalFileBytes = uint64_t(1) << 32;

bool fileExists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::exists(path, ec);
}

std::string pathAsWritten(const std::string& path, void*) { return path; }

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
    auto problem = [&](const std::string& what) {
        if (err) *err += "File " + what + " : " + path + "\n";
        return false;
    };
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (status.type() == std::filesystem::file_type::not_found) return problem("not found");
    if (!std::filesystem::is_regular_file(status)) return problem("is not a regular file");
    const uint64_t size = std::filesystem::file_size(path, ec);
    if (ec) return problem("size unreadable");
    if (size == 0) return problem("is empty");
    if (size > kMaxExternalFileBytes) return problem("is larger than 4 GiB");
    std::ifstream in(path, std::ios::binary);
    if (!in) return problem("cannot be opened");
    out->resize(size);
    if (!in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size))) return problem("read failed");
    return true;
}

bool refuseWrite(std::string* err, const std::string& path, const std::vector<unsigned char>&, void*) {
    if (err) *err += "pt never writes glTF files: " + path + "\n";
    return false;
}

void configureLoader(tinygltf::TinyGLTF& loader, DecodedImages& images) {
    loader.SetImageLoader(&decodeImage, &images);
    loader.SetFsCallbacks(tinygltf::FsCallbacks{&fileExists, &pathAsWritten, &readWholeFile, &refuseWrite, nullptr});
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

class GltfImporter {
public:
    GltfImporter(const tinygltf::Model& model, std::string file, DecodedImages& images)
        : model_(model), file_(std::move(file)), decoded_(images) {}

    Scene run() {
        scene_.source = file_;
        readHints();
        convertMaterials();
        std::vector<int> roots = rootNodes();
        std::vector<bool> onPath(model_.nodes.size(), false);
        for (int root : roots) visitNode(root, glm::mat4(1.0f), onPath, 0);
        if (scene_.triangleCount() == 0)
            fail("no renderable geometry (the scene has no triangle primitives)");
        noteUnsupportedExtensions();
        std::vector<std::string> notes;
        for (const auto& [what, count] : unsupportedCounts_)
            notes.push_back(count > 1 ? what + " (x" + std::to_string(count) + ")" : what);
        scene_.unsupported = notes;
        return std::move(scene_);
    }

private:
    [[noreturn]] void fail(const std::string& problem) const { throw SceneError(file_, problem); }
    void unsupported(const std::string& what) { unsupportedCounts_[what]++; }

    // ---- settings carried in scenes[].extras (width, height, max_depth) ----
    void readHints() {
        int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
        if (sceneIndex >= static_cast<int>(model_.scenes.size())) return;
        const tinygltf::Value& extras = model_.scenes[sceneIndex].extras;
        if (!extras.IsObject()) return;
        auto intHint = [&](const char* key, std::optional<int>& out, int lo, int hi) {
            if (!extras.Has(key)) return;
            const tinygltf::Value& v = extras.Get(key);
            if (!v.IsNumber()) return;
            double d = v.GetNumberAsDouble();
            if (!(d >= lo && d <= hi)) fail(std::string("scene extras: ") + key + " " + std::to_string(d) + " is out of range");
            out = static_cast<int>(d);
        };
        intHint("width", scene_.hints.width, 1, 1 << 16);
        intHint("height", scene_.hints.height, 1, 1 << 16);
        intHint("max_depth", scene_.hints.maxDepth, 1, 1 << 16);
    }

    // ---- materials ----
    static double number(const tinygltf::Value& obj, const char* key, double fallback) {
        if (!obj.IsObject() || !obj.Has(key)) return fallback;
        const tinygltf::Value& v = obj.Get(key);
        return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
    }
    static glm::vec3 color(const tinygltf::Value& obj, const char* key, glm::vec3 fallback) {
        if (!obj.IsObject() || !obj.Has(key)) return fallback;
        const tinygltf::Value& v = obj.Get(key);
        if (!v.IsArray() || v.ArrayLen() < 3) return fallback;
        glm::vec3 c;
        for (int i = 0; i < 3; ++i) c[i] = v.Get(i).IsNumber() ? static_cast<float>(v.Get(i).GetNumberAsDouble()) : fallback[i];
        return c;
    }
    static const tinygltf::Value* extension(const tinygltf::Material& m, const char* name) {
        auto it = m.extensions.find(name);
        return it == m.extensions.end() ? nullptr : &it->second;
    }

    // The glTF metallic-roughness factors and the KHR_materials_* extensions. Everything is a
    // MaterialType::Pbr (shaders/bsdf/gltf_pbr.glsl) except three cases where the glTF model
    // reduces exactly to a simpler one, kept because scenes made for other renderers (the
    // Mitsuba references in tests/references) use them to say "Lambertian", "mirror" and "glass":
    //   metallic 0, transmission 0, KHR_materials_specular specularFactor 0  -> Lambertian
    //   metallic 1, roughness 0                                               -> Schlick mirror
    //   metallic 0, transmission 1, default specular, KHR_materials_volume    -> dielectric (GGX
    //     when rough), which also carries the volume's Beer-Lambert absorption.
    void convertFactors(const tinygltf::Material& src, const std::string& label, Material& m) {
        const auto& pbr = src.pbrMetallicRoughness;
        auto unit = [&](double v, const char* what) {
            if (!(v >= 0.0 && v <= 1.0)) fail(label + ": " + what + " " + std::to_string(v) + " must be in [0, 1]");
            return static_cast<float>(v);
        };
        m.metallic = unit(pbr.metallicFactor, "metallicFactor");
        m.roughness = unit(pbr.roughnessFactor, "roughnessFactor");
        if (const auto* e = extension(src, "KHR_materials_transmission"))
            m.transmission = unit(number(*e, "transmissionFactor", 0.0), "transmissionFactor");
        if (const auto* e = extension(src, "KHR_materials_ior")) m.ior = static_cast<float>(number(*e, "ior", 1.5));
        if (!(m.ior >= 1.0f && m.ior < 10.0f)) fail(label + ": ior " + std::to_string(m.ior) + " must be in [1, 10)");
        m.specular = glm::vec3(1.0f);
        if (const auto* e = extension(src, "KHR_materials_specular")) {
            m.specularWeight = unit(number(*e, "specularFactor", 1.0), "specularFactor");
            m.specular = color(*e, "specularColorFactor", glm::vec3(1.0f));
            if (!finite(m.specular) || glm::any(glm::lessThan(m.specular, glm::vec3(0))))
                fail(label + ": specularColorFactor must be finite and non-negative");
        }
        // A volume makes transmission refract; thicknessFactor only approximates the volume's
        // depth for rasterisers (the path tracer has the mesh itself), so only 0 -- "thin
        // walled" -- is used from it.
        const tinygltf::Value* volume = extension(src, "KHR_materials_volume");
        m.thinWalled = volume == nullptr || number(*volume, "thicknessFactor", 0.0) <= 0.0;
        if (volume) {
            m.attenuationColor = color(*volume, "attenuationColor", glm::vec3(1.0f));
            m.attenuationDistance = static_cast<float>(number(*volume, "attenuationDistance", INFINITY));
            if (!(m.attenuationDistance > 0) || !finite(m.attenuationColor) ||
                glm::any(glm::lessThan(m.attenuationColor, glm::vec3(0))))
                fail(label + ": KHR_materials_volume attenuation must be positive");
        }
        const bool defaultSpecular = m.specularWeight == 1.0f && m.specular == glm::vec3(1.0f);
        if (m.metallic == 0.0f && m.transmission == 0.0f && m.specularWeight == 0.0f) {
            m.type = MaterialType::Diffuse;
        } else if (m.metallic == 1.0f && m.roughness == 0.0f) {
            m.type = MaterialType::Mirror;
        } else if (m.metallic == 0.0f && m.transmission == 1.0f && defaultSpecular && !m.thinWalled) {
            m.type = MaterialType::Dielectric;
        } else {
            m.type = MaterialType::Pbr;
        }
    }

    void convertMaterials() {
        for (size_t i = 0; i < model_.materials.size(); ++i) {
            const tinygltf::Material& src = model_.materials[i];
            const std::string label = "material " + std::to_string(i) + (src.name.empty() ? "" : " '" + src.name + "'");
            Material m;
            m.name = src.name.empty() ? "material " + std::to_string(i) : src.name;
            m.doubleSided = src.doubleSided;
            const auto& pbr = src.pbrMetallicRoughness;
            for (int c = 0; c < 3; ++c) m.baseColor[c] = pbr.baseColorFactor.size() > 2 ? static_cast<float>(pbr.baseColorFactor[c]) : 1.0f;
            for (int c = 0; c < 3; ++c) m.emission[c] = src.emissiveFactor.size() > 2 ? static_cast<float>(src.emissiveFactor[c]) : 0.0f;
            if (const auto* e = extension(src, "KHR_materials_emissive_strength"))
                m.emission *= static_cast<float>(number(*e, "emissiveStrength", 1.0));
            if (!finite(m.baseColor) || !finite(m.emission) || glm::any(glm::lessThan(m.emission, glm::vec3(0))))
                fail(label + ": base colour and emission must be finite and non-negative");
            m.baseColor = glm::clamp(m.baseColor, 0.0f, 1.0f);

            convertFactors(src, label, m);
            convertTextures(src, label, m);
            scene_.materials.push_back(m);
        }
    }

    // ---- textures ----
    // baseColor and emissive are sRGB-encoded, metallicRoughness and normal linear (glTF 2.0
    // section 3.9). Occlusion is for rasterisers: a path tracer computes it.
    void convertTextures(const tinygltf::Material& src, const std::string& label, Material& m) {
        const auto& pbr = src.pbrMetallicRoughness;
        m.baseColorTexture = texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, pbr.baseColorTexture.extensions,
            Texture::Encoding::Srgb, label + ": baseColorTexture");
        m.metallicRoughnessTexture = texture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
            pbr.metallicRoughnessTexture.extensions, Texture::Encoding::Linear, label + ": metallicRoughnessTexture");
        m.normalTexture = texture(src.normalTexture.index, src.normalTexture.texCoord, src.normalTexture.extensions,
            Texture::Encoding::Linear, label + ": normalTexture");
        m.normalScale = static_cast<float>(src.normalTexture.scale);
        if (!std::isfinite(m.normalScale)) fail(label + ": normalTexture scale must be finite");
        m.emissiveTexture = texture(src.emissiveTexture.index, src.emissiveTexture.texCoord, src.emissiveTexture.extensions,
            Texture::Encoding::Srgb, label + ": emissiveTexture");
        // A texture can make a "mirror" rough or part-metal: only the full model covers that.
        if (m.metallicRoughnessTexture && m.type == MaterialType::Mirror) m.type = MaterialType::Pbr;

        m.opacity = pbr.baseColorFactor.size() > 3 ? static_cast<float>(pbr.baseColorFactor[3]) : 1.0f;
        if (!(m.opacity >= 0.0f && m.opacity <= 1.0f)) fail(label + ": baseColorFactor alpha must be in [0, 1]");
        if (src.alphaMode == "MASK") {
            m.alphaMode = Material::AlphaMode::Mask;
            m.alphaCutoff = static_cast<float>(src.alphaCutoff);
            if (!std::isfinite(m.alphaCutoff)) fail(label + ": alphaCutoff must be finite");
        } else if (src.alphaMode == "BLEND") {
            m.alphaMode = Material::AlphaMode::Blend;
        } else if (!src.alphaMode.empty() && src.alphaMode != "OPAQUE") {
            fail(label + ": unknown alphaMode '" + src.alphaMode + "'");
        }
    }

    static int wrap(int mode, const std::string& where, const GltfImporter& self) {
        switch (mode) {
        case 10497: return static_cast<int>(TextureWrap::Repeat);
        case 33071: return static_cast<int>(TextureWrap::Clamp);
        case 33648: return static_cast<int>(TextureWrap::Mirror);
        default: self.fail(where + ": unknown wrap mode " + std::to_string(mode));
        }
    }

    // A scene texture for one textureInfo (with its KHR_texture_transform), or none.
    std::optional<uint32_t> texture(int index, int texCoord, const tinygltf::ExtensionMap& extensions, Texture::Encoding encoding,
        const std::string& where) {
        if (index < 0) return std::nullopt;
        if (index >= static_cast<int>(model_.textures.size())) fail(where + ": texture " + std::to_string(index) + " does not exist");
        const tinygltf::Texture& src = model_.textures[index];
        if (src.source < 0 || src.source >= static_cast<int>(model_.images.size()))
            fail(where + ": texture " + std::to_string(index) + " has no image (or one in an unsupported extension)");
        Texture t;
        t.encoding = encoding;
        t.image = imageIndex(src.source, where);
        if (src.sampler >= 0) {
            if (src.sampler >= static_cast<int>(model_.samplers.size())) fail(where + ": sampler " + std::to_string(src.sampler) + " does not exist");
            const tinygltf::Sampler& sampler = model_.samplers[src.sampler];
            t.bilinear = sampler.magFilter != 9728; // NEAREST
            t.wrapU = static_cast<TextureWrap>(wrap(sampler.wrapS, where, *this));
            t.wrapV = static_cast<TextureWrap>(wrap(sampler.wrapT, where, *this));
        }
        // KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv.
        if (auto e = extensions.find("KHR_texture_transform"); e != extensions.end()) {
            const tinygltf::Value& x = e->second;
            const double rotation = number(x, "rotation", 0.0);
            glm::dvec2 offset(0.0), scale(1.0);
            auto pair = [&](const char* key, glm::dvec2& out) {
                if (!x.Has(key) || !x.Get(key).IsArray() || x.Get(key).ArrayLen() < 2) return;
                for (int i = 0; i < 2; ++i)
                    if (x.Get(key).Get(i).IsNumber()) out[i] = x.Get(key).Get(i).GetNumberAsDouble();
            };
            pair("offset", offset);
            pair("scale", scale);
            if (!std::isfinite(rotation) || !std::isfinite(offset.x + offset.y + scale.x + scale.y))
                fail(where + ": KHR_texture_transform values must be finite");
            const double c = std::cos(rotation), s = std::sin(rotation);
            t.uvRow0 = glm::vec3(c * scale.x, s * scale.y, offset.x);
            t.uvRow1 = glm::vec3(-s * scale.x, c * scale.y, offset.y);
            if (x.Has("texCoord") && x.Get("texCoord").IsInt()) texCoord = x.Get("texCoord").GetNumberAsInt();
        }
        if (texCoord != 0) unsupported("texture coordinate sets other than TEXCOORD_0 (TEXCOORD_0 used)");
        scene_.textures.push_back(t);
        return static_cast<uint32_t>(scene_.textures.size() - 1);
    }

    // The scene image for glTF image `index`, moved out of the decoded set on first use.
    uint32_t imageIndex(int index, const std::string& where) {
        if (auto it = imageIndices_.find(index); it != imageIndices_.end()) return it->second;
        if (static_cast<size_t>(index) >= decoded_.images.size() || !decoded_.images[index])
            fail(where + ": image " + std::to_string(index) +
                 (model_.images[index].uri.empty() || model_.images[index].uri.rfind("data:", 0) == 0 ? "" : " '" + model_.images[index].uri + "'") +
                 " has no data (its file was not found or could not be read)");
        scene_.textureImages.push_back(std::move(*decoded_.images[index]));
        decoded_.images[index].reset();
        const uint32_t i = static_cast<uint32_t>(scene_.textureImages.size() - 1);
        imageIndices_.emplace(index, i);
        return i;
    }

    uint32_t defaultMaterial() {
        if (defaultMaterial_ < 0) {
            Material m;
            m.name = "glTF default";
            // The glTF default material: white, metallic 1, roughness 1.
            m.type = MaterialType::Pbr;
            m.baseColor = glm::vec3(1.0f);
            m.metallic = 1.0f;
            m.roughness = 1.0f;
            m.specular = glm::vec3(1.0f);
            defaultMaterial_ = static_cast<int>(scene_.materials.size());
            scene_.materials.push_back(m);
        }
        return static_cast<uint32_t>(defaultMaterial_);
    }

    // ---- node hierarchy ----
    std::vector<int> rootNodes() {
        std::vector<int> roots;
        if (!model_.scenes.empty()) {
            int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
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

    glm::mat4 localTransform(const tinygltf::Node& node, int index) {
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

    void visitNode(int index, const glm::mat4& parent, std::vector<bool>& onPath, int depth) {
        if (index < 0 || index >= static_cast<int>(model_.nodes.size())) fail("node index " + std::to_string(index) + " out of range");
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
            if (!std::isfinite(glm::value_ptr(world)[i])) fail("node " + std::to_string(index) + ": world transform overflows");
        if (node.mesh >= 0) {
            if (node.mesh >= static_cast<int>(model_.meshes.size())) fail("node " + std::to_string(index) + ": mesh index out of range");
            addMesh(model_.meshes[node.mesh], node.mesh, world);
        }
        if (node.camera >= 0) addCamera(node.camera, world);
        if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end()) addLight(it->second, index, world);
        onPath[index] = true;
        for (int child : node.children) visitNode(child, world, onPath, depth + 1);
        onPath[index] = false;
    }

    // ---- accessors ----
    // Checks that `count` elements of `elementBytes` each, `stride` apart, fit in the buffer
    // view and the buffer, and returns a pointer to the first one.
    const unsigned char* accessorData(int accessorIndex, const std::string& what, size_t& count, size_t& stride,
        int& componentType, int& type) {
        if (accessorIndex < 0 || accessorIndex >= static_cast<int>(model_.accessors.size()))
            fail(what + ": accessor " + std::to_string(accessorIndex) + " out of range");
        const tinygltf::Accessor& acc = model_.accessors[accessorIndex];
        const std::string label = what + " (accessor " + std::to_string(accessorIndex) + ")";
        if (acc.sparse.isSparse) fail(label + ": sparse accessors are not supported");
        if (acc.bufferView < 0 || acc.bufferView >= static_cast<int>(model_.bufferViews.size()))
            fail(label + ": missing or out-of-range bufferView");
        const tinygltf::BufferView& view = model_.bufferViews[acc.bufferView];
        if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size())) fail(label + ": buffer index out of range");
        const tinygltf::Buffer& buffer = model_.buffers[view.buffer];
        int componentBytes = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(acc.componentType));
        int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(acc.type));
        if (componentBytes <= 0 || components <= 0) fail(label + ": invalid componentType or type");
        const uint64_t elementBytes = static_cast<uint64_t>(componentBytes) * components;
        stride = view.byteStride ? view.byteStride : elementBytes;
        count = acc.count;
        if (count == 0) fail(label + ": count is 0");
        const uint64_t viewEnd = static_cast<uint64_t>(view.byteOffset) + view.byteLength;
        if (view.byteOffset > buffer.data.size() || viewEnd > buffer.data.size())
            fail(label + ": bufferView exceeds its buffer (" + std::to_string(buffer.data.size()) + " bytes)");
        if (count > view.byteLength / std::max<uint64_t>(1, stride) + 1)
            fail(label + ": count " + std::to_string(count) + " exceeds the bufferView");
        const uint64_t last = static_cast<uint64_t>(acc.byteOffset) + (count - 1) * stride + elementBytes;
        if (last > view.byteLength) fail(label + ": count " + std::to_string(count) + " exceeds the bufferView");
        componentType = acc.componentType;
        type = acc.type;
        return buffer.data.data() + view.byteOffset + acc.byteOffset;
    }

    template <int N>
    std::vector<glm::vec<N, float>> readVectors(int accessorIndex, const std::string& what, bool allowNormalizedInts) {
        size_t count, stride;
        int componentType, type;
        const unsigned char* data = accessorData(accessorIndex, what, count, stride, componentType, type);
        const int expectedType = N == 2 ? TINYGLTF_TYPE_VEC2 : (N == 3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4);
        if (type != expectedType) fail(what + " (accessor " + std::to_string(accessorIndex) + "): expected VEC" + std::to_string(N));
        std::vector<glm::vec<N, float>> out(count);
        for (size_t i = 0; i < count; ++i) {
            const unsigned char* e = data + i * stride;
            for (int c = 0; c < N; ++c) {
                float v;
                if (componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) std::memcpy(&v, e + 4 * c, 4);
                else if (allowNormalizedInts && componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) v = e[c] / 255.0f;
                else if (allowNormalizedInts && componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
                    uint16_t s;
                    std::memcpy(&s, e + 2 * c, 2);
                    v = s / 65535.0f;
                } else
                    fail(what + " (accessor " + std::to_string(accessorIndex) + "): unsupported component type " + std::to_string(componentType));
                out[i][c] = v;
            }
        }
        return out;
    }

    std::vector<uint32_t> readIndices(int accessorIndex, const std::string& what) {
        size_t count, stride;
        int componentType, type;
        const unsigned char* data = accessorData(accessorIndex, what, count, stride, componentType, type);
        if (type != TINYGLTF_TYPE_SCALAR) fail(what + ": indices must be SCALAR");
        std::vector<uint32_t> out(count);
        for (size_t i = 0; i < count; ++i) {
            const unsigned char* e = data + i * stride;
            switch (componentType) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[i] = e[0]; break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                uint16_t v;
                std::memcpy(&v, e, 2);
                out[i] = v;
                break;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&out[i], e, 4); break;
            default: fail(what + ": index component type must be unsigned byte, short or int");
            }
        }
        return out;
    }

    // ---- meshes ----
    void addMesh(const tinygltf::Mesh& mesh, int meshIndex, const glm::mat4& world) {
        const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(world));
        // A mirroring transform turns counter-clockwise into clockwise: swap to keep front faces.
        const bool mirrored = glm::determinant(glm::mat3(world)) < 0.0f;
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            const tinygltf::Primitive& prim = mesh.primitives[p];
            const std::string label = "mesh " + std::to_string(meshIndex) + (mesh.name.empty() ? "" : " '" + mesh.name + "'") +
                                      " primitive " + std::to_string(p);
            int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
            if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
                unsupported("point and line primitives (skipped)");
                continue;
            }
            auto pos = prim.attributes.find("POSITION");
            if (pos == prim.attributes.end()) fail(label + ": no POSITION attribute");
            Mesh out;
            out.name = mesh.name.empty() ? "mesh " + std::to_string(meshIndex) : mesh.name;
            out.positions = readVectors<3>(pos->second, label + " POSITION", false);
            for (size_t i = 0; i < out.positions.size(); ++i)
                if (!finite(out.positions[i]))
                    fail(label + " POSITION: vertex " + std::to_string(i) + " is non-finite (NaN or Inf)");
            for (auto& v : out.positions) v = glm::vec3(world * glm::vec4(v, 1.0f));
            for (size_t i = 0; i < out.positions.size(); ++i)
                if (!finite(out.positions[i])) fail(label + ": vertex " + std::to_string(i) + " overflows after transformation");
            if (auto n = prim.attributes.find("NORMAL"); n != prim.attributes.end()) {
                out.normals = readVectors<3>(n->second, label + " NORMAL", false);
                if (out.normals.size() != out.positions.size()) fail(label + ": NORMAL count differs from POSITION count");
                // Invalid normals become zero: the triangle then shades with its geometric normal.
                for (auto& v : out.normals) {
                    glm::vec3 w = normalMatrix * v;
                    float len = glm::length(w);
                    v = (std::isfinite(len) && len > 0.0f) ? w / len : glm::vec3(0.0f);
                }
            }
            if (auto t = prim.attributes.find("TANGENT"); t != prim.attributes.end() && !out.normals.empty()) {
                // Tangents map with the model matrix (they lie in the surface); a mirroring
                // transform flips the bitangent's handedness.
                out.tangents = readVectors<4>(t->second, label + " TANGENT", false);
                if (out.tangents.size() != out.positions.size()) fail(label + ": TANGENT count differs from POSITION count");
                const float handedness = mirrored ? -1.0f : 1.0f;
                for (auto& v : out.tangents) {
                    const glm::vec3 w = glm::mat3(world) * glm::vec3(v);
                    const float len = glm::length(w);
                    const bool ok = std::isfinite(len) && len > 0.0f && std::isfinite(v.w);
                    v = ok ? glm::vec4(w / len, (v.w < 0.0f ? -1.0f : 1.0f) * handedness) : glm::vec4(0.0f);
                }
            }
            if (auto t = prim.attributes.find("TEXCOORD_0"); t != prim.attributes.end()) {
                out.uvs = readVectors<2>(t->second, label + " TEXCOORD_0", true);
                if (out.uvs.size() != out.positions.size()) fail(label + ": TEXCOORD_0 count differs from POSITION count");
            }
            std::vector<uint32_t> indices;
            if (prim.indices >= 0) {
                indices = readIndices(prim.indices, label + " indices");
                for (size_t i = 0; i < indices.size(); ++i)
                    if (indices[i] >= out.positions.size())
                        fail(label + ": index " + std::to_string(indices[i]) + " at position " + std::to_string(i) +
                             " is out of range (" + std::to_string(out.positions.size()) + " vertices)");
            } else {
                indices.resize(out.positions.size());
                for (size_t i = 0; i < indices.size(); ++i) indices[i] = static_cast<uint32_t>(i);
            }
            auto addTriangle = [&](uint32_t a, uint32_t b, uint32_t c) {
                out.triangles.push_back(mirrored ? glm::uvec3(a, c, b) : glm::uvec3(a, b, c));
            };
            if (mode == TINYGLTF_MODE_TRIANGLES) {
                if (indices.size() % 3 != 0) unsupported("triangle lists whose length is not a multiple of 3 (tail dropped)");
                for (size_t i = 0; i + 2 < indices.size(); i += 3) addTriangle(indices[i], indices[i + 1], indices[i + 2]);
            } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                for (size_t i = 0; i + 2 < indices.size(); ++i)
                    if (i % 2 == 0) addTriangle(indices[i], indices[i + 1], indices[i + 2]);
                    else addTriangle(indices[i + 1], indices[i], indices[i + 2]);
            } else {
                for (size_t i = 1; i + 1 < indices.size(); ++i) addTriangle(indices[0], indices[i], indices[i + 1]);
            }
            if (prim.material >= static_cast<int>(model_.materials.size())) fail(label + ": material index out of range");
            out.material = prim.material >= 0 ? static_cast<uint32_t>(prim.material) : defaultMaterial();
            instancedVertices_ += out.positions.size();
            instancedTriangles_ += out.triangles.size();
            if (instancedTriangles_ > kMaxInstanced || instancedVertices_ > kMaxInstanced)
                fail("more than " + std::to_string(kMaxInstanced) + " vertices or triangles once every node instance is expanded");
            if (!out.triangles.empty()) scene_.meshes.push_back(std::move(out));
        }
    }

    // ---- cameras ----
    void addCamera(int cameraIndex, const glm::mat4& world) {
        if (cameraIndex >= static_cast<int>(model_.cameras.size())) fail("camera index " + std::to_string(cameraIndex) + " out of range");
        const tinygltf::Camera& cam = model_.cameras[cameraIndex];
        if (cam.type != "perspective") {
            unsupported("orthographic cameras (skipped)");
            return;
        }
        const double yfov = cam.perspective.yfov;
        if (!(yfov > 0.0 && yfov < M_PI))
            fail("camera " + std::to_string(cameraIndex) + ": yfov " + std::to_string(yfov) + " must be in (0, pi)");
        Camera c;
        c.name = cam.name.empty() ? "camera " + std::to_string(cameraIndex) : cam.name;
        c.position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
        glm::vec3 forward = glm::mat3(world) * glm::vec3(0, 0, -1);
        glm::vec3 up = glm::mat3(world) * glm::vec3(0, 1, 0);
        if (glm::length(forward) == 0.0f || glm::length(glm::cross(forward, up)) == 0.0f)
            fail("camera " + std::to_string(cameraIndex) + ": degenerate camera transform");
        c.forward = glm::normalize(forward);
        c.up = glm::normalize(up - glm::dot(up, c.forward) * c.forward);
        // Lengths that overflow (or vanish) leave no usable frame.
        if (!finite(c.forward) || !finite(c.up) || !(glm::length(c.forward) > 0.5f) || !(glm::length(c.up) > 0.5f))
            fail("camera " + std::to_string(cameraIndex) + ": degenerate camera transform");
        c.yfov = static_cast<float>(yfov);
        // Absent (0) means "the image's"; beyond 1:16384 no image of an allowed size has that shape,
        // and the height derived from it would overflow.
        const double aspect = cam.perspective.aspectRatio;
        if (aspect != 0.0 && !(aspect >= 1.0 / 16384 && aspect <= 16384))
            fail("camera " + std::to_string(cameraIndex) + ": aspectRatio " + std::to_string(aspect) + " must be in [1/16384, 16384]");
        c.aspectRatio = static_cast<float>(aspect);
        scene_.cameras.push_back(c);
    }

    // ---- lights (KHR_lights_punctual) ----
    // Photometric units read as radiometric ones: point and spot intensity (candela) is radiant
    // intensity (W/sr), directional intensity (lux) is irradiance (W/m^2); times the colour.
    // Lights sit at the node's origin and shine along its -z. `range` is a rasteriser's cut-off
    // and is ignored (inverse-square falloff to infinity, as the extension recommends for
    // physically based renderers).
    void addLight(const tinygltf::Value& ref, int nodeIndex, const glm::mat4& world) {
        const std::string where = "node " + std::to_string(nodeIndex) + ": KHR_lights_punctual";
        const int index = ref.IsObject() && ref.Has("light") && ref.Get("light").IsInt() ? ref.Get("light").GetNumberAsInt() : -1;
        if (index < 0 || index >= static_cast<int>(model_.lights.size())) fail(where + " light index out of range");
        const tinygltf::Light& src = model_.lights[index];
        const std::string label = "light " + std::to_string(index) + (src.name.empty() ? "" : " '" + src.name + "'");
        glm::vec3 colour(1.0f);
        if (src.color.size() >= 3) colour = glm::vec3(src.color[0], src.color[1], src.color[2]);
        if (!finite(colour) || glm::any(glm::lessThan(colour, glm::vec3(0))) || !(src.intensity >= 0.0) || !std::isfinite(src.intensity))
            fail(label + ": colour and intensity must be finite and non-negative");
        PunctualLight light;
        light.intensity = colour * static_cast<float>(src.intensity);
        light.position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
        const glm::vec3 axis = glm::mat3(world) * glm::vec3(0, 0, -1);
        if (!(glm::length(axis) > 0.0f)) fail(where + ": degenerate light transform");
        light.direction = glm::normalize(axis);
        if (!finite(light.direction) || !(glm::length(light.direction) > 0.5f)) fail(where + ": degenerate light transform");
        // A finite double intensity can still overflow a float.
        if (!finite(light.intensity)) fail(label + ": intensity times colour overflows");
        if (src.type == "point") {
            light.type = PunctualLight::Type::Point;
        } else if (src.type == "directional") {
            light.type = PunctualLight::Type::Directional;
        } else if (src.type == "spot") {
            const double inner = src.spot.innerConeAngle, outer = src.spot.outerConeAngle;
            if (!(inner >= 0.0 && inner <= outer && outer > 0.0 && outer <= M_PI / 2 + 1e-6))
                fail(label + ": spot cone angles need 0 <= innerConeAngle <= outerConeAngle <= pi/2");
            light.type = PunctualLight::Type::Spot;
            // glTF's smooth edge: t^2 with t = (cos a - cos outer) / (cos inner - cos outer).
            light.cosCoverage = static_cast<float>(std::cos(outer));
            light.cosFalloff = static_cast<float>(std::cos(inner));
            light.falloffExponent = 2.0f;
        } else {
            unsupported("KHR_lights_punctual light type '" + src.type + "' (skipped)");
            return;
        }
        if (src.range > 0.0) unsupported("KHR_lights_punctual range (ignored: lights fall off with the inverse square to infinity)");
        scene_.punctualLights.push_back(light);
    }

    void noteUnsupportedExtensions() {
        static const std::set<std::string> supported = {"KHR_materials_emissive_strength", "KHR_materials_ior",
            "KHR_materials_specular", "KHR_materials_transmission", "KHR_materials_volume", "KHR_lights_punctual",
            "KHR_texture_transform"};
        for (const auto& e : model_.extensionsUsed)
            if (!supported.count(e)) unsupported("extension " + e);
    }

    const tinygltf::Model& model_;
    std::string file_;
    DecodedImages& decoded_;
    std::map<int, uint32_t> imageIndices_;
    Scene scene_;
    int defaultMaterial_ = -1;
    std::vector<bool> visited_;
    size_t repeatedVisits_ = 0, instancedVertices_ = 0, instancedTriangles_ = 0;
    std::map<std::string, int> unsupportedCounts_;
};

// tinygltf's first error line, made safe to print: it can echo the file's bytes (a URI, a JSON
// excerpt), so control characters become '?' (a hostile file must not drive the terminal) and
// the length is bounded.
std::string firstLine(const std::string& s) {
    constexpr size_t kMaxLength = 300;
    std::string line = s.substr(0, s.find('\n'));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    for (char& c : line)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    if (line.size() > kMaxLength) line = line.substr(0, kMaxLength) + "...";
    return line;
}

Scene importModel(bool ok, const tinygltf::Model& model, const std::string& err, const std::string& displayName, DecodedImages& images) {
    if (!ok)
        throw SceneError(displayName, "invalid glTF: " + (err.empty() ? std::string("unknown error") : firstLine(err)));
    return GltfImporter(model, displayName, images).run();
}

} // namespace

Scene loadGltfFile(const std::filesystem::path& path) {
    const std::string name = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw SceneError(name, "file not found");
    if (std::filesystem::is_directory(path, ec)) throw SceneError(name, "is a directory, not a glTF file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SceneError(name, "cannot open for reading");
    char magic[4] = {};
    in.read(magic, 4);
    const bool binary = in.gcount() == 4 && std::memcmp(magic, "glTF", 4) == 0;
    if (!binary && path.extension() == ".glb") throw SceneError(name, "not a binary glTF file (bad magic)");
    if (in.gcount() == 0) throw SceneError(name, "empty file");

    tinygltf::TinyGLTF loader;
    DecodedImages images;
    configureLoader(loader, images);
    tinygltf::Model model;
    std::string err, warn;
    bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, name) : loader.LoadASCIIFromFile(&model, &err, &warn, name);
    return importModel(ok, model, err, name, images);
}

Scene loadGltfText(std::string_view text, const std::string& displayName, const std::filesystem::path& baseDir) {
    tinygltf::TinyGLTF loader;
    DecodedImages images;
    configureLoader(loader, images);
    tinygltf::Model model;
    std::string err, warn;
    bool ok = loader.LoadASCIIFromString(&model, &err, &warn, text.data(), static_cast<unsigned int>(text.size()), baseDir.string());
    return importModel(ok, model, err, displayName, images);
}

Scene loadGltfMemory(std::string_view bytes, const std::string& displayName, const std::filesystem::path& baseDir) {
    if (bytes.empty()) throw SceneError(displayName, "empty file");
    // tinygltf takes the length as an unsigned int.
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) throw SceneError(displayName, "file larger than 4 GiB");
    if (bytes.size() < 4 || std::memcmp(bytes.data(), "glTF", 4) != 0) return loadGltfText(bytes, displayName, baseDir);
    tinygltf::TinyGLTF loader;
    DecodedImages images;
    configureLoader(loader, images);
    tinygltf::Model model;
    std::string err, warn;
    const bool ok = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
        static_cast<unsigned int>(bytes.size()), baseDir.string());
    return importModel(ok, model, err, displayName, images);
}

} // namespace pt
