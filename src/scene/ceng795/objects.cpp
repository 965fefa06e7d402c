#include "scene/ceng795/objects.h"

#include "scene/memory_estimate.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <iterator>
#include <map>
#include <set>

namespace pt::ceng795 {
namespace {

constexpr long long kAnyInteger = std::numeric_limits<long long>::max();

class ObjectReader {
public:
    ObjectReader(Context& ctx, const VertexPool& pool, const Transforms& transforms, MaterialTable& materials,
        TextureTable& textures, Scene& out)
        : ctx_(ctx), faces_(ctx, pool), transforms_(transforms), materials_(materials), textures_(textures), out_(out) {
    }

    void read(pugi::xml_node scene) {
        for (pugi::xml_node objects : scene.children("Objects")) collectDefinitions(objects);
        // A Mesh that MeshInstances build on is kept once, each placement an instance of it:
        // refuse a scene whose meshes cannot fit before reading them.
        requireMemoryForTriangles(ctx_.file(), distinctTriangleCount(scene), "each Mesh once");
        for (pugi::xml_node objects : scene.children("Objects"))
            for (pugi::xml_node e : objects.children())
                if (e.type() == pugi::node_element) readObject(e);
    }

private:
    // A <Mesh>: what MeshInstances build on (raw geometry plus its own transform).
    struct MeshDefinition {
        std::shared_ptr<const ObjectMesh> geometry;
        glm::mat4 transform;
        uint32_t material;
        bool smooth;
        pugi::xml_node textures; // its <Textures>, or null
        glm::vec3 motion;        // its <MotionBlur>
    };
    // Where an instance chain ends up: the root mesh's geometry, placed and shaded.
    struct Placement {
        long long rootId;
        const MeshDefinition* root;
        glm::mat4 transform;
        uint32_t material;
        bool smooth;
        pugi::xml_node textures;
        glm::vec3 motion;
    };

    // Meshes and instances first, so instances may refer to objects later in the file.
    void collectDefinitions(pugi::xml_node objects) {
        for (pugi::xml_node e : objects.children("Mesh")) {
            const long long id = idOf(ctx_, e);
            if (meshes_.count(id)) ctx_.fail(e, "duplicate id");
            meshes_.emplace(
                id, MeshDefinition{faces_.faces(required(ctx_, e, "Faces")),
                        transforms_.compose(ctx_, e.child("Transformations")),
                        materials_.lookup(ctx_, required(ctx_, e, "Material")), smoothShading(e).value_or(false),
                        e.child("Textures"), motionBlur(e).value_or(glm::vec3(0.0f))});
        }
        for (pugi::xml_node e : objects.children("MeshInstance")) {
            const long long id = idOf(ctx_, e);
            if (!instances_.emplace(id, e).second) ctx_.fail(e, "duplicate id");
        }
    }

    void readObject(pugi::xml_node e) {
        const std::string type = e.name();
        if (type == "Mesh")
            emitMesh(e, meshes_.at(idOf(ctx_, e)));
        else if (type == "MeshInstance")
            emitInstance(e);
        else if (type == "Triangle")
            emitTriangle(e);
        else if (type == "LightMesh")
            emitLightMesh(e);
        else if (type == "Sphere")
            emitSphere(e, std::nullopt);
        else if (type == "LightSphere")
            emitSphere(e, radiance(e));
        else
            ctx_.note(printable(type) + " objects (ignored)");
    }

    std::optional<bool> smoothShading(pugi::xml_node e) const {
        pugi::xml_attribute a = e.attribute("shadingMode");
        if (!a) return std::nullopt;
        const std::string mode = lowercase(a.value());
        if (mode != "smooth" && mode != "flat")
            ctx_.fail(e, "shadingMode " + quote(a.value()) + " is not flat or smooth");
        return mode == "smooth";
    }

    glm::vec3 radiance(pugi::xml_node e) const {
        pugi::xml_node r = required(ctx_, e, "Radiance");
        const glm::vec3 L = vec3(ctx_, r);
        if (L.x < 0.0f || L.y < 0.0f || L.z < 0.0f) ctx_.fail(r, "must not be negative");
        return L;
    }

    // Appends the world-space copy; returns false when every triangle was degenerate.
    // <MotionBlur>: the object's translation over the shutter interval (HW3), world space.
    std::optional<glm::vec3> motionBlur(pugi::xml_node e) const {
        pugi::xml_node m = e.child("MotionBlur");
        if (!m) return std::nullopt;
        const glm::vec3 v = vec3(ctx_, m);
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) ctx_.fail(m, "must be finite");
        return v;
    }

    bool emit(pugi::xml_node e, const ObjectMesh& geometry, const glm::mat4& transform, uint32_t material, bool smooth,
        glm::vec3 motion = glm::vec3(0.0f)) {
        if (geometry.uvs.empty() && hasUvTextures(material))
            ctx_.note("image textures on meshes without TexCoordData (drawn with uv 0)");
        if (geometry.triangles.size() > kMaxSceneTriangles - triangles_)
            ctx_.fail(e, "the scene expands to more than " + std::to_string(kMaxSceneTriangles) + " triangles");
        Mesh mesh = toWorld(ctx_, e, geometry, transform, smooth);
        if (mesh.triangles.empty()) return false;
        mesh.name = printable(e.name()) + " " + idText(e, "?");
        mesh.material = material;
        mesh.motion = motion;
        triangles_ += mesh.triangles.size();
        out_.meshes.push_back(std::move(mesh));
        return true;
    }

    void emitMesh(pugi::xml_node e, const MeshDefinition& m) {
        const long long id = idOf(ctx_, e);
        if (instanceBases_.count(id)) {
            const Placement own{id, &m, m.transform, m.material, m.smooth, m.textures, m.motion};
            emitPlacement(e, own);
            return;
        }
        emit(e, *m.geometry, m.transform, textured(m.textures, m.material), m.smooth, m.motion);
    }

    // A placement of a Mesh that instances share: an instance of the mesh kept once (per
    // shading mode) in object space.
    void emitPlacement(pugi::xml_node e, const Placement& p) {
        const std::pair<long long, bool> key(p.rootId, p.smooth);
        auto shared = sharedMeshes_.find(key);
        if (shared == sharedMeshes_.end()) {
            SharedMesh mesh;
            mesh.name = "Mesh " + std::to_string(p.rootId);
            Mesh part = toWorld(ctx_, e, *p.root->geometry, glm::mat4(1.0f), p.smooth);
            part.name = mesh.name;
            part.material = p.material;
            if (p.root->geometry->triangles.size() > kMaxSceneTriangles - triangles_)
                ctx_.fail(e, "the scene holds more than " + std::to_string(kMaxSceneTriangles) + " triangles");
            triangles_ += part.triangles.size();
            if (!part.triangles.empty()) mesh.parts.push_back(std::move(part));
            shared = sharedMeshes_.emplace(key, static_cast<uint32_t>(out_.sharedMeshes.size())).first;
            out_.sharedMeshes.push_back(std::move(mesh));
        }
        const uint32_t material = textured(p.textures, p.material);
        if (p.root->geometry->uvs.empty() && hasUvTextures(material))
            ctx_.note("image textures on meshes without TexCoordData (drawn with uv 0)");
        MeshInstance instance;
        instance.name = printable(e.name()) + " " + idText(e, "?");
        instance.mesh = shared->second;
        instance.objectToWorld = p.transform;
        instance.material = material;
        instance.motion = p.motion;
        out_.instances.push_back(std::move(instance));
    }

    uint32_t textured(pugi::xml_node texturesNode, uint32_t material) {
        return textures_.apply(ctx_, texturesNode, material, out_);
    }

    bool hasUvTextures(uint32_t material) const {
        const Material& m = out_.materials[material];
        for (const auto& slot : {m.baseColorTexture, m.specularTexture, m.normalTexture, m.emissiveTexture})
            if (slot && out_.textures[*slot].type == Texture::Type::Image) return true;
        return false;
    }

    void emitLightMesh(pugi::xml_node e) {
        const uint32_t base = textured(e.child("Textures"), materials_.lookup(ctx_, required(ctx_, e, "Material")));
        const uint32_t material =
            addEmissiveCopy(out_.materials, base, radiance(e), std::string(e.name()) + " " + idText(e, "?"));
        const auto geometry = faces_.faces(required(ctx_, e, "Faces"));
        // A light with no area emits nothing and would divide by zero when sampled.
        if (!emit(e, *geometry, transforms_.compose(ctx_, e.child("Transformations")), material,
                smoothShading(e).value_or(false)))
            ctx_.fail(e, "all triangles are degenerate (zero area)");
    }

    void emitTriangle(pugi::xml_node e) {
        const ObjectMesh geometry = faces_.triangle(required(ctx_, e, "Indices"));
        const uint32_t material = textured(e.child("Textures"), materials_.lookup(ctx_, required(ctx_, e, "Material")));
        emit(e, geometry, transforms_.compose(ctx_, e.child("Transformations")), material, false,
            motionBlur(e).value_or(glm::vec3(0.0f)));
    }

    void emitInstance(pugi::xml_node e) { emitPlacement(e, resolve(idOf(ctx_, e))); }

    // An instance on top of what its base resolved to. resetTransform="true" places the raw base
    // geometry with the instance's own transform only; otherwise the own transform is applied
    // after the base's. Material and shadingMode default to the base's.
    Placement place(pugi::xml_node e, const Placement& base) {
        Placement p = base;
        const glm::mat4 own = transforms_.compose(ctx_, e.child("Transformations"));
        const bool reset = e.attribute("resetTransform") &&
                           booleanValue(ctx_, e, e.attribute("resetTransform").value(), "resetTransform");
        p.transform = reset ? own : own * base.transform;
        if (pugi::xml_node m = e.child("Material"))
            p.material = materials_.lookup(ctx_, m);
        else
            ctx_.note("MeshInstances without a Material (their base's assumed)");
        p.smooth = smoothShading(e).value_or(base.smooth);
        if (pugi::xml_node t = e.child("Textures")) p.textures = t;
        if (auto m = motionBlur(e)) p.motion = *m;
        return p;
    }

    // Follows baseMeshId to a Mesh, resolving each id against Meshes first and MeshInstances
    // second (ids of the two may collide: veach-ajar has Mesh 1 and MeshInstance 1). Walks
    // iteratively with memoisation so long chains cost neither stack nor quadratic time.
    Placement resolve(long long id) {
        std::vector<pugi::xml_node> chain; // instances still to place, innermost last
        std::vector<long long> ids;
        Placement base{};
        for (long long cur = id;;) {
            if (auto done = resolved_.find(cur); done != resolved_.end()) {
                base = done->second;
                break;
            }
            pugi::xml_node inst = instances_.at(cur);
            const bool cycle = std::find(ids.begin(), ids.end(), cur) != ids.end();
            ids.push_back(cur);
            if (cycle) ctx_.fail(instances_.at(id), "baseMeshId chain is cyclic (" + chainText(ids) + ")");
            chain.push_back(inst);
            const long long baseId = baseMeshId(inst);
            if (auto m = meshes_.find(baseId); m != meshes_.end()) {
                base = Placement{m->first, &m->second, m->second.transform, m->second.material, m->second.smooth,
                    m->second.textures, m->second.motion};
                break;
            }
            if (!instances_.count(baseId))
                ctx_.fail(inst, "baseMeshId " + std::to_string(baseId) + " is neither a Mesh nor a MeshInstance");
            cur = baseId;
        }
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
            base = place(*it, base);
            resolved_[idOf(ctx_, *it)] = base;
        }
        return base;
    }

    // The triangles the objects will add, each Mesh once (LightMeshes, small and not parsed yet,
    // left out), and which Meshes instances build on: the end of each MeshInstance's chain. A
    // chain that does not end at a Mesh (a cycle, a missing id) marks nothing; resolve() reports it.
    uint64_t distinctTriangleCount(pugi::xml_node scene) {
        for (const auto& [id, inst] : instances_) {
            long long cur = id;
            for (size_t steps = 0; steps <= instances_.size(); ++steps) {
                auto at = instances_.find(cur);
                if (at == instances_.end()) break;
                pugi::xml_attribute b = at->second.attribute("baseMeshId");
                const std::vector<std::string_view> t = tokens(b ? b.value() : "");
                if (t.size() != 1) break;
                const long long baseId = toInteger(ctx_, at->second, t[0]);
                if (meshes_.count(baseId)) {
                    instanceBases_.insert(baseId);
                    break;
                }
                cur = baseId;
            }
        }
        uint64_t total = 0;
        for (const auto& [id, mesh] : meshes_) total += mesh.geometry->triangles.size();
        for (pugi::xml_node objects : scene.children("Objects"))
            total += std::distance(objects.children("Triangle").begin(), objects.children("Triangle").end());
        return total;
    }

    long long baseMeshId(pugi::xml_node inst) const {
        pugi::xml_attribute b = inst.attribute("baseMeshId");
        if (!b) ctx_.fail(inst, "missing baseMeshId attribute");
        const std::vector<std::string_view> t = tokens(b.value());
        if (t.size() != 1) ctx_.fail(inst, "baseMeshId " + quote(b.value()) + " is not an id");
        return toInteger(ctx_, inst, t[0]);
    }

    // "3 -> 4 -> 3", shortened for long chains to keep the message on one readable line.
    static std::string chainText(const std::vector<long long>& ids) {
        constexpr size_t kShown = 8;
        std::string s;
        for (size_t i = 0; i < ids.size(); ++i) {
            if (ids.size() > kShown && i == kShown / 2) {
                s += " -> ...";
                i = ids.size() - kShown / 2;
            }
            s += (s.empty() ? "" : " -> ") + std::to_string(ids[i]);
        }
        return s;
    }

    // The unit sphere mapped to the object: M · translate(centre) · scale(radius), so the
    // object's Transformations act on the sphere as placed by its Center and Radius.
    void emitSphere(pugi::xml_node e, std::optional<glm::vec3> emission) {
        pugi::xml_node c = required(ctx_, e, "Center");
        const glm::vec3 centre = faces_.vertex(c, integer(ctx_, c, -kAnyInteger, kAnyInteger));
        pugi::xml_node r = required(ctx_, e, "Radius");
        const float radius = scalar(ctx_, r);
        if (!(radius > 0.0f)) ctx_.fail(r, "must be positive");
        Sphere s;
        s.name = std::string(e.name()) + " " + idText(e, "?");
        s.objectToWorld = transforms_.compose(ctx_, e.child("Transformations")) *
                          glm::translate(glm::mat4(1.0f), centre) * glm::scale(glm::mat4(1.0f), glm::vec3(radius));
        for (int col = 0; col < 4; ++col)
            for (int row = 0; row < 4; ++row)
                if (!std::isfinite(s.objectToWorld[col][row])) ctx_.fail(e, "transformed sphere is not finite");
        if (!(std::fabs(glm::determinant(glm::mat3(s.objectToWorld))) > 0.0f))
            ctx_.fail(e, "transformed sphere is degenerate");
        s.material = textured(e.child("Textures"), materials_.lookup(ctx_, required(ctx_, e, "Material")));
        if (emission) s.material = addEmissiveCopy(out_.materials, s.material, *emission, s.name);
        s.motion = motionBlur(e).value_or(glm::vec3(0.0f));
        if (emission && s.motion != glm::vec3(0.0f)) ctx_.note("motion blur on lights (rendered static)");
        out_.spheres.push_back(s);
    }

    Context& ctx_;
    FaceReader faces_;
    const Transforms& transforms_;
    MaterialTable& materials_;
    TextureTable& textures_;
    Scene& out_;
    std::map<long long, MeshDefinition> meshes_;
    std::map<long long, pugi::xml_node> instances_;
    std::map<long long, Placement> resolved_;
    std::set<long long> instanceBases_;                           // Meshes that MeshInstances build on
    std::map<std::pair<long long, bool>, uint32_t> sharedMeshes_; // (Mesh id, smooth) -> Scene::sharedMeshes
    size_t triangles_ = 0;
};

} // namespace

void readObjects(Context& ctx, pugi::xml_node scene, const VertexPool& pool, const Transforms& transforms,
    MaterialTable& materials, TextureTable& textures, Scene& out) {
    ObjectReader(ctx, pool, transforms, materials, textures, out).read(scene);
}

} // namespace pt::ceng795
