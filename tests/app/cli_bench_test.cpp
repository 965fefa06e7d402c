// pt bench: the CSV, plot and contact sheets of speed against error at equal time, and its bad
// configurations and budgets.
#include "cli_fixture.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace pt::test {
namespace {

// ---------------------------------------------------------------------------------------------
// pt bench: speed against error at equal time

// The rows of a CSV as column -> value maps.
std::vector<std::map<std::string, std::string>> readCsv(const fs::path& path) {
    std::ifstream in(path);
    std::vector<std::string> header;
    std::vector<std::map<std::string, std::string>> rows;
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> fields;
        std::istringstream s(line);
        for (std::string f; std::getline(s, f, ',');) fields.push_back(f);
        if (header.empty()) {
            header = fields;
            continue;
        }
        EXPECT_EQ(fields.size(), header.size()) << line;
        std::map<std::string, std::string> row;
        for (size_t i = 0; i < std::min(fields.size(), header.size()); ++i) row[header[i]] = fields[i];
        rows.push_back(row);
    }
    return rows;
}

TEST_F(CliTest, BenchWritesCsvPlotAndContactSheets) {
    const PtRun r = run({"bench", "--width", "32", "--height", "32", "--budgets", "0.8,0.2", "--configs",
                            "nee+is+rr,none,nee+is+rr+sobol", "--reference-spp", "256", "-o", "bench"},
        {}, 120);
    EXPECT_EXIT_STATUS(r, 0);
    const fs::path dir = dir_ / "bench";
    const auto rows = readCsv(dir / "bench.csv");
    ASSERT_EQ(rows.size(), 6u) << r; // 3 configurations x 2 budgets
    std::map<std::string, std::map<double, std::map<std::string, std::string>>> byConfig;
    for (const auto& row : rows) {
        for (const char* column : {"budget_s", "spp", "seconds", "mpaths_per_s", "mrays_per_s", "mrays_camera_per_s",
                 "mrays_shadow_per_s", "mrays_continuation_per_s", "relmse", "mse", "efficiency", "estimated_relmse"}) {
            const double v = std::stod(row.at(column));
            EXPECT_TRUE(std::isfinite(v) && v >= 0) << column << " = " << row.at(column);
        }
        EXPECT_GT(std::stod(row.at("relmse")), 0.0);
        EXPECT_EQ(row.at("dropped_samples"), "0");
        EXPECT_TRUE(fs::exists(dir / row.at("image"))) << row.at("image");
        byConfig[row.at("config")][std::stod(row.at("budget_s"))] = row;
    }
    ASSERT_EQ(byConfig.size(), 3u);
    for (const auto& [config, budgets] : byConfig) {
        ASSERT_EQ(budgets.size(), 2u) << config;
        const auto& shortRun = budgets.at(0.2);
        const auto& longRun = budgets.at(0.8);
        // Budgets are in ascending order of samples, each about within its time.
        EXPECT_LE(std::stoul(shortRun.at("spp")), std::stoul(longRun.at("spp"))) << config;
        EXPECT_LE(std::stod(longRun.at("seconds")), 0.8 * 3) << config; // loose: a busy machine slows passes
        EXPECT_GT(std::stoul(longRun.at("spp")), 1u) << config;
        // Ray counts: one camera ray per path; NEE traces shadow rays, "none" traces none.
        EXPECT_NEAR(std::stod(longRun.at("mrays_camera_per_s")), std::stod(longRun.at("mpaths_per_s")), 1e-9) << config;
        EXPECT_EQ(std::stod(longRun.at("mrays_shadow_per_s")) > 0, config != "none") << config;
        EXPECT_GT(std::stod(longRun.at("mrays_continuation_per_s")), 0.0) << config;
    }
    // The seed's finding holds at equal time in the Cornell box: NEE lowers the error by far.
    EXPECT_LT(std::stod(byConfig["nee+is+rr"][0.8].at("relmse")) * 4, std::stod(byConfig["none"][0.8].at("relmse")));

    for (const char* png : {"relmse_vs_time.png", "contact_0.2s.png", "contact_0.8s.png"}) {
        ASSERT_TRUE(fs::exists(dir / png)) << png << "\n" << r;
        EXPECT_EQ(readFile(dir / png).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << png;
        EXPECT_GT(fs::file_size(dir / png), 5000u) << png; // a real plot, not an empty canvas
    }
    EXPECT_TRUE(fs::exists(dir / "reference.exr")); // made here, as no --reference was given
    EXPECT_NE(readFile(dir / "bench_info.txt").find("made here"), std::string::npos);
}

TEST_F(CliTest, BenchRejectsUnknownConfigurationWord) {
    const PtRun r = run({"bench", "--width", "8", "--height", "8", "--configs", "nee+fast", "--no-plot"});
    EXPECT_EXIT_STATUS(r, 1);
    EXPECT_NE(r.errorLine().find("unknown word 'fast'"), std::string::npos) << r;
}

TEST_F(CliTest, BenchRejectsBadBudget) {
    const PtRun r = run({"bench", "--width", "8", "--height", "8", "--budgets", "1,x", "--no-plot"});
    EXPECT_EXIT_STATUS(r, 1);
    EXPECT_NE(r.errorLine().find("'x' is not a number of seconds"), std::string::npos) << r;
}

} // namespace
} // namespace pt::test
