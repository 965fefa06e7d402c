#include "flatten/flat_scene.h"

#include "flatten/flat_instances.h"
#include "scene/mesh_placement.h"

#include "lights/texture_emission.h"

#include "accel/quantized_bvh.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pt {
namespace {

static_assert(static_cast<uint32_t>(GlossyModel::OriginalPhong) == GLOSSY_ORIGINAL_PHONG &&
                  static_cast<uint32_t>(GlossyModel::OriginalBlinnPhong) == GLOSSY_ORIGINAL_BLINN_PHONG &&
                  static_cast<uint32_t>(GlossyModel::ModifiedPhong) == GLOSSY_MODIFIED_PHONG &&
                  static_cast<uint32_t>(GlossyModel::ModifiedBlinnPhong) == GLOSSY_MODIFIED_BLINN_PHONG &&
                  static_cast<uint32_t>(GlossyModel::TorranceSparrow) == GLOSSY_TORRANCE_SPARROW,
    "GlossyModel must list the models in the order of GLOSSY_*");

// Microfacet: alpha = roughness^2 (the glTF / Disney perceptual mapping); below MIN_ROUGH_ALPHA
// the surface stays a smooth delta one so nothing overflows.
float ggxAlpha(float roughness) {
    const float alpha = roughness * roughness;
    return alpha >= float(MIN_ROUGH_ALPHA) ? std::min(alpha, 1.0f) : 0.0f;
}

gpu::GpuMaterial toGpu(const Material& m) {
    gpu::GpuMaterial g{};
    g.baseColor = m.baseColor;
    g.emission = m.emission;
    g.ior = m.ior;
    g.flags = m.doubleSided ? MATERIAL_FLAG_DOUBLE_SIDED : 0u;
    switch (m.type) {
    case MaterialType::Diffuse: g.type = MATERIAL_DIFFUSE; break;
    case MaterialType::Mirror: g.type = MATERIAL_MIRROR; break;
    case MaterialType::Dielectric: g.type = MATERIAL_DIELECTRIC; break;
    case MaterialType::Conductor: g.type = MATERIAL_CONDUCTOR; break;
    case MaterialType::Glossy: g.type = MATERIAL_GLOSSY; break;
    case MaterialType::Pbr: g.type = MATERIAL_PBR; break;
    }
    g.alpha = ggxAlpha(m.roughness);
    g.metallic = m.metallic;
    g.transmission = m.transmission;
    g.diffuseTransmission = m.diffuseTransmission;
    g.diffuseTransmissionColor = m.diffuseTransmissionColor;
    g.specularWeight = m.specularWeight;
    g.clearcoat = m.clearcoat;
    g.clearcoatAlpha = ggxAlpha(m.clearcoatRoughness);
    g.clearcoatNormalScale = m.clearcoatNormalScale;
    g.sheenColor = m.sheenColor;
    g.sheenRoughness = m.sheenRoughness;
    g.iridescence = m.iridescence;
    g.iridescenceIor = m.iridescenceIor;
    g.iridescenceThicknessMinimum = m.iridescenceThicknessMinimum;
    g.iridescenceThickness = m.iridescenceThicknessMaximum;
    g.anisotropy = m.anisotropy;
    g.anisotropyRotation = m.anisotropyRotation;
    g.dispersion = m.dispersion;
    g.glossiness = m.glossiness;
    g.mirror = m.mirrorReflectance;
    if (m.glossinessTexture) g.flags |= MATERIAL_FLAG_GLOSSINESS;
    if (m.type == MaterialType::Pbr && m.thinWalled) g.flags |= MATERIAL_FLAG_THIN_WALLED;
    auto slot = [](const std::optional<uint32_t>& t) { return t ? *t : NO_TEXTURE; };
    g.baseColorTexture = slot(m.baseColorTexture);
    g.specularTexture = slot(m.specularTexture);
    g.specularWeightTexture = slot(m.specularWeightTexture);
    g.transmissionTexture = slot(m.transmissionTexture);
    g.diffuseTransmissionTexture = slot(m.diffuseTransmissionTexture);
    g.diffuseTransmissionColorTexture = slot(m.diffuseTransmissionColorTexture);
    g.clearcoatTexture = slot(m.clearcoatTexture);
    g.clearcoatRoughnessTexture = slot(m.clearcoatRoughnessTexture);
    g.clearcoatNormalTexture = slot(m.clearcoatNormalTexture);
    g.sheenColorTexture = slot(m.sheenColorTexture);
    g.sheenRoughnessTexture = slot(m.sheenRoughnessTexture);
    g.iridescenceTexture = slot(m.iridescenceTexture);
    g.iridescenceThicknessTexture = slot(m.iridescenceThicknessTexture);
    g.anisotropyTexture = slot(m.anisotropyTexture);
    g.metallicRoughnessTexture = slot(m.metallicRoughnessTexture);
    g.normalTexture = slot(m.normalTexture);
    g.emissiveTexture = slot(m.emissiveTexture);
    g.normalScale = m.normalScale;
    if (m.bumpMap) g.flags |= MATERIAL_FLAG_BUMP_MAP;
    if (m.normalMapYDown) g.flags |= MATERIAL_FLAG_NORMAL_Y_DOWN;
    if (m.blendBaseColor) g.flags |= MATERIAL_FLAG_BLEND_KD;
    if (m.unlit) g.flags |= MATERIAL_FLAG_UNLIT;
    if (m.alphaMode == Material::AlphaMode::Mask) g.flags |= MATERIAL_FLAG_ALPHA_MASK;
    if (m.alphaMode == Material::AlphaMode::Blend) g.flags |= MATERIAL_FLAG_ALPHA_BLEND;
    g.ambient = m.ambient;
    g.classicDiffuse = m.classicDiffuse;
    g.classicSpecular = m.classicSpecular;
    g.classicExponent = m.classicExponent;
    if (m.classicPhong) g.flags |= MATERIAL_FLAG_CLASSIC_PHONG;
    g.alphaCutoff = m.alphaCutoff;
    g.opacity = m.opacity;
    g.specular = m.specular;
    g.exponent = m.exponent;
    g.glossyModel = static_cast<uint32_t>(m.glossyModel); // same order as GLOSSY_*
    if (m.normalized) g.flags |= MATERIAL_FLAG_NORMALIZED;
    if (m.kdFresnel) g.flags |= MATERIAL_FLAG_KD_FRESNEL;
    g.conductorEta = m.conductorEta;
    g.conductorK = m.conductorK;
    // glTF's KHR_materials_volume: transmittance attenuationColor after attenuationDistance,
    // so sigma_a = -ln(color) / distance; an infinite distance means no absorption.
    const bool hasInterior =
        m.type == MaterialType::Dielectric || (m.type == MaterialType::Pbr && m.transmission > 0.0f && !m.thinWalled);
    if (hasInterior && std::isfinite(m.attenuationDistance) && m.attenuationColor != glm::vec3(1.0f)) {
        glm::vec3 c = glm::max(m.attenuationColor, glm::vec3(1e-30f));
        g.sigmaA = -glm::log(glm::min(c, glm::vec3(1.0f))) / m.attenuationDistance;
        g.flags |= MATERIAL_FLAG_ABSORBING;
    }
    return g;
}

// World-space box of the unit sphere under the affine map m: the half-extent along each axis
// is the length of that row of m's linear part.
Aabb sphereBounds(const glm::mat4& m) {
    const glm::vec3 centre(m[3]);
    glm::vec3 half;
    for (int axis = 0; axis < 3; ++axis)
        half[axis] = std::sqrt(m[0][axis] * m[0][axis] + m[1][axis] * m[1][axis] + m[2][axis] * m[2][axis]);
    Aabb box;
    box.grow(centre - half);
    box.grow(centre + half);
    return box;
}

void setRows(glm::vec4 rows[3], const glm::mat4& m) {
    for (int r = 0; r < 3; ++r) rows[r] = glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]);
}

Aabb translated(const Aabb& box, const glm::vec3& by) {
    Aabb moved;
    moved.grow(box.lo + by);
    moved.grow(box.hi + by);
    return moved;
}

void flattenSpheres(const Scene& scene, const BvhBuildOptions& bvhOptions, FlatScene& flat) {
    std::vector<gpu::GpuSphere> spheres;
    std::vector<Aabb> bounds;
    for (const Sphere& s : scene.spheres) {
        if (s.material >= scene.materials.size())
            throw std::runtime_error(scene.source + ": sphere '" + s.name + "' uses a material that does not exist");
        if (!isPlaceable(s.objectToWorld)) {
            flat.degenerateSpheres++;
            continue;
        }
        const glm::mat4 inverse = glm::inverse(s.objectToWorld);
        gpu::GpuSphere g{};
        setRows(g.worldToObject, inverse);
        setRows(g.objectToWorld, s.objectToWorld);
        g.materialIndex = s.material;
        g.lightIndex = NO_LIGHT;
        g.motion = motionIndex(s.motion, flat);
        spheres.push_back(g);
        Aabb box = sphereBounds(s.objectToWorld);
        if (g.motion != NO_MOTION) box.grow(translated(box, s.motion)); // swept over the shutter interval
        bounds.push_back(box);
    }
    const Bvh bvh = buildBvh(bounds, bvhOptions);
    flat.sphereNodes = gpuNodes(bvh, scene.source + ": sphere BVH").nodes;
    for (uint32_t original : bvh.primOrder) flat.spheres.push_back(spheres[original]);
}

// A constant environment becomes a small map so that one sampler serves both.
constexpr uint32_t kConstantEnvWidth = 8, kConstantEnvHeight = 16;

FlatEnvironment flattenEnvironment(const Environment& env, const std::string& source) {
    FlatEnvironment out;
    const bool constant = env.image.width == 0 || env.image.height == 0;
    out.width = constant ? kConstantEnvWidth : static_cast<uint32_t>(env.image.width);
    out.height = constant ? kConstantEnvHeight : static_cast<uint32_t>(env.image.height);
    const float angle = glm::radians(env.rotationDegrees);
    out.rotationCos = std::cos(angle);
    out.rotationSin = std::sin(angle);
    out.texels.resize(size_t(out.width) * out.height);
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x) {
            glm::vec3 c = constant ? env.colour : glm::vec3(glm::make_vec3(env.image.at(int(x), int(y))));
            c *= env.scale;
            if (!isFinite(c) || c.x < 0 || c.y < 0 || c.z < 0)
                throw std::runtime_error(source + ": environment texel (" + std::to_string(x) + ", " +
                                         std::to_string(y) + ") is negative or not finite");
            out.texels[size_t(y) * out.width + x] = glm::vec4(c, 0.0f);
        }
    // Sampling weights: the light table's selection weight x sin(theta)
    // at the row's centre, so the density follows solid angle and poles get no excess samples.
    std::vector<double> rowSum(out.height, 0.0);
    out.conditional.assign(size_t(out.height) * (out.width + 1), 0.0f);
    double total = 0, radianceIntegral = 0;
    for (uint32_t y = 0; y < out.height; ++y) {
        const double sinTheta = std::sin(M_PI * (y + 0.5) / out.height);
        std::vector<double> w(out.width);
        double sum = 0;
        for (uint32_t x = 0; x < out.width; ++x) {
            const glm::vec3 c(out.texels[size_t(y) * out.width + x]);
            w[x] = selectionWeight(c) * sinTheta;
            sum += w[x];
            radianceIntegral += luminance(c) * sinTheta;
        }
        float* cdf = &out.conditional[size_t(y) * (out.width + 1)];
        double running = 0;
        for (uint32_t x = 0; x < out.width; ++x) {
            running += w[x];
            cdf[x + 1] = sum > 0 ? static_cast<float>(running / sum) : static_cast<float>(double(x + 1) / out.width);
        }
        cdf[out.width] = 1.0f;
        rowSum[y] = sum;
        total += sum;
    }
    out.marginal.assign(out.height + 1, 0.0f);
    double running = 0;
    for (uint32_t y = 0; y < out.height; ++y) {
        running += rowSum[y];
        out.marginal[y + 1] =
            total > 0 ? static_cast<float>(running / total) : static_cast<float>(double(y + 1) / out.height);
    }
    out.marginal[out.height] = 1.0f;
    // Average over the sphere: integral of L dOmega / 4 pi, dOmega = 2 pi^2 sin(theta) / (W H) per texel.
    out.averageRadiance = radianceIntegral * 2.0 * M_PI * M_PI / (double(out.width) * out.height) / (4.0 * M_PI);
    return out;
}

// Radius of a sphere around all geometry (sizes directional lights' power estimate).
float sceneRadius(const FlatScene& flat) {
    const Aabb box = sceneBounds(flat);
    return box.empty() ? 1.0f : std::max(0.5f * glm::length(box.hi - box.lo), 1e-6f);
}

} // namespace

Aabb sceneBounds(const FlatScene& flat) {
    Aabb box;
    if (flat.worldNodes > 0 && !flat.nodes.empty()) box.grow(wideNodeBounds(flat.nodes[0]));
    if (flat.worldNodes > 0 && !flat.quantizedNodes.empty())
        box.grow(wideNodeBounds(decodeWideNode(flat.quantizedNodes[0])));
    if (!flat.instanceNodes.empty()) box.grow(wideNodeBounds(flat.instanceNodes[0]));
    if (!flat.sphereNodes.empty()) box.grow(wideNodeBounds(flat.sphereNodes[0]));
    return box;
}

namespace {

template <class T>
void releaseVector(std::vector<T>& v) {
    std::vector<T>().swap(v);
}

} // namespace

FlatScene flattenScene(const Scene& scene, const BvhBuildOptions& bvhOptions) {
    FlatScene flat;
    flat.source = scene.source;
    for (const Material& m : scene.materials) flat.materials.push_back(toGpu(m));
    flattenTextures(scene, flat);
    flat.ambientLight = scene.ambientLight;

    // The world tree (root 0): world-space meshes and the placements copied into world space.
    // The kept instances' meshes follow with trees of their own, and a tree over the placements.
    const bool keepTangents = sceneKeepsTangents(scene);
    const std::vector<bool> kept = chooseKeptInstances(scene, bvhOptions, flat);
    {
        TriangleSet world;
        world.triangles.reserve(scene.triangleCount());
        for (const Mesh& mesh : scene.meshes)
            gatherTriangles(scene, mesh, mesh.material, mesh.motion, keepTangents, flat, world);
        gatherExpandedInstances(scene, kept, keepTangents, flat, world);
        const AppendedTree tree = appendTriangleTree(world, bvhOptions, scene.source + ": BVH", flat);
        flat.worldNodes = static_cast<uint32_t>(flat.nodes.size());
        flat.bvhSeconds = tree.buildSeconds;
        flat.sahCost = tree.sahCost;
        flat.bvhDepth = tree.binaryDepth;
        flat.wideBvhDepth = tree.wideDepth;
    }
    flattenKeptInstances(scene, kept, bvhOptions, keepTangents, flat);
    if (flat.nodes.size() * sizeof(gpu::GpuBvh4Node) > bvhOptions.quantizeOverBytes && quantizable(flat.nodes)) {
        flat.quantizedNodes = quantizeWideNodes(flat.nodes);
        releaseVector(flat.nodes);
    }
    flattenSpheres(scene, bvhOptions, flat);
    flat.materialUsed.assign(flat.materials.size(), false);
    for (const gpu::GpuTriangle& t : flat.triangles) flat.materialUsed.at(t.materialIndex) = true;
    for (const gpu::GpuSphere& s : flat.spheres) flat.materialUsed.at(s.materialIndex) = true;
    if (scene.environment) flat.environment = flattenEnvironment(*scene.environment, scene.source);
    // Emitters are weighed by their emission texture's light (lights/texture_emission.h).
    auto triangleEmission = [&](uint32_t i) {
        const gpu::GpuMaterial& m = flat.materials[flat.triangles[i].materialIndex];
        if (m.emissiveTexture == NO_TEXTURE || flat.textures[m.emissiveTexture].type != TEXTURE_IMAGE)
            return glm::vec3(1.0f);
        const gpu::GpuTriangleShading& s = flat.shading[i];
        const glm::vec2 uv[3] = {{s.u0, s.v.x}, {s.u1, s.v.y}, {s.u2, s.v.z}};
        return averageOverTriangle(flat.textures[m.emissiveTexture], flat.texels, uv);
    };
    flat.lights = buildLightTable(flat.triangles, flat.spheres, scene.punctualLights, scene.materials,
        sceneRadius(flat), flat.environment.width > 0 ? flat.environment.averageRadiance : -1.0, triangleEmission);
    flat.lights.tree = buildLightTree(lightBoundsOf(flat.lights.lights, flat.lights.power, flat.triangles, flat.spheres,
                                          flat.materials, flat.motions),
        boundedLightShare(flat.lights));
    return flat;
}

} // namespace pt
