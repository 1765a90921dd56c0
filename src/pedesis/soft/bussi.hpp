#pragma once
// Stochastic velocity rescaling (the `bussi` integrator; Bussi, Donadio & Parrinello,
// J. Chem. Phys. 126, 014101, 2007): velocity Verlet with, over each thermostat
// half-step h (nvt_thermostat.hpp), the thermal kinetic energy K taken to the exact
// solution K' of
//   dK = (Kbar - K) dt / tau + 2 sqrt(K Kbar / f) dW / sqrt(tau),   Kbar = f T / 2,
// which with c = exp(-h / tau) is (the paper's appendix, eq. A7)
//   K' = (sqrt(c K) + sqrt((1 - c) Kbar / f) R1)^2 + (1 - c) (Kbar / f) S,
// R1 a standard normal and S a chi-square of f - 1 degrees of freedom (the sum of f - 1
// squared normals), drawn exactly as 2 Gamma((f - 1) / 2). The velocities are scaled by
// alpha = sgn(sqrt(c K) + sqrt((1 - c) Kbar / f) R1) sqrt(K' / K), and the canonical
// distribution of K (a Gamma of shape f / 2 and scale T) is stationary for any tau and
// h. The energy given to the particles, K' - K, is taken from the bath: bath_energy() is
// minus its sum, and K + U + bath_energy() is conserved up to the Verlet error.
//
// The draws of step s, half-step j come from Philox keyed by (seed, thermostat stream,
// j, s): the same for every thread count and after a restart. (The stream is Langevin's,
// with j in the place of a tag; the two are never in one run.)
#include "pedesis/core/rng.hpp"
#include "pedesis/soft/nvt_thermostat.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

namespace pedesis {

namespace detail {

// Gamma(a, 1) for a >= 1 by Marsaglia & Tsang (ACM TOMS 26, 363, 2000): a rejection
// method whose acceptance is above 95% for every such a.
inline double gamma_variate(double a, CounterRng& rng) {
    const double d = a - 1.0 / 3.0, c = 1.0 / std::sqrt(9.0 * d);
    for (;;) {
        const double x = rng.normal();
        double v = 1.0 + c * x;
        if (v <= 0.0) continue;
        v = v * v * v;
        const double u = rng.uniform();
        const double x2 = x * x;
        if (u < 1.0 - 0.0331 * x2 * x2) return d * v;
        if (std::log(u) < 0.5 * x2 + d * (1.0 - v + std::log(v))) return d * v;
    }
}

// A chi-square variate of n degrees of freedom, the sum of n squared standard normals
// (Bussi's sumnoises): 2 Gamma(n / 2), with one squared normal for an odd n.
inline double chi_square_variate(std::uint64_t n, CounterRng& rng) {
    double sum = 0.0;
    if (n % 2 == 1) {
        const double z = rng.normal();
        sum = z * z;
        --n;
    }
    if (n > 0) sum += 2.0 * gamma_variate(0.5 * static_cast<double>(n), rng);
    return sum;
}

} // namespace detail

template <int D> class BussiIntegrator final : public NvtThermostat<D> {
  public:
    BussiIntegrator(double T, double tau, std::uint64_t seed)
        : NvtThermostat<D>("bussi", T, tau, true), seed_(seed) {}
    std::string name() const override { return "bussi"; }
    double bath_energy() const override { return bath_; }
    std::vector<double> saved_state() const override { return {bath_}; }
    void restore_state(const std::vector<double>& saved) override {
        if (saved.size() != 1 || !std::isfinite(saved[0]))
            throw InputError("the bussi thermostat's state is corrupt");
        bath_ = saved[0];
    }

  protected:
    double rescale_factor(const ThermalKinetics<D>& k, double h, std::uint64_t step,
                          int half) override {
        // nothing to scale: no free component, or every particle at rest (a start from
        // zero velocities gets its first kinetic energy from the forces)
        if (!(k.freedom >= 1.0) || !(k.energy > 0.0)) return 1.0;
        const double f = k.freedom, target = 0.5 * f * this->T_;
        const double c = std::exp(-h / this->tau_);
        CounterRng rng(seed_, RngStream::thermostat, static_cast<std::uint32_t>(half),
                       static_cast<std::uint32_t>(step));
        const double r1 = rng.normal();
        const double s =
            detail::chi_square_variate(static_cast<std::uint64_t>(std::llround(f)) - 1, rng);
        const double share = (1.0 - c) * target / f; // (1 - c) Kbar / f
        const double a = std::sqrt(c * k.energy) + std::sqrt(share) * r1;
        const double next = a * a + share * s;
        bath_ -= next - k.energy;
        const double alpha = std::sqrt(next / k.energy);
        return a < 0.0 ? -alpha : alpha;
    }

  private:
    std::uint64_t seed_;
    double bath_ = 0.0; // minus the kinetic energy the rescales have added
};

} // namespace pedesis
