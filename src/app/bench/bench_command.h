#pragma once
#include "app/options.h"

namespace pt {

// `pt bench`: renders one scene under several integrator configurations to equal time
// budgets and writes DIR/bench.csv (speed and error per configuration and budget), the images,
// DIR/relmse_vs_time.png and DIR/contact_<budget>s.png. Returns the exit status.
int runBench(const BenchOptions& options);

} // namespace pt
