#pragma once
// What makes two renders' samples interchangeable: the same scene file bytes, environment map
// bytes and every setting that changes the image (size, camera, depth, switches, seed,
// environment colour/scale/rotation, background). `pt merge` and `pt render --resume` refuse
// files whose identity differs from theirs. Files the scene references (glTF buffers, textures)
// are not hashed: keep them unchanged between the parts of one render.
#include "app/options.h"
#include "app/scene_setup.h"
#include "image/image_io.h"
#include "scene/scene.h"

#include <string>

namespace pt {

struct RenderIdentity {
    std::string settings;  // canonical text of every image-changing setting (stored, shown on mismatch)
    std::string sceneHash; // 16 hex digits: FNV-1a 64 of the scene and environment bytes and `settings`

    void addTo(ImageMetadata& metadata) const; // keys render_settings, scene_hash
};

RenderIdentity renderIdentity(const RenderOptions& o, const Scene& scene, const Job& job);

// Empty when `metadata` has the same identity, else one line saying what differs.
std::string identityMismatch(const RenderIdentity& expected, const ImageMetadata& metadata);

} // namespace pt
