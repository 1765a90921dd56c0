#pragma once
// Counter-based random numbers (Philox4x32-10 from Random123). A draw is a pure
// function of (seed, stream, tag, counter), so results do not depend on thread
// count or particle order.
#include <Random123/philox.h>
#include <Random123/uniform.hpp>

#include "pedesis/core/sincos.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace pedesis {

enum class RngStream : std::uint32_t {
    placement = 1,
    velocity = 2,
    orientation = 3,
    thermostat = 4,
    initial_director = 5,
    active_velocity = 6, // active_ou's p: its stationary start and its noise
    tumble = 7,          // run_and_tumble: whether and where to
    andersen = 20,       // the event engine's Andersen thermostat (event/event_driving.cpp)
    white_noise = 21,    // the event engine's white-noise kicks
};

class CounterRng {
  public:
    CounterRng(std::uint64_t seed, RngStream stream, std::uint32_t tag, std::uint32_t step = 0)
        : key_{{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)}},
          ctr_{{tag, step, static_cast<std::uint32_t>(stream), 0u}} {}

    // uniform in (0, 1]
    double uniform() {
        if (used_ == 2) refill();
        const std::uint64_t hi = out_[2 * used_], lo = out_[2 * used_ + 1];
        ++used_;
        const std::uint64_t bits = ((hi << 32) | lo) >> 11; // 53 random bits
        return (static_cast<double>(bits) + 1.0) * 0x1.0p-53;
    }
    double uniform(double a, double b) { return a + (b - a) * uniform(); }

    // Standard normal by Box-Muller; keeps the second value for the next call.
    double normal() {
        if (has_spare_) {
            has_spare_ = false;
            return spare_;
        }
        const double u1 = uniform(), u2 = uniform();
        const double r = std::sqrt(-2.0 * std::log(u1));
        spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
        has_spare_ = true;
        return r * std::cos(2.0 * std::numbers::pi * u2);
    }

  private:
    using Philox = r123::Philox4x32;
    void refill() {
        out_ = Philox()(ctr_, key_);
        ctr_[3]++;
        used_ = 0;
    }
    Philox::key_type key_;
    Philox::ctr_type ctr_;
    Philox::ctr_type out_{};
    int used_ = 2;
    bool has_spare_ = false;
    double spare_ = 0.0;
};

} // namespace pedesis
