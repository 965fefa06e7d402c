// The one definition of everything the GPU sees: buffer records, push constants,
// specialization-constant ids and enums. Included by C++ (src/) and by GLSL (shaders/).
// Layout rule: std430, every struct a multiple of 16 bytes, vec3 always followed by a
// 4-byte scalar so C++ (glm) and GLSL agree without padding surprises; the C++ side
// checks every size with static_assert.
#ifndef PT_SHADERS_SHARED_LAYOUT_H
#define PT_SHADERS_SHARED_LAYOUT_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace pt::gpu {
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec2 = glm::uvec2;
using uvec4 = glm::uvec4;
using uint = std::uint32_t;
using uint64_t = std::uint64_t;
#define PT_CHECK_SIZE(type, bytes) static_assert(sizeof(type) == (bytes), #type " must match its GLSL std430 size")
#else
#define PT_CHECK_SIZE(type, bytes)
#endif

// ---- Material types (GpuMaterial::type) ----
#define MATERIAL_DIFFUSE 0u
#define MATERIAL_MIRROR 1u
#define MATERIAL_DIELECTRIC 2u
#define MATERIAL_CONDUCTOR 3u
#define MATERIAL_GLOSSY 4u // Lambert + one course BRDF lobe (GLOSSY_*)
#define MATERIAL_PBR 5u    // glTF metallic-roughness: Lambert under GGX dielectric, GGX metal, transmission
// MATERIAL_MIRROR, MATERIAL_CONDUCTOR and MATERIAL_DIELECTRIC with alpha > 0 are GGX-rough
// (alpha below MIN_ROUGH_ALPHA stays a smooth delta surface); a rough mirror is the glTF metal.
#define MIN_ROUGH_ALPHA 1e-3
// The sheen lobe's tables (src/flatten/sheen_tables.h): this many cos theta by as many roughness
// points each, the projected area then the albedo, as float bits at GpuSceneParams::sheenTables
// in the texel buffer.
#define SHEEN_TABLE_SIZE 32

// ---- Glossy lobes (GpuMaterial::glossyModel), the CENG795 course's BRDFs ----
#define GLOSSY_ORIGINAL_PHONG 0u
#define GLOSSY_ORIGINAL_BLINN_PHONG 1u
#define GLOSSY_MODIFIED_PHONG 2u
#define GLOSSY_MODIFIED_BLINN_PHONG 3u
#define GLOSSY_TORRANCE_SPARROW 4u

// ---- Material flags ----
#define MATERIAL_FLAG_DOUBLE_SIDED 1u     // back faces shade (and emit) like front faces
#define MATERIAL_FLAG_ABSORBING 2u        // dielectric interior has Beer-Lambert absorption
#define MATERIAL_FLAG_NORMALIZED 4u       // glossy: energy-normalised modified Phong / Blinn-Phong lobe
#define MATERIAL_FLAG_KD_FRESNEL 8u       // glossy Torrance-Sparrow: diffuse term times (1 - F)
#define MATERIAL_FLAG_BLEND_KD 16u        // course blend_kd: kd = (kd + texel) / 2 instead of kd * texel
#define MATERIAL_FLAG_BUMP_MAP 32u        // normalTexture holds heights (course bump_normal), not normals
#define MATERIAL_FLAG_UNLIT 64u           // course replace_all: shows baseColor (texture) as is, no shading
#define MATERIAL_FLAG_ALPHA_MASK 128u     // glTF alphaMode MASK: cut out where alpha < alphaCutoff
#define MATERIAL_FLAG_ALPHA_BLEND 256u    // glTF alphaMode BLEND: stochastic cut-out with probability 1 - alpha
#define MATERIAL_FLAG_THIN_WALLED 512u    // PBR transmission without KHR_materials_volume: no refraction bend
#define MATERIAL_FLAG_NORMAL_Y_DOWN 2048u // normal map +y along +v (down the image): the course's maps
#define MATERIAL_FLAG_CLASSIC_PHONG 1024u // classic integrator: the course's Blinn-Phong with classicDiffuse/Specular
#define MATERIAL_FLAG_GLOSSINESS 4096u    // metallicRoughnessTexture's alpha is glossiness (glTF specular-glossiness)

// ---- Textures (GpuTexture) ----
#define NO_TEXTURE 0xffffffffu
#define TEXTURE_IMAGE 0u
#define TEXTURE_CHECKERBOARD 1u // course checkerboard, from the world-space point
#define TEXTURE_PERLIN 2u       // course Perlin noise, from the world-space point
#define TEXTURE_FLAG_BILINEAR 1u
#define TEXTURE_FLAG_SRGB 2u        // texels are sRGB-encoded (glTF colour textures)
#define TEXTURE_FLAG_GAMMA_22 4u    // texels are gamma 2.2 encoded (course degamma="true")
#define TEXTURE_FLAG_FLOAT 8u       // texels are 4 floats (HDR images); otherwise one packed RGBA8 uint
#define TEXTURE_FLAG_PERLIN_ABS 16u // Perlin: |n| (veins) instead of (n + 1) / 2
#define TEXTURE_FLAG_TEXCOORD_1 32u // glTF TEXCOORD_1 (unused until meshes carry a second set)
#define TEXTURE_WRAP_U_SHIFT 8u     // 2 bits each: TEXTURE_WRAP_*
#define TEXTURE_WRAP_V_SHIFT 10u
#define TEXTURE_WRAP_REPEAT 0u
#define TEXTURE_WRAP_CLAMP 1u
#define TEXTURE_WRAP_MIRROR 2u

// ---- Triangle flags ----
#define TRIANGLE_FLAG_SHADING_NORMALS 1u // interpolate n0..n2; otherwise use the geometric normal
#define TRIANGLE_FLAG_ALPHA_TESTED 2u    // its material cuts out by alpha: any-hit test in traversal
#define TRIANGLE_FLAG_MOVING 4u          // motion blur: moves by motions[flags >> TRIANGLE_MOTION_SHIFT]
#define TRIANGLE_FLAG_TANGENTS 8u        // the file's vertex tangents (glTF TANGENT) orient its normal map
#define TRIANGLE_MOTION_SHIFT 8u
#define NO_MOTION 0xffffffffu

// ---- BVH traversal ----
// Entries of the kernel's traversal stack (shaders/geometry/traverse.glsl). Every tree's exact
// need is computed when it is built (src/accel/wide_bvh.cpp) and flattenScene refuses a tree
// that needs more (src/flatten/flat_scene.cpp), so the kernel never checks.
#define TRAVERSAL_STACK_SIZE 96

// With `--bvh auto`, scenes of at most this many triangles (and no instances) skip the tree: each ray tests
// every triangle, read from a uniform buffer at indices the compiler knows (shaders/geometry/
// traverse.glsl, UNIFORM_TRIANGLE_COUNT), where lavapipe loads each word once for the whole
// SIMD vector instead of gathering it lane by lane. The block is this size whatever the scene.
#define UNIFORM_TRIANGLES_MAX 48u
#define UNIFORM_TRIANGLE_VEC4S 3u // one GpuTriangle as std140 uvec4s

// Set 0's texel buffers (R32G32B32A32_UINT views, one 16-byte texel per load) of the triangle
// tree's nodes and of the triangles, read through them where TEXEL_LOADS (shared/features.h) is
// on. Lavapipe turns a texel fetch into one 16-byte load per lane, where a load through a buffer
// address is a gather per 64-bit word (bench/RESULTS.md, "Geometry read through texel buffers").
// Pipelines without a scene's views bind small placeholders (src/gpu/compute_pipeline.cpp).
#define TEXEL_BINDING_NODES 1
#define TEXEL_BINDING_TRIANGLES 2
#define TEXEL_BINDING_SPHERE_NODES 3
#define TEXEL_BINDING_SPHERES 4
#define TEXEL_BINDING_COUNT 4 // bindings 1 to 4
#define TRIANGLE_TEXELS 3u    // GpuTriangle in 16-byte texels
#define BVH4_QNODE_TEXELS 4u  // GpuBvh4QNode
#define BVH4_NODE_TEXELS 7u   // GpuBvh4Node
#define SPHERE_TEXELS 7u      // GpuSphere

// Child words of GpuBvh4Node. An inner child is the index of its node (bit 31 clear); a leaf
// has bit 31 set, its primitive count minus one in bits 27..30 and its first primitive (in the
// BVH-ordered primitive array) in bits 0..26; an unused slot is BVH4_EMPTY.
#define BVH4_EMPTY 0xffffffffu
#define BVH4_LEAF_BIT 0x80000000u
#define BVH4_COUNT_SHIFT 27u
#define BVH4_MAX_LEAF_PRIMITIVES 16u
#define BVH4_FIRST_MASK 0x07ffffffu // also the most primitives one tree can index, plus one

#define NO_LIGHT 0xffffffffu
// Hit::primitive: triangles are plain indices, spheres carry this bit.
#define SPHERE_BIT 0x80000000u
// Hit::instance of a triangle of the world tree (or a sphere): no instance transform applies.
#define NO_INSTANCE 0xffffffffu

// ---- Specialization constants ----
// The workgroup size; every other constant is a kernel feature, one row of shared/features.h.
#define SPEC_LOCAL_SIZE_X 0
#define SPEC_LOCAL_SIZE_Y 1

// ---- Forced random numbers (FORCED_RANDOM in shared/features.h) ----
#define FORCED_RANDOM_OFF 0u
#define FORCED_RANDOM_ZERO 1u // every sample dimension is 0
#define FORCED_RANDOM_ONE 2u  // every sample dimension is 1 - 2^-24, the largest value returned

// ---- Per-pixel accumulation (GpuSceneParams::accumulation) ----
// Each sum is a double-float (hi + lo, |lo| <= ulp(hi) / 2) kept by error-free transformations
// (Knuth's TwoSum; shaders/integrator/accumulate.glsl), so 1e5+ samples of a constant sum
// to the constant within ~1e-9 instead of float32's ~1e-3 drift, and the state is exact
// to store, reload (checkpoints) and merge (pt merge). Vec4 k of a pixel's ACCUM_* block:
#define ACCUMULATION_VEC4S_PER_PIXEL 4u
#define ACCUM_SUM 0u            // (sum rgb hi, count of dropped non-finite samples)
#define ACCUM_SUM_LO 1u         // (sum rgb lo, 0)
#define ACCUM_SUM_SQUARES 2u    // (sum of squares rgb hi, 0)
#define ACCUM_SUM_SQUARES_LO 3u // (sum of squares rgb lo, 0)

// ---- Light-tracing splats (LIGHT_TRACING in shared/features.h) ----
// Light paths land on any pixel, so their contributions are added with atomics. Integer
// atomics keep the image bit-identical however the work is split (float atomics would make
// it depend on the order of arrival): each pixel holds SPLAT_WORDS_PER_PIXEL uint64 fixed-point
// sums, placed after every pixel's ACCUM_* block in the same buffer. With one light path per
// pixel and sample, a pixel's mean is its splat sum / SPLAT_SUM_SCALE / spp. Headroom: the
// sums hold 2^35 (mean x spp), the sums of squares 2^39.
#define SPLAT_WORDS_PER_PIXEL 6u
#define SPLAT_SUM 0u                  // 3 words: rgb sums of the per-path contributions
#define SPLAT_SUM_SQUARES 3u          // 3 words: rgb sums of their squares
#define SPLAT_SUM_SCALE 268435456.0   // 2^28: resolution 3.7e-9 per path
#define SPLAT_SQUARE_SCALE 16777216.0 // 2^24

// ---- Bidirectional path tracing (BDPT in shared/features.h) ----
// Light subpath vertices a camera path can connect to: at most this many per sample, so BDPT
// needs max depth <= BDPT_MAX_LIGHT_VERTICES + 2 (the camera segment and one connection).
#define BDPT_MAX_LIGHT_VERTICES 32u
// BDPT_STRATEGY: every strategy, weighted by MIS; or (tests) one strategy alone, unweighted:
// BDPT_ONE_STRATEGY(segments, s) keeps only paths of that many segments whose light subpath
// has s vertices (0: the camera path hits the emitter; 1: light sampling).
#define BDPT_ALL_STRATEGIES 0u
#define BDPT_ONE_STRATEGY(segments, s) (((segments) << 8u) | ((s) + 1u))

// ---- Vertex merging (MERGING in shared/features.h: BDPT with photon merging, Georgiev et al.
// 2012's vertex connection and merging) ----
// A round (one sample index for every pixel) is two dispatches: VCM_PHASE_LIGHT traces each
// pixel's light subpath, splats its camera connections and stores its vertices, hashed by cell
// into a grid; VCM_PHASE_CAMERA traces each pixel's camera path, connects it to its own light
// subpath and merges it with the vertices of every pixel's near each of its own.
#define VCM_PHASE_WHOLE 0u  // whole samples in one dispatch (path tracing, BDPT)
#define VCM_PHASE_LIGHT 1u  // a round's light subpaths
#define VCM_PHASE_CAMERA 2u // the round's camera paths
#define VCM_PHASE_PILOT 3u  // before the first round: light subpaths of their own, counted per cell
// A stored light vertex: VCM_VERTEX_VEC4S vec4 (integrator/vcm.glsl). The vertex buffer holds
// them, pixels x verticesPerPixel, then one uint per pixel (its light subpath's vertex count).
#define VCM_VERTEX_VEC4S 7u
#define VCM_NO_VERTEX 0xffffffffu

// ---- Samplers (SAMPLER in shared/features.h) ----
#define SAMPLER_INDEPENDENT 0u // a hash of (pixel, sample index, dimension, seed)
#define SAMPLER_SOBOL 1u       // Owen-scrambled Sobol' points, shuffled per pixel

// ---- Debug views (DEBUG_VIEW in shared/features.h) ----
#define DEBUG_VIEW_NONE 0u
#define DEBUG_VIEW_ALBEDO 1u
#define DEBUG_VIEW_NORMAL 2u
#define DEBUG_VIEW_DEPTH 3u
#define DEBUG_VIEW_BVH_COST 4u
#define DEBUG_VIEW_NAN_MASK 5u
// Not one of the viewer's: how often light sampling at the surfaces the camera sees finds its
// light (integrator/debug_view.glsl; `--integrator auto` measures with it).
#define DEBUG_VIEW_LIGHT_VISIBILITY 6u
// Its red channel counts two outcomes of a sample in one number: 1 for a light sample that finds
// its light, LIGHT_VIA_SHARP_LOBE for a bounce that meets a lit sharp GGX lobe (a glossy
// caustic's carrier). The probe takes fewer samples per pixel than this, so each pixel's two
// counts are the quotient and remainder of its red sum by it.
#define LIGHT_VIA_SHARP_LOBE 8.0
// GGX alpha below which a lobe counts as sharp for that probe (flatten/feature_set.h).
#define SHARP_LOBE_MAX_ALPHA 0.2

// A triangle as the intersector reads it: world-space vertices plus the ids it needs at a hit.
struct GpuTriangle {
    vec3 p0;
    uint materialIndex;
    vec3 p1;
    uint lightIndex; // index into the light table, or NO_LIGHT
    vec3 p2;
    uint flags; // TRIANGLE_FLAG_*
};
#define TRIANGLE_WORDS64 6u // its size in 64-bit words (loadTriangle, common/buffers.glsl)
PT_CHECK_SIZE(GpuTriangle, TRIANGLE_WORDS64 * 8u);

// Per-vertex shading data, read only at the closest hit.
struct GpuTriangleShading {
    vec3 n0;
    float u0;
    vec3 n1;
    float u1;
    vec3 n2;
    float u2;
    vec3 v; // v0, v1, v2
    uint pad;
};
PT_CHECK_SIZE(GpuTriangleShading, 64);

// Vertex tangents of a triangle from the file (glTF TANGENT): xyz unit tangent, w bitangent
// sign. Only scenes with normal-mapped meshes that carry tangents have this array.
struct GpuTriangleTangents {
    vec4 t0;
    vec4 t1;
    vec4 t2;
};
PT_CHECK_SIZE(GpuTriangleTangents, 48);

// Four-wide BVH node: the boxes of up to four children, one component of all four per vector,
// so one ray tests them together, and their child words (BVH4_* above). Unused slots have
// empty boxes (lo +FLOAT_MAX, hi -FLOAT_MAX) so that a union over the slots is the node's box.
// Nodes are in depth-first preorder: node 0 is the root, a child follows its parent.
struct GpuBvh4Node {
    vec4 loX;
    vec4 hiX;
    vec4 loY;
    vec4 hiY;
    vec4 loZ;
    vec4 hiZ;
    uvec4 child;
};
PT_CHECK_SIZE(GpuBvh4Node, 112);

// The same node as stored for the kernel, its child boxes quantised to 8 bits per plane
// (src/accel/quantized_bvh.cpp; after Ylitie et al. 2017): plane = origin + q * 2^e per axis,
// with q in 0..255 rounded outwards so that the decoded box contains the exact one, and e the
// smallest exponent that reaches the node's far side. Half the bytes of GpuBvh4Node, so half the
// gathers on lavapipe, where loading nodes was the kernel's hottest work (big trees only:
// GpuSceneParams::nodeFormat). Read word by word
// (loadBvh4Node, common/buffers.glsl), never as a GLSL struct array, so its C++ size is its stride.
struct GpuBvh4QNode {
    vec3 origin;    // the node's box's low corner
    uint exponents; // per axis (bits 0-7 x, 8-15 y, 16-23 z): e + 127, the scale 2^e's float exponent bits
    uvec4 child;    // child words (BVH4_* above)
    uint lo[3];     // per axis: child i's low plane q in bits 8i..8i+7
    uint hi[3];     // per axis: the high planes likewise
    uvec2 pad;      // to one 64-byte cache line per node
};
#define BVH4_QNODE_WORDS64 8u // its size in 64-bit words; the last (pad) is never read
PT_CHECK_SIZE(GpuBvh4QNode, BVH4_QNODE_WORDS64 * 8u);
#define BVH4_NODE_WORDS64 14u // GpuBvh4Node's size in 64-bit words
// GpuSceneParams::nodeFormat. Quantised nodes pay where the tree outgrows the caches (the
// 1 M-triangle mesh: +11% paths/s) and cost where it does not (the 32-triangle box: -6%,
// the decoding), so only a tree of more float node bytes than BvhBuildOptions::quantizeOverBytes
// (src/accel/bvh.h) is stored quantised.
#define BVH_NODES_FLOAT 0u
#define BVH_NODES_QUANTIZED 1u
// NODE_FORMAT (shared/features.h) as compiled: read GpuSceneParams::nodeFormat at run time. A
// pipeline specialised to a scene has the scene's format instead, and only its loader.
#define BVH_NODES_FROM_SCENE 2u

struct GpuMaterial {
    vec3 baseColor;       // diffuse albedo, mirror/dielectric/conductor tint
    uint type;            // MATERIAL_*
    vec3 emission;        // emitted radiance (front side; both sides if double-sided)
    uint flags;           // MATERIAL_FLAG_*
    vec3 sigmaA;          // Beer-Lambert absorption coefficient inside a dielectric (1/length)
    float ior;            // interior index of refraction over exterior
    vec3 conductorEta;    // conductor, Torrance-Sparrow: real part of the complex index of refraction
    uint glossyModel;     // GLOSSY_*
    vec3 conductorK;      // imaginary part (absorption index)
    float exponent;       // glossy lobe exponent
    vec3 specular;        // glossy: ks; PBR: KHR_materials_specular colour factor
    float alpha;          // GGX alpha (perceptual roughness squared); below MIN_ROUGH_ALPHA: smooth
    float metallic;       // PBR: metal blend
    float transmission;   // PBR: KHR_materials_transmission factor
    float specularWeight; // PBR: KHR_materials_specular factor
    float normalScale;    // normal map scale, or the course BumpFactor for bump maps
    // Texture slots (index into the texture table, or NO_TEXTURE). Colour slots multiply the
    // factor above (course replace_* sets the factor to 1).
    uint baseColorTexture;         // rgb: baseColor (course kd), a: opacity
    uint specularTexture;          // rgb x specular: course replace_ks, glTF specularColorTexture
    uint metallicRoughnessTexture; // glTF: g roughness, b metallic
    uint normalTexture;            // tangent-space normals, or heights with MATERIAL_FLAG_BUMP_MAP
    uint emissiveTexture;
    float alphaCutoff;          // MATERIAL_FLAG_ALPHA_MASK threshold
    float opacity;              // baseColor alpha factor
    uint specularWeightTexture; // a x specularWeight: glTF KHR_materials_specular specularTexture
    // The course's classic shading (CLASSIC): ka * Ia + sum over lights of
    // (kd cos(theta) + ks cos^p(alpha_h)) E, added on every surface type, mirrors included.
    vec3 ambient;              // ka
    float classicExponent;     // Blinn-Phong p
    vec3 classicDiffuse;       // kd (no 1/pi: the course's convention)
    uint transmissionTexture;  // r x transmission: glTF KHR_materials_transmission transmissionTexture
    vec3 classicSpecular;      // ks
    float diffuseTransmission; // PBR: KHR_materials_diffuse_transmission factor
    vec3 diffuseTransmissionColor;
    uint diffuseTransmissionTexture;      // a x diffuseTransmission
    uint diffuseTransmissionColorTexture; // rgb (sRGB) x diffuseTransmissionColor
    // PBR layers (shaders/bsdf/pbr_layers.glsl): KHR_materials_clearcoat over KHR_materials_sheen
    // over the base.
    float clearcoat;        // coat weight (0: no coat)
    float clearcoatAlpha;   // coat GGX alpha (clearcoatRoughness squared); below MIN_ROUGH_ALPHA: smooth
    float sheenRoughness;   // sheen perceptual roughness (the Charlie distribution's alpha is its square)
    vec3 sheenColor;        // sheen colour (black: no sheen)
    uint sheenColorTexture; // rgb (sRGB) x sheenColor
    // The coat's normal. In the buffer: (0, 0, 0), "the surface's normal without the base's normal
    // map"; applyTextures sets it at a hit (world space, from clearcoatNormalTexture if any), and
    // orientClearcoat moves it into the BSDF's local frame.
    vec3 clearcoatNormal;
    float clearcoatNormalScale;
    uint clearcoatTexture;          // r x clearcoat
    uint clearcoatRoughnessTexture; // g x clearcoat roughness
    uint clearcoatNormalTexture;    // tangent-space normals of the coat
    uint sheenRoughnessTexture;     // a x sheenRoughness
    // KHR_materials_iridescence: a thin film over the base's Fresnel (shaders/bsdf/thin_film.glsl).
    float iridescence;                 // weight of the film's Fresnel (0: no film)
    float iridescenceIor;              // the film's index of refraction
    float iridescenceThicknessMinimum; // nm, at thickness texture value 0
    float iridescenceThickness;        // nm: the maximum in the buffer; applyTextures sets it at a hit
    uint iridescenceTexture;           // r x iridescence
    uint iridescenceThicknessTexture;  // g: mix(minimum, maximum, g)
    // KHR_materials_anisotropy: the specular lobes rougher along a direction in the tangent plane.
    float anisotropy;       // strength (0: isotropic)
    uint anisotropyTexture; // rg: direction in tangent space ([0, 1] -> [-1, 1]), b x strength
    // The direction (world space), which applyTextures sets at a hit from the tangents, the
    // rotation and the texture; (0, 0, 0) in the buffer. alignAnisotropy turns the BSDF's local x
    // axis to it.
    vec3 anisotropyDirection;
    float anisotropyRotation; // radians, counter-clockwise from the tangent
    float dispersion;         // KHR_materials_dispersion: 20 / Abbe number (0: none); shaders/common/spectrum.glsl
    float glossiness;         // MATERIAL_FLAG_GLOSSINESS: roughness = 1 - glossiness x texture alpha
    uint pad9;
    uint pad10;
    vec3 mirror; // glossy: reflectance of a perfect mirror lobe added to the BRDF (the course's layered mirror)
    uint pad11;
};
PT_CHECK_SIZE(GpuMaterial, 352);

// A texture: an image in the texel buffer (with filter, wrap, encoding and a uv transform) or
// a course procedural pattern.
struct GpuTexture {
    uint type;        // TEXTURE_*
    uint flags;       // TEXTURE_FLAG_* and wrap modes
    uint texelOffset; // first uint of the image in the texel buffer
    uint width;
    uint height;
    float valueScale;    // multiplies every value (course: 255 / Normalizer)
    float patternScale;  // checkerboard: Scale; Perlin: NoiseScale
    float patternOffset; // checkerboard: Offset
    vec4 uvRow0;         // uv' = (dot(uvRow0.xy, uv) + uvRow0.z, dot(uvRow1.xy, uv) + uvRow1.z)
    vec4 uvRow1;         //   (KHR_texture_transform; identity otherwise)
    vec3 colorA;         // checkerboard: BlackColor
    float pad0;
    vec3 colorB; // checkerboard: WhiteColor
    float pad1;
};
PT_CHECK_SIZE(GpuTexture, 96);

// An analytic sphere: the unit sphere at the origin under an affine map (so ellipsoids too).
// Both directions of the map are stored (rows of 3x4 matrices): rays go to object space for
// the intersection, hit points come back to world space without the error of o + t d.
struct GpuSphere {
    vec4 worldToObject[3];
    vec4 objectToWorld[3];
    uint materialIndex;
    uint lightIndex; // index into the light table, or NO_LIGHT
    uint motion;     // index into the motion table, or NO_MOTION
    uint pad1;
};
PT_CHECK_SIZE(GpuSphere, 112);

// A placement of a shared mesh (two-level BVH; src/flatten/flat_instances.cpp): the mesh's own
// tree in GpuSceneParams::nodes from node `root`, its triangles in object space, and the affine
// map both ways (rows of 3x4 matrices). Rays go to object space with worldToObject, where the
// watertight test runs unchanged (t is the same: the direction is not renormalised); hits come
// back with objectToWorld. The instances are the leaves of a tree of their own
// (GpuSceneParams::instanceNodes), in its order.
struct GpuInstance {
    vec4 worldToObject[3];
    vec4 objectToWorld[3];
    uint root;          // node index of the mesh's tree (a child word: never a leaf)
    uint firstTriangle; // the mesh's triangles: [firstTriangle, firstTriangle + triangleCount)
    uint triangleCount;
    uint pad0;
};
PT_CHECK_SIZE(GpuInstance, 112);

// Triangle emitters seen under at least this solid angle (steradians) are sampled by solid angle
// (shaders/lights/triangle_light.glsl); where no surface sees one so, the kernel leaves the code
// out (SPHERICAL_TRIANGLE_LIGHTS, src/lights/light_table.h).
#define SPHERICAL_SAMPLING_MIN 0.5

// ---- Light types (GpuLight::type) ----
#define LIGHT_TRIANGLE 0u
#define LIGHT_SPHERE 1u
#define LIGHT_POINT 2u
#define LIGHT_DIRECTIONAL 3u
#define LIGHT_SPOT 4u
#define LIGHT_SQUARE 5u // an invisible one-sided square emitter (the course's AreaLight)
#define LIGHT_ENVIRONMENT 6u

// One emitter in the light-selection table (all kinds share one power CDF).
struct GpuLight {
    uint type;         // LIGHT_*
    uint primitive;    // triangle or sphere index (BVH order)
    float pmf;         // probability of choosing this light
    float area;        // triangle: area; sphere: |det| of its linear map (area scale of the unit sphere);
                       // spot: the exponent of its falloff band (the course's 4, glTF's 2)
    vec3 position;     // point, spot: position; round sphere, square: centre
    float radius;      // round sphere: radius, sampled by solid angle; 0: ellipsoid, sampled by area;
                       // square: edge length
    vec3 intensity;    // point, spot: radiant intensity (W/sr); directional: irradiance on a facing
                       // surface; square: radiance
    float cosFalloff;  // spot: full intensity inside this cone
    vec3 direction;    // directional: the direction light travels; spot: axis; square: normal
    float cosCoverage; // spot: nothing outside this cone
};
PT_CHECK_SIZE(GpuLight, 64);

// One node of the light tree (src/lights/light_tree.h; Conty Estevez and Kulla 2018, as in
// pbrt-v4's BVHLightSampler): the bounded lights under it, by where they are (box), how much
// they emit (phi) and where to (a cone of normals around `axis` of half-angle acos(cosThetaO),
// each emitting up to acos(cosThetaE) away from its normal). Light sampling descends from the
// root by the children's importance at the shading point (shaders/lights/light_tree.glsl).
struct GpuLightTreeNode {
    vec3 boundsMin;
    float phi; // emitted power (the light table's weight) of the lights below
    vec3 boundsMax;
    float cosThetaO;
    vec3 axis;
    float cosThetaE;
    uint child;      // interior: the second child's index (the first is the next node); leaf: the light's index
    uint flags;      // LIGHT_NODE_*
    float sinThetaO; // of the cone of normals, so the kernel need not take it
    uint pad0;
};
PT_CHECK_SIZE(GpuLightTreeNode, 64);
#define LIGHT_NODE_LEAF 1u
#define LIGHT_NODE_TWO_SIDED 2u // some light below emits from both sides

struct GpuCamera {
    vec3 origin;
    float lensRadius; // thin lens; 0 = pinhole
    vec3 right;       // unit, image x
    float focusDistance;
    vec3 up; // unit, image y (up)
    float pad0;
    vec3 forward; // unit, view direction
    float pad1;
    vec4 window; // image plane (left, right, bottom, top) at unit distance along forward
};
PT_CHECK_SIZE(GpuCamera, 80);

// Per-render constants, in a buffer reached through its device address.
struct GpuSceneParams {
    // Device addresses of the scene arrays (buffer device address: no 128 MiB binding limit).
    uint64_t triangles;      // GpuTriangle[]
    uint64_t shading;        // GpuTriangleShading[]
    uint64_t nodes;          // GpuBvh4Node[]
    uint64_t materials;      // GpuMaterial[]
    uint64_t lights;         // GpuLight[]
    uint64_t lightCdf;       // float[numLights + 1]
    uint64_t accumulation;   // vec4[ACCUMULATION_VEC4S_PER_PIXEL * pixels], see ACCUM_* below
    uint64_t spheres;        // GpuSphere[]
    uint64_t sphereNodes;    // GpuBvh4Node[]: a second BVH, over the spheres
    uint64_t envTexels;      // vec4[envWidth * envHeight]: radiance (scale applied), row 0 at the top
    uint64_t envMarginal;    // float[envHeight + 1]: CDF over rows of the sampling weights
    uint64_t envConditional; // float[envHeight * (envWidth + 1)]: CDF over columns, per row
    uint64_t textures;       // GpuTexture[]
    uint64_t texels;         // uint[]: packed RGBA8 or float texels of every image texture
    GpuCamera camera;
    vec3 background; // radiance of rays that escape
    uint numLights;
    uvec2 imageSize;
    uint maxDepth;     // ray segments including the camera ray (Mitsuba's convention)
    uint rrStartDepth; // Russian roulette starts after this many segments
    uint seed;
    uint numTriangles;
    uint numNodes; // the world tree's nodes: the first of `nodes` (instanced meshes' trees follow)
    uint numSpheres;
    uint numSphereNodes;
    uint envWidth; // 0: no environment (escaping rays see `background`)
    uint envHeight;
    uint envLightIndex;   // the environment's entry in the light table, or NO_LIGHT
    float envRotationCos; // rotation about +y
    float envRotationSin;
    float envSamplingTotal; // sum of the sampling weights (for the pdf)
    uint backgroundTexture; // course replace_background: camera rays that escape see this, or NO_TEXTURE
    vec3 ambientLight;      // classic integrator: the course's AmbientLight Ia
    float rrThreshold;      // Russian roulette: throughput at or above this always continues
    uint64_t motions;       // vec4[]: xyz = an object's translation over the shutter interval
    uint64_t tangents;      // GpuTriangleTangents[] (one per triangle), or none
    uint nodeFormat;  // BVH_NODES_*: how `nodes` stores the triangle trees (the sphere and instance trees are float)
    uint sheenTables; // texel-buffer offset of the sheen lobe's tables (SHEEN_TABLE_SIZE), if any
    uint numInstances;
    uint numInstanceNodes;
    uint64_t instances;     // GpuInstance[], in the order of the instance tree's leaves
    uint64_t instanceNodes; // GpuBvh4Node[]: the top-level tree, over the instances
    // A sphere around all geometry (xyz centre, w radius): light subpaths from the environment and
    // directional lights start on a disc of this radius outside it (lights/light_emission.glsl).
    vec4 sceneSphere;
    // The light tree over the bounded lights (0: none; light selection is by the power CDF),
    // and for each light its path from the root: bit k set where the (k+1)-th step goes to the
    // second child (lights at infinity and those the tree leaves out: 0, unused).
    uint64_t lightTreeNodes;  // GpuLightTreeNode[]
    uint64_t lightTreeTrails; // uint64_t[numLights]
    // The probability of choosing a bounded light: the tree's share. Lights at infinity (the
    // environment, directional lights) come last in the light table and keep their power pmf,
    // so the CDF above this value selects among them.
    float lightTreeShare;
    // 1 / sceneSphere's radius: the tree's importance measures distances in units of the scene, so
    // that squared distances neither overflow nor underflow float at any scale.
    float lightTreeInvScale;
    uint lightTreePad1;
    uint lightTreePad2;
};
PT_CHECK_SIZE(GpuSceneParams, 112 + 80 + 80 + 16 + 16 + 16 + 16 + 16 + 32);

// Push constants of the render kernel: which pixels and which sample indices this dispatch adds.
struct GpuRenderPush {
    uint64_t sceneParams; // device address of GpuSceneParams
    uvec2 tileOrigin;
    uvec2 tileSize;
    uint sampleStart; // global index of the first sample added to each pixel
    uint sampleCount;
    float sampleClamp; // > 0: clamp each sample's largest component to this (biased; off by default)
    // With COUNT_RAYS: device address of uvec4[pixels] per-pixel ray counts (continuation
    // rays, shadow rays, 0, 0), added to by the pixel's own invocation (no atomics). Camera
    // rays are one per sample and not counted.
    uint64_t rayCounts;
    // Adaptive sampling (render/adaptive_sampling.h), 0 when every pixel takes sampleCount
    // samples: device address of uvec4[pixels], each pixel's (samples summed so far, samples
    // its current epoch gives it, rays its samples traced in the epoch, 0). The pass then adds
    // rounds [sampleStart, sampleStart + sampleCount) of the epoch's epochRounds: pixel p takes
    // its allocation a_p times those rounds over epochRounds, rounded down at both ends, from its
    // own next sample index, so however an epoch is split into passes each pixel ends it with
    // exactly a_p more samples.
    uint64_t adaptiveSamples;
    uint epochRounds;
    uint phase; // VCM_PHASE_*
    // Vertex merging (VCM_PHASE_LIGHT and _CAMERA): this round's merge radius, the vertex buffer
    // (VCM_VERTEX_VEC4S above), the grid's cell heads (uint[vcmCellMask + 1], VCM_NO_VERTEX
    // where empty) and the vertices kept per pixel.
    float mergeRadius;
    uint vcmCellMask;
    uint64_t vcmVertices;
    uint64_t vcmCells;
    // The pilot's vertex counts per cell (uint[vcmPilotMask + 1], cells vcmPilotCell wide), from
    // which a vertex is kept in the grid with probability min(1, vcmKeepTarget / count).
    uint64_t vcmPilot;
    uint vcmVerticesPerPixel;
    uint vcmPilotMask;
    float vcmPilotCell;
    float vcmKeepTarget;
    // The order of the dispatch's workgroups over its 8x8 blocks: workgroup l (row-major) renders
    // block (l * blockStride) mod blocks, a stride coprime with the block count near its golden
    // section (render/workgroup_order.h), so that any run of consecutive workgroups is spread over
    // the whole tile.
    uint blockStride;
};
PT_CHECK_SIZE(GpuRenderPush, 120);

// ---- Test kernels (shaders/tests) ----
#define TEST_MODE_COSINE_HEMISPHERE 0u // outputs[i] = (w, pdf); inputs: optional vec4[] of (u1, u2, _, _)
#define TEST_MODE_UNIFORM_HEMISPHERE 1u
#define TEST_MODE_LIGHT_SAMPLE 2u
#define TEST_MODE_LIGHT_PDF 3u
#define TEST_MODE_TRACE_BVH 4u
#define TEST_MODE_TRACE_BRUTE_FORCE 5u
// The trace modes' outputs[i] = (t, primitive, bary): a hit in an instance carries this bit on
// the primitive and the instance's index in place of the second barycentric.
#define TEST_HIT_INSTANCE_BIT 0x40000000u
#define TEST_MODE_BSDF_SAMPLE 6u // outputs[i] = (wi local, pdf), outputs[count + i] = (weight, valid)
#define TEST_MODE_BSDF_PDF 7u    // inputs: local wi; outputs[i] = (f cos, pdf)
#define TEST_MODE_TEXTURE 8u     // texture materialIndex at inputs[i] = (u, v, _, _) or point (xyz); outputs[i] = value
// The test kernel's specialization constant for the mode a pipeline runs (GpuTestPush::mode is
// informational).
#define TEST_MODE_CONSTANT_ID 63
// The light that light sampling chooses at (point, normal): outputs[i] = (index as float bits, pmf, _, _);
// and each light's pmf there: outputs[i] = (pmf of light i, _, _, _).
#define TEST_MODE_LIGHT_CHOICE 10u
#define TEST_MODE_LIGHT_SELECTION_PMF 11u
#define TEST_MODE_SOBOL_POINTS 9u // outputs[i] = Sobol' sample i of pixel (0, 0) in dimensions 0-1 and 3-4, as floats
// outputs[i] = the BSDF directions' 2D points of bounces 1 and 2 (one 4D point, common/rng.glsl)
// of sample i of pixel (0, 0), as floats
#define TEST_MODE_SOBOL_BOUNCE_PAIR 12u

struct GpuTestRay {
    vec3 origin;
    float tMax;
    vec3 direction;
    float pad;
};
PT_CHECK_SIZE(GpuTestRay, 32);

struct GpuTestPush {
    uint64_t sceneParams;
    uint64_t inputs;  // mode-dependent: GpuTestRay[] or vec4[] directions; 0 when the host gives none
    uint64_t outputs; // mode-dependent: vec4[]
    uint mode;        // what the pipeline runs is its TEST_MODE constant; this says it again, for debugging
    uint count;
    vec3 point; // shading point for light tests
    uint seed;
    vec3 normal;        // hemisphere tests: shading normal; BSDF tests: wo in the local frame
    uint materialIndex; // BSDF tests
};
PT_CHECK_SIZE(GpuTestPush, 64);

#ifdef __cplusplus
} // namespace pt::gpu
#endif
#endif
