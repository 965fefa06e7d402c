#include "app/bench/budget_run.h"

#include "render/progressive_render.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace pt {

void renderToBudgets(
    Renderer& renderer, std::vector<double> budgets, const std::function<void(const BudgetPoint&)>& atBudget) {
    using Clock = std::chrono::steady_clock;
    std::sort(budgets.begin(), budgets.end());
    double seconds = 0;
    for (double budget : budgets) {
        while (true) {
            const uint32_t done = renderer.samplesPerPixel();
            // Passes of about kPassSeconds (render/progressive_render.h), as pt render's, sized
            // from the measured rate; the first pass is one sample, to measure it.
            uint32_t pass = 1;
            if (done > 0) {
                const double secondsPerSpp = seconds / done;
                const double fits = std::floor((budget - seconds) / std::max(secondsPerSpp, 1e-9));
                if (fits < 1.0) break;
                pass = static_cast<uint32_t>(
                    std::clamp(std::min(fits, kPassSeconds / std::max(secondsPerSpp, 1e-9)), 1.0, 4096.0));
            }
            const auto start = Clock::now();
            renderer.addSamples(pass);
            seconds += std::chrono::duration<double>(Clock::now() - start).count();
            if (seconds >= budget) break;
        }
        atBudget(BudgetPoint{budget, seconds, renderer.samplesPerPixel()});
    }
}

} // namespace pt
