#pragma once
// <Objects> of the course format: Mesh, MeshInstance, Triangle, Sphere, LightMesh, LightSphere,
// flattened into world-space scene meshes and spheres.
#include "scene/ceng795/document.h"
#include "scene/ceng795/geometry.h"
#include "scene/ceng795/materials.h"
#include "scene/ceng795/textures.h"
#include "scene/ceng795/transforms.h"
#include "scene/scene.h"

namespace pt::ceng795 {

// Instancing can multiply geometry; refuse scenes that would expand beyond this.
constexpr size_t kMaxSceneTriangles = size_t(1) << 26;

// Appends the objects of every <Objects> element, in file order, to out.meshes and
// out.spheres; object lights also append their emissive materials to out.materials.
void readObjects(Context& ctx, pugi::xml_node scene, const VertexPool& pool, const Transforms& transforms,
    MaterialTable& materials, TextureTable& textures, Scene& out);

} // namespace pt::ceng795
