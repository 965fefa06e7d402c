#pragma once

#include <cstddef>
#include <vector>

namespace pt {

// A linear-light RGBA float image. Kept deliberately dumb (a plain aggregate)
// so that readback buffers, EXR/PNG I/O and metrics can all share it without
// conversions.
struct Image {
    int width = 0, height = 0;
    std::vector<float> rgba; // 4 floats per pixel, row-major, top row first

    // No bounds checking: these are used in per-pixel inner loops.
    float* at(int x, int y) { return rgba.data() + index(x, y); }
    const float* at(int x, int y) const { return rgba.data() + index(x, y); }

private:
    // size_t arithmetic so large images cannot overflow int.
    std::size_t index(int x, int y) const {
        return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 4;
    }
};

} // namespace pt
