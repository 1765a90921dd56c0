#include "pedesis/setup/build_system.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/particle_file.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/setup/lattice.hpp"
#include "pedesis/setup/random_placement.hpp"
#include "pedesis/setup/velocities.hpp"
#include "pedesis/setup/wall_margins.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace pedesis {

namespace {

template <int D> Vec<D> to_vec(const std::vector<double>& v) {
    Vec<D> r;
    for (int a = 0; a < D; ++a) r[a] = v[static_cast<std::size_t>(a)];
    return r;
}

std::string species_label(const RunConfig& c, std::size_t s) {
    const std::string& at = c.species[s].location;
    return (at.empty() ? c.file : at) + ": species '" + c.species[s].name + "'";
}

// Region the centres of species s may occupy, and which of its axes are closed
// (bounded by a wall or by the edge of a sub-region rather than tiling periodically).
template <int D> struct CentreRegion {
    Vec<D> lo, hi;
    std::array<bool, D> closed{};
};

template <int D>
CentreRegion<D> centre_region(const RunConfig& c, const Box<D>& box, std::size_t s,
                              const WallMargins<D>& walls) {
    const SpeciesConfig& sp = c.species[s];
    CentreRegion<D> reg;
    for (int a = 0; a < D; ++a) {
        const auto ua = static_cast<std::size_t>(a);
        double lo = box.lo(a), hi = box.hi(a);
        if (sp.region_lo) {
            lo = std::max(lo, (*sp.region_lo)[ua]);
            hi = std::min(hi, (*sp.region_hi)[ua]);
        }
        const bool full = lo <= box.lo(a) && hi >= box.hi(a);
        reg.closed[a] = !(box.periodic(a) && full);
        if (reg.closed[a]) {
            // a walled face keeps centres its wall's margin away, a sub-region's edge a radius
            const bool walled = !box.periodic(a);
            lo = walled && lo <= box.lo(a) ? lo + walls.face[s] : lo + sp.radius;
            hi = walled && hi >= box.hi(a) ? hi - walls.face[s] : hi - sp.radius;
        }
        if (!(lo <= hi))
            throw InputError(species_label(c, s) +
                             ": region is narrower than one particle along axis " +
                             std::to_string(a));
        if (lo == hi) hi = std::nextafter(hi, hi + 1.0);
        reg.lo[a] = lo;
        reg.hi[a] = hi;
    }
    return reg;
}

template <int D>
void place_species(const RunConfig& c, const Box<D>& box, std::size_t s, std::size_t count,
                   std::uint32_t first_tag, std::vector<Vec<D>>& pos, std::vector<double>& radii,
                   const WallMargins<D>& walls) {
    const SpeciesConfig& sp = c.species[s];
    if (sp.positions == "point") {
        pos.push_back(to_vec<D>(*sp.point));
        radii.push_back(sp.radius);
        return;
    }
    const CentreRegion<D> reg = centre_region(c, box, s, walls);
    if (sp.positions == "random") {
        PlacementRequest<D> req;
        req.count = count;
        // soft particles may overlap (the ABP tutorial's builder keeps only centres rcut
        // apart): for them only [initial] min_distance constrains the placement
        req.radius = c.soft() ? 0.0 : sp.radius;
        req.body_radius = sp.radius;
        req.lo = reg.lo;
        req.hi = reg.hi;
        req.min_distance = c.min_distance;
        req.first_tag = first_tag;
        req.what = species_label(c, s);
        if (!walls.containers.empty()) {
            req.allowed = [&walls, &box, s](const Vec<D>& r) { return walls.inside(r, s, box); };
            req.what += " (centres inside the container, as far from its wall as the wall's core)";
        }
        place_randomly(pos, radii, box, req, c.seed);
        return;
    }
    LatticeKind kind;
    try {
        kind = parse_lattice(sp.positions, D);
    } catch (const InputError& e) {
        throw InputError(species_label(c, s) + ": positions: " + e.what() +
                         ", random or point (or [initial] file)");
    }
    for (const auto& r : lattice_sites<D>(kind, reg.lo, reg.hi, reg.closed, count)) {
        pos.push_back(r);
        radii.push_back(sp.radius);
    }
}

// Draws the velocities of species s; returns the particles whose Maxwell-Boltzmann
// velocities still have to be brought to the species' temperature (see build_particles).
template <int D>
std::vector<std::size_t> draw_species_velocities(const RunConfig& c, ParticleStore<D>& p,
                                                 std::size_t s,
                                                 const std::vector<std::size_t>& members,
                                                 const std::vector<bool>& from_file) {
    const SpeciesConfig& sp = c.species[s];
    VelocitySpec spec;
    try {
        spec.kind =
            sp.velocities == "given" ? VelocityKind::given : parse_velocity_kind(sp.velocities);
    } catch (const InputError& e) {
        throw InputError(species_label(c, s) + ": velocities: " + e.what());
    }
    spec.speed = sp.speed;
    spec.sigma = sp.sigma;
    spec.temperature = sp.temperature;
    std::vector<std::size_t> drawn;
    for (std::size_t k = 0; k < members.size(); ++k) {
        const std::size_t i = members[k];
        if (from_file[i]) continue;
        if (spec.kind == VelocityKind::given) {
            p.velocity[i] = to_vec<D>(*sp.velocity);
            continue;
        }
        // equal speeds with zero momentum: antithetic pairs keep every speed equal
        if (spec.kind == VelocityKind::equal_speed && c.zero_momentum && k % 2 == 1 &&
            !from_file[members[k - 1]])
            p.velocity[i] = -p.velocity[members[k - 1]];
        else
            p.velocity[i] = draw_velocity<D>(spec, sp.mass, c.seed, p.tag[i]);
        drawn.push_back(i);
    }
    if (std::isinf(sp.mass) || drawn.empty()) return {};
    const bool random_kind = spec.kind == VelocityKind::uniform ||
                             spec.kind == VelocityKind::normal ||
                             spec.kind == VelocityKind::maxwell_boltzmann;
    if (c.zero_momentum && random_kind && drawn.size() > 1) remove_drift(p, drawn);
    if (spec.kind == VelocityKind::maxwell_boltzmann && drawn.size() > 1) return drawn;
    return {};
}

// True if a self-propulsion term gives any species a non-zero force.
// Whether a one-body force acts (a non-zero self_propulsion, gravity, a trap, active_ou's
// active force, a container's wall): then no axis conserves momentum. (Planes walls act
// along walled axes only, which the box already counts out.)
bool one_body_forces(const RunConfig& c) {
    for (const auto& f : c.forces) {
        if (f.name == "gravity" || f.name == "harmonic_trap" || f.name == "active_ou") return true;
        if (f.name == "wall") {
            const auto shape = f.choices.find("shape");
            if (shape != f.choices.end() && shape->second != "planes") return true;
        }
        if (f.name != "self_propulsion") continue;
        for (const auto& [key, param] : f.params) {
            if (param.uniform && *param.uniform != 0.0) return true;
            for (const auto& [species, value] : param.by_species)
                if (value != 0.0) return true;
        }
    }
    return false;
}

// ["wall", "periodic"], as [box] boundary is written.
std::string boundary_words(const std::vector<bool>& periodic) {
    std::string words;
    for (bool p : periodic)
        words += std::string(words.empty() ? "" : ", ") + (p ? "\"periodic\"" : "\"wall\"");
    return "[" + words + "]";
}

// A file that states its boundaries must have those of the run: a walled run's particles
// put in a periodic box would pass where its walls were, and a periodic run's would
// straddle the new walls.
template <int D>
void check_file_boundary(const ParticleFile<D>& f, const Box<D>& box, const RunConfig& c) {
    if (!f.periodic) return;
    std::vector<bool> file(D), run(D);
    for (int a = 0; a < D; ++a) {
        file[static_cast<std::size_t>(a)] = (*f.periodic)[static_cast<std::size_t>(a)];
        run[static_cast<std::size_t>(a)] = box.periodic(a);
    }
    if (file != run)
        throw InputError(fmt::format("{}: the file's box has boundary = {}, but [box] boundary "
                                     "of {} is {}; set boundary = {} in [box] to start from it",
                                     *c.initial_file, boundary_words(file), c.file,
                                     boundary_words(run), boundary_words(file)));
}

} // namespace

template <int D> ParticleFile<D> read_initial_file(const RunConfig& c) {
    ParticleFile<D> f = read_particle_file<D>(*c.initial_file, c.initial_frame);
    if (c.species.empty() || f.type_names.empty()) return f;
    // HOOMD-blue's "A" is the species "A": by name, whatever the order of either list
    std::vector<int> species_of(f.type_names.size(), -1);
    for (std::size_t t = 0; t < f.type_names.size(); ++t)
        for (std::size_t s = 0; s < c.species.size(); ++s)
            if (c.species[s].name == f.type_names[t]) species_of[t] = static_cast<int>(s);
    for (auto& fp : f.particles) {
        const int s = species_of[static_cast<std::size_t>(fp.type)];
        if (s < 0) {
            std::string names;
            for (const auto& sp : c.species) names += (names.empty() ? "'" : ", '") + sp.name + "'";
            throw InputError(fmt::format(
                "{}: particle {} is of type '{}', and {} has no [[species]] of that name (it has "
                "{}); species are matched to the file's types by name",
                *c.initial_file, fp.id, f.type_names[static_cast<std::size_t>(fp.type)], c.file,
                names));
        }
        fp.type = s;
    }
    f.type_names.clear(); // the types are the config's species now
    return f;
}

template <int D> Box<D> build_box(const RunConfig& c) {
    std::array<bool, D> periodic{};
    for (int a = 0; a < D; ++a) periodic[a] = c.periodic[static_cast<std::size_t>(a)];
    return Box<D>(to_vec<D>(c.box_lengths), periodic);
}

template <int D> ParticleStore<D> build_particles(const RunConfig& c, const Box<D>& box) {
    if (!c.initial_file) return build_particles<D>(c, box, nullptr);
    const ParticleFile<D> f = read_initial_file<D>(c);
    return build_particles<D>(c, box, &f);
}

template <int D>
ParticleStore<D> build_particles(const RunConfig& c, const Box<D>& box,
                                 const ParticleFile<D>* initial) {
    if (c.initial_file && !initial)
        throw std::logic_error("build_particles: the [initial] file was not read");
    ParticleStore<D> p;
    for (const auto& s : c.species) p.species_table.push_back(Species{s.name, s.radius, s.mass});
    if (p.species_table.size() > 65535) throw InputError(c.file + ": too many species");
    for (const auto& s : c.species)
        for (int a = 0; a < D; ++a)
            if (box.length(a) < 2.0 * s.radius)
                throw InputError(c.file + ": box length " + std::to_string(box.length(a)) +
                                 " along axis " + std::to_string(a) +
                                 " is smaller than one particle of species '" + s.name +
                                 "' (diameter " + std::to_string(2.0 * s.radius) + ")");

    std::vector<Vec<D>> pos;
    std::vector<double> radii;
    std::vector<std::uint16_t> species;
    std::vector<std::optional<Vec<D>>> file_velocity;

    if (c.initial_file) {
        const ParticleFile<D>& f = *initial;
        // (a GSD file's box is single precision)
        const double box_tolerance = std::max(1e-9, f.precision);
        if (f.box) {
            std::string file_box, config_box;
            for (int a = 0; a < D; ++a) {
                file_box += fmt::format("{}{:.9g}", a ? " x " : "", (*f.box)[a]);
                config_box += fmt::format("{}{:.9g}", a ? " x " : "", box.length(a));
            }
            for (int a = 0; a < D; ++a)
                if (std::abs((*f.box)[a] - box.length(a)) > box_tolerance * box.length(a))
                    throw InputError(fmt::format(
                        "{}: box does not match [box] of {}: the file's is {}, [box] gives {}{}",
                        *c.initial_file, c.lengths_where.empty() ? c.file : c.lengths_where,
                        file_box, config_box,
                        c.soft() ? " (leave [box] out to take the file's)" : ""));
        }
        check_file_boundary<D>(f, box, c);
        // tags follow the file's ids in increasing order
        std::vector<std::size_t> order(f.particles.size());
        std::iota(order.begin(), order.end(), std::size_t{0});
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
            return f.particles[a].id < f.particles[b].id;
        });
        std::vector<std::size_t> per_type(c.species.size(), 0);
        for (std::size_t k : order) {
            const auto& fp = f.particles[k];
            const std::string who = *c.initial_file + ": particle " + std::to_string(fp.id);
            if (fp.type < 0 || static_cast<std::size_t>(fp.type) >= c.species.size())
                throw InputError(who + ": type " + std::to_string(fp.type) +
                                 " has no [[species]] entry in " + c.file);
            const auto s = static_cast<std::size_t>(fp.type);
            if (fp.radius &&
                std::abs(*fp.radius - c.species[s].radius) > f.precision * c.species[s].radius)
                throw InputError(who + ": radius " + std::to_string(*fp.radius) +
                                 " differs from species '" + c.species[s].name + "' radius " +
                                 std::to_string(c.species[s].radius));
            if (fp.mass && !(*fp.mass == c.species[s].mass) &&
                !(std::abs(*fp.mass - c.species[s].mass) <= f.precision * c.species[s].mass))
                throw InputError(who + ": mass " + std::to_string(*fp.mass) +
                                 " differs from species '" + c.species[s].name + "' mass " +
                                 std::to_string(c.species[s].mass));
            pos.push_back(fp.r);
            radii.push_back(c.species[s].radius);
            species.push_back(static_cast<std::uint16_t>(s));
            file_velocity.push_back(fp.v);
            ++per_type[s];
        }
        for (std::size_t s = 0; s < c.species.size(); ++s)
            if (c.species[s].count && *c.species[s].count != per_type[s])
                throw InputError(species_label(c, s) + ": count " +
                                 std::to_string(*c.species[s].count) + " but " + *c.initial_file +
                                 " holds " + std::to_string(per_type[s]));
    } else {
        const WallMargins<D> walls = wall_margins<D>(c);
        for (std::size_t s = 0; s < c.species.size(); ++s) {
            if (!c.species[s].count)
                throw InputError(species_label(c, s) +
                                 ": count is required (or give [initial] file)");
            const std::size_t n = *c.species[s].count;
            place_species(c, box, s, n, static_cast<std::uint32_t>(pos.size()), pos, radii, walls);
            species.insert(species.end(), n, static_cast<std::uint16_t>(s));
        }
        file_velocity.assign(pos.size(), std::nullopt);
    }
    if (pos.empty()) throw InputError(c.file + ": no particles (N = 0)");

    p.resize(pos.size());
    std::vector<bool> from_file(pos.size(), false);
    std::vector<std::vector<std::size_t>> members(c.species.size());
    for (std::size_t i = 0; i < pos.size(); ++i) {
        p.position[i] = pos[i];
        p.tag[i] = static_cast<std::uint32_t>(i);
        p.species[i] = species[i];
        if (file_velocity[i]) {
            p.velocity[i] = *file_velocity[i];
            from_file[i] = true;
        }
        members[species[i]].push_back(i);
    }
    std::vector<std::vector<std::size_t>> maxwell(c.species.size());
    for (std::size_t s = 0; s < c.species.size(); ++s)
        maxwell[s] = draw_species_velocities(c, p, s, members[s], from_file);

    // A Maxwell-Boltzmann start with zero momentum, in a system that keeps it zero, gets
    // the requested temperature as observe/thermo.hpp measures it: each species gives up
    // its mass share of the conserved momentum components.
    const auto axes = conserved_momentum_axes(p, box, momentum_of(c));
    const double conserved =
        c.zero_momentum ? static_cast<double>(std::count(axes.begin(), axes.end(), true)) : 0.0;
    double total_mass = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (std::isfinite(p.mass(i))) total_mass += p.mass(i);
    for (std::size_t s = 0; s < c.species.size(); ++s) {
        if (maxwell[s].empty()) continue;
        const double share =
            conserved * c.species[s].mass * static_cast<double>(maxwell[s].size()) / total_mass;
        rescale_temperature(p, maxwell[s], c.species[s].temperature, share);
    }
    return p;
}

Momentum momentum_of(const RunConfig& c) {
    if (c.dynamics == "event" || c.dynamics == "stepped") return Momentum::conserving;
    // (bussi and nose_hoover scale the velocities about the centre of mass: they keep it)
    const bool newtonian =
        c.dynamics == "nve" || c.dynamics == "bussi" || c.dynamics == "nose_hoover";
    if (newtonian && !one_body_forces(c)) return Momentum::conserving;
    return Momentum::not_conserving;
}

template ParticleFile<2> read_initial_file<2>(const RunConfig&);
template ParticleFile<3> read_initial_file<3>(const RunConfig&);
template Box<2> build_box<2>(const RunConfig&);
template Box<3> build_box<3>(const RunConfig&);
template ParticleStore<2> build_particles<2>(const RunConfig&, const Box<2>&,
                                             const ParticleFile<2>*);
template ParticleStore<3> build_particles<3>(const RunConfig&, const Box<3>&,
                                             const ParticleFile<3>*);
template ParticleStore<2> build_particles<2>(const RunConfig&, const Box<2>&);
template ParticleStore<3> build_particles<3>(const RunConfig&, const Box<3>&);

} // namespace pedesis
