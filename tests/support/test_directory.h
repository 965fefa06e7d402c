#pragma once
// A fresh, empty directory for the running test, under the system temporary directory: its name
// holds the process id and the test's name, so parallel ctest runs and the tests of one run
// cannot collide, and a "no files left behind" check sees only the test's own output.
#include <filesystem>
#include <string>

namespace pt::test {

// <temp>/pt_<prefix>_<pid>_<test name> (characters other than letters and digits in the test's
// name, such as the '/' of a parameterised test, become '_'), emptied and created. Outside a
// test: <temp>/pt_<prefix>_<pid>.
std::filesystem::path freshTestDirectory(const std::string& prefix);

} // namespace pt::test
