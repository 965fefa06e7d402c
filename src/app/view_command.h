#pragma once
#include "app/options.h"

namespace pt {

// `pt view`: opens a window and renders progressively until closed. Without a display (or a
// device that can present to it) prints one line suggesting `pt render` and returns 1.
int runView(const ViewOptions& options);

} // namespace pt
