#pragma once
// FIRE energy minimisation (dynamics = "minimize"): FIRE 2.0 of Guenole et al. (Comput.
// Mater. Sci. 175, 109584 (2020), algorithm 2, semi-implicit Euler) after Bitzek et al.
// (Phys. Rev. Lett. 97, 170201 (2006)), as HOOMD-blue's FIRE and LAMMPS' min_style fire.
// Each step, with P = F . v over the whole system:
//   P > 0:  after n_delay such steps in a row, dt = min(f_inc dt, dt_max), alpha *= f_alpha
//   P <= 0: dt = f_dec dt (not below dt_min, and not in the first n_delay steps),
//           alpha = alpha_start, the half step back x -= dt v / 2, and v = 0
//   then    v += dt F;  v = (1 - alpha) v + alpha |v| F / |F|;  x += dt v
// with unit masses, so that the path does not depend on the species' masses (a minimum
// does not either; LAMMPS' FIRE divides by each atom's mass). A particle of infinite mass
// is a fixed obstacle and is left out of every sum. No particle moves further than
// max_move in one step (LAMMPS' dmax), the half step back included: the whole move is
// shortened for all, so that a large dt never jumps a particle past a neighbour or
// further than the neighbour list's skin, whose rebuild check then sees every step's
// moves.
//
// It is an integrator of the evolver, which computes the forces between pre-step and
// post-step and keeps the neighbour list, the wrap and the sorting as for any dynamics.
// The sums over particles go block by block in a fixed order, so that the path does not
// depend on the thread count.
#include "pedesis/core/error.hpp"
#include "pedesis/soft/fire_params.hpp"
#include "pedesis/soft/plugins.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace pedesis {

template <int D> class FireMinimizer final : public Integrator<D> {
  public:
    explicit FireMinimizer(const FireParams& p) : p_(p), dt_(p.dt_start), alpha_(p.alpha_start) {}

    std::string name() const override { return "fire"; }
    bool needs_initial_forces() const override { return true; }
    // Its velocities are the descent's, not thermal: the logged pressure has no kinetic
    // part, as an overdamped run's at a bath temperature of 0.
    bool overdamped_positions() const override { return true; }
    double bath_temperature(std::size_t, std::size_t) const override { return 0.0; }

    // FIRE starts at rest.
    void start(SoftState<D>& s) {
        for (auto& v : s.p.velocity) v = Vec<D>{};
    }

    void prestep(SoftState<D>& s, double, double max_move) override {
        tabulate_mobile(s);
        const double cap = std::min(p_.max_move, max_move);
        ++iteration_;
        Vec<D>* vel = s.p.velocity.data();
        const Vec<D>* force = s.force.data();
        const Sums now = sums(s, [&](std::size_t i, Sums& t) {
            t.a += dot(force[i], vel[i]);
            t.max = std::max(t.max, norm2(vel[i]));
        });
        double back = 0.0; // the longest move of the half step back
        if (now.a > 0.0) {
            ++since_uphill_;
            if (since_uphill_ > p_.n_delay) {
                dt_ = std::min(dt_ * p_.f_inc, p_.dt_max);
                alpha_ *= p_.f_alpha;
            }
        } else {
            since_uphill_ = 0;
            if (!(p_.initial_delay && iteration_ < p_.n_delay)) {
                if (dt_ * p_.f_dec >= p_.dt_min) dt_ *= p_.f_dec;
                alpha_ = p_.alpha_start;
            }
            // (at most half the step's move: the step below takes the rest)
            back = move(s, -0.5 * dt_, std::sqrt(now.max), 0.5 * cap);
            for (std::size_t i = 0; i < s.owned(); ++i) vel[i] = Vec<D>{};
        }
        // semi-implicit Euler: the velocity first, then the mixing, then the positions
        const Sums kicked = sums(s, [&](std::size_t i, Sums& t) {
            vel[i] += dt_ * force[i];
            t.a += norm2(vel[i]);
            t.b += norm2(force[i]);
        });
        const bool mix = kicked.b > 0.0;
        const double keep = 1.0 - alpha_;
        const double turn = mix ? alpha_ * std::sqrt(kicked.a / kicked.b) : 0.0;
        const Sums mixed = sums(s, [&](std::size_t i, Sums& t) {
            if (mix) vel[i] = keep * vel[i] + turn * force[i];
            t.max = std::max(t.max, norm2(vel[i]));
        });
        move(s, dt_, std::sqrt(mixed.max), cap - back);
    }

    void poststep(SoftState<D>& s, double, double) override { measure(s); }

    // The largest force and the force norm of the current forces (the run calls it once
    // at the start; every post-step after that).
    void measure(const SoftState<D>& s) {
        tabulate_mobile(s);
        const Vec<D>* force = s.force.data();
        const Sums f = sums(s, [&](std::size_t i, Sums& t) {
            const double f2 = norm2(force[i]);
            t.a += f2;
            t.max = std::max(t.max, f2);
        });
        if (!std::isfinite(f.a))
            throw RunError(fmt::format("FIRE minimisation at step {}: the forces are not finite "
                                       "(particles placed on top of each other, or a potential "
                                       "without a core pushed through): check the start",
                                       s.step));
        max_force_ = std::sqrt(f.max);
        force_norm_ = std::sqrt(f.a);
    }

    // Whether the energy `e` of the current positions differs from the last one given by
    // at most energy_tolerance, relative (LAMMPS' etol), once n_delay downhill steps have
    // passed since the last uphill one (as LAMMPS' FIRE checks it).
    bool energy_settled(double e) {
        const bool settled = have_energy_ && since_uphill_ > p_.n_delay &&
                             std::abs(e - last_energy_) <=
                                 p_.energy_tolerance * 0.5 * (std::abs(e) + std::abs(last_energy_));
        last_energy_ = e;
        have_energy_ = true;
        return settled;
    }

    bool forces_converged() const { return max_force_ < p_.force_tolerance; }
    double max_force() const { return max_force_; }
    double force_norm() const { return force_norm_; }
    double dt() const { return dt_; }
    double alpha() const { return alpha_; }
    const FireParams& params() const { return p_; }

  private:
    struct Sums {
        double a = 0.0, b = 0.0, max = 0.0;
    };

    // item(i, sums) over the mobile particles, in blocks of a fixed size summed in order.
    template <class Item> Sums sums(const SoftState<D>& s, Item&& item) {
        constexpr std::size_t block = 4096;
        const std::size_t n = s.owned();
        const auto blocks = static_cast<std::int64_t>((n + block - 1) / block);
        partial_.assign(static_cast<std::size_t>(blocks), Sums{});
        const std::uint16_t* sp = s.p.species.data();
#pragma omp parallel for schedule(static) if (blocks > 1)
        for (std::int64_t b = 0; b < blocks; ++b) {
            Sums& t = partial_[static_cast<std::size_t>(b)];
            const std::size_t last = std::min(n, static_cast<std::size_t>(b + 1) * block);
            for (std::size_t i = static_cast<std::size_t>(b) * block; i < last; ++i)
                if (mobile_[sp[i]]) item(i, t);
        }
        Sums total;
        for (const Sums& t : partial_) {
            total.a += t.a;
            total.b += t.b;
            total.max = std::max(total.max, t.max);
        }
        return total;
    }

    // x += h v, shortened for every particle alike when the fastest would move further
    // than cap; the longest move made.
    double move(SoftState<D>& s, double h, double fastest, double cap) {
        const double longest = std::abs(h) * fastest;
        if (!(longest > 0.0)) return 0.0;
        const double step = longest > cap ? h * (cap / longest) : h;
        Vec<D>* pos = s.p.position.data();
        const Vec<D>* vel = s.p.velocity.data();
        sums(s, [&](std::size_t i, Sums&) { pos[i] += step * vel[i]; });
        return std::min(longest, cap);
    }

    void tabulate_mobile(const SoftState<D>& s) {
        const auto& table = s.p.species_table;
        mobile_.resize(table.size());
        for (std::size_t k = 0; k < table.size(); ++k) mobile_[k] = std::isfinite(table[k].mass);
    }

    FireParams p_;
    double dt_, alpha_;
    std::uint64_t iteration_ = 0;
    std::uint64_t since_uphill_ = 0; // steps with P > 0 in a row
    // (none measured yet: not converged)
    double max_force_ = HUGE_VAL, force_norm_ = HUGE_VAL;
    double last_energy_ = 0.0;
    bool have_energy_ = false;
    std::vector<char> mobile_; // per species
    std::vector<Sums> partial_;
};

} // namespace pedesis
