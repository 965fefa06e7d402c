#include "gpu/shader_cache_directory.h"

#include "base/hash.h"
#include "image/atomic_file.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

namespace pt {
namespace {

constexpr char kMagic[8] = {'P', 'T', 'C', 'A', 'C', 'H', 'E', '1'};
constexpr const char* kExtension = ".ptcache";
// Larger than anything pt stores (specialised kernels are under 1 MB, driver caches a few MB):
// a header claiming more is corrupt, and is not allocated.
constexpr uint64_t kMaxPayloadBytes = uint64_t(256) << 20;
// A temporary file this old belongs to a writer that died before renaming it.
constexpr auto kStaleTemporary = std::chrono::hours(1);

struct Header {
    char magic[8];
    uint64_t key;
    uint64_t payloadBytes;
    uint64_t payloadHash;
};
static_assert(sizeof(Header) == 32);

} // namespace

ShaderCacheDirectory::ShaderCacheDirectory(std::filesystem::path directory) : directory_(std::move(directory)) {}

std::filesystem::path ShaderCacheDirectory::defaultPath() {
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "pt";
    if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "pt";
    return {};
}

std::filesystem::path ShaderCacheDirectory::fileOf(const std::string& name) const {
    return directory_ / (name + kExtension);
}

void ShaderCacheDirectory::warnOnce(const std::string& problem) {
    if (warned_) return;
    warned_ = true;
    std::fprintf(stderr, "pt: warning: pipeline cache: %s (continuing without it; --no-pipeline-cache skips it)\n",
        problem.c_str());
}

std::optional<std::vector<uint8_t>> ShaderCacheDirectory::read(const std::string& name, uint64_t key) {
    const std::filesystem::path file = fileOf(name);
    std::ifstream in(file, std::ios::binary);
    if (!in) return std::nullopt; // absent: the usual miss
    Header h{};
    std::vector<uint8_t> payload;
    bool valid = bool(in.read(reinterpret_cast<char*>(&h), sizeof h)) &&
                 std::memcmp(h.magic, kMagic, sizeof kMagic) == 0 && h.key == key && h.payloadBytes <= kMaxPayloadBytes;
    if (valid) {
        payload.resize(size_t(h.payloadBytes));
        valid = bool(in.read(reinterpret_cast<char*>(payload.data()), std::streamsize(payload.size()))) &&
                in.peek() == std::char_traits<char>::eof() && fnv1a64(payload.data(), payload.size()) == h.payloadHash;
    }
    if (!valid) {
        // Not an error: another version's file, or one cut short by a full disk. It is rebuilt.
        std::fprintf(
            stderr, "pt: note: pipeline cache: %s is invalid or from another build; replacing it\n", file.c_str());
        return std::nullopt;
    }
    std::error_code ignored;
    std::filesystem::last_write_time(file, std::filesystem::file_time_type::clock::now(), ignored);
    return payload;
}

void ShaderCacheDirectory::write(const std::string& name, uint64_t key, std::span<const uint8_t> payload) {
    if (!writable_) return;
    std::error_code ec;
    std::filesystem::create_directories(directory_, ec);
    if (ec) {
        writable_ = false;
        warnOnce(directory_.string() + ": cannot create directory (" + ec.message() + ")");
        return;
    }
    Header h{};
    std::memcpy(h.magic, kMagic, sizeof kMagic);
    h.key = key;
    h.payloadBytes = payload.size();
    h.payloadHash = fnv1a64(payload.data(), payload.size());
    try {
        AtomicFile out(fileOf(name));
        out.write(&h, sizeof h);
        out.write(payload.data(), payload.size());
        out.commit();
    } catch (const std::exception& e) {
        writable_ = false;
        warnOnce(e.what());
        return;
    }
    trim();
}

void ShaderCacheDirectory::trim() {
    struct Entry {
        std::filesystem::file_time_type used;
        std::filesystem::path path;
    };
    std::vector<Entry> entries;
    std::error_code ec;
    const auto now = std::filesystem::file_time_type::clock::now();
    for (const auto& item : std::filesystem::directory_iterator(directory_, ec)) {
        const std::string file = item.path().filename().string();
        const auto used = item.last_write_time(ec);
        if (ec) continue;
        if (file.starts_with(".")) {
            if (now - used > kStaleTemporary) std::filesystem::remove(item.path(), ec);
        } else if (file.ends_with(kExtension)) {
            entries.push_back({used, item.path()});
        }
    }
    if (entries.size() <= kMaxEntries) return;
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.used < b.used; });
    for (size_t i = 0; i + kMaxEntries < entries.size(); ++i) std::filesystem::remove(entries[i].path, ec);
}

} // namespace pt
