#pragma once
// What the command-line tests share (the cli_*_test.cpp files beside this one: the pt binary as a
// user runs it, by what it is asked to do): the reference scene's paths, the fixture that runs pt
// in its own temporary directory (its working directory too, so a default output path could not
// litter the source tree) with stdout and stderr captured to files, and the exit-status check.
#include "support/pt_process.h"
#include "support/test_directory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <system_error>
#include <vector>

namespace pt::test {

namespace fs = std::filesystem;

inline const fs::path kTests = PT_TEST_DATA_DIR;
inline const fs::path kDiffuseScene = kTests / "references" / "cbox-diffuse" / "scene.gltf";
inline const fs::path kDiffuseReference = kTests / "references" / "cbox-diffuse" / "reference.exr";

class CliTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = pt::test::freshTestDirectory("cli");
        captureDir_ = dir_ / ".capture";
        fs::create_directories(captureDir_);
    }
    void TearDown() override {
        std::error_code ignored;
        if (!HasFailure()) fs::remove_all(dir_, ignored); // keep the evidence of a failure
    }

    // Runs `pt args...` in dir_ with `env` added to (and PT_VALIDATION and PT_FAULT removed from,
    // unless given) the environment, stdout and stderr captured; kills it after `timeoutSeconds`.
    PtRun run(const std::vector<std::string>& args, const std::map<std::string, std::string>& env = {},
        double timeoutSeconds = 30) {
        std::vector<std::string> argv = {PT_BINARY};
        argv.insert(argv.end(), args.begin(), args.end());
        pt::test::RunOptions options;
        options.dir = dir_;
        options.env = env;
        options.stdoutFile = captureDir_ / "stdout";
        options.stderrFile = captureDir_ / "stderr";
        options.timeoutSeconds = timeoutSeconds;
        const PtRun r = pt::test::runProcess(argv, options);
        if (!r.launchError.empty()) ADD_FAILURE() << r.launchError;
        return r;
    }

    // The files pt left in dir_ (relative names, the capture directory excluded).
    std::vector<std::string> outputs() const {
        std::vector<std::string> names;
        for (const auto& e : fs::recursive_directory_iterator(dir_)) {
            const fs::path rel = fs::relative(e.path(), dir_);
            if (*rel.begin() == ".capture") continue;
            names.push_back(rel.string());
        }
        std::sort(names.begin(), names.end());
        return names;
    }

    fs::path dir_, captureDir_;
};

} // namespace pt::test

// Exited (not killed by a signal, not timed out) with status `expected`.
#define EXPECT_EXIT_STATUS(r, expected)                                                                                \
    do {                                                                                                               \
        EXPECT_FALSE((r).signaled) << (r);                                                                             \
        EXPECT_FALSE((r).timedOut) << (r);                                                                             \
        EXPECT_EQ((r).status, (expected)) << (r);                                                                      \
    } while (0)
