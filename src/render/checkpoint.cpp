#include "render/checkpoint.h"

#include "film/state_file.h"

#include <cstdio>
#include <sstream>

namespace pt {

Checkpointer::Checkpointer(
    std::filesystem::path path, double intervalSeconds, ImageMetadata metadata, double priorSeconds)
    : path_(std::move(path)), interval_(intervalSeconds), metadata_(std::move(metadata)), priorSeconds_(priorSeconds) {}

void Checkpointer::snapshot(const Renderer& renderer, double seconds) {
    latest_ = renderer.readState();
    latestSeconds_ = priorSeconds_ + seconds;
    lastSnapshot_ = seconds;
    written_ = false;
}

void Checkpointer::afterPass(const Renderer& renderer, double seconds) {
    if (seconds - lastSnapshot_ < interval_) return;
    snapshot(renderer, seconds);
    writeLatest();
}

void Checkpointer::save(const Renderer& renderer, double seconds) {
    snapshot(renderer, seconds);
    writeLatest();
}

bool Checkpointer::writeLatest() {
    if (path_.empty() || !latest_ || latest_->spp == 0) return false;
    if (!written_) writeLatestTo(path_);
    written_ = true;
    return true;
}

void Checkpointer::writeLatestTo(const std::filesystem::path& path) const {
    ImageMetadata meta = metadata_;
    std::ostringstream s;
    s.precision(9);
    s << latestSeconds_;
    meta["seconds"] = s.str();
    const AccumulatedImage image = resolve(*latest_);
    meta["dropped_samples"] = std::to_string(image.droppedSamples);
    writeStateExr(path, *latest_, image.mean, meta);
}

} // namespace pt
