#pragma once
// The malformed-input corpora (tests/data/malformed_gltf/, malformed_xml/, malformed_ply/): their
// files, and from each README's table the lowercase substring each file's error message must
// contain (after removing the file's path). `corpus` is the folder name; glTF by default.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace pt::test {

std::filesystem::path malformedCorpusDir(const std::string& corpus = "malformed_gltf");
std::vector<std::string> malformedCorpusFiles(const std::string& corpus = "malformed_gltf"); // sorted
std::map<std::string, std::string> malformedCorpusExpectations(const std::string& corpus = "malformed_gltf");
// A corpus file's name as the name of its parameterised test: characters other than letters and
// digits become '_'.
std::string corpusParamName(const ::testing::TestParamInfo<std::string>& info);
std::string trim(std::string s);
// For checking error messages: lower-cased text, and text with every occurrence of `what` removed
// (a file's own path can contain the word a test looks for).
std::string lower(std::string s);
std::string removeAll(std::string s, const std::string& what);

} // namespace pt::test
