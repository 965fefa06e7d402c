#pragma once
// Writing a file so that readers never see it half-written: the bytes go to a hidden
// temporary file next to the destination (same directory, hence same filesystem, so rename()
// is atomic), which replaces the destination only on commit(). If anything fails first, the
// destructor deletes the temporary and the previous file is untouched.
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace pt {

// what() is one line: "<path>: <problem>".
struct FileWriteError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class AtomicFile {
public:
    explicit AtomicFile(const std::filesystem::path& path);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::FILE* file() { return file_; }
    const std::filesystem::path& path() const { return path_; }
    void write(const void* data, std::size_t n);
    void commit();

private:
    [[noreturn]] void fail(const std::string& problem) const;

    std::filesystem::path path_, tmp_;
    std::FILE* file_ = nullptr;
    bool committed_ = false;
};

// Creates the folder an output file goes into (and its parents), if it names one. Throws
// std::runtime_error("<folder>: cannot create directory (<reason>)").
void prepareOutputDirectory(const std::filesystem::path& output);

} // namespace pt
