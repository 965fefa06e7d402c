// The input-file policy (src/image/file_read.cpp): which problem each kind of path is, in which
// order the checks run, the policy's own words, and that the readers built on it keep theirs.
#include "image/file_read.h"
#include "image/image_io.h"
#include "image/texture_image.h"

#include "support/test_directory.h"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using pt::FileProblem;

namespace {

class FileRead : public ::testing::Test {
protected:
    void SetUp() override { dir_ = pt::test::freshTestDirectory("file_read"); }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path write(const std::string& name, const std::string& bytes) {
        const fs::path p = dir_ / name;
        std::ofstream(p, std::ios::binary) << bytes;
        return p;
    }
    template <class F>
    static std::string message(F&& f) {
        try {
            f();
        } catch (const std::exception& e) {
            return e.what();
        }
        return "(no error)";
    }
    fs::path dir_;
};

TEST_F(FileRead, ReadsARegularFileWhole) {
    const std::string bytes("abc\0def", 7);
    const pt::FileRead r = pt::tryReadInputFile(write("a.bin", bytes));
    ASSERT_TRUE(r) << pt::describeFileProblem(r);
    EXPECT_TRUE(r.regular);
    EXPECT_EQ(r.size, 7u);
    EXPECT_EQ(std::string(r.bytes.begin(), r.bytes.end()), bytes);
    EXPECT_EQ(pt::readInputFile(dir_ / "a.bin").size(), 7u);
}

TEST_F(FileRead, MissingFilesAndPathsThroughAFileAreNotFoundWithTheSystemsReason) {
    const pt::FileRead missing = pt::tryReadInputFile(dir_ / "none.bin");
    EXPECT_EQ(missing.problem, FileProblem::NotFound);
    EXPECT_EQ(missing.reason, "No such file or directory");
    const pt::FileRead through = pt::tryReadInputFile(write("f", "x") / "child");
    EXPECT_EQ(through.problem, FileProblem::NotFound);
    EXPECT_EQ(through.reason, "Not a directory");
    EXPECT_EQ(pt::describeFileProblem(missing), "file not found");
    EXPECT_EQ(
        message([&] { pt::readInputFile(dir_ / "none.bin"); }), (dir_ / "none.bin").string() + ": file not found");
}

TEST_F(FileRead, DirectoriesDevicesFifosAndSocketsAreRefused) {
    EXPECT_EQ(pt::tryReadInputFile(dir_).problem, FileProblem::Directory);
    EXPECT_EQ(pt::describeFileProblem(pt::checkInputFile(dir_), "a PLY file"), "is a directory, not a PLY file");
    EXPECT_EQ(pt::tryReadInputFile("/dev/zero").problem, FileProblem::NotRegularFile);
    const fs::path fifo = dir_ / "fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // Refused without opening it: opening a FIFO without a writer would block.
    EXPECT_EQ(pt::tryReadInputFile(fifo).problem, FileProblem::NotRegularFile);
    EXPECT_TRUE(pt::checkInputFile(fifo).notARegularFile());
    EXPECT_EQ(pt::describeFileProblem(pt::checkInputFile(fifo)), "not a regular file");
}

TEST_F(FileRead, StreamedDevicesAreReadToTheirEndWithinTheLimit) {
    const pt::FileRead null = pt::tryReadInputFile("/dev/null", {.streamNonRegular = true});
    ASSERT_TRUE(null);
    EXPECT_FALSE(null.regular);
    EXPECT_TRUE(null.bytes.empty());
    EXPECT_EQ(
        pt::tryReadInputFile("/dev/null", {.refuseEmpty = true, .streamNonRegular = true}).problem, FileProblem::Empty);
    const pt::FileRead zero = pt::tryReadInputFile("/dev/zero", {.maxBytes = 100000, .streamNonRegular = true});
    EXPECT_EQ(zero.problem, FileProblem::TooLarge);
    EXPECT_TRUE(zero.bytes.empty());
    EXPECT_EQ(pt::describeFileProblem(zero), "file too large (more than 100000 bytes)");
}

TEST_F(FileRead, SocketsCannotBeOpened) {
    const fs::path path = dir_ / "sock";
    const int s = ::socket(AF_UNIX, SOCK_STREAM, 0);
    ASSERT_GE(s, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    ASSERT_LT(path.string().size(), sizeof address.sun_path);
    std::strcpy(address.sun_path, path.c_str());
    ASSERT_EQ(::bind(s, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
    EXPECT_EQ(pt::tryReadInputFile(path).problem, FileProblem::NotRegularFile);
    const pt::FileRead streamed = pt::tryReadInputFile(path, {.streamNonRegular = true});
    EXPECT_EQ(streamed.problem, FileProblem::CannotOpen);
    EXPECT_EQ(streamed.reason, "No such device or address");
    ::close(s);
}

TEST_F(FileRead, EmptinessAndTheLimitAreCheckedBeforeOpening) {
    const fs::path empty = write("empty", "");
    EXPECT_TRUE(pt::tryReadInputFile(empty));
    EXPECT_EQ(pt::tryReadInputFile(empty, {.refuseEmpty = true}).problem, FileProblem::Empty);
    EXPECT_EQ(pt::describeFileProblem(pt::checkInputFile(empty, {.refuseEmpty = true})), "empty file");
    const fs::path big = write("big", std::string(1000, 'x'));
    const pt::InputFileCheck over = pt::checkInputFile(big, {.maxBytes = 999});
    EXPECT_EQ(over.problem, FileProblem::TooLarge);
    EXPECT_EQ(over.size, 1000u);
    EXPECT_TRUE(pt::tryReadInputFile(big, {.maxBytes = 1000}));
}

// As root, permissions are not enforced; these checks run only for other users.
TEST_F(FileRead, UnreadableFilesAndFoldersWithoutSearchPermission) {
    if (::geteuid() == 0) GTEST_SKIP() << "root reads everything";
    const fs::path locked = dir_ / "locked";
    fs::create_directory(locked);
    write("locked/in.bin", "x");
    fs::permissions(locked, fs::perms::none);
    const pt::FileRead inLocked = pt::tryReadInputFile(locked / "in.bin");
    EXPECT_EQ(inLocked.problem, FileProblem::CannotAccess);
    EXPECT_EQ(inLocked.reason, "Permission denied");
    fs::permissions(locked, fs::perms::owner_all);
    const fs::path unreadable = write("unreadable", "x");
    fs::permissions(unreadable, fs::perms::none);
    const pt::FileRead r = pt::tryReadInputFile(unreadable);
    EXPECT_EQ(r.problem, FileProblem::CannotOpen);
    EXPECT_EQ(r.reason, "Permission denied");
    EXPECT_EQ(pt::describeFileProblem(r), "cannot open for reading");
}

// The readers built on the policy keep the words they had before it (other tests, the malformed
// corpora and the command-line tests compare them).
TEST_F(FileRead, ReadersKeepTheirOwnWords) {
    const fs::path fifo = dir_ / "fifo.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_EQ(message([&] { pt::loadTextureImage(dir_ / "none.png"); }),
        (dir_ / "none.png").string() + ": cannot open image file (not found)");
    EXPECT_EQ(message([&] { pt::loadTextureImage(dir_); }), dir_.string() + ": not a regular file");
    EXPECT_EQ(message([&] { pt::loadTextureImage(fifo); }), fifo.string() + ": not a regular file");
    EXPECT_EQ(message([&] { pt::loadTextureImage(write("empty.png", "")); }),
        (dir_ / "empty.png").string() + ": image data is empty");
    EXPECT_EQ(message([&] { pt::readExr(dir_ / "none.exr"); }),
        (dir_ / "none.exr").string() + ": cannot open (No such file or directory)");
    EXPECT_EQ(message([&] { pt::readExr(dir_); }), dir_.string() + ": read failed (Is a directory)");
    EXPECT_EQ(message([&] { pt::readExr("/dev/null"); }), "/dev/null: not an OpenEXR file"); // streamed, empty
}

} // namespace
