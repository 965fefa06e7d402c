#include "scene/ceng795/binary.h"

#include "image/file_read.h"

#include <cmath>
#include <cstring>
#include <fstream>

namespace pt::ceng795 {
namespace {

// Reads the whole payload after checking the count against the file's size, so a corrupt or
// hostile count cannot make us allocate more than the file holds. The file is checked by the
// input-file policy (image/file_read.h) but not read by it: only the count and the payload it
// announces are read, whatever follows them in the file.
std::vector<unsigned char> readPayload(const Context& ctx, pugi::xml_node where, size_t elementBytes, uint64_t& count) {
    const std::string relative = where.attribute("binaryFile").value();
    const std::filesystem::path path = ctx.resolve(relative);
    const InputFileCheck file = checkInputFile(path);
    if (file.notARegularFile()) ctx.fail(where, "binaryFile " + quote(relative) + " not found");
    if (file.problem == FileProblem::SizeUnknown)
        ctx.fail(where, "binaryFile " + quote(relative) + ": cannot read its size");
    const uint64_t size = file.size;
    std::ifstream in(path, std::ios::binary);
    int32_t n = 0;
    if (!in || size < 4 || !in.read(reinterpret_cast<char*>(&n), 4))
        ctx.fail(where, "binaryFile " + quote(relative) + ": missing count");
    if (n < 0) ctx.fail(where, "binaryFile " + quote(relative) + ": negative count " + std::to_string(n));
    const uint64_t bytes = static_cast<uint64_t>(n) * elementBytes;
    if (bytes > size - 4)
        ctx.fail(where, "binaryFile " + quote(relative) + ": count " + std::to_string(n) + " needs " +
                            std::to_string(bytes) + " bytes, the file has " + std::to_string(size - 4));
    std::vector<unsigned char> data(bytes);
    if (bytes > 0 && !in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(bytes)))
        ctx.fail(where, "binaryFile " + quote(relative) + ": read failed");
    count = static_cast<uint64_t>(n);
    return data;
}

template <int N>
std::vector<glm::vec<N, float>> readFloats(const Context& ctx, pugi::xml_node where) {
    uint64_t count = 0;
    const std::vector<unsigned char> data = readPayload(ctx, where, N * sizeof(float), count);
    std::vector<glm::vec<N, float>> out(count);
    if (count > 0) std::memcpy(out.data(), data.data(), data.size());
    for (const auto& v : out)
        for (int i = 0; i < N; ++i)
            if (!std::isfinite(v[i])) ctx.fail(where, "binaryFile holds a non-finite number");
    return out;
}

} // namespace

std::vector<glm::vec3> readBinaryVec3s(const Context& ctx, pugi::xml_node where) { return readFloats<3>(ctx, where); }

std::vector<glm::vec2> readBinaryVec2s(const Context& ctx, pugi::xml_node where) { return readFloats<2>(ctx, where); }

std::vector<int32_t> readBinaryIndices(const Context& ctx, pugi::xml_node where) {
    uint64_t count = 0;
    const std::vector<unsigned char> data = readPayload(ctx, where, 3 * sizeof(int32_t), count);
    std::vector<int32_t> out(count * 3);
    if (count > 0) std::memcpy(out.data(), data.data(), data.size());
    return out;
}

} // namespace pt::ceng795
