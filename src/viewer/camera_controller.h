#pragma once
// Interactive camera for `pt view`: orbit about a target point, pan, dolly, and a fly mode
// (move along the view axes, mouse look). Pure maths on the scene's Camera, so it is tested
// without a window. "Up" is the starting camera's up vector, kept as the world's up.
#include "scene/scene.h"

#include <glm/glm.hpp>

#include <string>

namespace pt::viewer {

class CameraController {
public:
    // `centre` and `radius` bound the scene: they set the orbit target when the camera looks
    // past the centre, and the speeds.
    CameraController(const Camera& start, glm::vec3 centre, float radius);

    void orbit(glm::vec2 dragPixels);                   // about the target
    void pan(glm::vec2 dragPixels, int viewportHeight); // target and camera together
    void dolly(float clicks);                           // towards the target (positive) or away
    void look(glm::vec2 dragPixels);                    // turn in place (fly mode)
    // Moves by `axes` (right, up, forward) times the fly speed times `seconds`.
    void fly(glm::vec3 axes, float seconds);
    void scaleSpeed(float factor) { speed_ *= factor; }
    void reset();

    Camera camera() const; // the starting camera with the current position and orientation
    float speed() const { return speed_; }
    glm::vec3 target() const { return position_ + distance_ * forward_; }

    // The current view as text to paste: a glTF node (with its perspective camera) and a
    // CENG795 course <Camera> for a width x height image.
    std::string gltfSnippet() const;
    std::string courseXmlSnippet(int width, int height) const;

private:
    void setForward(glm::vec3 forward);
    glm::vec3 right() const;

    Camera start_;
    glm::vec3 worldUp_;
    glm::vec3 position_, forward_;
    float distance_; // to the orbit target along forward
    float startDistance_;
    float radius_;
    float speed_, startSpeed_; // fly speed, scene units per second
};

} // namespace pt::viewer
