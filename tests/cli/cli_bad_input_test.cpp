// Bad input gives one clear message naming the culprit, exit code 2, and no output
// files that look complete.
#include "cli_support.hpp"

using namespace pedesis::test;

namespace {

// expect_rejected (cli_support.hpp): exit 2, the fragments, no output that looks complete
class BadInput : public ScratchDir {};

TEST_F(BadInput, ValidConfigRuns) {
    write("ok.toml", small_config());
    const CliResult r = run_pedesis("run ok.toml --out out", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / "summary.json"));
}

TEST_F(BadInput, OverlappingParticlesNameThePair) {
    expect_rejected(
        "dimension = 2\n[box]\nlength = 20.0\nboundary = \"wall\"\n"
        "[[species]]\nname = \"P\"\nradius = 1.0\nposition = [0.0, 0.0]\nvelocity = [0.0, 0.0]\n"
        "[[species]]\nname = \"Q\"\nradius = 1.0\nposition = [1.5, 0.0]\nvelocity = [0.0, 0.0]\n"
        "[run]\ntime = 1.0\n",
        {"particle 0", "particle 1", "overlap 0.5"});
}

TEST_F(BadInput, ParticleOutsideWalls) {
    expect_rejected(small_config("[[species]]\nname = \"P\"\nposition = [9.9, 0.0]\n"),
                    {"particle 50", "outside the walls"});
}

TEST_F(BadInput, NonPositiveRadiusOrMass) {
    expect_rejected(small_config("[[species]]\nname = \"P\"\ncount = 1\nradius = 0.0\n"),
                    {"bad.toml", "radius", "positive"});
    expect_rejected(small_config("[[species]]\nname = \"P\"\ncount = 1\nmass = -1.0\n"),
                    {"bad.toml", "mass", "positive"});
}

TEST_F(BadInput, RestitutionOutsideUnitInterval) {
    expect_rejected(small_config() + "[event]\nrestitution = 1.5\n",
                    {"bad.toml", "event.restitution", "[0, 1]"});
    expect_rejected(small_config() + "[event]\nwall_restitution = -0.1\n",
                    {"event.wall_restitution"});
}

TEST_F(BadInput, BoxSmallerThanOneParticle) {
    expect_rejected(small_config("", "length = 0.5"),
                    {"species[0].radius", "does not fit in the box"});
}

TEST_F(BadInput, NoParticles) {
    expect_rejected(
        "dimension = 2\n[box]\nlength = 10.0\n[[species]]\ncount = 0\n[run]\ntime = 1.0\n",
        {"bad.toml", "count", "N = 0"});
}

TEST_F(BadInput, NanAndInfinity) {
    expect_rejected(small_config("", "length = nan"), {"bad.toml:4", "box.length", "NaN"});
    expect_rejected(small_config("", "length = inf"), {"box.length", "finite"});
    expect_rejected(small_config("", "length = 20.0", "time = nan"), {"run.time", "NaN"});
}

TEST_F(BadInput, UnknownKeysAreErrors) {
    expect_rejected(small_config() + "tiem = 3\n", {"bad.toml", "unknown key", "output.tiem"});
    expect_rejected("colour = 1\n" + small_config(), {"bad.toml:1", "unknown key 'colour'"});
    expect_rejected(small_config("", "length = 20.0\nlenght = 3.0"), {"unknown key 'box.lenght'"});
}

TEST_F(BadInput, MalformedTomlGivesLineAndColumn) {
    expect_rejected("dimension = 2\n[box\nlength = 3\n", {"bad.toml:2:"});
}

TEST_F(BadInput, MalformedJsonInitialFileGivesLineAndColumn) {
    write("init.json", "{\"system\": {\"particles\": [\n  {\"id\": 0, \"r\": [0.0, 0.0]},\n  "
                       "{\"id\": 1 \"r\": [1.0, 1.0]}\n]}}\n");
    expect_rejected("dimension = 2\n[box]\nlength = 20.0\n[initial]\nfile = "
                    "\"init.json\"\n[[species]]\nname = \"A\"\n[run]\ntime = 1.0\n",
                    {"init.json:3:"});
}

TEST_F(BadInput, MissingConfigFile) {
    const CliResult r = run_pedesis("run nowhere.toml", dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("nowhere.toml"), std::string::npos) << r.output;
}

TEST_F(BadInput, CorruptCheckpoint) {
    write("ok.toml", small_config());
    write("junk.bin", "this is not a checkpoint");
    const CliResult r = run_pedesis("run ok.toml --restart junk.bin --out out", dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("junk.bin"), std::string::npos) << r.output;
}

TEST_F(BadInput, SpeciesNamesMustFitColumns) {
    expect_rejected(small_config("[[species]]\nname = \"big disk\"\ncount = 1\n"),
                    {"species[1].name", "letters A-Z"});
    // names the config accepted and an output format refused only once the run had started
    expect_rejected(small_config("[[species]]\nname = \"h\u00e9\"\ncount = 1\n"),
                    {"bad.toml:", "species[1].name", "letters A-Z"});
    expect_rejected(small_config("[[species]]\nname = \"\U0001F600\"\ncount = 1\n"),
                    {"species[1].name", "letters A-Z"});
}

TEST_F(BadInput, ImpossibleStopCondition) {
    expect_rejected(small_config("", "length = 20.0", "energy_fraction = 0.5"),
                    {"run.energy_fraction", "never be reached"});
    expect_rejected(small_config("", "length = 20.0", "energy_fraction = 1.5"),
                    {"run.energy_fraction"});
    expect_rejected(small_config("", "length = 20.0", "time = 1.0\ncolour = 2"),
                    {"unknown key 'run.colour'"});
    expect_rejected(small_config("", "length = 20.0", ""), {"[run] needs at least one of"});
}

} // namespace
