// What the viewer page learns of a run besides its frames: the scenery of its config.toml
// (containers, traps, gravity) as numbers checked in C++, whatever text the config holds.
#include "pedesis/render/run_directory.hpp"
#include "pedesis/view/run_data.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace pedesis::view {
namespace {

namespace fs = std::filesystem;

class ViewRunData : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() / ("pedesis_view_run_data_" + std::string(info->name()) +
                                           "_" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
        std::ofstream(dir / "trajectory.xyz")
            << "1\nLattice=\"20 0 0 0 20 0 0 0 20\" Origin=\"-10 -10 -10\" "
               "Properties=species:S:1:pos:R:3:radius:R:1 Time=0 pbc=\"T T F\"\nA 0 0 0 0.5\n";
    }
    void TearDown() override { fs::remove_all(dir); }

    nlohmann::json scenery_with(const std::string& config) {
        std::ofstream(dir / "config.toml") << config;
        auto run = render::open_run_directory(dir, render::SourceKind::automatic);
        const render::Frame f = run.source->frame(0);
        return run_info(*run.source, f, dir)["scenery"];
    }

    fs::path dir;
};

TEST_F(ViewRunData, SceneryIsSentAsNumbers) {
    const nlohmann::json s = scenery_with(R"(dimension = 3
[box]
boundary = ["periodic", "periodic", "wall"]
[[force]]
name = "wall"
shape = "cylinder"
axis = "x"
radius = 4.0
centre = [0, 1, -1]
[[force]]
name = "harmonic_trap"
k = [1, 2, 3]
centre = [2, 3, 4]
[[force]]
name = "gravity"
force = 0.5
)");
    EXPECT_EQ(s, nlohmann::json::parse(R"({
        "containers": [{"shape": "cylinder", "radius": 4.0, "centre": [0.0, 1.0, -1.0], "axis": 0}],
        "traps": [[2.0, 3.0, 4.0]],
        "gravity": [[0.0, 0.0, -1.0]]})"))
        << s.dump();
}

TEST_F(ViewRunData, NoSceneryOrHostileSceneryGivesEmptyLists) {
    const nlohmann::json empty =
        nlohmann::json::parse(R"({"containers": [], "traps": [], "gravity": []})");
    EXPECT_EQ(scenery_with("dimension = 3\n"), empty);
    EXPECT_EQ(scenery_with("dimension = 3\n[[force\n"), empty);
    // markup where words and numbers belong: nothing of it is sent
    const nlohmann::json s = scenery_with(R"(dimension = 3
[[force]]
name = "wall"
shape = "<script>alert(1)</script>"
radius = 4.0
[[force]]
name = "wall"
shape = "sphere"
radius = "<img src=x onerror=alert(2)>"
[[force]]
name = "harmonic_trap"
k = 1.0
centre = ["<b>", 0, 0]
[[force]]
name = "gravity"
force = 1.0
axis = "</script>"
)");
    EXPECT_EQ(s, empty) << s.dump();
}

} // namespace
} // namespace pedesis::view
