#pragma once
// What one input of fuzz_run does: the bytes choose a small config that the engines accept
// (engine, dimension, box, start, forces, cutoffs, skins, species, boundaries), and the
// config is run for a few steps, or a short time, the way `pedesis run` runs it. Fuzzing
// the choices instead of the text puts the fuzzer's effort into set-up and stepping; the
// parser has fuzz_config. Outcomes allowed: the run finishes, the config is refused
// (InputError), or the run stops for a physical reason the docs give for exit 3 (a
// blow-up, inelastic collapse, a time step too large); see physical_stop.
#include "fuzz_support.hpp"

#include "pedesis/run/run.hpp"
#include "pedesis/setup/run_config.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <numbers>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace pedesis::fuzz {

// The fuzzer's bytes as a sequence of choices. Past the end every byte reads 0, and 0
// always means the common choice, so a short input is already a complete config and each
// byte libFuzzer appends refines one more choice.
class Choices {
  public:
    Choices(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
    unsigned byte() { return next_ < size_ ? data_[next_++] : 0u; }
    unsigned pick(unsigned n) { return byte() % n; }
    // true with probability about in256/256, false for a zero byte
    bool sometimes(unsigned in256) { return byte() >= 256u - in256; }
    double unit() { return byte() / 255.0; }
    double linear(double lo, double hi) { return lo + (hi - lo) * unit(); }
    double geometric(double lo, double hi) { return lo * std::pow(hi / lo, unit()); }

  private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t next_ = 0;
};

namespace detail {

// Every digit, so that a length snapped to a multiple (or one ulp beside it) stays exact.
inline std::string toml_number(double v) {
    std::string s = fmt::format("{:.17g}", v);
    if (s.find_first_of(".eni") == std::string::npos) s += ".0";
    return s;
}

inline std::string toml_list(const std::vector<double>& v) {
    std::string s = "[";
    for (std::size_t k = 0; k < v.size(); ++k) s += (k ? ", " : "") + toml_number(v[k]);
    return s + "]";
}

inline double particle_volume(int dim, double r) {
    return dim == 2 ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

// Space per site of a lattice whose nearest neighbours are `spacing` apart.
inline double site_volume(const std::string& lattice, double spacing) {
    if (lattice == "square") return spacing * spacing;
    if (lattice == "hexagonal") return std::sqrt(3.0) / 2.0 * spacing * spacing;
    if (lattice == "sc") return spacing * spacing * spacing;
    return spacing * spacing * spacing / std::sqrt(2.0); // fcc: 4 sites per cell of a = s sqrt 2
}

// A count that fills whole cells of the lattice, near `n`: the perfect lattices where
// particles sit exactly on cell faces and list ranges divide the box.
inline unsigned whole_lattice(const std::string& lattice, unsigned n) {
    const int dim = lattice == "square" || lattice == "hexagonal" ? 2 : 3;
    const unsigned per_cell = lattice == "fcc" ? 4u : lattice == "hexagonal" ? 2u : 1u;
    const double cells = std::max(1.0, static_cast<double>(n) / per_cell);
    const auto k = std::max(1u, static_cast<unsigned>(std::lround(std::pow(cells, 1.0 / dim))));
    unsigned total = per_cell;
    for (int a = 0; a < dim; ++a) total *= k;
    return total;
}

struct SpeciesChoice {
    std::string name;
    unsigned count = 1;
    double radius = 0.5;
    std::string mass = "1.0";
    std::string positions = "random";
    double volume = 0.0;       // of the box it needs
    bool slab = false;         // its own slab of axis 0 (a region)
    std::vector<double> point; // positions = "point"
};

} // namespace detail

namespace detail {

inline void replace_first(std::string& t, const std::string& from, const std::string& to) {
    const std::size_t at = t.find(from);
    if (at != std::string::npos) t.replace(at, from.size(), to);
}

} // namespace detail

// The ensembles and minimisation of the soft engine (chosen after everything else, so
// that the choices before keep their meaning for the corpus): an nve run becomes bussi,
// nose_hoover or (without torques and active forces, which it refuses) minimize.
inline void add_ensembles(Choices& c, const std::string& dynamics, std::string& t) {
    using detail::toml_number;
    if (dynamics == "langevin" || dynamics == "nve") {
        // MTK ([barostat]) beside langevin or nve, at pressures from a gas's to a solid's
        if (c.sometimes(48)) {
            static const char* const couplings[] = {"isotropic", "anisotropic"};
            t += "[barostat]\npressure = " + toml_number(c.geometric(1e-3, 20.0)) +
                 "\ntau = " + toml_number(c.geometric(1e-3, 10.0)) + "\ncoupling = \"" +
                 couplings[c.pick(2)] + "\"\n";
            return;
        }
    }
    if (dynamics != "nve" || !c.sometimes(96)) return;
    const unsigned kind = c.pick(3);
    const std::string integrator = "[[integrator]]\nname = \"nve\"\n";
    if (kind < 2) {
        const std::string name = kind == 0 ? "bussi" : "nose_hoover";
        std::string entry = "[[integrator]]\nname = \"" + name +
                            "\"\nT = " + toml_number(c.geometric(1e-3, 2.0)) +
                            "\ntau = " + toml_number(c.geometric(1e-3, 10.0)) + "\n";
        if (kind == 1 && c.sometimes(64))
            entry += "chain = " + std::to_string(1 + c.pick(6)) + "\n";
        detail::replace_first(t, "dynamics = \"nve\"", "dynamics = \"" + name + "\"");
        detail::replace_first(t, integrator, entry);
        return;
    }
    detail::replace_first(t, "dynamics = \"nve\"", "dynamics = \"minimize\"");
    detail::replace_first(t, integrator, "");
    std::string table =
        "[minimize]\nforce_tolerance = " + toml_number(c.geometric(1e-10, 1.0)) + "\n";
    if (c.sometimes(64))
        table += "energy_tolerance = " + toml_number(c.geometric(1e-12, 0.5)) + "\n";
    if (c.sometimes(64)) table += "n_delay = " + std::to_string(c.pick(40)) + "\n";
    t += table;
}

// The drives of the hard engines (chosen last, as add_ensembles): gravity along a walled
// axis (event and stepped), and for the event engine the Andersen thermostat, white-noise
// kicks and a vibrated or driven wall. Refusals (shear, growth, obstacles) are allowed
// outcomes.
inline void add_hard_drives(Choices& c, const std::string& dynamics, const std::vector<bool>& wall,
                            std::string& t) {
    using detail::toml_number;
    if (dynamics != "event" && dynamics != "stepped") return;
    const std::string table = "[" + dynamics + "]\n";
    std::string keys;
    int walled = -1;
    for (std::size_t a = 0; a < wall.size(); ++a)
        if (wall[a]) walled = static_cast<int>(a);
    if (walled >= 0 && c.sometimes(64)) {
        std::vector<double> g(wall.size(), 0.0);
        g[static_cast<std::size_t>(walled)] = -c.geometric(1e-3, 50.0);
        if (c.sometimes(32)) g[static_cast<std::size_t>(walled)] *= -1.0;
        keys += "gravity = " + detail::toml_list(g) + "\n";
    }
    if (dynamics == "event") {
        if (c.sometimes(32) && t.find("thermostat = ") == std::string::npos)
            keys +=
                "thermostat = \"andersen\"\ntemperature = " + toml_number(c.geometric(0.01, 10.0)) +
                "\nthermostat_rate = " + toml_number(c.geometric(1e-3, 10.0)) + "\n";
        if (c.sometimes(32))
            keys += "driving = \"white_noise\"\ndriving_rate = " +
                    toml_number(c.geometric(1e-3, 10.0)) +
                    "\ndriving_strength = " + toml_number(c.geometric(1e-4, 1.0)) + "\n";
    }
    const std::size_t at = t.find(table);
    if (at == std::string::npos) return;
    t.insert(at + table.size(), keys);
    if (dynamics == "event" && walled >= 0 && c.sometimes(48)) {
        std::string wall_table = "[event.moving_wall]\naxis = \"";
        wall_table += "xyz"[walled];
        wall_table += c.sometimes(128) ? "\"\nside = \"upper\"\n" : "\"\n";
        if (c.sometimes(96))
            wall_table += "speed = " + toml_number(c.geometric(1e-3, 5.0)) + "\n";
        else
            wall_table += "amplitude = " + toml_number(c.geometric(1e-3, 2.0)) +
                          "\nfrequency = " + toml_number(c.geometric(1e-2, 20.0)) + "\n";
        // (a sub-table after its parent's keys: before the next table)
        const std::size_t next = t.find("\n[", at + table.size());
        t.insert(next == std::string::npos ? t.size() : next + 1, wall_table);
    }
}

// The config (TOML text) that the bytes choose.
inline std::string run_config_text(const std::uint8_t* data, std::size_t size) {
    using namespace detail;
    Choices c(data, size);
    static const char* const engines[] = {"event", "stepped", "brownian", "langevin", "nve"};
    const std::string dynamics = engines[c.pick(5)];
    const bool soft = dynamics != "event" && dynamics != "stepped";
    const int dim = 2 + static_cast<int>(c.pick(2));
    const unsigned seed = c.byte();

    // Species: A, maybe B with a radius ratio (1, 2 and 5 among them), maybe one particle
    // placed by hand at the box's edge.
    static const double ratios[] = {1.0, 2.0, 5.0, 0.5, 0.2, 1.25, 0.8, 3.0};
    std::vector<SpeciesChoice> species(1 + c.pick(2));
    species[0].name = "A";
    if (species.size() > 1) {
        species[1].name = "B";
        species[1].radius = 0.5 * ratios[c.pick(8)];
    }
    for (auto& s : species) {
        const unsigned b = c.byte();
        // mostly up to 56, one in eight up to 397: the large systems cost most
        s.count = b < 224 ? 1 + b / 4 : 57 + (b - 224) * 11;
        if (c.sometimes(48)) {
            static const char* const masses[] = {"0.1", "4.0", "25.0", "inf"};
            s.mass = masses[c.pick(4)];
        }
    }
    // Placement per species: a lattice or random. Lattices avoid nothing, so beside another
    // species of hard particles a lattice gets a slab of axis 0 of its own (random placement
    // into the holes of a dense lattice would only fail, slowly); soft ones may overlap.
    std::vector<unsigned> how(species.size());
    for (auto& h : how) h = c.pick(4);
    const bool any_lattice = std::any_of(how.begin(), how.end(), [](unsigned h) { return h >= 2; });
    const bool slabs = species.size() > 1 && (c.sometimes(96) || (!soft && any_lattice));
    const double max_fill = dim == 2 ? 0.3 : 0.2; // random sequential addition jams above
    for (std::size_t k = 0; k < species.size(); ++k) {
        auto& s = species[k];
        s.slab = slabs;
        if (how[k] >= 2) {
            s.positions =
                dim == 2 ? (how[k] == 2 ? "square" : "hexagonal") : (how[k] == 2 ? "sc" : "fcc");
            if (c.sometimes(128)) s.count = whole_lattice(s.positions, s.count);
            const double spacing = 2.0 * s.radius * (1.0 + c.geometric(0.005, 2.0));
            s.volume = s.count * site_volume(s.positions, spacing);
        } else {
            s.volume = s.count * particle_volume(dim, s.radius) / c.linear(0.005, max_fill);
        }
    }
    unsigned total = 0;
    for (const auto& s : species) total += s.count;
    if (total > 400) // keeps every input to milliseconds
        for (auto& s : species) {
            const unsigned n = std::max(1u, s.count * 400 / total);
            s.volume *= static_cast<double>(n) / s.count;
            s.count = n;
        }
    double r_max = 0.0, r_min = 1e300;
    for (const auto& s : species) {
        r_max = std::max(r_max, s.radius);
        r_min = std::min(r_min, s.radius);
    }

    // Boundaries: the soft engines take periodic boxes only.
    std::vector<bool> wall(dim, false);
    if (!soft) {
        const unsigned b = c.pick(4);
        for (int a = 0; a < dim; ++a) wall[a] = b == 1 || (b >= 2 && c.sometimes(128));
    }

    // The box: the volume the species need, square or stretched per axis.
    double volume = 0.0;
    for (const auto& s : species) volume += s.volume;
    std::vector<double> stretch(dim, 1.0);
    if (c.sometimes(96)) {
        double product = 1.0;
        for (int a = 0; a < dim; ++a) product *= (stretch[a] = std::pow(2.0, c.linear(-1.0, 1.0)));
        for (int a = 0; a < dim; ++a) stretch[a] /= std::pow(product, 1.0 / dim);
    }
    std::vector<double> length(dim);
    for (int a = 0; a < dim; ++a) {
        length[a] = std::pow(volume, 1.0 / dim) * stretch[a];
        // a closed axis loses a radius at each end to the centres
        if (wall[a]) length[a] += 2.0 * r_max;
    }
    double cross_section = 1.0; // of a slab
    for (int a = 1; a < dim; ++a) cross_section *= length[a];
    if (slabs) {
        length[0] = 0.0;
        for (const auto& s : species) length[0] += s.volume / cross_section + 2.0 * s.radius;
    }
    // the smallest boxes the hard engines accept (soft ones take any, by images)
    for (int a = 0; a < dim; ++a)
        length[a] = std::max(length[a], (soft || wall[a] ? 2.0 : 4.0) * r_max * 1.001);

    // Velocities (the hard engines move by them; zero ones mostly stop at once).
    std::string velocity_text;
    double fastest = 0.0; // about the largest start speed, for the stepped engine's dt
    if (!soft || dynamics != "brownian") {
        const double mass_min = species.size() > 1 || species[0].mass != "1.0" ? 0.1 : 1.0;
        switch (c.pick(soft ? 2 : 6)) {
        case 0:
        case 4:
        case 5: {
            const double t = c.geometric(0.05, 4.0);
            velocity_text = "velocities = \"maxwell_boltzmann\"\ntemperature = " + toml_number(t);
            fastest = 5.0 * std::sqrt(t / mass_min);
            break;
        }
        case 1:
            velocity_text = "velocities = \"zero\"";
            break;
        case 2: {
            const double v = c.geometric(0.05, 4.0);
            velocity_text = "velocities = \"uniform\"\nspeed = " + toml_number(v);
            fastest = 2.0 * v * std::sqrt(dim);
            break;
        }
        default: {
            const double v = c.geometric(0.05, 4.0);
            velocity_text = c.sometimes(128)
                                ? "velocities = \"equal_speed\"\nspeed = " + toml_number(v)
                                : "velocities = \"normal\"\nsigma = " + toml_number(v);
            fastest = 5.0 * v * std::sqrt(dim);
        }
        }
        if (c.sometimes(64)) velocity_text += "\nzero_momentum = false";
        velocity_text += "\n";
    }

    // The engine's own part, and the range of its spatial structure (for the snapping below).
    std::string engine_text;
    double run_length = 1.0; // in time, for the output intervals of the hard engines
    double reach = 2.0 * r_max;
    if (dynamics == "event") {
        engine_text += "[event]\n";
        bool inelastic = false;
        double skin = 1e300; // automatic: at least a radius
        if (c.sometimes(64)) {
            engine_text += "restitution = " + toml_number(c.linear(0.3, 0.99)) + "\n";
            inelastic = true;
        }
        if (c.sometimes(48)) {
            engine_text += "wall_restitution = " + toml_number(c.linear(0.3, 0.99)) + "\n";
            inelastic = true;
        }
        if (c.sometimes(64)) engine_text += "tc = " + toml_number(c.geometric(1e-6, 1e-2)) + "\n";
        if (c.sometimes(128)) {
            skin = 2.0 * r_max * c.geometric(1e-4, 4.0);
            engine_text += "skin = " + toml_number(skin) + "\n";
            reach += skin;
        }
        if (c.sometimes(64)) engine_text += "check_overlaps = true\n";
        const bool grow = c.sometimes(40);
        if (grow) {
            engine_text += "growth_rate = " + toml_number(c.geometric(0.01, 2.0)) + "\n";
            if (c.sometimes(128))
                engine_text +=
                    "growth_packing_fraction = " + toml_number(c.linear(0.3, 0.85)) + "\n";
            if (c.sometimes(64))
                engine_text += "growth_max_pressure = " + toml_number(c.geometric(2.0, 1e4)) + "\n";
        }
        // a particle's list is rebuilt each time it crosses its skin: a tiny skin gets a
        // short run, a few rebuilds per particle
        const double typical_speed = std::max(fastest / 5.0, 0.01);
        const double time = std::min(c.geometric(0.02, 2.0), 10.0 * skin / typical_speed);
        engine_text += "[run]\ntime = " + toml_number(time) + "\n";
        run_length = time;
        // a bound on the work, whatever the density
        engine_text += "collisions_per_particle = " + toml_number(c.linear(0.05, 1.0)) + "\n";
        if (inelastic && c.sometimes(96))
            engine_text += "energy_fraction = " + toml_number(c.linear(0.05, 0.95)) + "\n";
        if (grow && c.sometimes(128)) engine_text += "grown = true\n";
    }

    if (dynamics == "stepped") {
        const double max_move = c.sometimes(64) ? c.linear(0.1, 1.0) : 0.5;
        // at or somewhat past the largest dt the engine takes: some are refused
        const double dt = max_move * r_min / std::max(fastest, 0.1) * c.linear(0.05, 1.3);
        const unsigned steps = 1 + c.pick(10);
        engine_text += "[stepped]\ndt = " + toml_number(dt) +
                       "\nmax_move = " + toml_number(max_move) +
                       "\n[run]\nsteps = " + std::to_string(steps) + "\n";
        run_length = steps * dt;
        if (c.sometimes(64))
            engine_text += "time = " + toml_number(dt * c.linear(0.5, 20.0)) + "\n";
    }

    std::string min_distance;
    if (soft) {
        // Forces (at least one pair force), with their ranges, then torques and integrators.
        const double contact = 2.0 * r_max;
        double cutoff = 0.001;
        unsigned forces = c.pick(8);
        if (forces == 0) forces = 1;
        if (forces & 1u) {
            engine_text +=
                "[[force]]\nname = \"harmonic\"\nk = " + toml_number(c.geometric(1.0, 100.0)) +
                "\n";
            double a = contact;
            if (c.sometimes(64)) {
                a = contact * c.linear(0.3, 1.5);
                engine_text += "a = " + toml_number(a) + "\n";
            }
            cutoff = std::max(cutoff, a);
        }
        if (forces & 2u) {
            engine_text +=
                "[[force]]\nname = \"wca\"\nepsilon = " + toml_number(c.linear(0.1, 2.0)) + "\n";
            cutoff = std::max(cutoff, std::pow(2.0, 1.0 / 6.0) * contact);
        }
        if (forces & 4u) {
            engine_text +=
                "[[force]]\nname = \"lj\"\nepsilon = " + toml_number(c.linear(0.1, 2.0)) + "\n";
            double range = 2.5;
            if (c.sometimes(128)) {
                range = c.linear(1.0, 3.5);
                engine_text += "cutoff = " + toml_number(range) + "\n";
            }
            if (c.sometimes(128)) engine_text += "shift = true\n";
            if (species.size() > 1 && c.sometimes(96)) {
                const double sigma = contact * c.linear(0.5, 1.0);
                engine_text += "[[force.pairs]]\nspecies = [\"A\", \"B\"]\nepsilon = " +
                               toml_number(c.linear(0.1, 2.0)) + "\nsigma = " + toml_number(sigma) +
                               "\n";
            }
            cutoff = std::max(cutoff, range * contact);
        }
        if (c.sometimes(64))
            engine_text += "[[force]]\nname = \"self_propulsion\"\nalpha = " +
                           toml_number(c.linear(-2.0, 2.0)) + "\n";
        const bool torque = c.sometimes(64);
        if (torque) {
            const double a = contact * c.linear(0.5, 2.0);
            engine_text +=
                "[[torque]]\nname = \"polar_align\"\nJ = " + toml_number(c.linear(-1.0, 1.0)) +
                "\na = " + toml_number(a) + "\n";
            cutoff = std::max(cutoff, a);
        }
        engine_text += "[[integrator]]\nname = \"" + dynamics + "\"\n";
        if (dynamics != "nve")
            engine_text += "T = " + toml_number(c.geometric(1e-3, 1.0)) +
                           "\ngamma = " + toml_number(c.geometric(0.5, 5.0)) + "\n";
        if (torque || c.sometimes(48))
            engine_text += "[[integrator]]\nname = \"brownian_rotation\"\nT = " +
                           toml_number(c.geometric(1e-3, 1.0)) +
                           "\ngamma = " + toml_number(c.geometric(0.5, 5.0)) + "\n";
        // The list: skins from almost nothing to well past the cutoff.
        engine_text += "[neighbor_list]\n";
        if (c.sometimes(64)) {
            const double r_cut = c.linear(0.2, 2.0) * cutoff;
            engine_text += "r_cut = " + toml_number(r_cut) + "\n";
            cutoff = std::max(cutoff, r_cut);
        }
        double skin = 0.5;
        if (c.sometimes(192)) {
            skin = cutoff * c.geometric(1e-4, 1.5);
            engine_text += "skin = " + toml_number(skin) + "\n";
        }
        static const char* const sorts[] = {"500", "1", "3", "0"};
        engine_text += std::string("sort_every = ") + sorts[c.pick(4)] + "\n";
        reach = cutoff + skin;
        // the list's images need a periodic length of at least twice its range
        for (int a = 0; a < dim; ++a) length[a] = std::max(length[a], 2.0 * reach);
        engine_text += "[run]\nsteps = " + std::to_string(1 + c.pick(8)) +
                       "\ndt = " + toml_number(c.geometric(1e-4, 5e-3)) + "\n";
        // random starts not deep inside the repulsive cores (WCA and LJ are steep)
        if (c.sometimes(192))
            min_distance = "min_distance = " + toml_number(2.0 * r_min * c.linear(0.7, 1.0)) + "\n";
    }

    // Box lengths on the structures' grid: a whole number of list ranges, or one ulp
    // either side of it.
    const unsigned snap = c.pick(8);
    if (snap >= 5 && !slabs)
        for (int a = 0; a < dim; ++a) {
            const double smallest = length[a];
            const double cells = std::max(1.0, std::ceil(length[a] / reach));
            length[a] = cells * reach;
            if (snap == 6) length[a] = std::nextafter(length[a], 0.0);
            if (snap == 7) length[a] = std::nextafter(length[a], 1e300);
            if (length[a] < smallest * (1.0 - 1e-12)) length[a] = smallest; // never
        }

    // One particle more, by hand, at the box's edge: exactly at -L/2, or one ulp inside
    // L/2, on the periodic axes.
    if (c.sometimes(32)) {
        detail::SpeciesChoice p;
        p.name = "P";
        p.radius = r_min;
        p.positions = "point";
        for (int a = 0; a < dim; ++a) {
            const unsigned where = c.pick(3);
            double x = 0.0;
            if (!wall[a] && where == 1) x = -length[a] / 2.0;
            if (!wall[a] && where == 2) x = std::nextafter(length[a] / 2.0, 0.0);
            p.point.push_back(x);
        }
        species.push_back(p);
    }

    // Outputs: mostly none, sometimes a frame format, a log row every few steps.
    std::string output_text = "[output]\nprogress = false\n";
    static const char* const formats[] = {"gsd", "xyz", "json", "vtp", "table"};
    output_text += c.sometimes(32) ? std::string("formats = [\"") + formats[c.pick(5)] + "\"]\n"
                                   : "formats = []\n";
    if (soft) {
        output_text += "log_every = " + std::to_string(1 + c.pick(5)) + "\n";
        if (c.sometimes(64))
            output_text += "snapshot_every = " + std::to_string(1 + c.pick(5)) + "\n";
        if (c.sometimes(32))
            output_text += "checkpoint_every = " + std::to_string(1 + c.pick(5)) + "\n";
    } else {
        // a few rows and frames per run: writing them costs more than the steps
        output_text += "log_interval = " + toml_number(run_length * c.geometric(0.05, 1.5)) + "\n";
        if (c.sometimes(64))
            output_text +=
                "snapshot_interval = " + toml_number(run_length * c.geometric(0.1, 1.5)) + "\n";
        if (c.sometimes(32))
            output_text +=
                "checkpoint_interval = " + toml_number(run_length * c.geometric(0.2, 1.5)) + "\n";
        if (c.sometimes(48)) output_text += "histogram_start = 0.0\n";
        output_text += "histogram_bins = " + std::to_string(1 + c.pick(60)) + "\n";
    }

    // The text, as a user would write it.
    std::string t =
        fmt::format("dimension = {}\ndynamics = \"{}\"\nseed = {}\n[box]\n", dim, dynamics, seed);
    t += "lengths = " + toml_list(length) + "\n";
    if (!soft) {
        t += "boundary = [";
        for (int a = 0; a < dim; ++a)
            t += std::string(a ? ", " : "") + (wall[a] ? "\"wall\"" : "\"periodic\"");
        t += "]\n";
    }
    // slabs share axis 0 in proportion to the volume each needs, the last up to the end
    double slab_lo = -length[0] / 2.0;
    std::size_t slabs_left = 0;
    for (const auto& s : species) slabs_left += s.slab;
    for (const auto& s : species) {
        t += "[[species]]\nname = \"" + s.name + "\"\ncount = " + std::to_string(s.count) +
             "\nradius = " + toml_number(s.radius) + "\nmass = " + s.mass + "\n";
        if (!s.point.empty()) {
            t += "position = " + toml_list(s.point) + "\n";
            continue;
        }
        t += "positions = \"" + s.positions + "\"\n";
        if (s.slab) {
            const double hi = --slabs_left == 0
                                  ? length[0] / 2.0
                                  : slab_lo + s.volume / cross_section + 2.0 * s.radius;
            std::vector<double> lo(dim), up(dim);
            for (int a = 0; a < dim; ++a) {
                lo[a] = -length[a] / 2.0;
                up[a] = length[a] / 2.0;
            }
            lo[0] = slab_lo;
            up[0] = hi;
            t += "region = { lo = " + toml_list(lo) + ", hi = " + toml_list(up) + " }\n";
            slab_lo = hi;
        }
    }
    t += "[initial]\n" + velocity_text + min_distance;
    t += engine_text + output_text;
    // Lees-Edwards shear of the hard engines (x and y periodic), the event engine's
    // thermostat: chosen last, so that the choices before keep their meaning for the corpus
    if (!soft && !wall[0] && !wall[1] && c.sometimes(64)) {
        const std::string rate = "shear_rate = " + toml_number(c.geometric(0.01, 5.0)) + "\n";
        const std::size_t boundary = t.find("boundary = [");
        t.insert(t.find('\n', boundary) + 1, rate);
        if (dynamics == "event" && c.sometimes(128)) {
            const std::string thermostat =
                "thermostat = \"rescale\"\ntemperature = " + toml_number(c.geometric(0.1, 10.0)) +
                "\nthermostat_interval = " + toml_number(run_length * c.geometric(0.01, 2.0)) +
                "\n";
            t.insert(t.find("[event]\n") + 8, thermostat);
        }
    }
    add_ensembles(c, dynamics, t);
    add_hard_drives(c, dynamics, wall, t);
    // the soft engine's float pair rows (top level: before the first table)
    if (soft && c.sometimes(64)) t.insert(t.find("[box]\n"), "precision = \"mixed\"\n");
    return t;
}

// The stops the docs give for exit 3 that mean the dynamics were driven too hard (a dt too
// large for the forces or speeds, inelastic collapse, growth past the box): the config's
// fault, not the engine's. Any other RunError (an overlap in exact dynamics, a particle
// outside the box, a broken list, a collapse without inelastic collisions) is a finding.
inline bool physical_stop(const std::string& message, const RunConfig& config) {
    static const char* const allowed[] = {
        "in one step, more than",                // soft blow-up: a move past the skin
        "got a non-finite displacement",         // soft blow-up
        "radii in one step of dt",               // stepped: a particle too fast for dt
        "collisions in one step",                // stepped: packed too tightly for dt
        "have grown to a contact distance",      // event growth: the box became too small
        "the box changed by more than",          // [barostat]: far from its pressure for its tau
        "within a diameter of the opposite wall" // a driven wall at the end of its stroke
    };
    const auto has = [&](const char* a) { return message.find(a) != std::string::npos; };
    // events piling up at one instant: inelastic collapse (which needs inelastic
    // collisions), growing particles that have jammed, or a particle at rest on a floor
    // under gravity (a lattice placed on it: the stop's message says so); elastic
    // particles that do not grow or fall never should
    if (has("time stopped advancing"))
        return config.restitution < 1.0 || config.wall_restitution < 1.0 ||
               config.growth_rate > 0.0 || !config.gravity.empty();
    return std::any_of(std::begin(allowed), std::end(allowed), has);
}

// Set up and run the config of the bytes in a run directory of this process, removed
// afterwards whatever happens.
inline void run_input(const std::uint8_t* data, std::size_t size) {
    const std::string text = run_config_text(data, size);
    // in memory where there is a tmpfs: the checkpoint's fsync on a disk takes longer than
    // the whole run
    const std::filesystem::path shm = "/dev/shm";
    const auto dir =
        (std::filesystem::is_directory(shm) ? shm : std::filesystem::temp_directory_path()) /
        ("pedesis_fuzz_run_" + std::to_string(::getpid()));
    struct Remove {
        std::filesystem::path dir;
        ~Remove() {
            std::error_code ignored;
            std::filesystem::remove_all(dir, ignored);
        }
    } remove{dir};
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const auto config_path = dir / "fuzz_run.toml";
    std::ofstream(config_path, std::ios::trunc) << text; // copied into the run directory
    const RunConfig config = parse_run_config(text, config_path.string(), false);
    RunOptions o;
    o.out_dir = dir / "run";
    o.config_path = config_path;
    std::ostringstream console;
    try {
        const std::unique_ptr<Run> run = make_run(config, o, console);
        run->run();
    } catch (const RunError& e) {
        if (!physical_stop(e.what(), config)) throw;
    }
}

} // namespace pedesis::fuzz
