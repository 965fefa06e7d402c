#pragma once
// Inputs that Debian 12's stb_image (2022-09) mishandles, found by fuzzing (tests/fuzz/, the
// table in bench/RESULTS.md): each is recognised here, reading the data as stb_image will, and
// rejected with a message before stb_image sees it. Later stb_image versions fix most of them.
#include <cstddef>
#include <string>

namespace pt {

// Throws std::runtime_error("SOURCE: problem") for data stb_image would crash, hang or run out of
// memory on; returns for anything else (stb_image then decodes it or reports what is wrong).
void rejectInputsStbImageMishandles(const unsigned char* bytes, size_t size, const std::string& source);

} // namespace pt
