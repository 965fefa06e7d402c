// The disk cache's contract: what is written reads back; anything damaged, foreign or mislabelled
// reads as absent (never as wrong bytes); concurrent writers leave a valid file; the folder stays
// bounded; a folder that cannot be written is no error.
#include "gpu/shader_cache_directory.h"
#include "support/test_directory.h"

#include <gtest/gtest.h>

#include <fstream>
#include <thread>

namespace pt::test {
namespace {

namespace fs = std::filesystem;

std::vector<uint8_t> bytes(size_t n, uint8_t seed) {
    std::vector<uint8_t> b(n);
    for (size_t i = 0; i < n; ++i) b[i] = uint8_t(seed + i * 7);
    return b;
}

std::vector<char> fileBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

void writeBytes(const fs::path& p, const std::vector<char>& b) {
    std::ofstream(p, std::ios::binary).write(b.data(), std::streamsize(b.size()));
}

class ShaderCacheDirectoryTest : public ::testing::Test {
protected:
    void SetUp() override { dir_ = freshTestDirectory("shader-cache") / "pt"; }
    fs::path dir_;
};

TEST_F(ShaderCacheDirectoryTest, WhatIsWrittenReadsBackUnderItsKeyOnly) {
    ShaderCacheDirectory cache(dir_);
    EXPECT_FALSE(cache.read("spirv-a", 1).has_value()); // nothing yet: a quiet miss
    cache.write("spirv-a", 1, bytes(1000, 3));
    ASSERT_TRUE(fs::exists(cache.fileOf("spirv-a")));
    EXPECT_EQ(cache.read("spirv-a", 1), bytes(1000, 3));
    EXPECT_FALSE(cache.read("spirv-a", 2).has_value()); // same name, other content
    cache.write("empty", 5, {});
    EXPECT_EQ(cache.read("empty", 5), std::vector<uint8_t>{});
}

TEST_F(ShaderCacheDirectoryTest, DamagedFilesReadAsAbsent) {
    ShaderCacheDirectory cache(dir_);
    cache.write("k", 9, bytes(4096, 1));
    const fs::path file = cache.fileOf("k");
    const std::vector<char> good = fileBytes(file);

    auto damaged = good; // one payload bit flipped
    damaged[good.size() / 2] ^= 0x10;
    writeBytes(file, damaged);
    EXPECT_FALSE(cache.read("k", 9).has_value());

    damaged = good; // cut short, as by a full disk
    damaged.resize(good.size() - 100);
    writeBytes(file, damaged);
    EXPECT_FALSE(cache.read("k", 9).has_value());

    damaged = good; // trailing bytes
    damaged.push_back('x');
    writeBytes(file, damaged);
    EXPECT_FALSE(cache.read("k", 9).has_value());

    damaged = good; // a header claiming a huge payload: refused before any allocation
    for (int i = 16; i < 24; ++i) damaged[i] = char(0xff);
    writeBytes(file, damaged);
    EXPECT_FALSE(cache.read("k", 9).has_value());

    writeBytes(file, {'n', 'o', 't', ' ', 'a', ' ', 'c', 'a', 'c', 'h', 'e'}); // foreign
    EXPECT_FALSE(cache.read("k", 9).has_value());
    writeBytes(file, {});
    EXPECT_FALSE(cache.read("k", 9).has_value());

    cache.write("k", 9, bytes(4096, 1)); // and it is simply replaced
    EXPECT_EQ(cache.read("k", 9), bytes(4096, 1));
}

TEST_F(ShaderCacheDirectoryTest, ConcurrentWritersLeaveOneValidFile) {
    constexpr int kWriters = 8, kRounds = 20;
    std::vector<std::thread> threads;
    std::atomic<int> badReads{0};
    for (int w = 0; w < kWriters; ++w)
        threads.emplace_back([&, w] {
            ShaderCacheDirectory cache(dir_); // one per thread, as one per process
            for (int r = 0; r < kRounds; ++r) {
                cache.write("shared", 77, bytes(20000 + 13 * w, uint8_t(w)));
                if (auto got = cache.read("shared", 77)) {
                    bool one = false;
                    for (int v = 0; v < kWriters; ++v) one = one || *got == bytes(20000 + 13 * v, uint8_t(v));
                    if (!one) ++badReads;
                }
            }
        });
    for (auto& t : threads) t.join();
    EXPECT_EQ(badReads.load(), 0);
    ShaderCacheDirectory cache(dir_);
    ASSERT_TRUE(cache.read("shared", 77).has_value());
    for (const auto& e : fs::directory_iterator(dir_)) // no temporary left behind
        EXPECT_FALSE(e.path().filename().string().starts_with(".")) << e.path();
}

TEST_F(ShaderCacheDirectoryTest, TheFolderKeepsTheMostRecentlyUsedEntries) {
    ShaderCacheDirectory cache(dir_);
    const size_t n = ShaderCacheDirectory::kMaxEntries + 10;
    for (size_t i = 0; i < n; ++i) {
        cache.write("e" + std::to_string(i), i, bytes(16, uint8_t(i)));
        // Entry 0 is used again and again, so it survives while others age out.
        ASSERT_TRUE(cache.read("e0", 0).has_value()) << i;
        fs::last_write_time(cache.fileOf("e0"), fs::file_time_type::clock::now() + std::chrono::seconds(60));
    }
    size_t files = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++files;
    EXPECT_EQ(files, ShaderCacheDirectory::kMaxEntries);
    EXPECT_TRUE(cache.read("e0", 0).has_value());
    EXPECT_TRUE(cache.read("e" + std::to_string(n - 1), n - 1).has_value());
}

TEST_F(ShaderCacheDirectoryTest, AFolderThatCannotBeMadeIsNoError) {
    fs::create_directories(dir_.parent_path());
    writeBytes(dir_.parent_path() / "file", {'x'});
    ShaderCacheDirectory cache(dir_.parent_path() / "file" / "pt"); // under a regular file
    testing::internal::CaptureStderr();
    cache.write("a", 1, bytes(10, 0));
    cache.write("b", 2, bytes(10, 0));
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_FALSE(cache.read("a", 1).has_value());
    EXPECT_NE(err.find("pipeline cache"), std::string::npos) << err;
    EXPECT_EQ(err.find("pipeline cache", err.find("pipeline cache") + 1), std::string::npos) << "warned twice: " << err;
}

TEST(ShaderCacheDirectoryPath, FollowsXdgThenHome) {
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    const char* home = std::getenv("HOME");
    const std::string savedXdg = xdg ? xdg : "", savedHome = home ? home : "";
    setenv("XDG_CACHE_HOME", "/x/cache", 1);
    setenv("HOME", "/h", 1);
    EXPECT_EQ(ShaderCacheDirectory::defaultPath(), fs::path("/x/cache/pt"));
    setenv("XDG_CACHE_HOME", "", 1);
    EXPECT_EQ(ShaderCacheDirectory::defaultPath(), fs::path("/h/.cache/pt"));
    unsetenv("XDG_CACHE_HOME");
    unsetenv("HOME");
    EXPECT_EQ(ShaderCacheDirectory::defaultPath(), fs::path());
    if (xdg) setenv("XDG_CACHE_HOME", savedXdg.c_str(), 1);
    if (home) setenv("HOME", savedHome.c_str(), 1);
}

} // namespace
} // namespace pt::test
