#pragma once
// The scene flattened into the arrays the kernel reads: BVH-ordered triangles with their
// shading data, BVH nodes, materials and the light table. Built once per scene on the CPU.
#include "accel/bvh.h"
#include "accel/wide_bvh.h"
#include "lights/light_table.h"
#include "scene/scene.h"
#include "shared/layout.h"

#include <array>
#include <optional>
#include <vector>

namespace pt {

// Every texture slot of a material (NO_TEXTURE where unused), for the passes that look at all
// of them: which texture kinds a scene uses, which indices must exist.
inline std::array<uint32_t, 17> materialTextureSlots(const gpu::GpuMaterial& m) {
    return {m.baseColorTexture, m.specularTexture, m.metallicRoughnessTexture, m.normalTexture, m.emissiveTexture,
        m.specularWeightTexture, m.transmissionTexture, m.diffuseTransmissionTexture, m.diffuseTransmissionColorTexture,
        m.clearcoatTexture, m.clearcoatRoughnessTexture, m.clearcoatNormalTexture, m.sheenColorTexture,
        m.sheenRoughnessTexture, m.iridescenceTexture, m.iridescenceThicknessTexture, m.anisotropyTexture};
}

// A metallic-roughness material with a KHR_materials_sheen layer (its colour multiplies any texture).
inline bool hasSheen(const gpu::GpuMaterial& m) {
    return m.type == MATERIAL_PBR && (m.sheenColor.x > 0.0f || m.sheenColor.y > 0.0f || m.sheenColor.z > 0.0f);
}

// The environment as the kernel samples it (shaders/lights/environment_light.glsl).
struct FlatEnvironment {
    uint32_t width = 0, height = 0; // 0: none
    std::vector<glm::vec4> texels;  // radiance with the scale applied, row 0 at the top
    std::vector<float> marginal;    // height + 1: CDF over rows
    std::vector<float> conditional; // height x (width + 1): CDF over columns, per row
    float rotationCos = 1.0f, rotationSin = 0.0f;
    double averageRadiance = 0; // luminance averaged over the sphere (for its power)
};

struct FlatScene {
    std::string source; // the scene's file (Scene::source), for messages
    std::vector<gpu::GpuTriangle> triangles;
    std::vector<gpu::GpuTriangleShading> shading;
    std::vector<gpu::GpuTriangleTangents> tangents; // per triangle when any mesh has tangents, else empty
    // The triangles' four-wide trees (accel/wide_bvh.h): the world tree's nodes first (root 0),
    // then each instanced mesh's (src/flatten/flat_instances.h). Float nodes, or quantised ones
    // (accel/quantized_bvh.h) when they are big (BvhBuildOptions::quantizeOverBytes) and within
    // 2^60 of the origin (quantizable); one is empty.
    std::vector<gpu::GpuBvh4Node> nodes;
    std::vector<gpu::GpuBvh4QNode> quantizedNodes;
    uint32_t worldNodes = 0; // the world tree's nodes (0: no world-space triangles)
    // Placements of instanced meshes, in the order of the leaves of the tree over them.
    std::vector<gpu::GpuInstance> instances;
    std::vector<gpu::GpuBvh4Node> instanceNodes;
    std::string instancing;                    // what became of the scene's instances, for the log ("" without any)
    size_t degenerateInstances = 0;            // placements with a singular or non-finite transform dropped
    std::vector<gpu::GpuSphere> spheres;       // BVH-ordered
    std::vector<gpu::GpuBvh4Node> sphereNodes; // a second BVH, over the spheres
    std::vector<gpu::GpuMaterial> materials;
    // materialUsed[i]: some triangle or sphere has material i. The kernel is specialised to these
    // only (flatten/feature_set.cpp): a material no object uses costs nothing. Empty: all count.
    std::vector<bool> materialUsed;
    std::vector<gpu::GpuTexture> textures;
    std::vector<uint32_t> texels; // every image texture's texels, packed (see GpuTexture)
    uint32_t backgroundTexture = NO_TEXTURE;
    uint32_t sheenTables = 0;       // offset of the sheen lobe's tables in `texels` (scenes with a sheen)
    glm::vec3 ambientLight{0.0f};   // classic integrator
    std::vector<glm::vec4> motions; // motion blur: xyz = translation over the shutter interval
    FlatEnvironment environment;
    LightTable lights;
    // Measured on the device before a render's features are decided, for `--integrator auto`
    // (src/render/light_visibility_probe.h): the fraction of light samples at the surfaces the
    // camera sees that find their light. Absent where not measured.
    std::optional<float> lightVisibility;
    // Measured by the same probe: the fraction of cosine-weighted bounces from those surfaces
    // that meet a lit surface scattering mostly in a sharp GGX lobe (rough gold, rough glass): the
    // carriers of glossy caustics (shaders/integrator/debug_view.glsl, sharpLobeWeight).
    std::optional<float> glossyCausticBounces;
    // Measured by the same probe: the median distance from the camera to the surfaces it sees that
    // sample lights (vertex merging's radius is a number of pixel footprints there).
    std::optional<float> cameraHitDistance;
    size_t degenerateTriangles = 0; // zero-area or non-finite triangles dropped
    size_t degenerateSpheres = 0;   // singular or non-finite sphere transforms dropped
    // The world tree's build.
    double bvhSeconds = 0;
    double sahCost = 0;
    int bvhDepth = 0;     // binary tree's depth (edges)
    int wideBvhDepth = 0; // nodes on the wide tree's longest path
};

FlatScene flattenScene(const Scene& scene, const BvhBuildOptions& bvhOptions = {});

// The box around all triangles and spheres (their trees' roots); empty for an empty scene.
Aabb sceneBounds(const FlatScene& flat);

// The scene's textures and their images as the kernel reads them (src/flatten/flat_textures.cpp).
void flattenTextures(const Scene& scene, FlatScene& flat);

} // namespace pt
