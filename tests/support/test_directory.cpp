#include "support/test_directory.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>

namespace pt::test {

std::filesystem::path freshTestDirectory(const std::string& prefix) {
    std::string name = "pt_" + prefix + "_" + std::to_string(::getpid());
    if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info()) {
        std::string test = info->name();
        for (char& c : test)
            if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
        name += "_" + test;
    }
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

} // namespace pt::test
