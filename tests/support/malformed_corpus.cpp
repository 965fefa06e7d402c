#include "support/malformed_corpus.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

namespace pt::test {
namespace {

std::string firstBackticked(const std::string& s) {
    const size_t a = s.find('`');
    if (a == std::string::npos) return "";
    const size_t b = s.find('`', a + 1);
    return b == std::string::npos ? "" : s.substr(a + 1, b - a - 1);
}

} // namespace

std::filesystem::path malformedCorpusDir(const std::string& corpus) {
    return std::filesystem::path(PT_TEST_DATA_DIR) / "data" / corpus;
}

std::string trim(std::string s) {
    const char* ws = " \t\r\n";
    s.erase(0, s.find_first_not_of(ws));
    s.erase(s.find_last_not_of(ws) + 1);
    return s;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

std::string removeAll(std::string s, const std::string& what) {
    if (what.empty()) return s;
    for (size_t at; (at = s.find(what)) != std::string::npos;) s.erase(at, what.size());
    return s;
}

// README.md table rows: | `file` | problem | `substring` | (more columns allowed)
std::map<std::string, std::string> malformedCorpusExpectations(const std::string& corpus) {
    std::ifstream in(malformedCorpusDir(corpus) / "README.md");
    std::map<std::string, std::string> out;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("| `", 0) != 0) continue;
        std::vector<std::string> cells;
        std::stringstream ss(line);
        for (std::string cell; std::getline(ss, cell, '|');) cells.push_back(trim(cell));
        if (cells.size() < 4) continue; // cells[0]: the empty text before the first |
        const std::string file = firstBackticked(cells[1]), substring = firstBackticked(cells[3]);
        if (!file.empty() && !substring.empty()) out[file] = substring;
    }
    return out;
}

std::vector<std::string> malformedCorpusFiles(const std::string& corpus) {
    std::vector<std::string> files;
    for (const auto& e : std::filesystem::directory_iterator(malformedCorpusDir(corpus))) {
        const std::string name = e.path().filename().string();
        // Data files the scenes refer to are not cases themselves.
        const std::string ext = e.path().extension().string();
        if (!e.is_regular_file() || name == "README.md" || name == "make_corpus.py" || ext == ".bin" || ext == ".ply" ||
            ext == ".png")
            continue;
        files.push_back(name);
    }
    std::sort(files.begin(), files.end());
    return files;
}

std::string corpusParamName(const ::testing::TestParamInfo<std::string>& info) {
    std::string s = info.param;
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return s;
}

} // namespace pt::test
