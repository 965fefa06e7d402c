// tinygltf's implementation compiled into the fuzz targets, so that its JSON and GLB parsing is
// instrumented too (Debian's libtinygltf.so is not): libFuzzer then gets coverage from inside
// the parser and AddressSanitizer checks its memory accesses. These definitions take precedence
// over the shared library's. Images are decoded by our own callback (image/texture_image.cpp),
// so tinygltf's stb_image loader and writer are left out.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>
