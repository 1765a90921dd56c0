// `pedesis init random`: the tutorial's initial configuration (N = round(phi V) centres
// at least rcut apart in a periodic box centred at the origin, unit directors), the
// same file for the same seed, and exit 2 naming the option for impossible requests.
#include "cli/cli_support.hpp"

#include "pedesis/io/tutorial_json.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

using namespace pedesis;
using pedesis::test::run_pedesis;

namespace {

class cli_init : public pedesis::test::ScratchDir {
  protected:
    // Runs the command, expects success, and returns the file it wrote.
    template <int D> ParticleFile<D> init(const std::string& args, const std::string& file) {
        const auto r = run_pedesis("init random " + args + " -o " + file, dir);
        EXPECT_EQ(r.exit_code, 0) << r.output;
        EXPECT_NE(r.output.find(file), std::string::npos) << r.output;
        return read_tutorial_json<D>(dir / file);
    }

    nlohmann::json document(const std::string& file) { return nlohmann::json::parse(read(file)); }

    // Exit 2, a message naming every one of `parts`, and no file left behind.
    void expect_refused(const std::string& args, const std::vector<std::string>& parts) {
        SCOPED_TRACE(args);
        const auto r = run_pedesis("init random " + args + " -o bad.json", dir);
        EXPECT_EQ(r.exit_code, 2) << r.output;
        for (const auto& part : parts)
            EXPECT_NE(r.output.find(part), std::string::npos)
                << "'" << part << "' not in: " << r.output;
        EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "bad.json"));
    }
};

// Minimum-image separation in a periodic box of lengths L.
template <int D> double separation(const Vec<D>& a, const Vec<D>& b, const Vec<D>& L) {
    double d2 = 0.0;
    for (int k = 0; k < D; ++k) {
        double d = std::abs(a[k] - b[k]);
        d = std::min(d, L[k] - d);
        d2 += d * d;
    }
    return std::sqrt(d2);
}

template <int D>
void expect_tutorial_configuration(const ParticleFile<D>& f, std::size_t n, const Vec<D>& L,
                                   double rcut) {
    ASSERT_TRUE(f.box.has_value());
    EXPECT_EQ(*f.box, L);
    ASSERT_EQ(f.particles.size(), n);
    double closest = INFINITY;
    for (std::size_t i = 0; i < n; ++i) {
        const FileParticle<D>& p = f.particles[i];
        SCOPED_TRACE("particle " + std::to_string(i));
        EXPECT_EQ(p.id, i);
        EXPECT_EQ(p.type, 0);
        EXPECT_EQ(p.radius, 1.0);
        for (int a = 0; a < D; ++a) {
            EXPECT_GE(p.r[a], -0.5 * L[a]);
            EXPECT_LT(p.r[a], 0.5 * L[a]);
        }
        ASSERT_TRUE(p.n.has_value());
        EXPECT_NEAR(norm(*p.n), 1.0, 1e-14);
        ASSERT_TRUE(p.v.has_value());
        EXPECT_EQ(*p.v, Vec<D>{});
        for (std::size_t j = 0; j < i; ++j)
            closest = std::min(closest, separation<D>(p.r, f.particles[j].r, L));
    }
    EXPECT_GE(closest, rcut);
}

} // namespace

TEST_F(cli_init, TutorialConfiguration) {
    // The tutorial's random_init(0.4, 50, rcut=1.0): N = 1000 in a 50 x 50 box.
    const auto r = run_pedesis("init random --phi 0.4 --L 50 --rcut 1.0 -o init.json", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("1000 particles"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("50 x 50"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("init.json"), std::string::npos) << r.output;

    expect_tutorial_configuration<2>(read_tutorial_json<2>(dir / "init.json"), 1000,
                                     Vec<2>{{50.0, 50.0}}, 1.0);
    // What the tutorial's pymd reads: box Lx, Ly and per particle id, r, n, v, f.
    const auto doc = document("init.json");
    EXPECT_EQ(doc.at("system").at("box"), (nlohmann::json{{"Lx", 50.0}, {"Ly", 50.0}}));
    const auto& p0 = doc.at("system").at("particles").at(0);
    for (const char* key : {"id", "r", "n", "v", "f"}) EXPECT_TRUE(p0.contains(key)) << key;
    EXPECT_EQ(p0.at("f"), (nlohmann::json{0.0, 0.0}));
}

TEST_F(cli_init, SameSeedSameFileOtherSeedOtherFile) {
    init<2>("--phi 0.4 --L 20 --rcut 1.0 --seed 5", "a.json");
    init<2>("--phi 0.4 --L 20 --rcut 1.0 --seed 5", "b.json");
    init<2>("--phi 0.4 --L 20 --rcut 1.0 --seed 6", "c.json");
    EXPECT_FALSE(read("a.json").empty());
    EXPECT_EQ(read("a.json"), read("b.json"));
    EXPECT_NE(read("a.json"), read("c.json"));
}

TEST_F(cli_init, RectangularBoxAndThreeDimensions) {
    expect_tutorial_configuration<2>(init<2>("--phi 0.5 --L 20 --Ly 10 --rcut 1.0", "r.json"), 100,
                                     Vec<2>{{20.0, 10.0}}, 1.0);
    expect_tutorial_configuration<3>(
        init<3>("--dim 3 --phi 0.3 --L 10 --Lz 5 --rcut 1.0 --seed 2", "s.json"), 150,
        Vec<3>{{10.0, 10.0, 5.0}}, 1.0);
}

TEST_F(cli_init, RadiusAndNoMinimumDistance) {
    const auto f = init<2>("--phi 0.5 --L 4 --radius 0.25", "p.json");
    ASSERT_EQ(f.particles.size(), 8u);
    EXPECT_EQ(f.particles[3].radius, 0.25);
}

TEST_F(cli_init, ImpossibleRequestsExitTwoNamingTheOption) {
    expect_refused("--phi 0 --L 50 --rcut 1.0", {"--phi"});
    expect_refused("--phi -0.4 --L 50", {"--phi"});
    expect_refused("--phi 0.4 --L -1 --rcut 1.0", {"--L"});
    expect_refused("--phi 0.4 --L 50 --Ly 0", {"--Ly"});
    expect_refused("--phi 0.4 --L 50 --rcut nan", {"--rcut"});
    expect_refused("--phi 0.4 --L 50 --rcut -1", {"--rcut"});
    expect_refused("--phi 0.4 --L 50 --radius 0", {"--radius"});
    expect_refused("--phi 0.4 --L 50 --Lz 3", {"--Lz"});
    expect_refused("--phi 1e-6 --L 50", {"--phi", "no particle"});
    expect_refused("--phi 0.4 --L 50 --dim 4", {"--dim"});
    // Denser than close packing of points rcut apart: refused at once.
    expect_refused("--phi 2 --L 50 --rcut 1.0", {"--phi", "--rcut"});
    expect_refused("--dim 3 --phi 1.5 --L 10 --rcut 1.0", {"--phi", "--rcut"});
    // Possible in principle, beyond random placement: bounded attempts, then a message.
    expect_refused("--phi 0.9 --L 20 --rcut 1.0", {"--phi", "--rcut", "gave up"});
}

TEST_F(cli_init, MissingOptionsExitTwo) {
    auto r = run_pedesis("init random --L 50 -o x.json", dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--phi"), std::string::npos) << r.output;
    r = run_pedesis("init random --phi 0.4 --L 50", dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--output"), std::string::npos) << r.output;
}
