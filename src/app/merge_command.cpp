#include "app/merge_command.h"

#include "film/accumulation_state.h"
#include "film/state_file.h"
#include "film/tonemap.h"
#include "film/metrics.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace pt {
namespace {

namespace fs = std::filesystem;

// Keys that must agree between parts, beyond the identity (which already holds the seed; it is
// checked on its own for a clearer message).
constexpr const char* kMustAgree[] = {"seed", "render_settings", "scene_hash"};

std::string value(const ImageMetadata& meta, const char* key) {
    const auto it = meta.find(key);
    return it == meta.end() ? std::string() : it->second;
}

} // namespace

void addMergeOptions(CLI::App* cmd, MergeOptions& o) {
    cmd->add_option("parts", o.parts, "Partial renders (pt render --samples A:B) of one scene and seed")->required();
    cmd->add_option("-o,--output", o.output, "Merged EXR; a tone-mapped PNG is written beside it")->required();
    cmd->add_flag(
        "--allow-gaps", o.allowGaps, "Merge even if the sample ranges leave gaps (fewer spp; still unbiased)");
    cmd->add_option("--exposure", o.exposure, "Exposure in stops for the PNG");
    cmd->add_flag("-q,--quiet", o.quiet, "Only print the summary line and errors");
}

int runMerge(const MergeOptions& o) {
    std::vector<AccumulationState> states;
    std::vector<ImageMetadata> metas;
    std::vector<SampleRange> ranges;
    double seconds = 0;
    for (const std::string& part : o.parts) {
        ImageMetadata meta;
        states.push_back(readStateExr(part, meta));
        for (const char* key : kMustAgree)
            if (!metas.empty() && value(meta, key) != value(metas[0], key))
                throw std::runtime_error(part + ": not a part of the same render as " + o.parts[0] + ": its " + key +
                                         " is '" + value(meta, key) + "', not '" + value(metas[0], key) + "'");
        if (value(meta, "scene_hash").empty()) throw std::runtime_error(part + ": carries no scene hash");
        if (!metas.empty() && (states.back().width != states[0].width || states.back().height != states[0].height))
            throw std::runtime_error(part + ": is " + std::to_string(states.back().width) + "x" +
                                     std::to_string(states.back().height) + ", " + o.parts[0] + " is " +
                                     std::to_string(states[0].width) + "x" + std::to_string(states[0].height));
        for (size_t k = 0; k < ranges.size(); ++k) {
            const SampleRange r = states.back().samples;
            if (r.begin < ranges[k].end && ranges[k].begin < r.end)
                throw std::runtime_error(part + ": its samples " + r.describe() + " overlap those of " + o.parts[k] +
                                         " (" + ranges[k].describe() + ")");
        }
        ranges.push_back(states.back().samples);
        seconds += std::strtod(value(meta, "seconds").c_str(), nullptr);
        metas.push_back(std::move(meta));
    }
    const std::vector<SampleRange> gaps = findGaps(ranges);
    std::string gapText;
    for (SampleRange g : gaps) gapText += (gapText.empty() ? "" : ", ") + g.describe();
    if (!gaps.empty() && !o.allowGaps)
        throw std::runtime_error(o.output + ": the parts leave sample ranges " + gapText +
                                 " unrendered (render them, or pass --allow-gaps)");

    const AccumulationState merged = mergeStates(std::move(states));
    const AccumulatedImage image = resolve(merged);
    ImageMetadata meta = metas[0]; // scene, camera, device, settings of the first part
    meta.erase("mpaths_per_second");
    meta["seconds"] = std::to_string(seconds);
    meta["dropped_samples"] = std::to_string(image.droppedSamples);
    meta["merged_parts"] = std::to_string(o.parts.size());
    meta["samples"] = merged.samples.describe() + (gaps.empty() ? "" : " with gaps " + gapText);
    const double estimate = estimatedRelMse(image.mean, image.varianceOfMean);
    meta["estimated_relmse"] = std::to_string(estimate);
    const fs::path output = o.output;
    if (output.has_parent_path()) fs::create_directories(output.parent_path());
    writeStateExr(output, merged, image.mean, meta); // mergeable again (hierarchical merges)
    fs::path png = output;
    png.replace_extension(".png");
    writeTonemappedPng(png, image.mean, TonemapSettings{}, o.exposure);
    if (!gaps.empty())
        std::fprintf(stderr, "pt: warning: merged with gaps in the sample ranges: %s\n", gapText.c_str());
    std::fprintf(stderr,
        "pt: wrote %s and %s: %zu parts, samples %s, %u spp, %llu non-finite samples dropped, "
        "estimated relMSE %.6g\n",
        output.c_str(), png.c_str(), o.parts.size(), merged.samples.describe().c_str(), merged.spp,
        static_cast<unsigned long long>(image.droppedSamples), estimate);
    return 0;
}

} // namespace pt
