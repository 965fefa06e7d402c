#pragma once
// Rendering to a list of time budgets in one go: samples are added in passes that never
// overrun the next budget, and each budget is reported when reached. Samples are addressed by
// index, so the image at a budget is exactly the image of a separate render of that many
// samples: one run per configuration measures every budget.
#include "render/renderer.h"

#include <functional>
#include <vector>

namespace pt {

struct BudgetPoint {
    double budget = 0;  // seconds asked for
    double seconds = 0; // render time spent (passes only: no readback or metrics)
    uint32_t spp = 0;
};

// Calls `atBudget` once per budget (ascending; the renderer holds that budget's samples).
// A budget too short for one sample still gets one, so every point has an image.
void renderToBudgets(
    Renderer& renderer, std::vector<double> budgets, const std::function<void(const BudgetPoint&)>& atBudget);

} // namespace pt
