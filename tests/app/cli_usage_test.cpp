// pt's command line: usage errors exit 2 with nothing rendered, --help exits 0.
#include "cli_fixture.h"

namespace pt::test {
namespace {

// ---------------------------------------------------------------------------------------------
// Usage errors: exit status 2, nothing rendered.

TEST_F(CliTest, SppAndTimeTogetherIsAUsageError) {
    const PtRun r = run({"render", "--spp", "4", "--time", "1", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 2);
    EXPECT_NE(r.err.find("--time"), std::string::npos) << r;
    EXPECT_TRUE(outputs().empty());
}

TEST_F(CliTest, BadSwitchValueIsAUsageError) {
    const PtRun r = run({"render", "--nee", "maybe", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 2);
    EXPECT_NE(r.err.find("maybe"), std::string::npos) << r;
    EXPECT_TRUE(outputs().empty());
}

TEST_F(CliTest, UnknownOptionIsAUsageError) {
    const PtRun r = run({"render", "--no-such-option", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 2);
    EXPECT_TRUE(outputs().empty());
}

TEST_F(CliTest, MissingSubcommandIsAUsageError) {
    const PtRun r = run({});
    EXPECT_EXIT_STATUS(r, 2);
}

TEST_F(CliTest, ErrorLogWithoutReferenceIsAUsageError) {
    const PtRun r = run({"render", "--error-log", (dir_ / "e.csv").string(), "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 2);
    EXPECT_NE(r.err.find("--reference"), std::string::npos) << r;
    EXPECT_TRUE(outputs().empty());
}

TEST_F(CliTest, HelpExitsZero) {
    const PtRun r = run({"render", "--help"});
    EXPECT_EXIT_STATUS(r, 0);
    EXPECT_NE(r.out.find("--spp"), std::string::npos) << r;
}

} // namespace
} // namespace pt::test
