#pragma once
// pt merge PART.exr... -o OUT.exr: the parts of one render (pt render --samples A:B, on one
// machine or many) summed into the image of their union of sample ranges.
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace pt {

struct MergeOptions {
    std::vector<std::string> parts;
    std::string output;
    bool allowGaps = false; // merge even if the ranges leave samples out (fewer spp, still unbiased)
    float exposure = 0.0f;  // for the PNG
    bool quiet = false;
};

void addMergeOptions(CLI::App* command, MergeOptions& options);
int runMerge(const MergeOptions& options);

} // namespace pt
