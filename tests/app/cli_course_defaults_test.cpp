// pt render on course scenes, for what pt decides when the command line does not: the depth of
// each camera (the course's convention, stated in the log line; --max-depth overrides), and a
// warning naming the file for every value the file leaves out and pt fills in.
#include "cli_fixture.h"
#include "image/image_io.h"

#include <fstream>
#include <sstream>

namespace pt::test {
namespace {

const fs::path kGlassBox = kTests / "data" / "ceng795" / "cornellbox_jaroslav_path_glass.xml";

// The log line of the integrator settings ("pt: nee=... max-depth=...").
std::string integratorLine(const PtRun& r) {
    std::istringstream lines(r.err);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("pt: nee=", 0) == 0 || line.rfind("pt: integrator=", 0) == 0) return line;
    ADD_FAILURE() << "no integrator line in\n" << r;
    return "";
}

// The warning lines that name `file`.
std::vector<std::string> warningsAbout(const PtRun& r, const std::string& file) {
    std::vector<std::string> out;
    std::istringstream lines(r.err);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("pt: warning: " + file + ": ", 0) == 0) out.push_back(line);
    return out;
}

bool anyContains(const std::vector<std::string>& lines, const std::string& text) {
    return std::any_of(
        lines.begin(), lines.end(), [&](const std::string& l) { return l.find(text) != std::string::npos; });
}

// The HW6 glass box (MaxRecursionDepth 3): camera 3 has NEE, camera 5 not, camera 4 Russian
// roulette; the course's renderer counted NEE paths one segment deeper (bench/RESULTS.md).
TEST_F(CliTest, CourseCamerasRenderAtTheCourseDepthAndTheLogSaysWhy) {
    const std::string scene = kGlassBox.string();
    const std::pair<const char*, const char*> cases[] = {
        {"3", "max-depth=5 (course: MaxRecursionDepth 3 + 2 with NEE)"},
        {"5", "max-depth=4 (course: MaxRecursionDepth 3 + 1 without NEE)"},
        {"4", "max-depth=256 (course: Russian roulette without a depth cap)"},
    };
    for (const auto& [camera, expected] : cases) {
        SCOPED_TRACE(camera);
        const fs::path out = dir_ / (std::string("camera") + camera + ".exr");
        const PtRun r = run(
            {"render", scene, "--camera", camera, "--spp", "1", "--width", "4", "--height", "4", "-o", out.string()});
        EXPECT_EXIT_STATUS(r, 0);
        EXPECT_NE(integratorLine(r).find(expected), std::string::npos) << integratorLine(r);
        pt::ImageMetadata meta;
        pt::readExr(out, &meta);
        const std::string depth = std::string(expected).substr(0, std::string(expected).find(' '));
        EXPECT_NE(meta["integrator"].find(depth + " "), std::string::npos) << meta["integrator"];
    }
    // The camera's own NEE decides the depth, not --nee (a switch changes the estimator, not the
    // image); --max-depth overrides, and the line then gives no course reason.
    const PtRun off = run({"render", scene, "--camera", "3", "--nee", "off", "--spp", "1", "--width", "4", "--height",
        "4", "-o", (dir_ / "off.exr").string()});
    EXPECT_EXIT_STATUS(off, 0);
    EXPECT_NE(integratorLine(off).find("nee=off"), std::string::npos) << integratorLine(off);
    EXPECT_NE(integratorLine(off).find("max-depth=5 (course: MaxRecursionDepth 3 + 2 with NEE)"), std::string::npos)
        << integratorLine(off);
    const PtRun given = run({"render", scene, "--camera", "3", "--max-depth", "7", "--spp", "1", "--width", "4",
        "--height", "4", "-o", (dir_ / "given.exr").string()});
    EXPECT_EXIT_STATUS(given, 0);
    EXPECT_NE(integratorLine(given).find("max-depth=7 rr-start"), std::string::npos) << integratorLine(given);
    // The official files give every value: no warning about assumed values.
    EXPECT_FALSE(anyContains(warningsAbout(given, scene), "assumed")) << given;
    EXPECT_FALSE(anyContains(warningsAbout(given, scene), "camera 3:")) << given;
}

// A course file that leaves out what its cameras and materials usually give: each value pt fills
// in is named in a warning that starts with the file's name.
TEST_F(CliTest, CourseValuesTheFileLeavesOutAreWarnedAbout) {
    const fs::path ply = dir_ / "short.ply";
    std::ofstream(ply) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
                          "-1 -1 -2\n1 -1 -2\n0 1 -2\n3 0 1 2\n2 0 1\n";
    const fs::path scene = dir_ / "sparse.xml";
    std::ofstream(scene)
        << "<Scene><Cameras><Camera id=\"1\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
           "<FovY>60</FovY><Tonemap><TMO>Photographic</TMO></Tonemap></Camera></Cameras>"
           "<Lights><PointLight id=\"1\"><Position>0 0 0</Position><Intensity>10 10 10</Intensity></PointLight>"
           "</Lights><Materials><Material id=\"1\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance>"
           "<SpecularReflectance>0.5 0.5 0.5</SpecularReflectance></Material></Materials>"
           "<Objects><Mesh id=\"1\"><Material>1</Material><Faces plyFile=\"short.ply\"/></Mesh></Objects></Scene>";
    const std::string file = scene.string();
    // No size, samples or output name on the command line either: a 512x512, 1-sample render
    // would need --spp, so the samples are checked at a tiny size in a second run.
    const PtRun r = run({"render", file, "--spp", "1"}, {}, 60);
    EXPECT_EXIT_STATUS(r, 0);
    const std::vector<std::string> w = warningsAbout(r, file);
    for (const char* expected : {"camera 1: no ImageResolution: rendered at 512x512",
             "camera 1: no ImageName: written to out/sparse.exr", "no MaxRecursionDepth: max depth 16, pt's default",
             "values assumed: ", "Camera id=1: Tonemap without TMOOptions (key 0.18, burn 0% assumed)",
             "Material id=1: no PhongExponent for its SpecularReflectance (1 assumed)",
             "Mesh id=1: Faces: plyFile 'short.ply': 1 face with fewer than 3 vertices (dropped)"})
        EXPECT_TRUE(anyContains(w, expected)) << expected << " missing from\n" << r;
    EXPECT_TRUE(fs::exists(dir_ / "out" / "sparse.exr"));
    EXPECT_FALSE(anyContains(w, "NumSamples")) << r; // --spp gave it
    const PtRun sized = run({"render", file, "--width", "4", "--height", "4", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(sized, 0);
    const std::vector<std::string> ws = warningsAbout(sized, file);
    EXPECT_TRUE(anyContains(ws, "camera 1: no NumSamples: 64 samples per pixel")) << sized;
    EXPECT_FALSE(anyContains(ws, "ImageResolution")) << sized;
    EXPECT_FALSE(anyContains(ws, "ImageName")) << sized;
}

} // namespace
} // namespace pt::test
