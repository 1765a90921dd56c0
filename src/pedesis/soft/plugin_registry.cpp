#include "pedesis/soft/plugin_registry.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/config_table.hpp"
#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/bussi.hpp"
#include "pedesis/soft/langevin.hpp"
#include "pedesis/soft/nose_hoover.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"
#include "pedesis/soft/plugin_rows.hpp"
#include "pedesis/soft/polar_align.hpp"
#include "pedesis/soft/self_propulsion.hpp"
#include "pedesis/soft/velocity_verlet.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace pedesis {

namespace {

using namespace rows;

// A pair force with one evaluator per species pair; make(value) builds the evaluator of
// one pair from value(key, fallback), that pair's parameter.
template <class Pair, int D, class Make>
void add_pair_force(Evolver<D>& e, const PluginSpec& spec, const std::vector<Species>& species,
                    Make make) {
    const std::size_t n = species.size();
    std::vector<Pair> table(n * n);
    for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = 0; b < n; ++b)
            table[a * n + b] = make([&](const char* key, double fallback) {
                return pair_parameter(spec, key, species, a, b, fallback);
            });
    e.add_force(std::make_unique<PairForce<D, Pair>>(spec.name, std::move(table), n));
}

constexpr const char* uniform_noise_doc =
    "draw the noise uniform on [-sqrt 3, sqrt 3] (mean 0, variance 1, as LAMMPS' fix "
    "langevin and fix brownian's default) instead of Gaussian: the same diffusion and "
    "temperature, cheaper to draw (default false)";

detail::NoiseShape noise_shape(const PluginSpec& spec) {
    return flag(spec, "uniform_noise") ? detail::NoiseShape::uniform : detail::NoiseShape::gaussian;
}

// The pair potentials, the ABP tutorial's terms and the integrators.
std::vector<PluginInfo> core_rows() {
    return {
        row({PluginKind::force,
             "harmonic",
             "HarmonicForce",
             {{"k", required, ParamLimit::non_negative, per_species, "spring constant"},
              {"a", optional, ParamLimit::positive, per_species,
               "range; default: the contact distance r_i + r_j", length}},
             "F_ij = k (a - r_ij) r_ij/|r_ij| for r_ij < a; U = k (a - r_ij)^2 / 2",
             true},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>& sp,
                               std::uint64_t) {
                add_pair_force<HarmonicPair>(e, s, sp, [](auto value) {
                    return HarmonicPair{value("k", 0.0), value("a", -1.0)};
                });
            })),
        row({PluginKind::force,
             "wca",
             "WcaForce",
             {{"epsilon", required, ParamLimit::non_negative, per_species, "energy scale"},
              {"sigma", optional, ParamLimit::positive, per_species,
               "length scale; default: the contact distance r_i + r_j", length}},
             "U = 4 eps [(sigma/r)^12 - (sigma/r)^6] + eps for r < 2^(1/6) sigma",
             true},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>& sp,
                               std::uint64_t) {
                add_pair_force<WcaPair>(e, s, sp, [](auto value) {
                    return WcaPair{value("epsilon", 0.0), value("sigma", -1.0)};
                });
            })),
        row({PluginKind::force,
             "lj",
             "LjForce",
             {{"epsilon", required, ParamLimit::non_negative, per_species, "energy scale"},
              {"sigma", optional, ParamLimit::positive, per_species,
               "length scale; default: the contact distance r_i + r_j", length},
              {"cutoff", optional, ParamLimit::positive, shared,
               "cutoff in units of sigma; default 2.5"}},
             "U = 4 eps [(sigma/r)^12 - (sigma/r)^6] (- U(r_c) with shift) for r < cutoff sigma",
             true,
             {{"shift", "subtract U(r_c), so that the energy is continuous at the cutoff "
                        "(default false, as LAMMPS' lj/cut)"},
              {"tail", "add the energy and pressure beyond the cutoff of a homogeneous fluid "
                       "(g(r) = 1 there), as LAMMPS' pair_modify tail yes; forces unchanged; "
                       "not with shift (default false)"}}},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>& sp,
                               std::uint64_t) {
                const bool shift = flag(s, "shift"), tail = flag(s, "tail");
                if (shift && tail)
                    throw InputError(s.name +
                                     ": shift and tail together: the tail correction completes "
                                     "the truncated potential, not the shifted one (as in LAMMPS, "
                                     "where pair_modify tail yes goes with lj/cut unshifted); "
                                     "choose one");
                add_pair_force<LjPair>(e, s, sp, [shift, tail](auto value) {
                    return LjPair{value("epsilon", 0.0), value("sigma", -1.0), value("cutoff", 2.5),
                                  shift, tail};
                });
            })),
        row({PluginKind::force,
             "self_propulsion",
             "SelfPropulsion",
             {{"alpha", required, ParamLimit::any, per_species, "active force magnitude"}},
             "F_i = alpha n_i"},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>& sp,
                               std::uint64_t) {
                e.add_force(std::make_unique<SelfPropulsion<D>>(plugin_parameter(s, "alpha", sp)));
            })),
        row({PluginKind::torque,
             "polar_align",
             "PolarAlign",
             {{"J", required, ParamLimit::any, shared, "alignment strength"},
              {"a", required, ParamLimit::positive, shared, "alignment range"}},
             "tau_i = J sum_{r_ij < a} n_i x n_j (2D: J sum sin(theta_j - theta_i))"},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>&,
                               std::uint64_t) {
                e.add_torque(
                    std::make_unique<PolarAlign<D>>(uniform(s, "J", 0.0), uniform(s, "a", 0.0)));
            })),
        row({PluginKind::integrator,
             "brownian",
             "BrownianIntegrator",
             {{"T", required, ParamLimit::non_negative, per_species, "temperature"},
              {"gamma", required, ParamLimit::positive, per_species, "friction coefficient"}},
             "r += dt F / gamma + sqrt(2 T dt / gamma) xi",
             false,
             {{"uniform_noise", uniform_noise_doc}}},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>& sp,
                               std::uint64_t seed) {
                e.add_integrator(std::make_unique<BrownianIntegrator<D>>(
                    plugin_parameter(s, "T", sp), plugin_parameter(s, "gamma", sp), seed,
                    noise_shape(s)));
            })),
        row({PluginKind::integrator,
             "brownian_rotation",
             "BrownianRotIntegrator",
             {{"T", required, ParamLimit::non_negative, per_species,
               "rotational temperature (D_r = T / gamma)"},
              {"gamma", required, ParamLimit::positive, per_species, "rotational friction"}},
             "theta += dt tau / gamma + sqrt(2 T dt / gamma) xi (3D: n rotated about the same "
             "vector)"},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>& sp,
                               std::uint64_t seed) {
                e.add_integrator(std::make_unique<BrownianRotationIntegrator<D>>(
                    plugin_parameter(s, "T", sp), plugin_parameter(s, "gamma", sp), seed));
            })),
        row({PluginKind::integrator,
             "langevin",
             "LangevinIntegrator",
             {{"T", required, ParamLimit::non_negative, per_species, "temperature"},
              {"gamma", required, ParamLimit::positive, per_species,
               "friction coefficient (force -gamma v)"}},
             "m dv = F dt - gamma v dt + sqrt(2 gamma T) dW (BAOAB splitting)",
             false,
             {{"uniform_noise", uniform_noise_doc}}},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>& sp,
                               std::uint64_t seed) {
                e.add_integrator(std::make_unique<LangevinIntegrator<D>>(
                    plugin_parameter(s, "T", sp), plugin_parameter(s, "gamma", sp), seed,
                    noise_shape(s)));
            })),
        row({PluginKind::integrator, "nve", "NVEIntegrator", {}, "velocity Verlet: m dv/dt = F"},
            builders([]<int D>(Evolver<D>& e, const PluginSpec&, const std::vector<Species>&,
                               std::uint64_t) {
                e.add_integrator(std::make_unique<VelocityVerletIntegrator<D>>());
            })),
        row({PluginKind::integrator,
             "bussi",
             "BussiIntegrator",
             {{"T", required, ParamLimit::non_negative, shared, "temperature"},
              {"tau", required, ParamLimit::positive, shared,
               "relaxation time of the kinetic energy"}},
             "velocity Verlet with the kinetic energy rescaled stochastically: dK = (f T / 2 - "
             "K) dt / tau + 2 sqrt(K T / 2) dW / sqrt(tau) (Bussi, Donadio & Parrinello 2007)"},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>&,
                               std::uint64_t seed) {
                e.add_integrator(std::make_unique<BussiIntegrator<D>>(
                    uniform(s, "T", 0.0), uniform(s, "tau", 0.0), seed));
            })),
        row({PluginKind::integrator,
             "nose_hoover",
             "NoseHooverIntegrator",
             {{"T", required, ParamLimit::positive, shared, "temperature"},
              {"tau", required, ParamLimit::positive, shared,
               "period of the thermostat's oscillations (masses Q_1 = f T tau^2, Q_j = T tau^2)"},
              {"chain", optional, ParamLimit::positive, shared,
               "thermostats in the chain, a whole number (default 3, as LAMMPS' tchain)"}},
             "velocity Verlet with m dv/dt = F - m v_1 v, v_1 the first of a Nose-Hoover chain "
             "(Martyna, Klein & Tuckerman 1992)"},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>&,
                               std::uint64_t) {
                const double chain = uniform(s, "chain", 3.0);
                if (chain != std::floor(chain) || chain > 1000.0)
                    throw InputError(s.params.at("chain").where +
                                     ": must be a whole number of thermostats (at most 1000)");
                e.add_integrator(std::make_unique<NoseHooverIntegrator<D>>(
                    uniform(s, "T", 0.0), uniform(s, "tau", 0.0), static_cast<int>(chain)));
            })),
    };
}

} // namespace

const std::vector<PluginInfo>& plugin_catalogue() {
    static const std::vector<PluginInfo> catalogue = [] {
        std::vector<PluginInfo> all = core_rows();
        for (auto more : {active_model_rows, active_ou_rows, external_field_rows, wall_rows})
            for (PluginInfo& info : more()) all.push_back(std::move(info));
        return all;
    }();
    return catalogue;
}

const char* kind_name(PluginKind kind) {
    switch (kind) {
    case PluginKind::force:
        return "force";
    case PluginKind::torque:
        return "torque";
    case PluginKind::integrator:
        return "integrator";
    }
    return "?";
}

namespace {

const PluginInfo* find_plugin(PluginKind kind, const std::string& name) {
    for (const auto& p : plugin_catalogue())
        if (p.kind == kind && name == p.name) return &p;
    return nullptr;
}

std::string known_names(PluginKind kind) {
    std::string s;
    for (const auto& p : plugin_catalogue())
        if (p.kind == kind) s += std::string(s.empty() ? "" : ", ") + p.name;
    return s;
}

void check_limit(double v, ParamLimit limit, const std::string& where) {
    if (!std::isfinite(v)) throw InputError(where + ": must be a finite number");
    if (limit == ParamLimit::positive && !(v > 0.0)) throw InputError(where + ": must be positive");
    if (limit == ParamLimit::non_negative && !(v >= 0.0))
        throw InputError(where + ": must be >= 0");
}

const PluginInfo& plugin_info(PluginKind kind, const std::string& name, const std::string& where) {
    const PluginInfo* info = find_plugin(kind, name);
    if (!info)
        throw InputError(where + ": unknown " + kind_name(kind) + " '" + name +
                         "' (known: " + known_names(kind) + ")");
    return *info;
}

void require_param(const PluginSpec& spec, const ParamInfo& p) {
    if (p.required)
        throw InputError(spec.where + ": " + kind_name(spec.kind) + " '" + spec.name + "' needs " +
                         p.key + " (" + p.meaning + ")");
}

const ParamInfo* param_info(const PluginInfo& info, const std::string& key) {
    for (const ParamInfo& p : info.params)
        if (key == p.key) return &p;
    return nullptr;
}

// The options only a pair potential has: per-pair values and the mixing rule.
void check_pair_options(const PluginSpec& spec, const PluginInfo& info) {
    if (!info.pair_potential) return;
    if (std::find_if(std::begin(mixing_rules), std::end(mixing_rules),
                     [&](const char* r) { return spec.mixing == r; }) == std::end(mixing_rules))
        throw InputError(spec.where + ": " + spec.name + ": mixing '" + spec.mixing +
                         "' is not a mixing rule (known: geometric, arithmetic)");
    for (std::size_t k = 0; k < spec.pairs.size(); ++k) {
        const PairValues& pv = spec.pairs[k];
        if (pv.values.empty())
            throw InputError(pv.where + ": the pair " + pv.a + "-" + pv.b +
                             " gives no parameter of " + spec.name);
        for (const auto& [key, v] : pv.values) {
            const ParamInfo* p = param_info(info, key);
            if (!p)
                throw InputError(pv.where + ": " + spec.name + " has no parameter '" + key + "'");
            check_limit(v, p->limit, pv.where + " (" + key + ")");
        }
        for (std::size_t j = 0; j < k; ++j) {
            const PairValues& other = spec.pairs[j];
            if ((other.a == pv.a && other.b == pv.b) || (other.a == pv.b && other.b == pv.a))
                throw InputError(pv.where + ": the pair " + pv.a + "-" + pv.b +
                                 " is given twice (also at " + other.where + ")");
        }
    }
}

const ChoiceInfo* choice_info(const PluginInfo& info, const std::string& key) {
    for (const ChoiceInfo& c : info.choices)
        if (key == c.key) return &c;
    return nullptr;
}

void check_choice(const ChoiceInfo& c, const std::string& word, const std::string& where) {
    std::string known;
    for (const char* option : c.options) {
        if (word == option) return;
        known += std::string(known.empty() ? "" : ", ") + option;
    }
    throw InputError(where + ": '" + word + "' is not one of " + known + " (" + c.meaning + ")");
}

PairValues read_pair_values(ConfigTable& t, const PluginInfo& info) {
    PairValues pv;
    pv.where = t.where("species");
    const auto names = t.strings("species", 2);
    if (!names || names->size() != 2)
        throw InputError(pv.where + ": each [[force.pairs]] needs species = [\"A\", \"B\"]");
    pv.a = (*names)[0];
    pv.b = (*names)[1];
    for (const ParamInfo& p : info.params)
        if (t.has(p.key)) pv.values[p.key] = *t.number(p.key);
    t.finish();
    return pv;
}

} // namespace

PluginSpec make_plugin_spec(PluginKind kind, const std::string& name,
                            std::map<std::string, PluginParam> given, const std::string& where,
                            std::map<std::string, bool> flags, std::vector<PairValues> pairs,
                            const std::string& mixing, std::map<std::string, std::string> choices) {
    PluginSpec spec;
    spec.kind = kind;
    spec.name = name;
    spec.where = where;
    const PluginInfo& info = plugin_info(kind, name, where);
    // (words first: a word given for a number says so before a missing number does)
    for (auto& [key, word] : choices) {
        const ChoiceInfo* choice = choice_info(info, key);
        if (!choice && param_info(info, key))
            throw InputError(where + ": " + key + ": must be a number, got '" + word + "'");
        if (!choice)
            throw InputError(where + ": " + kind_name(kind) + " '" + name + "' has no option '" +
                             key + "'");
        check_choice(*choice, word, where + ": " + key);
        spec.choices[key] = word;
    }
    for (const ParamInfo& p : info.params) {
        const auto it = given.find(p.key);
        if (it == given.end()) {
            require_param(spec, p);
            continue;
        }
        PluginParam& value = it->second;
        if (!value.by_species.empty() && !p.per_species)
            throw InputError(value.where + ": is one number for all species");
        if (!value.components.empty() && !p.per_axis)
            throw InputError(value.where + ": is one number, not a list");
        if (!value.uniform && value.by_species.empty() && value.components.empty())
            throw InputError(value.where + ": names no species");
        if (value.uniform) check_limit(*value.uniform, p.limit, value.where);
        for (double v : value.components) check_limit(v, p.limit, value.where);
        for (const auto& [species, v] : value.by_species)
            check_limit(v, p.limit, value.where + " (species '" + species + "')");
        spec.params[p.key] = value;
        given.erase(it);
    }
    if (!given.empty()) {
        std::string keys;
        for (const ParamInfo& p : info.params)
            keys += std::string(keys.empty() ? "" : ", ") + p.key;
        throw InputError(given.begin()->second.where + ": " + kind_name(kind) + " '" + name +
                         "' has no parameter '" + given.begin()->first +
                         "' (it has: " + (keys.empty() ? std::string("none") : keys) + ")");
    }
    for (const auto& flag : flags) {
        const std::string& key = flag.first;
        const bool on = flag.second;
        if (std::none_of(info.flags.begin(), info.flags.end(),
                         [&](const FlagInfo& f) { return key == f.key; }))
            throw InputError(where + ": " + kind_name(kind) + " '" + name + "' has no option '" +
                             key + "'");
        spec.flags[key] = on;
    }
    if (!info.pair_potential && (!pairs.empty() || mixing != "geometric"))
        throw InputError(where + ": " + name + " is not a pair potential: no pairs or mixing");
    spec.pairs = std::move(pairs);
    spec.mixing = mixing;
    check_pair_options(spec, info);
    return spec;
}

PluginSpec read_plugin(ConfigTable& t, PluginKind kind) {
    PluginSpec spec;
    spec.kind = kind;
    const auto name = t.string("name");
    if (!name)
        throw InputError(t.where("name") + ": a [[" + std::string(kind_name(kind)) +
                         "]] needs a name (one of: " + known_names(kind) + ")");
    spec.name = *name;
    spec.where = t.where("name");
    const PluginInfo& info = plugin_info(kind, *name, spec.where);
    for (const ParamInfo& p : info.params) {
        if (!t.has(p.key)) {
            require_param(spec, p);
            continue;
        }
        PluginParam value;
        value.where = t.where(p.key);
        if (t.is_table(p.key)) {
            if (!p.per_species) throw InputError(value.where + ": is one number for all species");
            auto sub = t.table(p.key);
            for (const std::string& species : sub->keys()) {
                const double v = *sub->number(species);
                check_limit(v, p.limit, sub->where(species));
                value.by_species.emplace_back(species, v);
            }
            if (value.by_species.empty()) throw InputError(value.where + ": names no species");
        } else if (const auto size = t.list_size(p.key); size && p.per_axis) {
            value.components = *t.numbers(p.key, *size);
            if (value.components.empty())
                throw InputError(value.where + ": give one number per axis");
            for (double v : value.components) check_limit(v, p.limit, value.where);
        } else {
            const double v = *t.number(p.key);
            check_limit(v, p.limit, value.where);
            value.uniform = v;
        }
        spec.params[p.key] = value;
    }
    for (const FlagInfo& f : info.flags)
        if (t.has(f.key)) spec.flags[f.key] = *t.boolean(f.key);
    for (const ChoiceInfo& c : info.choices)
        if (t.has(c.key)) {
            const std::string word = *t.string(c.key);
            check_choice(c, word, t.where(c.key));
            spec.choices[c.key] = word;
        }
    if (info.pair_potential) {
        if (t.has("mixing")) spec.mixing = *t.string("mixing");
        for (ConfigTable& pair : t.tables("pairs"))
            spec.pairs.push_back(read_pair_values(pair, info));
    }
    check_pair_options(spec, info);
    t.finish();
    return spec;
}

PerSpecies plugin_parameter(const PluginSpec& spec, const std::string& key,
                            const std::vector<Species>& species) {
    const PluginParam& p = spec.params.at(key);
    if (p.uniform) return PerSpecies(*p.uniform);
    if (!p.components.empty())
        throw InputError(p.where + ": a list per axis here is not read by " + spec.name);
    std::vector<double> v;
    for (const auto& s : species) {
        const auto it = std::find_if(p.by_species.begin(), p.by_species.end(),
                                     [&](const auto& e) { return e.first == s.name; });
        if (it == p.by_species.end())
            throw InputError(p.where + ": has no value for species '" + s.name + "'");
        v.push_back(it->second);
    }
    for (const auto& entry : p.by_species) {
        const std::string& name = entry.first; // (clang 14 cannot capture a binding)
        if (std::none_of(species.begin(), species.end(),
                         [&](const Species& s) { return s.name == name; }))
            throw InputError(p.where + ": there is no species '" + name + "'");
    }
    return PerSpecies(std::move(v));
}

std::string plugin_choice(const PluginSpec& spec, const std::string& key) {
    if (const auto it = spec.choices.find(key); it != spec.choices.end()) return it->second;
    const ChoiceInfo* c = choice_info(plugin_info(spec.kind, spec.name, spec.where), key);
    if (!c) throw std::logic_error(spec.name + " has no choice '" + key + "'");
    return c->fallback;
}

std::vector<double> plugin_axes(const PluginSpec& spec, const std::string& key, int dimension,
                                double fallback) {
    const auto it = spec.params.find(key);
    if (it == spec.params.end()) return std::vector<double>(dimension, fallback);
    const PluginParam& p = it->second;
    if (!p.components.empty()) {
        if (p.components.size() != static_cast<std::size_t>(dimension))
            throw InputError(p.where + ": gives " + std::to_string(p.components.size()) +
                             " numbers for a " + std::to_string(dimension) +
                             "D box: give one per axis, or one for all");
        return p.components;
    }
    if (!p.uniform) throw InputError(p.where + ": is one number for all species");
    return std::vector<double>(dimension, *p.uniform);
}

int axis_index(const std::string& name, int dimension, const std::string& where) {
    static constexpr const char* names[] = {"x", "y", "z"};
    for (int a = 0; a < dimension; ++a)
        if (name == names[a]) return a;
    throw InputError(where + ": a " + std::to_string(dimension) + "D box has no axis '" + name +
                     "'");
}

double pair_parameter(const PluginSpec& spec, const std::string& key,
                      const std::vector<Species>& species, std::size_t a, std::size_t b,
                      double fallback) {
    for (const PairValues& pv : spec.pairs) {
        for (const std::string* name : {&pv.a, &pv.b})
            if (std::none_of(species.begin(), species.end(),
                             [&](const Species& s) { return s.name == *name; }))
                throw InputError(pv.where + ": there is no species '" + *name + "'");
        const std::string &na = species[a].name, &nb = species[b].name;
        if ((pv.a == na && pv.b == nb) || (pv.a == nb && pv.b == na))
            if (const auto it = pv.values.find(key); it != pv.values.end()) return it->second;
    }
    const auto it = spec.params.find(key);
    if (it == spec.params.end()) return fallback;
    if (it->second.uniform) return *it->second.uniform;
    const PerSpecies v = plugin_parameter(spec, key, species);
    const double va = v.at(a, species.size()), vb = v.at(b, species.size());
    const ParamInfo* p = param_info(plugin_info(spec.kind, spec.name, spec.where), key);
    if (p && p->length && spec.mixing == "arithmetic") return 0.5 * (va + vb);
    return std::sqrt(va * vb);
}

template <int D>
void add_plugin(Evolver<D>& e, const PluginSpec& spec, const std::vector<Species>& species,
                std::uint64_t seed) {
    const PluginInfo& info = plugin_info(spec.kind, spec.name, spec.where);
    if constexpr (D == 2)
        info.add2(e, spec, species, seed);
    else
        info.add3(e, spec, species, seed);
}

template void add_plugin<2>(Evolver<2>&, const PluginSpec&, const std::vector<Species>&,
                            std::uint64_t);
template void add_plugin<3>(Evolver<3>&, const PluginSpec&, const std::vector<Species>&,
                            std::uint64_t);

} // namespace pedesis
