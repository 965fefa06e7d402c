#pragma once
// The renderer's scene model: what every loader (glTF, course XML) produces and everything
// downstream (BVH, light table, GPU upload) consumes. World space, except meshes placed more than
// once: those are kept once with a transform per placement (SharedMesh, MeshInstance).
#include "image/image.h"
#include "image/texture_image.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace pt {

// Pbr: the glTF metallic-roughness model (Lambert base under a GGX dielectric coat, a GGX
// metal blended by `metallic`, optional transmission). Conductor and Dielectric are GGX-rough
// when `roughness` > 0.
enum class MaterialType { Diffuse, Mirror, Dielectric, Conductor, Glossy, Pbr };

// The CENG795 course's BRDF models: a Lambertian term plus one specular lobe of exponent p.
enum class GlossyModel { OriginalPhong, OriginalBlinnPhong, ModifiedPhong, ModifiedBlinnPhong, TorranceSparrow };

struct Material {
    std::string name;
    MaterialType type = MaterialType::Diffuse;
    glm::vec3 baseColor{0.8f}; // diffuse albedo; mirror F0; dielectric transmission tint
    glm::vec3 emission{0.0f};  // emitted radiance
    bool doubleSided = false;
    float ior = 1.5f;
    // Beer-Lambert inside a dielectric: transmittance attenuationColor after attenuationDistance.
    glm::vec3 attenuationColor{1.0f};
    float attenuationDistance = std::numeric_limits<float>::infinity();
    // Conductor (complex index of refraction eta + i k), tinted by baseColor.
    glm::vec3 conductorEta{1.0f};
    glm::vec3 conductorK{0.0f};
    // Glossy (course BRDF): baseColor is kd, specular is ks. Torrance-Sparrow's Fresnel uses
    // conductorEta and conductorK.
    GlossyModel glossyModel = GlossyModel::ModifiedBlinnPhong;
    glm::vec3 specular{0.0f};
    float exponent = 1.0f;
    bool normalized = false; // Modified Phong / Blinn-Phong: energy-normalised lobes
    bool kdFresnel = false;  // Torrance-Sparrow: diffuse term scaled by (1 - F)

    // Microfacet (GGX) and glTF PBR parameters.
    float roughness = 0.0f;    // perceptual roughness; GGX alpha = roughness^2
    float metallic = 0.0f;     // Pbr
    float transmission = 0.0f; // Pbr: KHR_materials_transmission
    // Pbr: KHR_materials_diffuse_transmission (Lambertian transmission of the base, tinted).
    float diffuseTransmission = 0.0f;
    glm::vec3 diffuseTransmissionColor{1.0f};
    float specularWeight = 1.0f; // Pbr: KHR_materials_specular factor (colour in `specular`)
    bool thinWalled = true;      // Pbr transmission: no KHR_materials_volume, so no bending
    // Pbr layers: KHR_materials_clearcoat (a GGX coat, F0 0.04) over KHR_materials_sheen (Charlie).
    float clearcoat = 0.0f;
    float clearcoatRoughness = 0.0f; // perceptual; GGX alpha = its square
    float clearcoatNormalScale = 1.0f;
    glm::vec3 sheenColor{0.0f};
    float sheenRoughness = 0.0f; // perceptual; the Charlie alpha = its square
    // Pbr: KHR_materials_iridescence, a thin film (thicknesses in nm).
    float iridescence = 0.0f;
    float iridescenceIor = 1.3f;
    float iridescenceThicknessMinimum = 100.0f, iridescenceThicknessMaximum = 400.0f;
    // Pbr: KHR_materials_anisotropy (strength, and the direction's rotation from the tangent).
    float anisotropy = 0.0f;
    float anisotropyRotation = 0.0f;
    // Dielectric and Pbr transmission: KHR_materials_dispersion, 20 / Abbe number (0: none).
    float dispersion = 0.0f;
    // glTF KHR_materials_pbrSpecularGlossiness: metallicRoughnessTexture holds glossiness in its
    // alpha (roughness = 1 - glossiness x alpha) instead of roughness and metallic.
    bool glossinessTexture = false;
    float glossiness = 1.0f;
    // Glossy: a perfect mirror of this reflectance (no Fresnel) added to the BRDF, the course's
    // mirror with diffuse or specular layers (ceng795 FORMAT.md: "the diffuse and specular terms
    // are still added").
    glm::vec3 mirrorReflectance{0.0f};

    // Textures: indices into Scene::textures. Colour slots multiply the factor above.
    std::optional<uint32_t> baseColorTexture;                // rgb: baseColor, a: opacity
    std::optional<uint32_t> specularTexture;                 // rgb multiplies `specular`: the course's replace_ks,
                                                             // glTF's KHR_materials_specular specularColorTexture
    std::optional<uint32_t> specularWeightTexture;           // a multiplies specularWeight (specularTexture)
    std::optional<uint32_t> transmissionTexture;             // r multiplies transmission (KHR_materials_transmission)
    std::optional<uint32_t> diffuseTransmissionTexture;      // a multiplies diffuseTransmission
    std::optional<uint32_t> diffuseTransmissionColorTexture; // rgb multiplies diffuseTransmissionColor
    std::optional<uint32_t> clearcoatTexture;                // r multiplies clearcoat
    std::optional<uint32_t> clearcoatRoughnessTexture;       // g multiplies clearcoatRoughness
    std::optional<uint32_t> clearcoatNormalTexture;          // the coat's own tangent-space normal map
    std::optional<uint32_t> sheenColorTexture;               // rgb multiplies sheenColor
    std::optional<uint32_t> sheenRoughnessTexture;           // a multiplies sheenRoughness
    std::optional<uint32_t> iridescenceTexture;              // r multiplies iridescence
    std::optional<uint32_t> iridescenceThicknessTexture;     // g: thickness from minimum to maximum
    std::optional<uint32_t> anisotropyTexture;               // rg: direction, b multiplies anisotropy
    std::optional<uint32_t> metallicRoughnessTexture;
    std::optional<uint32_t> normalTexture; // tangent-space normal map, or heights if bumpMap
    std::optional<uint32_t> emissiveTexture;
    float normalScale = 1.0f;    // normal map strength; the course's BumpFactor for bump maps
    bool bumpMap = false;        // normalTexture holds heights (the course's bump_normal)
    bool normalMapYDown = false; // the map's +y runs down the image (the course's), not up (glTF)
    bool blendBaseColor = false; // the course's blend_kd: kd = (kd + texel) / 2
    bool unlit = false; // the course's replace_all, glTF KHR_materials_unlit: the base colour is shown unshaded

    // The course's classic shading (its Whitted / direct-lighting ray tracer; the classic
    // integrator uses these, the path tracer ignores them): ka, and Blinn-Phong kd, ks, p.
    glm::vec3 ambient{0.0f};
    bool classicPhong = false; // false: shade with the BSDF above (course BRDF materials)
    glm::vec3 classicDiffuse{0.0f}, classicSpecular{0.0f};
    float classicExponent = 1.0f;

    enum class AlphaMode { Opaque, Mask, Blend };
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    float opacity = 1.0f; // baseColor alpha factor

    bool emissive() const { return emission.x > 0 || emission.y > 0 || emission.z > 0 || (unlit && baseColorTexture); }
};

enum class TextureWrap { Repeat, Clamp, Mirror };

// What a material slot samples: an image (with filter, wrap, encoding, uv transform) or one of
// the course's procedural patterns, evaluated at the world-space point.
struct Texture {
    enum class Type { Image, Checkerboard, Perlin };
    enum class Encoding { Linear, Srgb, Gamma22 };
    Type type = Type::Image;
    uint32_t image = 0; // index into Scene::textureImages
    Encoding encoding = Encoding::Linear;
    bool bilinear = true;
    TextureWrap wrapU = TextureWrap::Repeat, wrapV = TextureWrap::Repeat;
    float valueScale = 1.0f; // course: 255 / Normalizer
    // KHR_texture_transform as a 2x3 matrix: uv' = (dot(row0.xy, uv) + row0.z, dot(row1.xy, uv) + row1.z)
    glm::vec3 uvRow0{1, 0, 0}, uvRow1{0, 1, 0};
    // Checkerboard
    glm::vec3 black{0.0f}, white{1.0f};
    float scale = 1.0f, offset = 0.0f; // also Perlin's NoiseScale (scale)
    bool perlinAbs = false;            // Perlin: |n| instead of (n + 1) / 2
};

struct Mesh {
    std::string name;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals; // empty, or one per position (unit length where valid)
    std::vector<glm::vec2> uvs;     // empty, or one per position
    // Empty, or one per position: xyz the unit tangent (along +u), w = +-1 the bitangent's sign
    // (bitangent = cross(normal, tangent) * w), as glTF's TANGENT; zero where invalid.
    std::vector<glm::vec4> tangents;
    std::vector<glm::uvec3> triangles;
    uint32_t material = 0;
    glm::vec3 motion{0.0f}; // motion blur: translation over the shutter interval (world space)
};

// A mesh placed more than once (glTF nodes sharing a mesh, the course's Meshes that
// MeshInstances build on): its parts once, in object space, and a MeshInstance per placement.
// The flattener keeps it as one tree under an instance tree (two-level BVH), or copies it into
// world space where that pays or is needed (src/flatten/flat_instances.h).
struct SharedMesh {
    std::string name;
    std::vector<Mesh> parts; // object space; each part's material unless an instance replaces it
    size_t triangleCount() const {
        size_t n = 0;
        for (const Mesh& m : parts) n += m.triangles.size();
        return n;
    }
};

struct MeshInstance {
    std::string name;
    uint32_t mesh = 0; // index into Scene::sharedMeshes
    glm::mat4 objectToWorld{1.0f};
    std::optional<uint32_t> material; // replaces every part's material (the course's instances)
    glm::vec3 motion{0.0f};           // motion blur: translation over the shutter interval (world space)
};

// Tone mapping for the PNG (the EXR stays linear): the CENG795 course's operators.
struct TonemapSettings {
    enum class Operator { Clamp, Photographic };
    Operator op = Operator::Clamp;
    float key = 0.18f;        // Photographic: key value
    float burnPercent = 0.0f; // Photographic: percentage of pixels allowed to burn out
    float saturation = 1.0f;
    float scale = 1.0f; // Clamp: multiplies the radiance first (the course's classic images use 0..255)
    float gamma = 1.0f; // display gamma; ignored when srgb
    bool srgb = true;   // the sRGB transfer curve instead of a power
};

// Settings a camera may carry for its own image (the course format has them per camera);
// the command line overrides them.
struct CameraRenderSettings {
    std::optional<int> width, height;
    std::optional<uint32_t> spp;
    std::optional<int> maxDepth;
    std::optional<bool> nee, importanceSampling, russianRoulette;
    std::optional<bool> classic; // the course's classic ray tracer (cameras without <Renderer>)
    std::optional<TonemapSettings> tonemap;
    std::string imageName; // output file name, relative to the scene file's directory
};

struct Camera {
    std::string name;
    int id = -1; // the course format's Camera id (selects it with --camera); -1 for glTF
    glm::vec3 position{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f}; // unit
    glm::vec3 up{0.0f, 1.0f, 0.0f};       // unit, orthogonal to forward
    float yfov = 0.8f;                    // radians
    float aspectRatio = 0.0f;             // width / height, 0 when the file does not say
    // Image-plane window (left, right, bottom, top) at unit distance along forward, for
    // off-centre frusta; when absent the window is symmetric from yfov and the image aspect.
    std::optional<glm::vec4> window;
    float apertureSize = 0.0f; // thin lens: 0 = pinhole
    float focusDistance = 0.0f;
    CameraRenderSettings settings;
};

// An analytic sphere: the unit sphere at the origin mapped by objectToWorld (any affine map,
// so ellipsoids too).
struct Sphere {
    std::string name;
    glm::mat4 objectToWorld{1.0f};
    uint32_t material = 0;
    glm::vec3 motion{0.0f}; // motion blur: translation over the shutter interval (world space)
};

// Settings a scene file may carry for itself; the command line overrides them.
struct RenderHints {
    std::optional<int> width;
    std::optional<int> height;
    std::optional<int> maxDepth;
};

// Lights without geometry: reached by light sampling only (BSDF rays never hit them).
struct PunctualLight {
    enum class Type { Point, Directional, Spot, Square };
    Type type = Type::Point;
    glm::vec3 position{0.0f};      // point, spot; square: centre
    glm::vec3 direction{0, -1, 0}; // directional: the direction light travels; spot: cone axis;
                                   // square: normal (it emits on that side) -- all unit
    glm::vec3 intensity{0.0f};     // point, spot: radiant intensity (W/sr); directional: irradiance
                                   // (W/m^2); square: radiance
    float cosFalloff = 1.0f;       // spot: full intensity inside this cone (cosine of the half angle)
    float cosCoverage = 1.0f;      // spot: nothing outside this cone
    float falloffExponent = 4.0f;  // spot: the band is t^exponent (the course's 4; glTF's 2)
    float size = 0.0f;             // square: edge length
};

// Light arriving from infinitely far away in every direction: an equirectangular (lat-long)
// radiance map, or a constant colour. Direction d maps to u = (1 + atan2(d.x, -d.z) / pi) / 2,
// v = acos(d.y) / pi (the CENG795 course's convention; +y is up).
struct Environment {
    Image image;                  // linear RGB; empty for a constant environment
    glm::vec3 colour{1.0f};       // the constant radiance when image is empty
    float scale = 1.0f;           // multiplies the radiance
    float rotationDegrees = 0.0f; // about +y
    std::string source;           // file name, for messages
};

struct Scene {
    std::string source; // file name, or "built-in Cornell box"
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<TextureImage> textureImages;
    std::optional<uint32_t> backgroundTexture; // the course's replace_background (camera rays)
    std::vector<Mesh> meshes;                  // world space
    std::vector<SharedMesh> sharedMeshes;
    std::vector<MeshInstance> instances;
    std::vector<Sphere> spheres;
    std::vector<PunctualLight> punctualLights;
    std::optional<Environment> environment; // replaces `background` for rays that escape
    std::vector<Camera> cameras;
    glm::vec3 background{0.0f};
    glm::vec3 ambientLight{0.0f}; // the course's AmbientLight (classic integrator only)
    RenderHints hints;
    // Things the file uses that the renderer does not model yet (shown as one warning).
    std::vector<std::string> unsupported;
    // glTF KHR_materials_variants: the scene's variant names, and the one rendered (empty: the
    // default materials).
    std::vector<std::string> materialVariants;
    std::string variant;

    // Distinct triangles: the world-space meshes' and each shared mesh's once.
    size_t triangleCount() const {
        size_t n = 0;
        for (const auto& m : meshes) n += m.triangles.size();
        for (const auto& m : sharedMeshes) n += m.triangleCount();
        return n;
    }
};

} // namespace pt
