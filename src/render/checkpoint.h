#pragma once
// Saving a long render's progress: every `interval` seconds of rendering the renderer's exact
// state is snapshotted and, when a checkpoint file is given, written as a state EXR
// (film/state_file.h) by write-then-rename, so a killed, interrupted or failed render resumes
// bit-identically (pt render --resume). The in-memory snapshot outlives the device: after a
// device loss the device's memory cannot be trusted, the snapshot can.
#include "film/accumulation_state.h"
#include "image/image_io.h"
#include "render/renderer.h"

#include <filesystem>
#include <optional>

namespace pt {

class Checkpointer {
public:
    // `path` empty: snapshots in memory only. `priorSeconds`: render time of the runs this one
    // resumes, added to the stored `seconds`.
    Checkpointer(std::filesystem::path path, double intervalSeconds, ImageMetadata metadata, double priorSeconds);

    // After a pass: snapshot, and write the file, when `interval` has passed since the last.
    void afterPass(const Renderer& renderer, double seconds);
    // Snapshot and write now (the end of an interrupted render).
    void save(const Renderer& renderer, double seconds);
    // The latest snapshot, or null before the first.
    const AccumulationState* latest() const { return latest_ ? &*latest_ : nullptr; }
    // Writes the latest snapshot to the checkpoint file if it is not there yet; false if there is
    // no file or no snapshot.
    bool writeLatest();
    // Writes the latest snapshot as an image with its state channels (a partial output).
    void writeLatestTo(const std::filesystem::path& path) const;
    const std::filesystem::path& path() const { return path_; }
    double seconds() const { return latestSeconds_; } // total render seconds at the latest snapshot

private:
    void snapshot(const Renderer& renderer, double seconds);

    std::filesystem::path path_;
    double interval_;
    ImageMetadata metadata_;
    double priorSeconds_;
    double lastSnapshot_ = 0; // render seconds of this run at the latest snapshot
    std::optional<AccumulationState> latest_;
    double latestSeconds_ = 0;
    bool written_ = false;
};

} // namespace pt
