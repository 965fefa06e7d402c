#include "flatten/flat_scene.h"

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

// Whether any-hit traversal must test this material's alpha (glTF MASK and BLEND).
bool cutsOut(const Material& m) {
    if (m.alphaMode == Material::AlphaMode::Opaque) return false;
    if (m.baseColorTexture) return true;
    return m.alphaMode == Material::AlphaMode::Mask ? m.opacity < m.alphaCutoff : m.opacity < 1.0f;
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The tree as the kernel reads it, four-wide; `what` names it if the traversal stack cannot
// hold it.
WideBvh gpuNodes(const Bvh& bvh, const std::string& what) {
    WideBvh wide = collapseToWide(bvh);
    if (wide.stackNeed > TRAVERSAL_STACK_SIZE)
        throw std::runtime_error(what + " needs " + std::to_string(wide.stackNeed) +
                                 " traversal stack entries; the kernel has " + std::to_string(TRAVERSAL_STACK_SIZE));
    return wide;
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

// The motion-table entry of an object that moves by `motion` over the shutter, or NO_MOTION.
// Emitters stay where they are: light sampling picks points on them without a time.
uint32_t motionIndex(const glm::vec3& motion, const Material& material, FlatScene& flat) {
    if (motion == glm::vec3(0.0f) || material.emissive() || !finite(motion)) return NO_MOTION;
    if (flat.motions.size() >= (1u << (32 - TRIANGLE_MOTION_SHIFT)))
        throw std::runtime_error("more moving objects than the motion table holds");
    flat.motions.emplace_back(motion, 0.0f);
    return static_cast<uint32_t>(flat.motions.size() - 1);
}

void flattenSpheres(const Scene& scene, const BvhBuildOptions& bvhOptions, FlatScene& flat) {
    std::vector<gpu::GpuSphere> spheres;
    std::vector<Aabb> bounds;
    for (const Sphere& s : scene.spheres) {
        if (s.material >= scene.materials.size())
            throw std::runtime_error(scene.source + ": sphere '" + s.name + "' uses a material that does not exist");
        const glm::mat4 inverse = glm::inverse(s.objectToWorld);
        const float det = glm::determinant(glm::mat3(s.objectToWorld));
        bool ok = std::isfinite(det) && det != 0.0f;
        for (int c = 0; c < 4 && ok; ++c) ok = finite(glm::vec3(inverse[c])) && finite(glm::vec3(s.objectToWorld[c]));
        if (!ok) {
            flat.degenerateSpheres++;
            continue;
        }
        gpu::GpuSphere g{};
        setRows(g.worldToObject, inverse);
        setRows(g.objectToWorld, s.objectToWorld);
        g.materialIndex = s.material;
        g.lightIndex = NO_LIGHT;
        g.motion = motionIndex(s.motion, scene.materials[s.material], flat);
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
            if (!finite(c) || c.x < 0 || c.y < 0 || c.z < 0)
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
    if (!flat.nodes.empty()) box.grow(wideNodeBounds(flat.nodes[0]));
    if (!flat.quantizedNodes.empty()) box.grow(wideNodeBounds(decodeWideNode(flat.quantizedNodes[0])));
    if (!flat.sphereNodes.empty()) box.grow(wideNodeBounds(flat.sphereNodes[0]));
    return box;
}

namespace {

template <class T>
void releaseVector(std::vector<T>& v) {
    std::vector<T>().swap(v);
}

// a[i] = a_before[order[i]] for each array (tangents may be empty), in place: each cycle of the
// permutation is followed once, with one bit per element to mark what is placed, so no second
// copy of the arrays is made.
void applyOrderInPlace(const std::vector<uint32_t>& order, std::vector<gpu::GpuTriangle>& triangles,
    std::vector<gpu::GpuTriangleShading>& shading, std::vector<gpu::GpuTriangleTangents>& tangents) {
    const bool withTangents = !tangents.empty();
    std::vector<bool> placed(order.size(), false);
    for (size_t start = 0; start < order.size(); ++start) {
        if (placed[start]) continue;
        const gpu::GpuTriangle firstTriangle = triangles[start];
        const gpu::GpuTriangleShading firstShading = shading[start];
        const gpu::GpuTriangleTangents firstTangents = withTangents ? tangents[start] : gpu::GpuTriangleTangents{};
        size_t to = start;
        for (;;) {
            placed[to] = true;
            const size_t from = order[to];
            if (from == start) break;
            triangles[to] = triangles[from];
            shading[to] = shading[from];
            if (withTangents) tangents[to] = tangents[from];
            to = from;
        }
        triangles[to] = firstTriangle;
        shading[to] = firstShading;
        if (withTangents) tangents[to] = firstTangents;
    }
}

} // namespace

FlatScene flattenScene(const Scene& scene, const BvhBuildOptions& bvhOptions) {
    FlatScene flat;
    flat.source = scene.source;
    for (const Material& m : scene.materials) flat.materials.push_back(toGpu(m));
    flattenTextures(scene, flat);
    flat.ambientLight = scene.ambientLight;

    // Gather valid triangles in scene order; zero-area ones can never be hit and would only
    // cost traversal time (and break light sampling if emissive).
    std::vector<gpu::GpuTriangle> triangles;
    std::vector<gpu::GpuTriangleShading> shading;
    std::vector<gpu::GpuTriangleTangents> tangents;
    // The file's tangents matter to normal maps and to anisotropy's direction.
    const bool anyTangents = std::any_of(scene.meshes.begin(), scene.meshes.end(), [&](const Mesh& m) {
        if (m.tangents.empty() || m.material >= scene.materials.size()) return false;
        const Material& material = scene.materials[m.material];
        return material.normalTexture.has_value() || material.anisotropy > 0.0f;
    });
    std::vector<Aabb> bounds;
    triangles.reserve(scene.triangleCount());
    for (const Mesh& mesh : scene.meshes) {
        if (mesh.material >= scene.materials.size())
            throw std::runtime_error(scene.source + ": mesh '" + mesh.name + "' uses a material that does not exist");
        const uint32_t motion = motionIndex(mesh.motion, scene.materials[mesh.material], flat);
        for (const glm::uvec3& t : mesh.triangles) {
            gpu::GpuTriangle tri{};
            tri.p0 = mesh.positions.at(t.x);
            tri.p1 = mesh.positions.at(t.y);
            tri.p2 = mesh.positions.at(t.z);
            const glm::vec3 n = glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
            if (!finite(n) || glm::dot(n, n) == 0.0f || !finite(tri.p0) || !finite(tri.p1) || !finite(tri.p2)) {
                flat.degenerateTriangles++;
                continue;
            }
            tri.materialIndex = mesh.material;
            tri.lightIndex = NO_LIGHT;
            if (cutsOut(scene.materials[mesh.material])) tri.flags |= TRIANGLE_FLAG_ALPHA_TESTED;
            gpu::GpuTriangleShading sh{};
            if (!mesh.normals.empty()) {
                sh.n0 = mesh.normals[t.x];
                sh.n1 = mesh.normals[t.y];
                sh.n2 = mesh.normals[t.z];
                // Zero normals mark invalid input (see the loaders): use the geometric normal.
                if (sh.n0 != glm::vec3(0.0f) && sh.n1 != glm::vec3(0.0f) && sh.n2 != glm::vec3(0.0f))
                    tri.flags |= TRIANGLE_FLAG_SHADING_NORMALS;
            }
            if (!mesh.uvs.empty()) {
                sh.u0 = mesh.uvs[t.x].x;
                sh.u1 = mesh.uvs[t.y].x;
                sh.u2 = mesh.uvs[t.z].x;
                sh.v = glm::vec3(mesh.uvs[t.x].y, mesh.uvs[t.y].y, mesh.uvs[t.z].y);
            }
            Aabb box;
            box.grow(tri.p0);
            box.grow(tri.p1);
            box.grow(tri.p2);
            if (motion != NO_MOTION) {
                tri.flags |= TRIANGLE_FLAG_MOVING | (motion << TRIANGLE_MOTION_SHIFT);
                box.grow(translated(box, mesh.motion));
            }
            if (anyTangents) {
                gpu::GpuTriangleTangents tg{};
                if (!mesh.tangents.empty()) {
                    tg = {mesh.tangents[t.x], mesh.tangents[t.y], mesh.tangents[t.z]};
                    // Zero tangents mark invalid input: fall back to the triangle's own frame.
                    const Material& material = scene.materials[mesh.material];
                    if (tg.t0.w != 0.0f && tg.t1.w != 0.0f && tg.t2.w != 0.0f &&
                        (material.normalTexture || material.anisotropy > 0.0f))
                        tri.flags |= TRIANGLE_FLAG_TANGENTS;
                }
                tangents.push_back(tg);
            }
            triangles.push_back(tri);
            shading.push_back(sh);
            bounds.push_back(box);
        }
    }

    // The peak of a big scene's memory is here (bench/RESULTS.md, "Memory per triangle"): each
    // temporary goes as soon as it has served, and the arrays are put in BVH order in place.
    Bvh bvh = buildBvh(bounds, bvhOptions);
    releaseVector(bounds);
    flat.bvhSeconds = bvh.buildSeconds;
    flat.sahCost = bvh.sahCost;
    flat.bvhDepth = bvh.maxDepth;
    {
        WideBvh wide = gpuNodes(bvh, scene.source + ": BVH");
        flat.wideBvhDepth = wide.depth;
        if (wide.nodes.size() * sizeof(gpu::GpuBvh4Node) > bvhOptions.quantizeOverBytes)
            flat.quantizedNodes = quantizeWideNodes(wide.nodes);
        else
            flat.nodes = std::move(wide.nodes);
    }
    std::vector<uint32_t> order = std::move(bvh.primOrder);
    bvh = Bvh{};
    applyOrderInPlace(order, triangles, shading, tangents);
    flat.triangles = std::move(triangles);
    flat.shading = std::move(shading);
    flat.tangents = std::move(tangents);
    flattenSpheres(scene, bvhOptions, flat);
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
    return flat;
}

} // namespace pt
