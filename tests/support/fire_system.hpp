#pragma once
// A soft system minimised by FIRE as `pedesis run` sets it up for dynamics = "minimize"
// (the config's state, its [[force]] terms through the registry, FireMinimizer with its
// [minimize] parameters), for the FIRE tests (physics and validation), which then look
// at the state, its energy and its pressure directly.
#include "pedesis/setup/build_soft_state.hpp"
#include "pedesis/setup/run_config.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/fire.hpp"
#include "pedesis/soft/plugin_registry.hpp"

#include <cmath>
#include <memory>
#include <string>

namespace pedesis::test {

template <int D> struct FireSystem {
    explicit FireSystem(const std::string& toml)
        : config(parse_run_config(toml, "fire_test.toml", false)),
          state(build_soft_state<D>(config)) {
        start();
    }

    // A fresh evolver on the current state and box (after the box was changed), with
    // FIRE started anew.
    void start() {
        std::vector<Species> table;
        for (const auto& s : config.species) table.push_back({s.name, s.radius, s.mass});
        evolver = std::make_unique<Evolver<D>>(state, config.list_skin, config.list_r_cut);
        for (const auto& f : config.forces) add_plugin(*evolver, f, table, config.seed);
        auto fire = std::make_unique<FireMinimizer<D>>(config.minimize);
        fire_ = fire.get();
        fire_->start(state);
        evolver->add_integrator(std::move(fire));
        evolver->compute_forces();
        fire_->measure(state);
    }

    // FIRE steps until the force tolerance or `max_steps`; the steps taken.
    std::uint64_t minimise(std::uint64_t max_steps) {
        std::uint64_t k = 0;
        for (; k < max_steps && !fire_->forces_converged(); ++k) evolver->evolve(config.dt);
        return k;
    }

    // The box and the positions scaled by `factor` about the box's centre, the origin
    // (affine), and FIRE started anew.
    void scale(double factor) {
        std::array<bool, D> periodic{};
        for (int a = 0; a < D; ++a) periodic[a] = state.box.periodic(a);
        for (auto& r : state.p.position) r *= factor;
        state.box = Box<D>(state.box.lengths() * factor, periodic);
        start();
    }

    double energy() { return evolver->pair_totals().energy; }
    // The pair virial's pressure sum r_ij . F_ij / (d V): at rest, the whole pressure.
    double pressure() { return evolver->pair_totals().virial / (D * state.box.volume()); }
    double packing_fraction() const {
        double area = 0.0;
        for (std::size_t i = 0; i < state.size(); ++i) {
            const double r = state.p.species_table[state.p.species[i]].radius;
            area += D == 2 ? M_PI * r * r : 4.0 / 3.0 * M_PI * r * r * r;
        }
        return area / state.box.volume();
    }

    const FireMinimizer<D>& fire() const { return *fire_; }

    RunConfig config;
    SoftState<D> state;
    std::unique_ptr<Evolver<D>> evolver;

  private:
    FireMinimizer<D>* fire_ = nullptr;
};

} // namespace pedesis::test
