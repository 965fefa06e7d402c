#pragma once
#include "app/options.h"

namespace pt {

// `pt render`: loads, renders progressively and writes EXR + PNG. Returns the exit status.
int runRender(const RenderOptions& options);

} // namespace pt
