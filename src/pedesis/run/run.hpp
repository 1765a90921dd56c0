#pragma once
// A run of any engine in any dimension, built from a config: what the command line and
// the Python module drive. The engine is chosen by `dynamics`, the dimension by
// `dimension`; the loop is the one Simulation of simulation.hpp.
#include "pedesis/run/run_options.hpp"
#include "pedesis/run/trigger.hpp"
#include "pedesis/setup/run_config.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace pedesis {

// The current state as plain arrays in tag order (row k is the particle of tag k), with
// three components per vector whatever the dimension (z = 0 in 2D).
struct FrameArrays {
    int dimension = 2;
    double time = 0.0;
    std::uint64_t step = 0;
    std::array<double, 3> box{};
    std::array<bool, 3> periodic{true, true, true}; // per axis; false: walls
    std::vector<std::string> species;               // names, by species index
    std::vector<std::uint32_t> type;                // species index per particle
    std::vector<double> position;                   // 3 per particle
    std::vector<double> velocity;                   // 3 per particle
    std::vector<double> radius;                     // per particle
    std::vector<double> mass;                       // per particle (inf: fixed obstacle)
    std::vector<double> director;                   // 3 per particle; empty without directors
    std::vector<std::int32_t> image;                // 3 per particle; zero where not counted
};

class Run {
  public:
    virtual ~Run() = default;

    virtual int dimension() const = 0;
    virtual std::uint64_t step() const = 0;
    virtual double time() const = 0;
    // Whether the engine counts time steps (the event engine does not).
    virtual bool has_steps() const = 0;

    // As Simulation: the whole run; or open / advance / close step by step.
    virtual void run() = 0;
    virtual const char* advance(std::uint64_t max_step = std::numeric_limits<std::uint64_t>::max(),
                                double max_time = std::numeric_limits<double>::infinity()) = 0;
    virtual void close(const char* ended_by) = 0;
    virtual bool closed() const = 0;
    virtual const char* stopped_by() const = 0;

    virtual void add_operation(Trigger trigger, std::function<void()> act) = 0;
    // A trajectory file of the script's own (format "gsd" or "xyz") that gets a frame
    // whenever `trigger` fires; committed when the run closes or fails.
    virtual void add_trajectory(const std::filesystem::path& path, const std::string& format,
                                Trigger trigger) = 0;

    virtual const std::vector<std::string>& log_names() const = 0;
    virtual const std::vector<double>& last_log_row() const = 0;
    virtual FrameArrays frame() = 0;

    // The parameters that may change between steps, and a change from the next step on
    // (RunEngine::steerable, steer; run/steering.hpp records and replays them).
    virtual std::vector<std::pair<std::string, double>> steerable() const = 0;
    virtual void steer(const std::string& name, double value) = 0;
};

// Throws InputError for a config the engine refuses (before any file is written).
std::unique_ptr<Run> make_run(const RunConfig& config, const RunOptions& options,
                              std::ostream& console);

} // namespace pedesis
