#pragma once
// How input files are read, once for every reader (glTF buffers and images, PLY meshes, texture
// images, OpenEXR files, the course's XML and binary geometry): the checks, their order, and
// what each problem is called.
//
// The policy, in the order the checks run:
//   1. the path names something (else NotFound) that can be looked at (else CannotAccess: no
//      permission on a folder, a loop of links, a name too long);
//   2. it is not a directory (Directory) and is a regular file (NotRegularFile: a device, FIFO
//      or socket could block or never end) -- unless the reader streams such files;
//   3. its size is known (SizeUnknown), it is not empty if the reader refuses empty files
//      (Empty), and it is within the reader's limit (TooLarge);
//   4. it opens (CannotOpen), a buffer for it can be had (OutOfMemory), and every byte reads
//      (ReadFailed: a read error, or the file shrank while being read).
// A regular file is read for the size step 3 found; a streamed one to its end, bounded by the
// same limit.
//
// Readers keep their own wording where their messages predate this module (tests compare them):
// they map the FileProblem to it. describeFileProblem() is the wording new readers should use.
// Paths are not made printable here: the scene layer's SceneError does that for every problem
// text, and a path from the command line is printed as the user typed it.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace pt {

enum class FileProblem {
    None,
    NotFound,
    CannotAccess,
    Directory,
    NotRegularFile,
    SizeUnknown,
    Empty,
    TooLarge,
    CannotOpen,
    OutOfMemory,
    ReadFailed,
};

struct FileReadOptions {
    uintmax_t maxBytes = std::numeric_limits<uintmax_t>::max();
    bool refuseEmpty = false;
    // Read devices, FIFOs and the like to their end instead of refusing them (NotRegularFile).
    bool streamNonRegular = false;
};

// The outcome of the checks (and of the read, for FileRead).
struct InputFileCheck {
    FileProblem problem = FileProblem::None;
    // The system's words for the problem (NotFound, CannotAccess, SizeUnknown, CannotOpen,
    // ReadFailed; empty for a file that shrank), e.g. "No such file or directory".
    std::string reason;
    uintmax_t size = 0;   // the file's size once known (for a streamed file: the bytes read)
    uintmax_t limit = 0;  // FileReadOptions::maxBytes, for TooLarge
    bool regular = false; // a regular file (else a streamed one)

    explicit operator bool() const { return problem == FileProblem::None; }
    // Refused as a file at all (steps 1 and 2): missing, not accessible, a directory or not a
    // regular file.
    bool notARegularFile() const;
};

struct FileRead : InputFileCheck {
    std::vector<unsigned char> bytes; // the whole file when there is no problem
};

// Steps 1 to 3, without opening the file.
InputFileCheck checkInputFile(const std::filesystem::path& path, const FileReadOptions& options = {});

// The whole policy; never throws (a failed allocation is OutOfMemory).
FileRead tryReadInputFile(const std::filesystem::path& path, const FileReadOptions& options = {});

// The policy's wording of a problem: "file not found", "cannot access file (<reason>)",
// "is a directory, not <what>", "not a regular file", "cannot determine file size (<reason>)",
// "empty file", "file too large (more than <limit> bytes)", "cannot open for reading",
// "file too large to read (<size> bytes)", "read error (<reason>)".
std::string describeFileProblem(const InputFileCheck& check, std::string_view what = "a regular file");

// tryReadInputFile, throwing std::runtime_error("<path>: <describeFileProblem>") on a problem.
std::vector<unsigned char> readInputFile(
    const std::filesystem::path& path, const FileReadOptions& options = {}, std::string_view what = "a regular file");

} // namespace pt
