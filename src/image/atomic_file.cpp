#include "image/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <system_error>
#include <unistd.h>

namespace pt {
namespace {
std::string errnoText(int err) { return std::generic_category().message(err); }
} // namespace

AtomicFile::AtomicFile(const std::filesystem::path& path) : path_(path) {
    // pid + counter keep concurrent writers (threads or processes) apart.
    static std::atomic<unsigned> counter{0};
    std::string name = ".";
    name += path.filename().string();
    name += ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
    tmp_ = path.parent_path() / name;
    file_ = std::fopen(tmp_.c_str(), "wb");
    if (!file_) fail("cannot write (" + errnoText(errno) + ")");
}

AtomicFile::~AtomicFile() {
    if (file_) std::fclose(file_);
    if (!committed_) {
        std::error_code ignored;
        std::filesystem::remove(tmp_, ignored);
    }
}

void AtomicFile::fail(const std::string& problem) const { throw FileWriteError(path_.string() + ": " + problem); }

void AtomicFile::write(const void* data, std::size_t n) {
    if (n != 0 && std::fwrite(data, 1, n, file_) != n) fail("write failed (" + errnoText(errno) + ")");
}

void AtomicFile::commit() {
    // fsync before rename: otherwise a power loss can leave the renamed file empty on some
    // filesystems, defeating the point of the rename.
    if (std::fflush(file_) != 0 || ::fsync(::fileno(file_)) != 0) fail("write failed (" + errnoText(errno) + ")");
    std::FILE* f = file_;
    file_ = nullptr;
    if (std::fclose(f) != 0) fail("write failed (" + errnoText(errno) + ")");
    std::error_code ec;
    std::filesystem::rename(tmp_, path_, ec);
    if (ec) fail("cannot replace file (" + ec.message() + ")");
    committed_ = true;
}

void prepareOutputDirectory(const std::filesystem::path& output) {
    if (output.parent_path().empty()) return;
    std::error_code ec;
    std::filesystem::create_directories(output.parent_path(), ec);
    if (ec)
        throw std::runtime_error(output.parent_path().string() + ": cannot create directory (" + ec.message() + ")");
}

} // namespace pt
