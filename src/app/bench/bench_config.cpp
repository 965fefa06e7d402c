#include "app/bench/bench_config.h"

#include <sstream>
#include <stdexcept>

namespace pt {

IntegratorSettings BenchConfig::apply(IntegratorSettings base) const {
    base.nee = nee;
    base.mis = mis;
    base.rr = rr;
    base.sampling = importanceSampling ? DirectionSampling::Cosine : DirectionSampling::Uniform;
    base.sampler = sampler;
    base.lightTracing = lightTracing;
    return base;
}

BenchConfig parseBenchConfig(const std::string& text) {
    BenchConfig c;
    c.label = text;
    if (text == "none") return c;
    if (text.empty()) throw std::invalid_argument("empty configuration (use 'none' for every technique off)");
    bool noMis = false;
    std::istringstream words(text);
    std::string word;
    while (std::getline(words, word, '+')) {
        if (word == "nee")
            c.nee = true;
        else if (word == "is")
            c.importanceSampling = true;
        else if (word == "rr")
            c.rr = true;
        else if (word == "nomis")
            noMis = true;
        else if (word == "sobol")
            c.sampler = SamplerKind::Sobol;
        else if (word == "nolt")
            c.lightTracing = false;
        else
            throw std::invalid_argument("configuration '" + text + "': unknown word '" + word +
                                        "' (words: nee, is, rr, nomis, sobol, nolt, or none)");
    }
    if (noMis && !c.nee) throw std::invalid_argument("configuration '" + text + "': nomis needs nee");
    c.mis = c.nee && !noMis;
    return c;
}

std::vector<BenchConfig> parseBenchConfigs(const std::string& list) {
    std::vector<BenchConfig> configs;
    std::istringstream items(list);
    std::string item;
    while (std::getline(items, item, ',')) configs.push_back(parseBenchConfig(item));
    if (configs.empty()) throw std::invalid_argument("no configuration given");
    for (size_t i = 0; i < configs.size(); ++i)
        for (size_t j = 0; j < i; ++j)
            if (configs[i].label == configs[j].label)
                throw std::invalid_argument("configuration '" + configs[i].label + "' is listed twice");
    return configs;
}

std::vector<BenchConfig> defaultBenchConfigs() {
    return parseBenchConfigs(
        "nee+is+rr,nee+is,nee+rr,nee,is+rr,is,rr,none,nee+is+rr+nomis,nee+is+rr+sobol,nee+is+rr+nolt");
}

} // namespace pt
