#include "image/file_read.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <new>
#include <stdexcept>
#include <system_error>

namespace pt {
namespace {

namespace fs = std::filesystem;

std::string errnoText(int err) { return std::generic_category().message(err); }

class Descriptor {
public:
    explicit Descriptor(int fd) : fd_(fd) {}
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    ~Descriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    int get() const { return fd_; }

private:
    int fd_;
};

// One read(2), retried when a signal interrupts it; -1 with errno set on an error.
ssize_t readSome(int fd, unsigned char* into, size_t bytes) {
    constexpr size_t kMaxChunk = size_t(1) << 30; // Linux reads at most about 2 GiB at once
    for (;;) {
        const ssize_t n = ::read(fd, into, std::min(bytes, kMaxChunk));
        if (n >= 0 || errno != EINTR) return n;
    }
}

InputFileCheck& fail(InputFileCheck& check, FileProblem problem, std::string reason = {}) {
    check.problem = problem;
    check.reason = std::move(reason);
    return check;
}

// A regular file: exactly the size the checks found.
void readRegular(int fd, FileRead& r) {
    try {
        r.bytes.resize(r.size);
    } catch (const std::exception&) { // bad_alloc, or length_error beyond max_size()
        fail(r, FileProblem::OutOfMemory);
        return;
    }
    size_t done = 0;
    while (done < r.bytes.size()) {
        const ssize_t n = readSome(fd, r.bytes.data() + done, r.bytes.size() - done);
        if (n <= 0) { // an error, or the end: the file shrank since its size was read
            fail(r, FileProblem::ReadFailed, n < 0 ? errnoText(errno) : std::string());
            return;
        }
        done += static_cast<size_t>(n);
    }
}

// A device, FIFO or the like: to its end, within the limit.
void readStream(int fd, const FileReadOptions& options, FileRead& r) {
    unsigned char chunk[1 << 16];
    for (;;) {
        const ssize_t n = readSome(fd, chunk, sizeof chunk);
        if (n < 0) {
            fail(r, FileProblem::ReadFailed, errnoText(errno));
            return;
        }
        if (n == 0) break;
        r.size += static_cast<uintmax_t>(n);
        if (r.size > options.maxBytes) {
            fail(r, FileProblem::TooLarge);
            return;
        }
        try {
            r.bytes.insert(r.bytes.end(), chunk, chunk + n);
        } catch (const std::exception&) {
            fail(r, FileProblem::OutOfMemory);
            return;
        }
    }
    if (r.size == 0 && options.refuseEmpty) fail(r, FileProblem::Empty);
}

} // namespace

bool InputFileCheck::notARegularFile() const {
    return problem == FileProblem::NotFound || problem == FileProblem::CannotAccess ||
           problem == FileProblem::Directory || problem == FileProblem::NotRegularFile;
}

InputFileCheck checkInputFile(const fs::path& path, const FileReadOptions& options) {
    InputFileCheck check;
    check.limit = options.maxBytes;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (status.type() == fs::file_type::not_found) return fail(check, FileProblem::NotFound, ec.message());
    if (ec) return fail(check, FileProblem::CannotAccess, ec.message());
    if (fs::is_directory(status)) return fail(check, FileProblem::Directory);
    check.regular = fs::is_regular_file(status);
    if (!check.regular) {
        if (!options.streamNonRegular) fail(check, FileProblem::NotRegularFile);
        return check; // a stream's size and emptiness are known once it is read
    }
    check.size = fs::file_size(path, ec);
    if (ec) {
        check.size = 0;
        return fail(check, FileProblem::SizeUnknown, ec.message());
    }
    if (check.size == 0 && options.refuseEmpty) return fail(check, FileProblem::Empty);
    if (check.size > options.maxBytes) fail(check, FileProblem::TooLarge);
    return check;
}

FileRead tryReadInputFile(const fs::path& path, const FileReadOptions& options) {
    FileRead r;
    static_cast<InputFileCheck&>(r) = checkInputFile(path, options);
    if (!r) return r;
    const Descriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
    if (fd.get() < 0) {
        fail(r, FileProblem::CannotOpen, errnoText(errno));
        return r;
    }
    if (r.regular)
        readRegular(fd.get(), r);
    else
        readStream(fd.get(), options, r);
    if (!r) std::vector<unsigned char>().swap(r.bytes);
    return r;
}

std::string describeFileProblem(const InputFileCheck& check, std::string_view what) {
    switch (check.problem) {
    case FileProblem::None: return "no problem";
    case FileProblem::NotFound: return "file not found";
    case FileProblem::CannotAccess: return "cannot access file (" + check.reason + ")";
    case FileProblem::Directory: return "is a directory, not " + std::string(what);
    case FileProblem::NotRegularFile: return "not a regular file";
    case FileProblem::SizeUnknown: return "cannot determine file size (" + check.reason + ")";
    case FileProblem::Empty: return "empty file";
    case FileProblem::TooLarge: return "file too large (more than " + std::to_string(check.limit) + " bytes)";
    case FileProblem::CannotOpen: return "cannot open for reading";
    case FileProblem::OutOfMemory: return "file too large to read (" + std::to_string(check.size) + " bytes)";
    case FileProblem::ReadFailed:
        return "read error (" + (check.reason.empty() ? std::string("file shrank while reading?") : check.reason) + ")";
    }
    return "unknown problem";
}

std::vector<unsigned char> readInputFile(const fs::path& path, const FileReadOptions& options, std::string_view what) {
    FileRead r = tryReadInputFile(path, options);
    if (!r) throw std::runtime_error(path.string() + ": " + describeFileProblem(r, what));
    return std::move(r.bytes);
}

} // namespace pt
