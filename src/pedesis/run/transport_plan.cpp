#include "pedesis/run/transport_plan.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/observe/theory.hpp"
#include "pedesis/observe/thermo.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pedesis {

namespace {

// The Enskog mean free time of the particles as they start (number-weighted mean
// diameter and mass: a sampling scale, not a reference).
template <int D>
double mean_free_time(const ParticleStore<D>& p, const Box<D>& box, double contact) {
    double diameter = 0.0, mass = 0.0, kinetic = 0.0;
    std::size_t mobile = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (std::isinf(p.mass(i))) continue;
        diameter += 2.0 * p.radius(i);
        mass += p.mass(i);
        kinetic += 0.5 * p.mass(i) * norm2(p.velocity[i]);
        ++mobile;
    }
    if (mobile == 0) return 0.0;
    const auto n = static_cast<double>(mobile);
    const double T = 2.0 * kinetic / (D * n);
    if (!(T > 0.0)) return 0.0;
    const double sigma = contact > 0.0 ? contact : diameter / n;
    if (!(theory::packing_fraction(D, n / box.volume(), sigma) < 0.74)) return 0.0;
    const double rate = theory::enskog_collision_frequency(D, n / box.volume(), sigma, T, mass / n);
    return 1.0 / rate;
}

// A whole number (at least one) of steps, when there are steps.
double in_steps(double t, double step) {
    return step > 0.0 ? std::max(1.0, std::round(t / step)) * step : t;
}

} // namespace

template <int D>
TransportMeasurement<D> start_transport(const RunConfig& c, const ParticleStore<D>& p,
                                        const Box<D>& box, double start, double step,
                                        double contact, bool soft_heat) {
    const TransportConfig& t = c.transport;
    const std::string& where = t.where;
    if (box.any_wall())
        throw InputError(where + ": transport coefficients need a periodic box (the moments "
                                 "of walled axes are not defined): remove [box] boundary walls");
    if (c.growth_rate > 0.0)
        throw InputError(where + ": transport coefficients need a fluid at equilibrium: not "
                                 "with [event] growth_rate");
    double interval = 0.0, diffusion = 0.0;
    const double free = mean_free_time(p, box, contact);
    if (c.soft()) {
        interval = t.interval.value_or(20.0 * step);
        interval = in_steps(interval, step);
        diffusion = t.diffusion_interval.value_or(3.0 * interval);
    } else {
        if (!t.interval || !t.diffusion_interval) {
            if (!(free > 0.0 && std::isfinite(free)))
                throw InputError(where + ": the particles do not move (no mean free time to "
                                         "sample by): give interval and diffusion_interval");
        }
        interval = in_steps(t.interval.value_or(free / 5.0), step);
        diffusion = t.diffusion_interval.value_or(2.0 * free);
    }
    typename TransportMeasurement<D>::Plan plan;
    plan.start = start;
    plan.interval = interval;
    // (capped before the conversion: a block must hold 20 of them, which refuses the rest)
    plan.diffusion_every =
        static_cast<std::uint64_t>(std::clamp(std::round(diffusion / interval), 1.0, 1e12));
    if (t.block_time) {
        plan.block_time = *t.block_time;
    } else {
        std::optional<double> end = c.stop_time;
        if (c.soft() && c.steps > 0) end = static_cast<double>(c.steps) * c.dt;
        if (!end || !(*end > start))
            throw InputError(where +
                             ": give block_time: the run's length is not fixed by [run] "
                             "time" +
                             std::string(c.soft() ? " or steps" : ""));
        // whole samples of every moment, so that all the blocks fit in the run
        const double unit =
            interval * static_cast<double>(t.particles > 0 ? plan.diffusion_every : 1);
        plan.block_time =
            std::floor((*end - start) / static_cast<double>(t.blocks) / unit + 1e-9) * unit;
    }
    plan.particles = std::min<std::size_t>(static_cast<std::size_t>(t.particles), p.size());
    plan.heat = !c.soft() || soft_heat;
    plan.vacf = t.velocity_autocorrelation;
    plan.time_scale = std::isfinite(free) ? free : 0.0;
    return TransportMeasurement<D>(plan, where);
}

template <int D>
std::vector<std::uint32_t> followed_particles(const ParticleStore<D>& p, std::size_t count) {
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (p.tag[i] < count) out.push_back(static_cast<std::uint32_t>(i));
    return out;
}

template <int D>
typename TransportMeasurement<D>::Scales transport_scales(const RunConfig& c, const Box<D>& box,
                                                          const ParticleStore<D>& p,
                                                          double temperature) {
    typename TransportMeasurement<D>::Scales s;
    s.volume = box.volume();
    s.temperature = temperature;
    bool cube = true;
    for (int a = 1; a < D; ++a) cube = cube && box.length(a) == box.length(0);
    s.cube_edge = cube ? box.length(0) : 0.0;
    if (!c.soft() && p.species_table.size() == 1 && std::isfinite(p.species_table[0].mass)) {
        const auto& sp = p.species_table[0];
        s.enskog = theory::enskog_transport(D, static_cast<double>(p.size()) / s.volume,
                                            2.0 * sp.radius, sp.mass, temperature);
    }
    if (c.dynamics == "langevin")
        s.bulk_missing = "the Langevin thermostat's temperature fluctuations swamp the pressure's "
                         "(measure the bulk viscosity with nve dynamics)";
    if (c.soft())
        s.heat_missing = "the heat flux of soft particles is measured with nve dynamics and pair "
                         "forces only (no walls, fields or active forces), on one process on the "
                         "CPU";
    return s;
}

template TransportMeasurement<2> start_transport(const RunConfig&, const ParticleStore<2>&,
                                                 const Box<2>&, double, double, double, bool);
template TransportMeasurement<3> start_transport(const RunConfig&, const ParticleStore<3>&,
                                                 const Box<3>&, double, double, double, bool);
template std::vector<std::uint32_t> followed_particles(const ParticleStore<2>&, std::size_t);
template std::vector<std::uint32_t> followed_particles(const ParticleStore<3>&, std::size_t);
template TransportMeasurement<2>::Scales transport_scales(const RunConfig&, const Box<2>&,
                                                          const ParticleStore<2>&, double);
template TransportMeasurement<3>::Scales transport_scales(const RunConfig&, const Box<3>&,
                                                          const ParticleStore<3>&, double);

} // namespace pedesis
