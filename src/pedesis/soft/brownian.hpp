#pragma once
// Overdamped integrators of the ABP tutorial, Euler-Maruyama:
//   brownian:          r += dt F / gamma + sqrt(2 T dt / gamma) xi
//   brownian_rotation: theta += dt tau / gamma + sqrt(2 T dt / gamma) xi  (2D),
//                      n += dt (tau x n) / gamma + sqrt(2 D_r dt) (xi x n), renormalised (3D)
// with D = T / gamma. The noise of particle i at step s is drawn from Philox keyed by
// (seed, stream, tag, s): the trajectory does not depend on thread count or storage order.
#include "pedesis/core/error.hpp"
#include "pedesis/core/rng.hpp"
#include "pedesis/soft/plugins.hpp"
#include "pedesis/soft/polar_align.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace pedesis {

namespace detail {
// Lowest storage index whose move was not finite or exceeded max_move; the caller throws.
template <int D>
[[noreturn]] inline void throw_bad_move(const SoftState<D>& s, std::size_t i, const Vec<D>& move,
                                        double max_move, const std::string& who) {
    std::ostringstream m;
    m << who << ": at step " << s.step << " particle " << s.p.tag[i];
    if (!all_finite(move))
        m << " got a non-finite displacement (the run blew up)";
    else
        m << " moved " << norm(move) << " in one step, more than " << max_move
          << " (the neighbour-list skin); reduce dt";
    throw RunError(m.str());
}
} // namespace detail

template <int D> class BrownianIntegrator final : public Integrator<D> {
  public:
    BrownianIntegrator(double T, double gamma, std::uint64_t seed)
        : T_(T), gamma_(gamma), seed_(seed) {}
    std::string name() const override { return "brownian"; }
    double temperature() const { return T_; }
    double gamma() const { return gamma_; }

    void poststep(SoftState<D>& s, double dt, double max_move) override {
        const double drift = dt / gamma_;
        const double kick = std::sqrt(2.0 * T_ * dt / gamma_);
        const auto n = static_cast<std::int64_t>(s.size());
        const auto step = static_cast<std::uint32_t>(s.step);
        const double max2 = max_move * max_move;
        std::int64_t bad = std::numeric_limits<std::int64_t>::max();
#pragma omp parallel for schedule(static) reduction(min : bad)
        for (std::int64_t i = 0; i < n; ++i) {
            Vec<D> move = drift * s.force[i];
            if (kick > 0.0) {
                CounterRng rng(seed_, RngStream::thermostat, s.p.tag[i], step);
                for (int a = 0; a < D; ++a) move[a] += kick * rng.normal();
            }
            if (!(norm2(move) <= max2)) bad = std::min(bad, i);
            s.p.position[i] += move;
            s.p.velocity[i] = move * (1.0 / dt);
        }
        if (bad != std::numeric_limits<std::int64_t>::max()) {
            const auto i = static_cast<std::size_t>(bad);
            detail::throw_bad_move(s, i, s.p.velocity[i] * dt, max_move, name());
        }
    }

  private:
    double T_, gamma_;
    std::uint64_t seed_;
};

template <int D> class BrownianRotationIntegrator final : public Integrator<D> {
  public:
    BrownianRotationIntegrator(double T, double gamma, std::uint64_t seed)
        : T_(T), gamma_(gamma), seed_(seed) {}
    std::string name() const override { return "brownian_rotation"; }
    double rotational_diffusion() const { return T_ / gamma_; }

    void poststep(SoftState<D>& s, double dt, double) override {
        const double drift = dt / gamma_;
        const double kick = std::sqrt(2.0 * T_ * dt / gamma_);
        const auto n = static_cast<std::int64_t>(s.size());
        const auto step = static_cast<std::uint32_t>(s.step);
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i) {
            CounterRng rng(seed_, RngStream::orientation, s.p.tag[i], step);
            Vec<D>& d = s.director[i];
            if constexpr (D == 2) {
                double dtheta = drift * s.torque[i][0];
                if (kick > 0.0) dtheta += kick * rng.normal();
                const double c = std::cos(dtheta), sn = std::sin(dtheta);
                d = Vec<D>{{c * d[0] - sn * d[1], sn * d[0] + c * d[1]}};
            } else {
                Vec<D> w = drift * s.torque[i]; // angular displacement
                if (kick > 0.0)
                    for (int a = 0; a < D; ++a) w[a] += kick * rng.normal();
                d += cross(w, d);
                d *= 1.0 / norm(d);
            }
        }
    }

  private:
    double T_, gamma_;
    std::uint64_t seed_;
};

} // namespace pedesis
