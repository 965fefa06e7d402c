#pragma once
// Progress for long renders: a bar redrawn in place on a terminal, plain lines every few
// seconds otherwise (CI logs, pipes).
#include <cstdint>
#include <cstdio>

namespace pt {

class Progress {
public:
    // targetSpp > 0 for --spp runs; targetSeconds > 0 for --time runs.
    Progress(uint32_t targetSpp, double targetSeconds, bool enabled);
    // relMse: error against a reference, NaN when there is none.
    void update(uint32_t spp, double seconds, double mpathsPerSecond, double relMse);
    void finish();

private:
    uint32_t targetSpp_;
    double targetSeconds_;
    bool enabled_;
    bool terminal_;
    double lastPrint_ = -1e9;
    bool drewBar_ = false;
};

} // namespace pt
