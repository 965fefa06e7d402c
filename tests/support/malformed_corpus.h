#pragma once
// The malformed-glTF corpus (tests/data/malformed_gltf/): its files, and from its README's table
// the lowercase substring each file's error message must contain (after removing the file's path).
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace pt::test {

std::filesystem::path malformedCorpusDir();
std::vector<std::string> malformedCorpusFiles();                 // file names, sorted
std::map<std::string, std::string> malformedCorpusExpectations(); // file name -> substring
std::string trim(std::string s);

} // namespace pt::test
