#include "pedesis/setup/build_soft_state.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/rng.hpp"
#include "pedesis/setup/build_system.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace pedesis {

namespace {

template <int D> std::string particle_label(const std::string& file, std::uint32_t id) {
    return fmt::format("{}: particle {}", file, id);
}

// Checks what only a soft run needs of the file: ids 0..N-1 (they become the tags, and
// outputs are written in tag order), and positions inside the box.
template <int D>
void check_file(const ParticleFile<D>& f, const Box<D>& box, const std::string& name) {
    const std::size_t n = f.particles.size();
    std::vector<bool> seen(n, false);
    for (const auto& fp : f.particles) {
        if (fp.id >= n)
            throw InputError(
                fmt::format("{}: particle ids must be 0..{} (one per particle), but one is {}",
                            name, n - 1, fp.id));
        seen[fp.id] = true;
    }
    for (const auto& fp : f.particles)
        for (int a = 0; a < D; ++a) {
            const double half = 0.5 * box.length(a);
            if (!(fp.r[a] >= -half && fp.r[a] <= half))
                throw InputError(fmt::format(
                    "{}: \"r\" component {} is {}, outside the box [{}, {}] (the box is "
                    "centred at the origin)",
                    particle_label<D>(name, fp.id), a, fp.r[a], -half, half));
        }
}

template <int D> Vec<D> random_unit_vector(std::uint64_t seed, std::uint32_t tag) {
    CounterRng rng(seed, RngStream::initial_director, tag);
    Vec<D> v;
    // a draw this short has probability below 1e-36; 64 in a row means a broken generator
    for (int draw = 0; draw < 64; ++draw) {
        for (int a = 0; a < D; ++a) v[a] = rng.normal();
        const double len2 = norm2(v);
        if (len2 >= 1e-24) return v * (1.0 / std::sqrt(len2));
    }
    throw std::logic_error("initial directors: 64 normal draws in a row of length zero");
}

} // namespace

template <int D> RunConfig complete_from_initial_file(const RunConfig& config) {
    if (!config.initial_file || (!config.box_lengths.empty() && !config.species.empty()))
        return config;
    const ParticleFile<D> f = read_initial_file<D>(config);
    return complete_from_initial_file<D>(config, &f);
}

template <int D>
RunConfig complete_from_initial_file(const RunConfig& config, const ParticleFile<D>* file) {
    RunConfig c = config;
    if (!c.initial_file || (!c.box_lengths.empty() && !c.species.empty())) return c;
    if (!file) throw std::logic_error("complete_from_initial_file: the file was not read");
    const ParticleFile<D>& f = *file;
    if (c.box_lengths.empty()) {
        if (!f.box)
            throw InputError(*c.initial_file + ": has no \"box\", and " + c.file +
                             " has no [box] either");
        c.box_lengths.clear();
        for (int a = 0; a < D; ++a) c.box_lengths.push_back((*f.box)[a]);
        // the file's walls where it states them (a pedesis trajectory does)
        c.periodic.assign(D, true);
        if (f.periodic)
            for (int a = 0; a < D; ++a) c.periodic[static_cast<std::size_t>(a)] = (*f.periodic)[a];
    }
    if (c.species.empty()) {
        // the file's type names (GSD, XYZ), else A, B, ... for the JSON's type numbers
        const bool named = !f.type_names.empty();
        int types = 0;
        for (const auto& fp : f.particles) {
            if (!named && (fp.type < 0 || fp.type >= 26))
                throw InputError(particle_label<D>(*c.initial_file, fp.id) +
                                 ": \"type\" must lie in 0..25 when " + c.file +
                                 " names no [[species]]");
            types = std::max(types, fp.type + 1);
        }
        c.species.resize(static_cast<std::size_t>(types));
        std::vector<bool> set(c.species.size(), false);
        for (std::size_t s = 0; s < c.species.size(); ++s) {
            c.species[s] = c.species_defaults; // velocities as [initial] says
            c.species[s].name =
                named ? f.type_names[s] : std::string(1, static_cast<char>('A' + s));
            if (!valid_species_name(c.species[s].name))
                throw InputError(fmt::format(
                    "{}: the type name '{}' cannot name a species (1 to 64 of A-Z a-z 0-9 _ - . "
                    "+: it names log columns and output types); give [[species]] in {} and "
                    "rename the type in the file",
                    *c.initial_file, c.species[s].name, c.file));
            c.species[s].positions = "file";
            // where the file gives none: 1 for the tutorial's JSON, 0.5 for GSD and XYZ
            c.species[s].radius = f.default_radius;
        }
        for (const auto& fp : f.particles) {
            auto& s = c.species[static_cast<std::size_t>(fp.type)];
            const double r = fp.radius.value_or(f.default_radius), m = fp.mass.value_or(1.0);
            if (!set[static_cast<std::size_t>(fp.type)]) {
                s.radius = r;
                s.mass = m;
                set[static_cast<std::size_t>(fp.type)] = true;
            } else if (r != s.radius || !(m == s.mass))
                throw InputError(fmt::format(
                    "{}: radius {} and mass {} differ from those of the first particle of type "
                    "{} ({} and {}); give [[species]] in {} to say which is meant",
                    particle_label<D>(*c.initial_file, fp.id), r, m,
                    named ? "'" + s.name + "'" : std::to_string(fp.type), s.radius, s.mass,
                    c.file));
        }
    }
    return c;
}

template <int D> SoftState<D> build_soft_state(const RunConfig& config) {
    // read once, for the config's completion, the directors and build_particles
    std::optional<ParticleFile<D>> file;
    if (config.initial_file) file = read_initial_file<D>(config);
    return build_soft_state<D>(config, file ? &*file : nullptr);
}

template <int D>
SoftState<D> build_soft_state(const RunConfig& config, const ParticleFile<D>* file) {
    if (config.initial_file && !file)
        throw std::logic_error("build_soft_state: the [initial] file was not read");
    const RunConfig c = complete_from_initial_file<D>(config, file);
    SoftState<D> s;
    s.box = build_box<D>(c);
    std::vector<std::optional<Vec<D>>> file_director;
    if (c.initial_file) {
        const ParticleFile<D>& f = *file;
        check_file(f, s.box, *c.initial_file);
        file_director.resize(f.particles.size());
        for (const auto& fp : f.particles) {
            if (fp.n && !(norm(*fp.n) > 0.0))
                throw InputError(particle_label<D>(*c.initial_file, fp.id) +
                                 ": \"n\" is the zero vector; a director needs a direction");
            file_director[fp.id] = fp.n;
        }
    }
    s.p = build_particles<D>(c, s.box, file); // tags follow the file's ids
    const std::size_t n = s.p.size();
    s.director.resize(n);
    s.force.assign(n, Vec<D>{});
    s.torque.assign(n, TorqueVec<D>{});
    s.image.assign(n, std::array<std::int32_t, D>{});
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t tag = s.p.tag[i];
        if (tag < file_director.size() && file_director[tag])
            s.director[i] = *file_director[tag] * (1.0 / norm(*file_director[tag]));
        else
            s.director[i] = random_unit_vector<D>(c.seed, tag);
        // a particle exactly on the upper face belongs to the lower one
        const Vec<D> shift = s.box.wrap(s.p.position[i]);
        for (int a = 0; a < D; ++a) s.image[i][a] = static_cast<std::int32_t>(shift[a]);
    }
    return s;
}

template RunConfig complete_from_initial_file<2>(const RunConfig&, const ParticleFile<2>*);
template RunConfig complete_from_initial_file<3>(const RunConfig&, const ParticleFile<3>*);
template SoftState<2> build_soft_state<2>(const RunConfig&, const ParticleFile<2>*);
template SoftState<3> build_soft_state<3>(const RunConfig&, const ParticleFile<3>*);
template RunConfig complete_from_initial_file<2>(const RunConfig&);
template RunConfig complete_from_initial_file<3>(const RunConfig&);
template SoftState<2> build_soft_state<2>(const RunConfig&);
template SoftState<3> build_soft_state<3>(const RunConfig&);

} // namespace pedesis
