#pragma once
// Walls for soft particles: the two faces of each walled axis of the box ("planes"), or
// a spherical (2D: circular) or cylindrical container. A particle feels each wall
// surface through a one-body potential of its distance h from the surface, along the
// surface's normal (the walls of LAMMPS' fix wall/lj93 and wall/harmonic, HOOMD-blue's
// wall potentials):
//   wca:      U = 4 eps [(s/h)^12 - (s/h)^6] + eps          for h < 2^(1/6) s
//   lj93:     U = eps [2/15 (s/h)^9 - (s/h)^3] - U(h_c)      for h < h_c = cutoff s
//   harmonic: U = k (s - h)^2 / 2                            for h < s
// s is per species, by default the species' radius (the particle's surface touches the
// wall at h = s). The force the particles exert back on each wall is what the log's
// wall_pressure_* columns report (per area: the mechanical pressure of an active gas
// is a property of the wall, Solon et al. 2015).
// With `torque` = c != 0 the wall also turns a particle's director towards the force it
// exerts on the particle: tau_i = c n_i x F_i (c > 0 turns swimmers away from the wall).
#include "pedesis/core/chunk_shares.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/soft/per_species.hpp"
#include "pedesis/soft/plugins.hpp"
#include "pedesis/soft/polar_align.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace pedesis {

enum class WallPotential { wca, lj93, harmonic };
enum class WallShape { planes, sphere, cylinder };

// One species' law: the force pushing the particle away from the wall (along the
// normal into the allowed region) and the energy at distance h.
struct WallLaw {
    WallPotential potential = WallPotential::wca;
    double epsilon = 1.0, sigma = 1.0, k = 0.0, reach = 0.0, shift = 0.0;

    static WallLaw make(WallPotential p, double epsilon, double sigma, double k, double cutoff) {
        WallLaw w{p, epsilon, sigma, k, 0.0, 0.0};
        switch (p) {
        case WallPotential::wca:
            w.reach = std::pow(2.0, 1.0 / 6.0) * sigma;
            break;
        case WallPotential::lj93: // (shifted: the energy is continuous at the cutoff)
            w.reach = cutoff * sigma;
            w.shift = w.raw_lj93(w.reach);
            break;
        case WallPotential::harmonic:
            w.reach = sigma;
            break;
        }
        return w;
    }

    double raw_lj93(double h) const {
        const double s3 = std::pow(sigma / h, 3);
        return epsilon * (2.0 / 15.0 * s3 * s3 * s3 - s3);
    }

    // False beyond the reach. A particle on or through a wca / lj93 wall (h <= 0) gets the
    // force of h = 1e-6 s: large enough that the integrator reports a blow-up there.
    bool eval(double h, double& force, double& energy) const {
        if (!(h < reach)) return false;
        switch (potential) {
        case WallPotential::wca: {
            const double hh = std::max(h, 1e-6 * sigma);
            const double s2 = sigma * sigma / (hh * hh);
            const double s6 = s2 * s2 * s2;
            force = 24.0 * epsilon * (2.0 * s6 * s6 - s6) / hh;
            energy = 4.0 * epsilon * (s6 * s6 - s6) + epsilon;
            return true;
        }
        case WallPotential::lj93: {
            const double hh = std::max(h, 1e-6 * sigma);
            const double s3 = std::pow(sigma / hh, 3);
            const double s9 = s3 * s3 * s3;
            force = epsilon * (1.2 * s9 - 3.0 * s3) / hh;
            energy = epsilon * (2.0 / 15.0 * s9 - s3) - shift;
            return true;
        }
        case WallPotential::harmonic:
            force = k * (sigma - h);
            energy = 0.5 * k * (sigma - h) * (sigma - h);
            return true;
        }
        return false;
    }
};

template <int D> class WallForce final : public ForceTerm<D> {
  public:
    struct Shape {
        WallShape kind = WallShape::planes;
        double radius = 0.0; // container
        Vec<D> centre{};     // container
        int axis = D - 1;    // cylinder
    };

    // sigma: per species, or empty for the species' radii; epsilon and k per species.
    WallForce(WallPotential potential, Shape shape, PerSpecies epsilon,
              std::optional<PerSpecies> sigma, PerSpecies k, double cutoff, double torque)
        : potential_(potential), shape_(shape), epsilon_(std::move(epsilon)),
          sigma_(std::move(sigma)), k_(std::move(k)), cutoff_(cutoff), torque_(torque) {
        if (shape_.kind == WallShape::cylinder && D == 2)
            throw InputError("wall: a cylinder needs a 3D box (a 2D container is shape = "
                             "\"sphere\", a circle; a channel is walls on one axis)");
    }

    std::string name() const override { return "wall"; }
    WallShape shape() const { return shape_.kind; }

    void add_forces(SoftState<D>& s, const NeighborList<D>&) const override {
        // (the config reader says so at set-up; a program that builds its own evolver
        // learns it here, at the first step, rather than from particles that never stop)
        if (shape_.kind == WallShape::planes && !s.box.any_wall())
            throw InputError("wall: shape \"planes\" stands on the box's walled faces, and "
                             "every axis of this box is periodic: wall an axis, or give the "
                             "wall shape = \"sphere\" or \"cylinder\"");
        tabulate(s);
        const WallLaw* law = laws_.data();
        const std::uint16_t* sp = s.p.species.data();
        const double c = torque_;
        const auto n = static_cast<std::int64_t>(s.owned());
        parallel_for_each_index(n, s.thread_shares, [&](std::int64_t i) {
            for_each_contact(s, law[sp[i]], static_cast<std::size_t>(i),
                             [&](int, const Vec<D>& normal, double f, double) {
                                 const Vec<D> push = f * normal;
                                 s.force[i] += push;
                                 if (c != 0.0) s.torque[i] += c * cross(s.director[i], push);
                             });
        });
    }

    void add_totals(const SoftState<D>& s, const NeighborList<D>&, PairTotals& t) const override {
        tabulate(s);
        for (std::size_t i = 0; i < s.owned(); ++i)
            for_each_contact(s, laws_[s.p.species[i]], i,
                             [&](int, const Vec<D>&, double, double u) { t.energy += u; });
    }

    std::vector<std::string> log_columns(const SoftState<D>& s) const override {
        static constexpr const char* axis_names[] = {"x", "y", "z"};
        std::vector<std::string> c;
        if (shape_.kind == WallShape::sphere) return {"wall_pressure_sphere"};
        if (shape_.kind == WallShape::cylinder) return {"wall_pressure_cylinder"};
        for (int a = 0; a < D; ++a)
            if (!s.box.periodic(a)) c.push_back(std::string("wall_pressure_") + axis_names[a]);
        return c;
    }

    // Planes: per walled axis, (|F_lo| + |F_hi|) / (2 A); a container: |F| / A, its area.
    void log_values(const SoftState<D>& s, std::vector<double>& out) const override {
        tabulate(s);
        std::array<double, D> push{};
        for (std::size_t i = 0; i < s.owned(); ++i)
            for_each_contact(s, laws_[s.p.species[i]], i,
                             [&](int slot, const Vec<D>&, double f, double) { push[slot] += f; });
        if (shape_.kind != WallShape::planes) {
            out.push_back(push[0] / container_area(s.box));
            return;
        }
        for (int a = 0; a < D; ++a)
            if (!s.box.periodic(a))
                out.push_back(push[a] / (2.0 * s.box.volume() / s.box.length(a)));
    }

    // The first particle (storage index) on or beyond a wca or lj93 wall (h <= 0), which
    // such a wall cannot push back, or -1 (a harmonic wall pulls every particle back).
    std::int64_t first_outside(const SoftState<D>& s) const {
        if (potential_ == WallPotential::harmonic) return -1;
        for (std::size_t i = 0; i < s.owned(); ++i) {
            const Vec<D>& r = s.p.position[i];
            if (shape_.kind == WallShape::planes) {
                for (int a = 0; a < D; ++a)
                    if (!s.box.periodic(a) && !(r[a] > s.box.lo(a) && r[a] < s.box.hi(a)))
                        return static_cast<std::int64_t>(i);
                continue;
            }
            if (!(radial(s, r) < shape_.radius)) return static_cast<std::int64_t>(i);
        }
        return -1;
    }

    // The particle that starts deepest inside a wca or lj93 wall's core (closer than the
    // distance where its energy passes eps: sigma for wca, (2/15)^(1/6) sigma, its zero,
    // for lj93), relative to that distance.
    std::string start_overlap(const SoftState<D>& s) const override {
        if (potential_ == WallPotential::harmonic) return {};
        tabulate(s);
        const double core_fraction =
            potential_ == WallPotential::wca ? 1.0 : std::pow(2.0 / 15.0, 1.0 / 6.0);
        double deepest = 1.0, distance = 0.0, core = 0.0;
        std::size_t who = 0;
        for (std::size_t i = 0; i < s.owned(); ++i) {
            const double c = core_fraction * laws_[s.p.species[i]].sigma;
            const double h = nearest_wall(s, s.p.position[i]);
            if (h / c < deepest) {
                deepest = h / c;
                distance = h;
                core = c;
                who = i;
            }
        }
        if (deepest >= 1.0) return {};
        return "Particle " + std::to_string(s.p.tag[who]) + " began " + short_number(distance) +
               " from a wall, inside the " + potential_name() + " wall's core (" +
               short_number(core) +
               "): place the particles at least that far from the walls (a [[species]] "
               "region), or give the wall a smaller sigma";
    }

  private:
    static std::string short_number(double x) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3g", x);
        return text;
    }
    std::string potential_name() const {
        return potential_ == WallPotential::wca    ? "wca"
               : potential_ == WallPotential::lj93 ? "lj93"
                                                   : "harmonic";
    }
    // The distance from position r to the nearest wall surface of this force.
    double nearest_wall(const SoftState<D>& s, const Vec<D>& r) const {
        double h = std::numeric_limits<double>::infinity();
        if (shape_.kind == WallShape::planes) {
            for (int a = 0; a < D; ++a)
                if (!s.box.periodic(a)) h = std::min({h, r[a] - s.box.lo(a), s.box.hi(a) - r[a]});
            return h;
        }
        return shape_.radius - radial(s, r);
    }

    // A container's outward displacement of position r from its centre (or axis).
    Vec<D> radial_vector(const SoftState<D>& s, const Vec<D>& r) const {
        Vec<D> d = s.box.minimum_image(r - shape_.centre);
        if (shape_.kind == WallShape::cylinder) d[shape_.axis] = 0.0;
        return d;
    }
    double radial(const SoftState<D>& s, const Vec<D>& r) const {
        return norm(radial_vector(s, r));
    }

    // Calls f(slot, normal, force, energy) for each wall within reach of particle i:
    // normal the unit vector into the allowed region, slot the log's (the axis for
    // planes, 0 for a container).
    template <class F>
    void for_each_contact(const SoftState<D>& s, const WallLaw& law, std::size_t i, F&& f) const {
        const Vec<D>& r = s.p.position[i];
        double force, energy;
        if (shape_.kind == WallShape::planes) {
            for (int a = 0; a < D; ++a) {
                if (s.box.periodic(a)) continue;
                Vec<D> normal{};
                normal[a] = 1.0;
                if (law.eval(r[a] - s.box.lo(a), force, energy)) f(a, normal, force, energy);
                normal[a] = -1.0;
                if (law.eval(s.box.hi(a) - r[a], force, energy)) f(a, normal, force, energy);
            }
            return;
        }
        const Vec<D> d = radial_vector(s, r);
        const double rho = norm(d);
        if (!law.eval(shape_.radius - rho, force, energy)) return;
        Vec<D> inward{};
        if (rho > 0.0)
            inward = d * (-1.0 / rho);
        else
            inward[0] = -1.0; // (at the centre a wall within reach pushes every way alike)
        f(0, inward, force, energy);
    }

    double container_area(const Box<D>& box) const {
        const double R = shape_.radius;
        if (shape_.kind == WallShape::cylinder)
            return 2.0 * std::numbers::pi * R * box.length(shape_.axis);
        return D == 2 ? 2.0 * std::numbers::pi * R : 4.0 * std::numbers::pi * R * R;
    }

    void tabulate(const SoftState<D>& s) const {
        const auto& table = s.p.species_table;
        const std::size_t n = table.size();
        laws_.resize(n);
        for (std::size_t a = 0; a < n; ++a) {
            const double sigma = sigma_ ? sigma_->at(a, n) : table[a].radius;
            laws_[a] = WallLaw::make(potential_, epsilon_.at(a, n), sigma, k_.at(a, n), cutoff_);
        }
    }

    WallPotential potential_;
    Shape shape_;
    PerSpecies epsilon_;
    std::optional<PerSpecies> sigma_;
    PerSpecies k_;
    double cutoff_;
    double torque_;
    mutable std::vector<WallLaw> laws_; // per species, remade from the parameters each call
};

} // namespace pedesis
