#pragma once
// <Textures> of the course format (HW4): images, TextureMaps (image, checkerboard, Perlin) and
// their decal modes, turned into scene textures and per-object material variants.
#include "scene/ceng795/document.h"
#include "scene/scene.h"

#include <map>
#include <vector>

namespace pt::ceng795 {

class TextureTable {
public:
    // Reads every <TextureMap>; images load when a map is first used. A replace_background map
    // becomes the scene's background texture.
    static TextureTable read(Context& ctx, pugi::xml_node scene, Scene& out);

    // The material an object shows: `base` with the decal modes of the maps its <Textures>
    // element lists (null: none) applied. Variants are shared between objects.
    uint32_t apply(Context& ctx, pugi::xml_node objectTextures, uint32_t base, Scene& out);

private:
    struct MapDefinition {
        pugi::xml_node element;
        std::string decalMode;
        std::optional<uint32_t> texture; // index into Scene::textures once loaded
    };
    uint32_t texture(Context& ctx, MapDefinition& map, Scene& out);
    uint32_t image(Context& ctx, pugi::xml_node where, long long imageId, Scene& out);

    pugi::xml_node scene_;
    std::map<long long, MapDefinition> maps_;
    std::map<long long, uint32_t> images_; // Image id -> Scene::textureImages index
    std::map<std::pair<uint32_t, std::vector<long long>>, uint32_t> variants_;
};

} // namespace pt::ceng795
