#pragma once
// A shared mesh placed in world space: what an instance stands for, made explicit. The
// flattener copies instances this way where it does not keep them as instances, and tests
// compare the two forms.
#include "scene/scene.h"

namespace pt {

// `part` (object space) mapped by `objectToWorld`: positions by the map, normals by its inverse
// transpose (renormalised; zero ones, which mark invalid input, stay zero), tangents by the map
// with the bitangent's handedness flipped under a mirroring map, and each triangle's winding
// swapped under a mirroring map so that its front stays the object's front (glTF's rule for a
// negative determinant, and the course's). Motion is left as the part's.
Mesh placeMesh(const Mesh& part, const glm::mat4& objectToWorld);

// The instance's parts in world space: its material where it replaces the parts', its motion.
std::vector<Mesh> placeInstance(const Scene& scene, const MeshInstance& instance);

// Every instance copied into Scene::meshes; sharedMeshes and instances are emptied.
void expandInstances(Scene& scene);

// Whether an affine map can place a mesh or a sphere: finite, invertible, and its inverse finite.
bool isPlaceable(const glm::mat4& objectToWorld);

} // namespace pt
