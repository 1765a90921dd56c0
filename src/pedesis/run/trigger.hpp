#pragma once
// When an operation of a run is due: every N steps, or every dt of simulated time, on a
// grid anchored at step 0 / t = 0 (so a restarted run keeps the grid of the run it
// continues), or never.
#include <cmath>
#include <cstdint>
#include <limits>

namespace pedesis {

class Trigger {
  public:
    static Trigger never() { return Trigger{}; }
    static Trigger every_steps(std::uint64_t n) {
        Trigger t;
        t.steps_ = n;
        return t;
    }
    static Trigger every_time(double interval) {
        Trigger t;
        t.interval_ = interval;
        return t;
    }

    bool active() const { return steps_ > 0 || interval_ > 0.0; }

    // Places the next firing after (step, time): called at the start and after each firing.
    void schedule(std::uint64_t step, double time) {
        if (steps_ > 0) next_step_ = (step / steps_ + 1) * steps_;
        if (interval_ > 0.0) next_time_ = next_multiple(time, interval_);
    }

    // A time within rounding of a grid point belongs to it: a stepped engine's time is
    // k dt, which lands on a multiple of the interval only up to rounding.
    bool due(std::uint64_t step, double time) const {
        if (steps_ > 0) return step >= next_step_;
        if (interval_ > 0.0) return time >= next_time_ - 1e-9 * interval_;
        return false;
    }

    // The targets the engine must not run past (the largest values when none).
    std::uint64_t next_step() const {
        return steps_ > 0 ? next_step_ : std::numeric_limits<std::uint64_t>::max();
    }
    double next_time() const {
        return interval_ > 0.0 ? next_time_ : std::numeric_limits<double>::infinity();
    }

    // The first multiple of `interval` after t (a grid anchored at t = 0).
    static double next_multiple(double t, double interval) {
        return (std::floor(t / interval + 1e-9) + 1.0) * interval;
    }

  private:
    Trigger() = default;
    std::uint64_t steps_ = 0;
    double interval_ = 0.0;
    std::uint64_t next_step_ = std::numeric_limits<std::uint64_t>::max();
    double next_time_ = std::numeric_limits<double>::infinity();
};

} // namespace pedesis
