#pragma once
// A folder of cached shader artefacts that survive the process: specialised SPIR-V and the
// driver's pipeline cache (pipeline_cache.h decides what goes in). Every file starts with a header
// naming what it holds (a 64-bit key of everything its payload depends on) and a checksum of the
// payload, so a truncated, corrupt or foreign file reads as absent instead of reaching the driver.
// Files are written atomically (temporary file + rename), so concurrent processes see the old or
// the new file, never a mix; when two write the same entry, the last one wins, which is harmless
// because both wrote a valid file. The folder is kept to kMaxEntries files, least recently used
// first out. Nothing here throws: a cache that cannot be read or written is reported once on
// stderr and rendering goes on without it.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace pt {

class ShaderCacheDirectory {
public:
    static constexpr size_t kMaxEntries = 64;

    explicit ShaderCacheDirectory(std::filesystem::path directory);

    // $XDG_CACHE_HOME/pt, else $HOME/.cache/pt; empty when neither variable is set.
    static std::filesystem::path defaultPath();

    const std::filesystem::path& path() const { return directory_; }

    // The payload stored as `name` under `key`, or nothing when there is none or it is invalid
    // (an invalid file is reported and later overwritten). A hit marks the file recently used.
    std::optional<std::vector<uint8_t>> read(const std::string& name, uint64_t key);

    // Stores `payload` as `name` under `key`, then trims the folder to kMaxEntries files.
    void write(const std::string& name, uint64_t key, std::span<const uint8_t> payload);

    // The file an entry lives in (for tests and messages).
    std::filesystem::path fileOf(const std::string& name) const;

private:
    void warnOnce(const std::string& problem);
    void trim();

    std::filesystem::path directory_;
    bool warned_ = false;
    bool writable_ = true;
};

} // namespace pt
