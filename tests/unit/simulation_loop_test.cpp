// The one run loop (run/simulation.hpp) with a scripted engine: a logged quantity that
// stops being finite ends the run with a RunError and keeps the good rows and frames under
// their final names; +inf is accepted only where the catalogue allows it; a caught signal
// ends run() early with a closed, complete run directory.
#include "pedesis/core/error.hpp"
#include "pedesis/core/interrupt.hpp"
#include "pedesis/run/simulation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

namespace pedesis {
namespace {

namespace fs = std::filesystem;

// One particle that steps along x; `temperature` becomes `bad_value` from `bad_step` on.
class ScriptedEngine final : public RunEngine<2> {
  public:
    ScriptedEngine(std::uint64_t bad_step, double bad_value, std::uint64_t last_step)
        : bad_step_(bad_step), bad_value_(bad_value), last_step_(last_step) {
        p_.resize(1);
        p_.species_table = {Species{"A", 0.5, 1.0}};
        signal_at_ = std::numeric_limits<std::uint64_t>::max();
    }
    void raise_signal_at(std::uint64_t step) { signal_at_ = step; }

    std::uint64_t step() const override { return step_; }
    double time() const override { return 0.1 * static_cast<double>(step_); }
    Advance advance(std::uint64_t until_step, double) override {
        // one step per call, as the stepped engine does
        if (step_ < until_step) ++step_;
        p_.position[0][0] = 0.01 * static_cast<double>(step_);
        if (step_ == signal_at_) std::raise(SIGTERM);
        return {step_ >= last_step_ ? "steps" : nullptr, false};
    }
    Frame<2> frame() override { return frame_of(p_, box_, time(), step_); }
    std::uint64_t frames() const override { return frames_; }
    void frame_written() override { ++frames_; }
    void save_checkpoint(const fs::path& path) override {
        std::ofstream(path) << "step " << step_ << "\n";
    }
    std::vector<const char*> stale_results() const override { return {}; }
    std::vector<std::string> log_columns() const override {
        return {"step", "time", "temperature", "mean_free_time"};
    }
    void measure(std::vector<double>& values) override {
        values.insert(values.end(),
                      {static_cast<double>(step_), time(), step_ >= bad_step_ ? bad_value_ : 1.0,
                       std::numeric_limits<double>::infinity()});
    }
    void start(bool) override {}
    nlohmann::json summary(const char*) override { return {{"engine", "scripted"}}; }
    void finish(const nlohmann::json& summary) override {
        finished_by = summary.at("stopped_by").get<std::string>();
    }

    std::string finished_by;

  private:
    ParticleStore<2> p_;
    Box<2> box_{Vec<2>{10.0, 10.0}, {true, true}};
    std::uint64_t step_ = 0, frames_ = 0;
    std::uint64_t bad_step_, signal_at_;
    double bad_value_;
    std::uint64_t last_step_;
};

struct Dir {
    fs::path path;
    explicit Dir(const std::string& name) : path(fs::temp_directory_path() / name) {
        fs::remove_all(path);
    }
    ~Dir() { fs::remove_all(path); }
};

std::string read(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

bool has_part_files(const fs::path& dir) {
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().string().find(".part") != std::string::npos) return true;
    return false;
}

Schedule every_step_log_every_ten_frames() {
    return {Trigger::every_steps(1), Trigger::every_steps(10), Trigger::never()};
}

void expect_stops_at_step_25(double bad_value, const std::string& shown) {
    Dir dir("pedesis_simulation_loop_" + shown);
    ScriptedEngine engine(25, bad_value, 1000);
    RunOptions o;
    o.out_dir = dir.path;
    Simulation<2> sim(engine, every_step_log_every_ten_frames(), {{"xyz"}, {}, {}}, o);
    try {
        sim.run();
        FAIL() << "a " << shown << " temperature must stop the run";
    } catch (const RunError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("at step 25"), std::string::npos) << m;
        EXPECT_NE(m.find("'temperature' is " + shown), std::string::npos) << m;
        EXPECT_NE(m.find("last good snapshot is frame 2 at t = 2"), std::string::npos) << m;
    }
    // rows 0..24 (25 good rows after the header), frames 0, 10, 20, all under final names
    const std::string log = read(dir.path / "log.csv");
    EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 26) << log;
    EXPECT_EQ(log.find("nan"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir.path / "trajectory.xyz"));
    EXPECT_FALSE(has_part_files(dir.path));
    EXPECT_EQ(engine.finished_by, ""); // a failed run is not finished
}

TEST(SimulationLoop, NaNInALoggedQuantityStopsTheRunAndKeepsTheGoodOutput) {
    expect_stops_at_step_25(std::numeric_limits<double>::quiet_NaN(), "nan");
}

TEST(SimulationLoop, InfinityWhereTheCatalogueDoesNotAllowItStopsTheRun) {
    expect_stops_at_step_25(std::numeric_limits<double>::infinity(), "inf");
}

TEST(SimulationLoop, ANaNFoundByTheLastRowOfCloseStopsTheRunToo) {
    // a script advances to step 35 (rows every 10 steps) and closes: the row close writes
    // at step 35 is the first to see the NaN (from step 32 on)
    Dir dir("pedesis_simulation_loop_close");
    ScriptedEngine engine(32, std::numeric_limits<double>::quiet_NaN(), 1000);
    RunOptions o;
    o.out_dir = dir.path;
    Simulation<2> sim(engine,
                      {Trigger::every_steps(10), Trigger::every_steps(10), Trigger::never()},
                      {{"xyz"}, {}, {}}, o);
    EXPECT_EQ(sim.advance(35), nullptr);
    try {
        sim.close("script");
        FAIL() << "the last row's NaN must stop the run";
    } catch (const RunError& e) {
        EXPECT_NE(std::string(e.what()).find("at step 35"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("last good snapshot is frame 3 at t = 3"),
                  std::string::npos)
            << e.what();
    }
    const std::string log = read(dir.path / "log.csv"); // rows 0, 10, 20, 30
    EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 5) << log;
    EXPECT_FALSE(has_part_files(dir.path));
    EXPECT_FALSE(fs::exists(dir.path / "summary.json"));
    EXPECT_EQ(engine.finished_by, "");
}

TEST(SimulationLoop, InfinityWhereTheCatalogueAllowsItIsAValue) {
    // mean_free_time is +inf in every row of the scripted engine
    Dir dir("pedesis_simulation_loop_inf_ok");
    ScriptedEngine engine(std::numeric_limits<std::uint64_t>::max(), 0.0, 30);
    RunOptions o;
    o.out_dir = dir.path;
    Simulation<2> sim(engine, every_step_log_every_ten_frames(), {{"xyz"}, {}, {}}, o);
    sim.run();
    EXPECT_EQ(engine.finished_by, "steps");
    const std::string log = read(dir.path / "log.csv");
    EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 32); // header + steps 0..30
    EXPECT_NE(log.find(",inf\n"), std::string::npos);
}

TEST(SimulationLoop, ACaughtSignalEndsTheRunClosedAndComplete) {
    Dir dir("pedesis_simulation_loop_signal");
    ScriptedEngine engine(std::numeric_limits<std::uint64_t>::max(), 0.0, 1000);
    engine.raise_signal_at(37);
    RunOptions o;
    o.out_dir = dir.path;
    Simulation<2> sim(engine, every_step_log_every_ten_frames(), {{"xyz"}, {}, {}}, o);
    {
        InterruptGuard guard;
        sim.run();
        EXPECT_EQ(guard.signal(), SIGTERM);
    } // the guard puts the default handler back without raising
    EXPECT_EQ(engine.step(), 37u);
    EXPECT_EQ(engine.finished_by, "interrupted");
    EXPECT_TRUE(sim.closed());
    EXPECT_EQ(read(dir.path / "checkpoint.bin"), "step 37\n");
    // summary.json: the engine's entries, the stop, and the last row by quantity name
    const auto summary = nlohmann::json::parse(read(dir.path / "summary.json"));
    EXPECT_EQ(summary.at("engine"), "scripted");
    EXPECT_EQ(summary.at("stopped_by"), "interrupted");
    EXPECT_EQ(summary.at("final").at("step"), 37);
    EXPECT_DOUBLE_EQ(summary.at("final").at("time").get<double>(), 3.7);
    EXPECT_TRUE(summary.at("final").at("mean_free_time").is_null()); // +inf
    const std::string log = read(dir.path / "log.csv");
    EXPECT_NE(log.find("\n37,3.7,1,inf\n"), std::string::npos) << log; // the row of the end
    // frames 0, 10, 20, 30 and the last one at step 37
    EXPECT_EQ(engine.frames(), 5u);
    EXPECT_FALSE(has_part_files(dir.path));
}

TEST(SimulationLoop, ASignalIsForgottenWithItsGuard) {
    {
        InterruptGuard guard;
        std::raise(SIGINT);
        EXPECT_TRUE(interrupt_requested());
    }
    EXPECT_FALSE(interrupt_requested()); // a later run without a guard is not stopped
}

} // namespace
} // namespace pedesis
