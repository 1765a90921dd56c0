#pragma once
// An engine that a script's own driver runs through the loop without a run directory
// (the Python module's Evolver.run and Gas.run): nothing is logged, framed or
// checkpointed, so only the clock, advance and frame are its own.
#include "pedesis/run/run_engine.hpp"

#include <stdexcept>

namespace pedesis {

template <int D> class ScriptEngine : public RunEngine<D> {
  public:
    std::uint64_t frames() const override { return 0; }
    void frame_written() override {}
    void save_checkpoint(const std::filesystem::path&) override {
        throw std::logic_error("an engine run without a run directory has no checkpoint");
    }
    std::vector<const char*> stale_results() const override { return {}; }
    std::vector<std::string> log_columns() const override { return {}; }
    void measure(std::vector<double>&) override {}
    void start(bool) override {}
    nlohmann::json summary(const char*) override { return {}; }
    void finish(const nlohmann::json&) override {}
};

} // namespace pedesis
