#pragma once
// The integrator configurations `pt bench` compares. A configuration is written as words
// joined by '+': nee (next event estimation, with MIS unless nomis), is (BSDF importance
// sampling; without it uniform directions), rr (Russian roulette), nomis, sobol (the
// Owen-scrambled Sobol' sampler; without it independent), nolt (no light tracing of caustics,
// which is otherwise used where the scene has them), or none. "nee+is+rr+sobol" is the renderer's
// default; the words name what is on, everything unnamed is off (light tracing aside).
#include "flatten/integrator_settings.h"

#include <string>
#include <vector>

namespace pt {

struct BenchConfig {
    std::string label; // as written, e.g. "nee+is+rr+sobol"
    bool nee = false, mis = false, importanceSampling = false, rr = false;
    SamplerKind sampler = SamplerKind::Independent;
    bool lightTracing = true;

    // `base` with this configuration's switches (depth, seed and the rest kept).
    IntegratorSettings apply(IntegratorSettings base) const;
};

// Throws std::invalid_argument naming the unknown or contradictory word.
BenchConfig parseBenchConfig(const std::string& text);
// A comma-separated list of configurations.
std::vector<BenchConfig> parseBenchConfigs(const std::string& list);

// The seed course's experiment: the eight NEE / importance sampling / roulette combinations,
// then the default with MIS off, with each other sampler, and without light tracing.
std::vector<BenchConfig> defaultBenchConfigs();

} // namespace pt
