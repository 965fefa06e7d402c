// pt_exr_equal A.exr B.exr: exit 0 when every channel of the two files holds the same pixels,
// bit for bit (metadata, such as render times, is ignored); 1 when they differ; 2 on errors.
// scripts/compare_renders.sh uses it to show that a refactor leaves every image unchanged.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <string>
#include <vector>

namespace {

struct Channels {
    int width = 0, height = 0;
    std::map<std::string, std::vector<float>> values; // every channel, read as float
};

Channels readAllChannels(const char* path) {
    Imf::InputFile file(path);
    const Imath::Box2i dw = file.header().dataWindow();
    Channels c;
    c.width = dw.max.x - dw.min.x + 1;
    c.height = dw.max.y - dw.min.y + 1;
    Imf::FrameBuffer fb;
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
        std::vector<float>& v = c.values[it.name()];
        v.assign(static_cast<size_t>(c.width) * static_cast<size_t>(c.height), 0.0f);
        fb.insert(it.name(), Imf::Slice::Make(Imf::FLOAT, v.data(), dw, sizeof(float), sizeof(float) * c.width));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return c;
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: pt_exr_equal A.exr B.exr\n");
        return 2;
    }
    Channels a, b;
    try {
        a = readAllChannels(argv[1]);
        b = readAllChannels(argv[2]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pt_exr_equal: %s\n", e.what());
        return 2;
    }
    if (a.width != b.width || a.height != b.height || a.values.size() != b.values.size()) {
        std::printf("differ: size or channel set\n");
        return 1;
    }
    for (const auto& [name, va] : a.values) {
        const auto it = b.values.find(name);
        if (it == b.values.end() || std::memcmp(va.data(), it->second.data(), va.size() * sizeof(float)) != 0) {
            std::printf("differ: channel %s\n", name.c_str());
            return 1;
        }
    }
    std::printf("identical: %zu channels, %dx%d\n", a.values.size(), a.width, a.height);
    return 0;
}
