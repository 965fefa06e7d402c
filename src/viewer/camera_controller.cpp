#include "viewer/camera_controller.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pt::viewer {
namespace {

constexpr float kRadiansPerPixel = 0.005f;    // orbit and look
constexpr float kDollyPerClick = 0.9f;        // distance factor per wheel click
constexpr float kMaxElevation = 1.5533f;      // 89 degrees: the view never reaches the up axis
constexpr float kMinDistanceFraction = 1e-4f; // of the scene radius

// Rotation of v about the unit axis by angle (Rodrigues).
glm::vec3 rotate(glm::vec3 v, glm::vec3 axis, float angle) {
    const float c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0f - c);
}

std::string fmt(float v) {
    if (v == 0.0f) v = 0.0f; // no "-0"
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", v);
    return b;
}

std::string vec(glm::vec3 v, const char* sep) { return fmt(v.x) + sep + fmt(v.y) + sep + fmt(v.z); }

} // namespace

CameraController::CameraController(const Camera& start, glm::vec3 centre, float radius)
    : start_(start), radius_(std::max(radius, 1e-6f)) {
    worldUp_ = glm::normalize(start.up);
    // Orbit about the point of the view axis nearest the scene centre, or one radius ahead.
    const float along = glm::dot(centre - start.position, glm::normalize(start.forward));
    startDistance_ = along > 0.1f * radius_ ? along : radius_;
    startSpeed_ = radius_;
    reset();
}

void CameraController::reset() {
    position_ = start_.position;
    forward_ = glm::normalize(start_.forward);
    distance_ = startDistance_;
    speed_ = startSpeed_;
}

glm::vec3 CameraController::right() const {
    glm::vec3 r = glm::cross(forward_, worldUp_);
    // Looking along the up axis (only possible for a starting camera): use the camera's own right.
    if (glm::length(r) < 1e-6f) r = glm::cross(glm::normalize(start_.forward), start_.up);
    return glm::normalize(r);
}

// Sets the view direction, keeping it at most kMaxElevation from the horizon.
void CameraController::setForward(glm::vec3 forward) {
    forward = glm::normalize(forward);
    const float elevation = std::asin(std::clamp(glm::dot(forward, worldUp_), -1.0f, 1.0f));
    const float clamped = std::clamp(elevation, -kMaxElevation, kMaxElevation);
    if (clamped != elevation) {
        glm::vec3 horizontal = forward - glm::dot(forward, worldUp_) * worldUp_;
        if (glm::length(horizontal) < 1e-6f) horizontal = glm::cross(worldUp_, right());
        horizontal = glm::normalize(horizontal);
        forward = std::cos(clamped) * horizontal + std::sin(clamped) * worldUp_;
    }
    forward_ = glm::normalize(forward);
}

void CameraController::orbit(glm::vec2 drag) {
    const glm::vec3 target = this->target();
    // Dragging right turns the scene to the right: the camera goes left about the up axis.
    glm::vec3 f = rotate(forward_, worldUp_, -drag.x * kRadiansPerPixel);
    const glm::vec3 r =
        glm::length(glm::cross(f, worldUp_)) > 1e-6f ? glm::normalize(glm::cross(f, worldUp_)) : right();
    f = rotate(f, r, -drag.y * kRadiansPerPixel);
    setForward(f);
    position_ = target - distance_ * forward_;
}

void CameraController::look(glm::vec2 drag) {
    glm::vec3 f = rotate(forward_, worldUp_, -drag.x * kRadiansPerPixel);
    f = rotate(f, right(), -drag.y * kRadiansPerPixel);
    setForward(f);
}

void CameraController::pan(glm::vec2 drag, int viewportHeight) {
    // One pixel moves the target plane by one pixel's footprint at the target distance.
    const float perPixel = 2.0f * distance_ * std::tan(0.5f * start_.yfov) / float(std::max(viewportHeight, 1));
    const glm::vec3 up = glm::normalize(glm::cross(right(), forward_));
    position_ += perPixel * (-drag.x * right() + drag.y * up);
}

void CameraController::dolly(float clicks) {
    const glm::vec3 target = this->target();
    distance_ = std::max(distance_ * std::pow(kDollyPerClick, clicks), kMinDistanceFraction * radius_);
    position_ = target - distance_ * forward_;
}

void CameraController::fly(glm::vec3 axes, float seconds) {
    const glm::vec3 up = glm::normalize(glm::cross(right(), forward_));
    position_ += speed_ * seconds * (axes.x * right() + axes.y * up + axes.z * forward_);
}

Camera CameraController::camera() const {
    Camera c = start_;
    c.position = position_;
    c.forward = forward_;
    c.up = glm::normalize(glm::cross(right(), forward_));
    return c;
}

std::string CameraController::gltfSnippet() const {
    const Camera c = camera();
    // glTF cameras look down their local -z with +y up.
    const glm::vec3 r = glm::normalize(glm::cross(c.forward, c.up));
    const glm::quat q = glm::quat_cast(glm::mat3(r, c.up, -c.forward));
    return "{\"name\": \"pt view camera\", \"camera\": 0, \"translation\": [" + vec(c.position, ", ") +
           "], \"rotation\": [" + fmt(q.x) + ", " + fmt(q.y) + ", " + fmt(q.z) + ", " + fmt(q.w) +
           "]}   // camera 0: {\"type\": \"perspective\", " + "\"perspective\": {\"yfov\": " + fmt(c.yfov) +
           ", \"znear\": 0.01}}";
}

std::string CameraController::courseXmlSnippet(int width, int height) const {
    const Camera c = camera();
    return "<Camera id=\"1\" type=\"lookAt\">\n"
           "    <Position>" +
           vec(c.position, " ") +
           "</Position>\n"
           "    <GazePoint>" +
           vec(target(), " ") +
           "</GazePoint>\n"
           "    <Up>" +
           vec(c.up, " ") +
           "</Up>\n"
           "    <FovY>" +
           fmt(glm::degrees(c.yfov)) +
           "</FovY>\n"
           "    <NearDistance>1</NearDistance>\n"
           "    <ImageResolution>" +
           std::to_string(width) + " " + std::to_string(height) +
           "</ImageResolution>\n"
           "</Camera>";
}

} // namespace pt::viewer
