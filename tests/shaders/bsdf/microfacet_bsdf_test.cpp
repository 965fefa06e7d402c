// GGX microfacet BSDFs (shaders/bsdf/ggx.glsl, rough_conductor.glsl, rough_dielectric.glsl,
// gltf_pbr.glsl) through the GLSL test kernel: each sampler against its own pdf over the whole
// sphere (chi-square, the mass lost to invalid samples as one more bin), the pdf's mass, every
// sample weight equal to f cos / pdf, delta lobes of smooth PBR materials taken with their
// reported probability, reciprocity of the reflection lobes, white-furnace energy bounds; and
// two renders: a rough glass sphere at alpha 1e-3 against the smooth one (with Beer-Lambert
// absorption), and a rough glass sphere under a uniform sky.
#include "support/gpu_test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace pt::test {
namespace {

// Bins over the whole sphere: z in [-1, 1], phi in [0, 2 pi), all of equal solid angle. Each
// bin's probability is the pdf integrated by a midpoint rule: kSub x kSub points, and a finer
// kFineZ x kFinePhi where that is not enough -- in the two rows at the horizon (grazing lobes
// are steep there) and in bins where no coarse point landed on the pdf's support (the edge of
// the refraction lobe), which the chi-square test would otherwise call impossible. Lobes of a
// grazing wo are thin crescents along the horizon, so grazing cases use kGrazingPhi points
// across phi everywhere.
constexpr int kZBins = 32, kPhiBins = 32, kBins = kZBins * kPhiBins, kSub = 8, kFineZ = 64, kFinePhi = 16;
constexpr int kGrazingPhi = 48;
constexpr float kGrazingCos = 0.15f;
constexpr uint32_t kSamples = 200000;

glm::vec3 direction(double z, double phi) {
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
}

// nz x nphi midpoints inside each listed bin, bin after bin.
std::vector<glm::vec4> midpoints(const std::vector<int>& bins, int nz, int nphi) {
    std::vector<glm::vec4> dirs;
    dirs.reserve(bins.size() * nz * nphi);
    for (int bin : bins) {
        const int zi = bin / kPhiBins, pi = bin % kPhiBins;
        for (int a = 0; a < nz; ++a)
            for (int b = 0; b < nphi; ++b)
                dirs.emplace_back(direction(-1.0 + 2.0 * (zi + (a + 0.5) / nz) / kZBins,
                                      2 * M_PI * (pi + (b + 0.5) / nphi) / kPhiBins),
                    0.0f);
    }
    return dirs;
}

int binOf(const glm::vec3& w) {
    double phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2 * M_PI;
    const int zi = std::clamp(static_cast<int>((w.z + 1.0) * 0.5 * kZBins), 0, kZBins - 1);
    const int pi = std::clamp(static_cast<int>(phi / (2 * M_PI) * kPhiBins), 0, kPhiBins - 1);
    return zi * kPhiBins + pi;
}

glm::vec3 woAt(float cosThetaO) { return glm::vec3(std::sqrt(1.0f - cosThetaO * cosThetaO), 0.0f, cosThetaO); }

// Exact unpolarised Fresnel reflectance of a dielectric, eta = n_t / n_i (as fresnel.glsl).
double fresnelDielectric(double cosI, double eta) {
    const double sin2T = (1 - cosI * cosI) / (eta * eta);
    if (sin2T >= 1) return 1;
    const double cosT = std::sqrt(1 - sin2T);
    const double rs = (cosI - eta * cosT) / (cosI + eta * cosT), rp = (eta * cosI - cosT) / (eta * cosI + cosT);
    return 0.5 * (rs * rs + rp * rp);
}

Material roughConductor(float roughness, float eta, float k, float tint) {
    Material m;
    m.type = MaterialType::Conductor;
    m.roughness = roughness;
    m.baseColor = glm::vec3(tint);
    m.conductorEta = glm::vec3(eta);
    m.conductorK = glm::vec3(k);
    return m;
}

Material roughDielectric(float roughness, float ior) {
    Material m;
    m.type = MaterialType::Dielectric;
    m.roughness = roughness;
    m.ior = ior;
    m.baseColor = glm::vec3(1.0f);
    return m;
}

// The glTF metal (metallic 1) as the loader makes it: a mirror, GGX-rough, Schlick's Fresnel.
Material schlickMetal(glm::vec3 f0, float roughness) {
    Material m;
    m.type = MaterialType::Mirror;
    m.baseColor = f0;
    m.roughness = roughness;
    return m;
}

Material pbr(float base, float metallic, float roughness, float transmission = 0.0f, bool thinWalled = false) {
    Material m;
    m.type = MaterialType::Pbr;
    m.baseColor = glm::vec3(base);
    m.metallic = metallic;
    m.roughness = roughness;
    m.transmission = transmission;
    m.thinWalled = thinWalled;
    m.specular = glm::vec3(1.0f);
    return m;
}

struct Case {
    const char* name;
    Material material;
    std::vector<float> cosThetaO; // negative: wo inside (transmissive materials)
    double ior = 1.0;             // > 1: transmitted weights are multiplied by eta^2 for R + T (flux)
};

// KHR_materials_diffuse_transmission on the metallic-roughness model.
Material diffuseTransmitting(float dt, glm::vec3 colour, float transmission, bool thinWalled) {
    Material m = pbr(0.7f, 0.0f, 0.4f, transmission, thinWalled);
    m.diffuseTransmission = dt;
    m.diffuseTransmissionColor = colour;
    return m;
}

// The layers of KHR_materials_clearcoat and KHR_materials_sheen over a metallic-roughness base.
Material layered(Material base, float clearcoat, float coatRoughness, glm::vec3 sheen, float sheenRoughness) {
    base.clearcoat = clearcoat;
    base.clearcoatRoughness = coatRoughness;
    base.sheenColor = sheen;
    base.sheenRoughness = sheenRoughness;
    return base;
}

// KHR_materials_anisotropy: rougher along the local x axis.
Material anisotropic(Material m, float strength) {
    m.anisotropy = strength;
    return m;
}

// A KHR_materials_iridescence film (1.4, 350 nm) over the whole Fresnel.
Material iridescent(Material m) {
    m.iridescence = 1.0f;
    m.iridescenceIor = 1.4f;
    m.iridescenceThicknessMaximum = 350.0f;
    return m;
}

std::vector<Case> cases() {
    Material lowSpecular = pbr(0.5f, 0.0f, std::sqrt(0.5f));
    lowSpecular.ior = 1.3f;
    lowSpecular.specularWeight = 0.5f;
    lowSpecular.specular = glm::vec3(0.8f);
    return {
        {"rough conductor, alpha 0.09", roughConductor(0.3f, 0.2f, 3.0f, 0.9f), {0.8f, 0.3f, 0.05f}},
        {"rough conductor, alpha 0.49", roughConductor(0.7f, 1.5f, 1.0f, 1.0f), {0.9f, 0.1f}},
        {"rough dielectric, alpha 0.09", roughDielectric(0.3f, 1.5f), {0.8f, 0.2f, 0.05f, -0.9f, -0.5f}, 1.5},
        {"rough dielectric, alpha 0.36", roughDielectric(0.6f, 1.5f), {0.6f, -0.3f}, 1.5},
        {"pbr dielectric, roughness 0.5", pbr(0.6f, 0.0f, 0.5f), {0.8f, 0.1f}},
        {"pbr half metal, roughness 0.4", pbr(0.7f, 0.5f, 0.4f), {0.7f, 0.2f}},
        {"pbr transmission 0.7 with volume, roughness 0.4", pbr(0.9f, 0.0f, 0.4f, 0.7f, false), {0.7f, -0.8f, -0.3f},
            1.5},
        {"pbr thin-walled transmission, roughness 0.3", pbr(0.9f, 0.0f, 0.3f, 1.0f, true), {0.6f, -0.4f}},
        {"pbr ior 1.3, specular 0.5 x 0.8", lowSpecular, {0.75f, 0.15f}},
        {"rough Schlick metal, alpha 0.16", schlickMetal(glm::vec3(0.95f, 0.7f, 0.3f), 0.4f), {0.85f, 0.25f, 0.05f}},
        {"pbr diffuse transmission 0.6, thin", diffuseTransmitting(0.6f, glm::vec3(0.9f, 0.6f, 0.3f), 0.0f, true),
            {0.8f, 0.2f, -0.7f}},
        // ior left at 1 here: the flux correction by eta^2 applies to refraction, not to the
        // diffuse transmission, which carries no radiance scaling (the albedo is then a lower bound).
        {"pbr diffuse transmission 0.5 and transmission 0.3 with volume",
            diffuseTransmitting(0.5f, glm::vec3(1.0f), 0.3f, false), {0.7f, -0.6f, -0.2f}},
        {"pbr clearcoat 1 (roughness 0.3) over a dielectric", layered(pbr(0.6f, 0.0f, 0.5f), 1.0f, 0.3f, {}, 0.0f),
            {0.8f, 0.2f, 0.05f}},
        {"pbr sheen (0.9, 0.6, 0.3), roughness 0.5",
            layered(pbr(0.5f, 0.0f, 0.6f), 0.0f, 0.0f, {0.9f, 0.6f, 0.3f}, 0.5f), {0.9f, 0.3f, 0.05f}},
        {"pbr clearcoat 0.6 over sheen 1 (roughness 0.15) over a half metal",
            layered(pbr(0.7f, 0.5f, 0.4f), 0.6f, 0.3f, glm::vec3(1.0f), 0.15f), {0.7f, 0.15f}},
        {"pbr iridescent half metal under a clearcoat",
            iridescent(layered(pbr(0.7f, 0.5f, 0.4f), 0.5f, 0.3f, {}, 0.0f)), {0.8f, 0.2f}},
        {"pbr anisotropic half metal (strength 0.7 along x)", anisotropic(pbr(0.6f, 0.5f, 0.4f), 0.7f), {0.8f, 0.2f}},
        {"pbr anisotropic thin-walled transmission", anisotropic(pbr(0.9f, 0.0f, 0.3f, 1.0f, true), 0.5f),
            {0.6f, -0.4f}},
        {"pbr clearcoat and sheen over transmission with volume",
            layered(pbr(0.9f, 0.0f, 0.4f, 0.7f, false), 1.0f, 0.4f, glm::vec3(0.5f), 0.6f), {0.7f, -0.8f, -0.3f}, 1.5},
    };
}

class MicrofacetBsdf : public GpuTest {
public:
    void SetUp() override {
        GpuTest::SetUp();
        for (const Case& c : cases()) scene_.materials.push_back(c.material);
        scene_.meshes.push_back(makeQuad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0)); // any geometry
    }
    // Appends a material for the test's own use; call upload() after the last one.
    uint32_t add(const Material& m) {
        scene_.materials.push_back(m);
        return static_cast<uint32_t>(scene_.materials.size() - 1);
    }
    void upload() {
        flat_ = flattenScene(scene_);
        gpu_ = std::make_unique<GpuScene>(sharedContext(), flat_, gpu::GpuSceneParams{}, 0);
    }
    // (f cos, 0, 0, pdf) at each direction, for material `index` seen from wo.
    std::vector<glm::vec4> evaluate(uint32_t index, glm::vec3 wo, const std::vector<glm::vec4>& dirs) {
        return runTestKernel(TEST_MODE_BSDF_PDF, static_cast<uint32_t>(dirs.size()), gpu_.get(),
            std::as_bytes(std::span<const glm::vec4>(dirs)), glm::vec3(0.0f), wo, 1, index);
    }
    // kSamples (wi, pdf), then kSamples (weight, valid).
    std::vector<glm::vec4> sample(uint32_t index, glm::vec3 wo, uint32_t seed = 3) {
        return runTestKernel(TEST_MODE_BSDF_SAMPLE, kSamples, gpu_.get(), {}, glm::vec3(0.0f), wo, seed, index);
    }
    Scene scene_;
    FlatScene flat_;
    std::unique_ptr<GpuScene> gpu_;
};

struct FitResult {
    double pValue = 0, mass = 0, validFraction = 0;
    size_t badWeights = 0, nonFinite = 0;
    double albedo = 0; // mean sample weight (flux: transmitted weights times eta^2 when ior > 1)
};

// Probability of each bin under the pdf of material `index` seen from wo (see kSub).
template <class Evaluate>
std::vector<double> binProbabilities(Evaluate&& evaluate, bool grazing) {
    const int phiPoints = grazing ? kGrazingPhi : kSub, finePhiPoints = grazing ? kGrazingPhi : kFinePhi;
    std::vector<int> all(kBins), fine;
    for (int k = 0; k < kBins; ++k) all[k] = k;
    std::vector<double> p(kBins, 0.0);
    auto integrate = [&](const std::vector<int>& bins, int nz, int nphi) {
        const auto values = evaluate(midpoints(bins, nz, nphi));
        const double cell = (2.0 / kZBins / nz) * (2 * M_PI / kPhiBins / nphi);
        for (size_t j = 0; j < bins.size(); ++j) {
            double sum = 0;
            for (int q = 0; q < nz * nphi; ++q) sum += values[j * nz * nphi + q].w;
            p[bins[j]] = sum * cell;
        }
    };
    integrate(all, kSub, phiPoints);
    for (int k = 0; k < kBins; ++k)
        if (p[k] == 0.0 || k / kPhiBins == kZBins / 2 - 1 || k / kPhiBins == kZBins / 2) fine.push_back(k);
    integrate(fine, kFineZ, finePhiPoints);
    return p;
}

// Chi-square of the non-delta samples against the pdf, pdf mass, weights == f cos / pdf.
// Samples whose direction is in `deltaDirections` are left out (smooth lobes); their count is
// returned in `deltaCount`.
FitResult fit(MicrofacetBsdf& t, uint32_t index, glm::vec3 wo, double ior, std::vector<glm::vec4>& samples,
    std::vector<glm::vec4>& evaluated, std::vector<glm::vec3> deltaDirections, size_t* deltaCount) {
    FitResult r;
    const auto probability = binProbabilities(
        [&](const std::vector<glm::vec4>& d) { return t.evaluate(index, wo, d); }, std::abs(wo.z) < kGrazingCos);
    std::vector<double> expected(kBins + 1, 0.0), observed(kBins + 1, 0.0);
    for (int k = 0; k < kBins; ++k) {
        expected[k] = probability[k] * kSamples;
        r.mass += probability[k];
    }
    samples = t.sample(index, wo);
    std::vector<glm::vec4> sampled;
    size_t deltas = 0;
    double nonDeltaMassObserved = 0;
    for (uint32_t i = 0; i < kSamples; ++i) {
        const glm::vec4 s = samples[i], w = samples[kSamples + i];
        if (!std::isfinite(s.x + s.y + s.z + s.w + w.x + w.y + w.z)) ++r.nonFinite;
        if (w.w == 0.0f) continue;
        double weight = w.x;
        // Flux albedo: undo the 1 / eta^2 radiance scaling of refraction.
        if (ior > 1.0 && (s.z < 0) != (wo.z < 0)) weight *= wo.z > 0 ? ior * ior : 1.0 / (ior * ior);
        r.albedo += weight / kSamples;
        bool isDelta = false;
        for (const glm::vec3& d : deltaDirections) isDelta |= glm::length(glm::vec3(s) - d) < 1e-4f;
        if (isDelta) {
            ++deltas;
            continue;
        }
        nonDeltaMassObserved += 1;
        observed[binOf(glm::vec3(s))] += 1;
        sampled.emplace_back(glm::vec3(s), static_cast<float>(i));
    }
    r.validFraction = nonDeltaMassObserved / kSamples;
    // Everything not in a bin (invalid samples, delta samples) is one more bin, expected where
    // the pdf's mass is missing.
    observed.back() = kSamples - nonDeltaMassObserved;
    expected.back() = std::max(0.0, 1.0 - r.mass) * kSamples;
    r.pValue = chiSquarePValue(observed, expected);
    if (deltaCount) *deltaCount = deltas;

    evaluated = t.evaluate(index, wo, sampled);
    for (size_t j = 0; j < sampled.size(); ++j) {
        const uint32_t i = static_cast<uint32_t>(sampled[j].w);
        const glm::vec4 v = evaluated[j];
        const float expectedWeight = v.x / v.w;
        if (!(std::abs(samples[kSamples + i].x - expectedWeight) <= 1e-3f * std::max(1.0f, expectedWeight)) ||
            !(std::abs(samples[i].w - v.w) <= 1e-3f * v.w))
            ++r.badWeights;
    }
    return r;
}

TEST_F(MicrofacetBsdf, SamplingMatchesPdfAndWeightsAreFCosOverPdf) {
    upload();
    const auto all = cases();
    for (uint32_t index = 0; index < all.size(); ++index) {
        const Case& c = all[index];
        for (float cosO : c.cosThetaO) {
            SCOPED_TRACE(std::string(c.name) + ", cos theta_o " + std::to_string(cosO));
            std::vector<glm::vec4> samples, evaluated;
            const FitResult r = fit(*this, index, woAt(cosO), c.ior, samples, evaluated, {}, nullptr);
            std::printf("[          ] %s, cos_o %+.2f: chi-square p %.4f, pdf mass %.4f (valid %.4f), albedo %.4f\n",
                c.name, cosO, r.pValue, r.mass, r.validFraction, r.albedo);
            EXPECT_GT(r.pValue, 1e-3);
            EXPECT_LE(r.mass, 1.0 + 3e-3);
            // The sampler's valid fraction is the pdf's mass (binomial, 5 sigma).
            EXPECT_NEAR(r.validFraction, r.mass, 5 * std::sqrt(r.mass * (1 - r.mass) / kSamples) + 3e-3);
            EXPECT_EQ(r.badWeights, 0u);
            EXPECT_EQ(r.nonFinite, 0u);
            EXPECT_LE(r.albedo, 1.0 + 5e-3) << "reflects or transmits more than arrives";
        }
    }
}

// The loader turns glTF's metallic 1 into a rough mirror (gltf_materials.cpp): the same f cos, pdf
// and samples as the full metallic-roughness model at metallic 1, for less code and work.
TEST_F(MicrofacetBsdf, SchlickMetalIsThePbrModelAtMetallicOne) {
    const glm::vec3 f0(0.95f, 0.7f, 0.3f);
    Material full = pbr(0.0f, 1.0f, 0.4f);
    full.baseColor = f0;
    const uint32_t metal = add(schlickMetal(f0, 0.4f)), model = add(full);
    upload();
    for (float cosO : {0.9f, 0.4f, 0.03f}) {
        SCOPED_TRACE("cos theta_o " + std::to_string(cosO));
        const glm::vec3 wo = woAt(cosO);
        std::vector<glm::vec4> dirs;
        for (int i = 0; i < 64; ++i) {
            const float z = -0.95f + 1.9f * (i + 0.5f) / 64.0f, phi = 2.4f * i;
            const float r = std::sqrt(1 - z * z);
            dirs.emplace_back(r * std::cos(phi), r * std::sin(phi), z, 0.0f);
        }
        const auto a = evaluate(metal, wo, dirs), b = evaluate(model, wo, dirs);
        double nonZero = 0;
        for (size_t i = 0; i < dirs.size(); ++i) {
            EXPECT_NEAR(a[i].x, b[i].x, 1e-5f * std::max(1.0f, b[i].x)) << "f cos at " << i;
            EXPECT_NEAR(a[i].w, b[i].w, 1e-5f * std::max(1.0f, b[i].w)) << "pdf at " << i;
            nonZero += b[i].x > 0;
        }
        EXPECT_GT(nonZero, 10) << "the directions compared must include the lobe";
        const auto sa = sample(metal, wo, 7), sb = sample(model, wo, 7);
        size_t compared = 0;
        for (uint32_t i = 0; i < kSamples; ++i) {
            if (sb[kSamples + i].w == 0.0f) continue;
            ++compared;
            ASSERT_NEAR(glm::distance(glm::vec3(sa[i]), glm::vec3(sb[i])), 0.0f, 1e-4f) << "sample " << i;
            ASSERT_NEAR(sa[kSamples + i].x, sb[kSamples + i].x, 1e-4f * std::max(1.0f, sb[kSamples + i].x));
        }
        EXPECT_GT(compared, kSamples / 2);
    }
}

// Light sampling evaluates f and the pdf in one routine (surfaceEvalPdf, sharing the half vector,
// Fresnel and D); the chi-square tests above check that one. It must equal the separate routines
// (surfaceEval, surfacePdf) the light tracer and the classic integrator use.
TEST_F(MicrofacetBsdf, FusedEvalAndPdfEqualTheSeparateRoutines) {
    upload();
    const auto all = cases();
    for (uint32_t index = 0; index < all.size(); ++index)
        for (float cosO : all[index].cosThetaO) {
            SCOPED_TRACE(std::string(all[index].name) + ", cos theta_o " + std::to_string(cosO));
            std::vector<glm::vec4> dirs;
            for (int i = 0; i < 256; ++i) {
                const float z = -0.995f + 1.99f * (i + 0.5f) / 256.0f, phi = 2.39996f * i;
                const float r = std::sqrt(1 - z * z);
                dirs.emplace_back(r * std::cos(phi), r * std::sin(phi), z, 0.0f);
            }
            const auto v = evaluate(index, woAt(cosO), dirs);
            int nonZero = 0;
            for (size_t i = 0; i < v.size(); ++i) {
                EXPECT_NEAR(v[i].x, v[i].y, 1e-5f * std::max(1.0f, std::abs(v[i].y))) << "f cos at " << i;
                EXPECT_NEAR(v[i].w, v[i].z, 1e-5f * std::max(1.0f, std::abs(v[i].z))) << "pdf at " << i;
                nonZero += v[i].z > 0.0f;
            }
            EXPECT_GT(nonZero, 8);
        }
}

TEST_F(MicrofacetBsdf, ChiSquareRejectsAWrongRoughness) {
    // Negative control: samples of alpha 0.09 judged by the pdf of alpha 0.16.
    const uint32_t wrong = add(roughConductor(0.4f, 0.2f, 3.0f, 0.9f));
    upload();
    const glm::vec3 wo = woAt(0.8f);
    const auto probability =
        binProbabilities([&](const std::vector<glm::vec4>& d) { return evaluate(wrong, wo, d); }, false);
    std::vector<double> expected(kBins, 0.0), observed(kBins, 0.0);
    for (int k = 0; k < kBins; ++k) expected[k] = probability[k] * kSamples;
    const auto samples = sample(0, wo);
    for (uint32_t i = 0; i < kSamples; ++i)
        if (samples[kSamples + i].w != 0.0f) observed[binOf(glm::vec3(samples[i]))] += 1;
    EXPECT_LT(chiSquarePValue(observed, expected), 1e-6);
}

TEST_F(MicrofacetBsdf, SmoothPbrTakesDeltaLobesWithTheirProbability) {
    // alpha 0: the specular reflection (and the thin-wall transmission) are delta lobes.
    const uint32_t opaque = add(pbr(0.5f, 0.3f, 0.0f));
    const uint32_t thin = add(pbr(0.8f, 0.0f, 0.0f, 0.5f, true));
    upload();
    for (uint32_t index : {opaque, thin}) {
        for (float cosO : {0.8f, 0.2f}) {
            SCOPED_TRACE("material " + std::to_string(index) + ", cos theta_o " + std::to_string(cosO));
            const glm::vec3 wo = woAt(cosO);
            const glm::vec3 mirror(-wo.x, -wo.y, wo.z);
            std::vector<glm::vec4> samples, evaluated;
            size_t deltas = 0;
            const FitResult r = fit(*this, index, wo, 1.0, samples, evaluated, {mirror, -wo}, &deltas);
            // Every delta sample reports its lobe's discrete probability; together they are
            // drawn that often, and the non-delta pdf has the rest of the mass.
            double deltaProbability = 0;
            double reflected = 0, transmitted = 0;
            float pSpecular = -1, pTransmission = -1;
            for (uint32_t i = 0; i < kSamples; ++i) {
                const glm::vec3 s(samples[i]);
                if (samples[kSamples + i].w == 0.0f) continue;
                if (glm::length(s - mirror) < 1e-4f) {
                    reflected += 1;
                    pSpecular = samples[i].w;
                    // weight * probability = the lobe's f cos integral: the Fresnel blend.
                    const double F =
                        (1 - 0.3) * fresnelDielectric(cosO, 1.5) + 0.3 * (0.5 + 0.5 * std::pow(1.0 - cosO, 5.0));
                    if (index == opaque) EXPECT_NEAR(samples[kSamples + i].x * samples[i].w, F, 1e-4);
                    if (index == thin)
                        EXPECT_NEAR(samples[kSamples + i].x * samples[i].w, fresnelDielectric(cosO, 1.5), 1e-4);
                } else if (glm::length(s + wo) < 1e-4f) {
                    transmitted += 1;
                    pTransmission = samples[i].w;
                    // Thin wall, straight through: transmission x base colour x (1 - F).
                    EXPECT_NEAR(
                        samples[kSamples + i].x * samples[i].w, 0.5 * 0.8 * (1 - fresnelDielectric(cosO, 1.5)), 1e-4);
                }
            }
            ASSERT_GT(pSpecular, 0.0f);
            deltaProbability += pSpecular;
            auto binomial = [](double p) { return 5 * std::sqrt(p * (1 - p) / kSamples) + 1e-4; };
            EXPECT_NEAR(reflected / kSamples, pSpecular, binomial(pSpecular));
            if (index == thin) {
                ASSERT_GT(pTransmission, 0.0f);
                deltaProbability += pTransmission;
                EXPECT_NEAR(transmitted / kSamples, pTransmission, binomial(pTransmission));
            } else {
                EXPECT_EQ(transmitted, 0.0);
            }
            std::printf("[          ] smooth pbr %u, cos_o %.2f: p %.4f, delta probability %.4f, non-delta pdf mass "
                        "%.4f, albedo %.4f\n",
                index, cosO, r.pValue, deltaProbability, r.mass, r.albedo);
            EXPECT_NEAR(r.mass, 1.0 - deltaProbability, 3e-3);
            EXPECT_GT(r.pValue, 1e-3);
            EXPECT_EQ(r.badWeights, 0u);
            EXPECT_EQ(r.nonFinite, 0u);
            EXPECT_LE(r.albedo, 1.0 + 5e-3);
        }
    }
}

// KHR_materials_diffuse_transmission on a thin wall: reciprocal across the wall (f / |cos(theta_i)|
// the same both ways), and a white base that transmits everything diffusely keeps nearly all the
// energy (only the product-form Fresnel weighting of the base loses a little) and never gains.
TEST_F(MicrofacetBsdf, DiffuseTransmissionIsReciprocalAndKeepsTheEnergy) {
    Material white = diffuseTransmitting(1.0f, glm::vec3(1.0f), 0.0f, true);
    white.baseColor = glm::vec3(1.0f);
    const uint32_t leaf = add(white);
    upload();
    std::vector<glm::vec4> above, below;
    for (int i = 0; i < 10; ++i) {
        const glm::vec3 d = direction(0.15 + 0.8 * ((i * 7) % 10) / 9.0, 0.7 + 2.1 * i);
        above.emplace_back(d, 0.0f);
        below.emplace_back(d.x, d.y, -d.z, 0.0f);
    }
    for (size_t a = 0; a < above.size(); ++a) {
        const auto fromAbove = evaluate(leaf, glm::vec3(above[a]), below);
        for (size_t b = 0; b < below.size(); ++b) {
            const auto fromBelow = evaluate(leaf, glm::vec3(below[b]), {above[a]});
            const double ab = fromAbove[b].x / std::abs(below[b].z), ba = fromBelow[0].x / std::abs(above[a].z);
            EXPECT_GT(ab, 0.0);
            EXPECT_NEAR(ab, ba, 1e-4 * std::max(1.0, ab)) << "pair " << a << ", " << b;
        }
    }
    for (float cosO : {0.9f, 0.5f, -0.7f}) {
        std::vector<glm::vec4> samples, evaluated;
        const FitResult r = fit(*this, leaf, woAt(cosO), 1.0, samples, evaluated, {}, nullptr);
        size_t through = 0;
        for (uint32_t i = 0; i < kSamples; ++i)
            through += samples[kSamples + i].w != 0.0f && (samples[i].z < 0) != (cosO < 0);
        std::printf("[          ] white diffuse transmission, cos_o %+.2f: albedo %.4f, %.3f of samples through\n",
            cosO, r.albedo, double(through) / kSamples);
        EXPECT_GT(r.pValue, 1e-3);
        EXPECT_LE(r.albedo, 1.0 + 5e-3);
        EXPECT_GT(r.albedo, 0.85);
        EXPECT_GT(through, kSamples / 2) << "most of it goes through";
    }
}

TEST_F(MicrofacetBsdf, ReflectionLobesAreReciprocal) {
    upload();
    // Directions above the surface, away from grazing.
    std::vector<glm::vec4> dirs;
    for (int i = 0; i < 12; ++i) dirs.emplace_back(direction(0.15 + 0.8 * ((i * 7) % 12) / 11.0, 0.7 + 2.1 * i), 0.0f);
    // Rough conductor, rough dielectric (reflection), opaque PBR, half-metal PBR, the three
    // opaque layered ones (clearcoat, sheen, both), the iridescent and the anisotropic one.
    for (uint32_t index : {0u, 2u, 4u, 5u, 12u, 13u, 14u, 15u, 16u}) {
        std::vector<std::vector<glm::vec4>> f;
        for (const glm::vec4& wo : dirs) f.push_back(evaluate(index, glm::vec3(wo), dirs));
        for (size_t a = 0; a < dirs.size(); ++a)
            for (size_t b = 0; b < dirs.size(); ++b) {
                if (a == b) continue;
                const double fab = f[a][b].x / dirs[b].z, fba = f[b][a].x / dirs[a].z;
                EXPECT_NEAR(fab, fba, 1e-4 * std::max(1.0, std::abs(fab)))
                    << "material " << index << " pair " << a << ", " << b;
            }
    }
}

TEST_F(MicrofacetBsdf, WhiteFurnaceConductorLosesOnlySingleScatteringEnergy) {
    // eta 0, k 0 makes the exact conductor Fresnel 1 at every angle: what is lost is the
    // energy single-scattering GGX drops (light masked after one bounce).
    struct Level {
        float roughness;
        double minAlbedoNormal, minAlbedoGrazing;
    };
    // Single-scattering GGX albedo E(cos theta_o) falls with alpha, most at normal incidence
    // (a quadrature of the same D and G2 gives 0.987 / 0.970 / 0.883 at alpha 0.1, 0.684 /
    // 0.698 / 0.860 at 0.5 and 0.328 / 0.451 / 0.760 at 1, for cos 0.9 / 0.5 / 0.1; Kulla and
    // Conty 2017 show the same up-to-60% loss at roughness 1).
    const Level levels[] = {
        {0.1f, 0.995, 0.99}, {std::sqrt(0.1f), 0.96, 0.87}, {std::sqrt(0.5f), 0.66, 0.84}, {1.0f, 0.31, 0.74}};
    std::vector<uint32_t> index;
    for (const Level& l : levels) index.push_back(add(roughConductor(l.roughness, 0.0f, 0.0f, 1.0f)));
    upload();
    double previousNormal = 2.0;
    for (size_t k = 0; k < index.size(); ++k) {
        for (float cosO : {0.9f, 0.5f, 0.1f}) {
            const auto samples = sample(index[k], woAt(cosO), 7);
            double sum = 0, sum2 = 0;
            for (uint32_t i = 0; i < kSamples; ++i) {
                const double w = samples[kSamples + i].w != 0.0f ? samples[kSamples + i].x : 0.0;
                sum += w;
                sum2 += w * w;
            }
            const double albedo = sum / kSamples,
                         se = std::sqrt(std::max(0.0, sum2 / kSamples - albedo * albedo) / kSamples);
            std::printf("[          ] furnace conductor alpha %.3f, cos_o %.1f: albedo %.4f +- %.4f\n",
                levels[k].roughness * levels[k].roughness, cosO, albedo, se);
            EXPECT_LE(albedo, 1.0 + 4 * se + 1e-4);
            EXPECT_GE(albedo, cosO > 0.3f ? levels[k].minAlbedoNormal : levels[k].minAlbedoGrazing)
                << "alpha " << levels[k].roughness * levels[k].roughness << ", cos " << cosO;
            EXPECT_EQ(samples.size(), 2u * kSamples);
            if (cosO == 0.9f) {
                EXPECT_LT(albedo, previousNormal) << "rougher must lose more at normal incidence";
                previousNormal = albedo;
            }
        }
    }
}

TEST_F(MicrofacetBsdf, RoughDielectricReflectsAndTransmitsAtMostWhatArrives) {
    upload();
    // Material 2: alpha 0.09, ior 1.5. Flux albedo R + T from outside and from inside (where
    // most of it is total internal reflection).
    for (float cosO : {1.0f, 0.7f, 0.3f, 0.05f, -0.95f, -0.6f, -0.2f}) {
        const glm::vec3 wo = woAt(cosO);
        const auto samples = sample(2, wo, 11);
        double R = 0, T = 0;
        for (uint32_t i = 0; i < kSamples; ++i) {
            if (samples[kSamples + i].w == 0.0f) continue;
            const bool transmitted = (samples[i].z < 0) != (wo.z < 0);
            const double w = samples[kSamples + i].x;
            if (transmitted)
                T += w * (wo.z > 0 ? 1.5 * 1.5 : 1 / (1.5 * 1.5)) / kSamples;
            else
                R += w / kSamples;
        }
        std::printf(
            "[          ] rough dielectric alpha 0.09, cos_o %+.2f: R %.4f T %.4f R+T %.4f\n", cosO, R, T, R + T);
        EXPECT_LE(R + T, 1.0 + 5e-3);
        if (std::abs(cosO) >= 0.3f) EXPECT_GE(R + T, 0.97) << "alpha 0.09 loses little energy away from grazing";
        if (cosO > 0)
            EXPECT_NEAR(R, fresnelDielectric(cosO, 1.5), 0.05 + 0.5 * (1 - cosO)) << "reflectance near Fresnel";
    }
}

TEST_F(MicrofacetBsdf, ExtremeRoughnessAndGrazingAnglesStayFinite) {
    // alpha at both ends (MIN_ROUGH_ALPHA and 1), wo at normal incidence, almost in the surface
    // and just below it (inside, for the transmissive ones); total internal reflection included.
    const float smallest = std::sqrt(1.0001e-3f);
    std::vector<uint32_t> index;
    for (float r : {smallest, 1.0f}) {
        index.push_back(add(roughConductor(r, 0.2f, 3.0f, 1.0f)));
        index.push_back(add(roughDielectric(r, 1.5f)));
        index.push_back(add(pbr(0.8f, 0.5f, r)));
        index.push_back(add(pbr(0.8f, 0.0f, r, 0.8f, false)));
        index.push_back(add(pbr(0.8f, 0.0f, r, 0.8f, true)));
    }
    upload();
    std::vector<glm::vec4> dirs;
    for (int i = 0; i < 4096; ++i)
        dirs.emplace_back(direction(-1.0 + (i / 64 + 0.5) / 32.0, (i % 64 + 0.5) / 64.0 * 2 * M_PI), 0.0f);
    for (float c : {-1e-4f, -0.5f, 1e-4f, 1.0f}) dirs.emplace_back(woAt(c), 0.0f); // the grazing and axial ones exactly
    for (uint32_t m : index)
        for (float cosO : {1.0f, 1e-4f, -1e-4f, -1.0f}) {
            const glm::vec3 wo = woAt(cosO);
            size_t bad = 0;
            for (const glm::vec4& v : evaluate(m, wo, dirs))
                bad += !std::isfinite(v.x) || !std::isfinite(v.w) || v.x < 0 || v.w < 0;
            const auto samples = runTestKernel(TEST_MODE_BSDF_SAMPLE, 20000, gpu_.get(), {}, glm::vec3(0.0f), wo, 5, m);
            for (const glm::vec4& v : samples) bad += !std::isfinite(v.x + v.y + v.z + v.w) || v.w < 0;
            EXPECT_EQ(bad, 0u) << "material " << m << ", cos theta_o " << cosO;
        }
}

// ---------------------------------------------------------------------------------------------
// Renders

class MicrofacetRender : public GpuTest {
protected:
    static Camera lookingAtOrigin() {
        Camera c;
        c.position = glm::vec3(0.0f, 0.0f, 6.0f);
        c.yfov = 0.45f;
        return c;
    }
    // A smooth sky: bright above, dim below, a warm side, so refraction shows.
    static Environment gradientSky() {
        Environment env;
        env.image.width = 16;
        env.image.height = 8;
        env.image.rgba.assign(16 * 8 * 4, 1.0f);
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 16; ++x) {
                float* t = env.image.at(x, y);
                t[0] = 0.2f + 1.8f * (7 - y) / 7.0f + (x < 8 ? 0.5f : 0.0f);
                t[1] = 0.2f + 1.8f * (7 - y) / 7.0f;
                t[2] = 0.3f + 0.5f * x / 15.0f;
            }
        return env;
    }
    static Scene glassSphere(float roughness, bool absorbing) {
        Scene scene;
        Material glass;
        glass.type = MaterialType::Dielectric;
        glass.roughness = roughness;
        glass.ior = 1.5f;
        glass.baseColor = glm::vec3(1.0f);
        if (absorbing) {
            glass.attenuationColor = glm::vec3(0.4f, 0.7f, 0.9f);
            glass.attenuationDistance = 1.0f;
        }
        scene.materials.push_back(glass);
        Sphere s;
        s.material = 0;
        scene.spheres.push_back(s);
        return scene;
    }
};

TEST_F(MicrofacetRender, RoughGlassAtTinyAlphaConvergesToSmoothGlass) {
    IntegratorSettings s = independentSettings();
    s.maxDepth = 32;
    Scene smooth = glassSphere(0.0f, true), rough = glassSphere(std::sqrt(1.0001e-3f), true);
    smooth.environment = gradientSky();
    rough.environment = gradientSky();
    const auto a = renderScene(smooth, s, lookingAtOrigin(), 16, 16, 128);
    const auto b = renderScene(rough, s, lookingAtOrigin(), 16, 16, 128);
    EXPECT_EQ(a.droppedSamples, 0u);
    EXPECT_EQ(b.droppedSamples, 0u);
    double sumA = 0, sumB = 0, var = 0;
    int outliers = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            for (int c = 0; c < 3; ++c) {
                const double d = a.mean.at(x, y)[c] - b.mean.at(x, y)[c];
                const double v = a.varianceOfMean.at(x, y)[c] + b.varianceOfMean.at(x, y)[c];
                sumA += a.mean.at(x, y)[c];
                sumB += b.mean.at(x, y)[c];
                var += v;
                if (std::abs(d) > 5 * std::sqrt(v) + 2e-3 * std::abs(a.mean.at(x, y)[c]) + 1e-4) ++outliers;
            }
    std::printf("[          ] smooth mean %.5f, rough (alpha 1e-3) mean %.5f, sigma %.5f, outliers %d\n", sumA / 768,
        sumB / 768, std::sqrt(var) / 768, outliers);
    EXPECT_LE(outliers, 3);
    EXPECT_NEAR(sumA / 768, sumB / 768, 4 * std::sqrt(var) / 768 + 1e-4);
    // And the absorption is there: the sphere's centre is darker in red than in blue.
    EXPECT_LT(b.mean.at(8, 8)[0] / a.mean.at(0, 0)[0], b.mean.at(8, 8)[2] / a.mean.at(0, 0)[2]);
}

TEST_F(MicrofacetRender, RoughGlassUnderUniformSkyLosesLittle) {
    Scene scene = glassSphere(0.3f, false);
    Environment sky;
    sky.colour = glm::vec3(1.0f);
    scene.environment = sky;
    IntegratorSettings s = independentSettings();
    s.maxDepth = 64;
    s.rr = false;
    const auto r = renderScene(scene, s, lookingAtOrigin(), 16, 16, 64);
    EXPECT_EQ(r.droppedSamples, 0u);
    double minimum = 1e9, maximum = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const double v = r.mean.at(x, y)[0], se = std::sqrt(r.varianceOfMean.at(x, y)[0]);
            EXPECT_LE(v, 1.0 + 5 * se + 1e-4) << x << ", " << y;
            minimum = std::min(minimum, v);
            maximum = std::max(maximum, v);
        }
    double centre = 0;
    for (int y = 6; y < 10; ++y)
        for (int x = 6; x < 10; ++x) centre += r.mean.at(x, y)[0] / 16;
    std::printf("[          ] rough glass (alpha 0.09) in a white furnace: pixels in [%.4f, %.4f], centre %.4f\n",
        minimum, maximum, centre);
    // Single-scattering GGX at alpha 0.09 loses little head-on (R + T = 0.997 at cos 0.7) and
    // more at the silhouette, where light meets the surface at grazing angles (0.93 at cos 0.05).
    EXPECT_GE(centre, 0.95);
    EXPECT_GE(minimum, 0.75);
}

} // namespace
} // namespace pt::test
