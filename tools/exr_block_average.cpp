// exr_block_average IN.exr K OUT.exr: OUT is IN reduced K times in each direction, every output
// pixel the mean of a KxK block of input pixels (R, G, B; summed in double in row order, then
// rounded to float32 once), written as float32 R, G, B with ZIP compression and no metadata.
// Made the downsampled official course images in tests/data/ceng795/official/ (README there): a
// box-filtered render at the smaller size converges to exactly this image. Not part of the
// build; compile it with
//   c++ -O2 -std=c++17 tools/exr_block_average.cpp $(pkg-config --cflags --libs OpenEXR) -o exr_block_average
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <vector>

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: exr_block_average IN.exr K OUT.exr\n");
        return 2;
    }
    try {
        const int k = std::atoi(argv[2]);
        Imf::InputFile in(argv[1]);
        const Imath::Box2i dw = in.header().dataWindow();
        const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
        if (k < 1 || w % k != 0 || h % k != 0) {
            std::fprintf(stderr, "exr_block_average: %dx%d is not a multiple of %d\n", w, h, k);
            return 2;
        }
        std::vector<float> rgb(size_t(w) * h * 3, 0.0f);
        Imf::FrameBuffer fb;
        const char* names[3] = {"R", "G", "B"};
        for (int c = 0; c < 3; ++c) {
            char* origin = reinterpret_cast<char*>(rgb.data() + c) -
                           (size_t(dw.min.x) + size_t(dw.min.y) * size_t(w)) * 3 * sizeof(float);
            fb.insert(names[c], Imf::Slice(Imf::FLOAT, origin, 3 * sizeof(float), size_t(w) * 3 * sizeof(float)));
        }
        in.setFrameBuffer(fb);
        in.readPixels(dw.min.y, dw.max.y);

        const int ow = w / k, oh = h / k;
        std::vector<float> out(size_t(ow) * oh * 3);
        for (int by = 0; by < oh; ++by)
            for (int bx = 0; bx < ow; ++bx)
                for (int c = 0; c < 3; ++c) {
                    double sum = 0.0;
                    for (int y = by * k; y < (by + 1) * k; ++y)
                        for (int x = bx * k; x < (bx + 1) * k; ++x) sum += rgb[(size_t(y) * w + x) * 3 + c];
                    out[(size_t(by) * ow + bx) * 3 + c] = static_cast<float>(sum / (double(k) * k));
                }

        Imf::Header header(ow, oh);
        header.compression() = Imf::ZIP_COMPRESSION;
        Imf::FrameBuffer ofb;
        for (int c = 0; c < 3; ++c) {
            header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
            ofb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(out.data() + c), 3 * sizeof(float),
                                     size_t(ow) * 3 * sizeof(float)));
        }
        Imf::OutputFile file(argv[3], header);
        file.setFrameBuffer(ofb);
        file.writePixels(oh);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "exr_block_average: %s\n", e.what());
        return 1;
    }
    return 0;
}
