#include "pedesis/soft/plugin_registry.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/config_table.hpp"
#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/langevin.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"
#include "pedesis/soft/polar_align.hpp"
#include "pedesis/soft/self_propulsion.hpp"
#include "pedesis/soft/velocity_verlet.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

namespace pedesis {

namespace {

constexpr bool required = true, optional = false;
constexpr bool per_species = true, shared = false;

} // namespace

const std::vector<PluginInfo>& plugin_catalogue() {
    static const std::vector<PluginInfo> catalogue = {
        {PluginKind::force,
         "harmonic",
         {{"k", required, ParamLimit::non_negative, shared, "spring constant"},
          {"a", optional, ParamLimit::positive, shared,
           "range; default: the contact distance r_i + r_j"}},
         "F_ij = k (a - r_ij) r_ij/|r_ij| for r_ij < a; U = k (a - r_ij)^2 / 2"},
        {PluginKind::force,
         "wca",
         {{"epsilon", required, ParamLimit::non_negative, shared, "energy scale"},
          {"sigma", optional, ParamLimit::positive, shared,
           "length scale; default: the contact distance r_i + r_j"}},
         "U = 4 eps [(sigma/r)^12 - (sigma/r)^6] + eps for r < 2^(1/6) sigma"},
        {PluginKind::force,
         "lj",
         {{"epsilon", required, ParamLimit::non_negative, shared, "energy scale"},
          {"sigma", optional, ParamLimit::positive, shared,
           "length scale; default: the contact distance r_i + r_j"},
          {"cutoff", optional, ParamLimit::positive, shared,
           "cutoff in units of sigma; default 2.5"}},
         "U = 4 eps [(sigma/r)^12 - (sigma/r)^6] for r < cutoff sigma (not shifted)"},
        {PluginKind::force,
         "self_propulsion",
         {{"alpha", required, ParamLimit::any, per_species, "active force magnitude"}},
         "F_i = alpha n_i"},
        {PluginKind::torque,
         "polar_align",
         {{"J", required, ParamLimit::any, shared, "alignment strength"},
          {"a", required, ParamLimit::positive, shared, "alignment range"}},
         "tau_i = J sum_{r_ij < a} n_i x n_j (2D: J sum sin(theta_j - theta_i))"},
        {PluginKind::integrator,
         "brownian",
         {{"T", required, ParamLimit::non_negative, per_species, "temperature"},
          {"gamma", required, ParamLimit::positive, per_species, "friction coefficient"}},
         "r += dt F / gamma + sqrt(2 T dt / gamma) xi"},
        {PluginKind::integrator,
         "brownian_rotation",
         {{"T", required, ParamLimit::non_negative, per_species,
           "rotational temperature (D_r = T / gamma)"},
          {"gamma", required, ParamLimit::positive, per_species, "rotational friction"}},
         "theta += dt tau / gamma + sqrt(2 T dt / gamma) xi (3D: n rotated about the same "
         "vector)"},
        {PluginKind::integrator,
         "langevin",
         {{"T", required, ParamLimit::non_negative, per_species, "temperature"},
          {"gamma", required, ParamLimit::positive, per_species,
           "friction coefficient (force -gamma v)"}},
         "m dv = F dt - gamma v dt + sqrt(2 gamma T) dW (BAOAB splitting)"},
        {PluginKind::integrator, "nve", {}, "velocity Verlet: m dv/dt = F"},
    };
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

} // namespace

PluginSpec make_plugin_spec(PluginKind kind, const std::string& name,
                            std::map<std::string, PluginParam> given, const std::string& where) {
    PluginSpec spec;
    spec.kind = kind;
    spec.name = name;
    spec.where = where;
    const PluginInfo& info = plugin_info(kind, name, where);
    for (const ParamInfo& p : info.params) {
        const auto it = given.find(p.key);
        if (it == given.end()) {
            require_param(spec, p);
            continue;
        }
        PluginParam& value = it->second;
        if (!value.by_species.empty() && !p.per_species)
            throw InputError(value.where + ": is one number for all species");
        if (!value.uniform && value.by_species.empty())
            throw InputError(value.where + ": names no species");
        if (value.uniform) check_limit(*value.uniform, p.limit, value.where);
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
        } else {
            const double v = *t.number(p.key);
            check_limit(v, p.limit, value.where);
            value.uniform = v;
        }
        spec.params[p.key] = value;
    }
    t.finish();
    return spec;
}

PerSpecies plugin_parameter(const PluginSpec& spec, const std::string& key,
                            const std::vector<Species>& species) {
    const PluginParam& p = spec.params.at(key);
    if (p.uniform) return PerSpecies(*p.uniform);
    std::vector<double> v;
    for (const auto& s : species) {
        const auto it = std::find_if(p.by_species.begin(), p.by_species.end(),
                                     [&](const auto& e) { return e.first == s.name; });
        if (it == p.by_species.end())
            throw InputError(p.where + ": has no value for species '" + s.name + "'");
        v.push_back(it->second);
    }
    for (const auto& [name, value] : p.by_species)
        if (std::none_of(species.begin(), species.end(),
                         [&](const Species& s) { return s.name == name; }))
            throw InputError(p.where + ": there is no species '" + name + "'");
    return PerSpecies(std::move(v));
}

namespace {

double uniform(const PluginSpec& spec, const std::string& key, double fallback) {
    const auto it = spec.params.find(key);
    return it == spec.params.end() ? fallback : *it->second.uniform;
}

} // namespace

template <int D>
void add_plugin(Evolver<D>& e, const PluginSpec& spec, const std::vector<Species>& species,
                std::uint64_t seed) {
    const std::string& n = spec.name;
    if (n == "harmonic")
        e.add_force(std::make_unique<PairForce<D, HarmonicPair>>(
            n, HarmonicPair{uniform(spec, "k", 0.0), uniform(spec, "a", -1.0)}));
    else if (n == "wca")
        e.add_force(std::make_unique<PairForce<D, WcaPair>>(
            n, WcaPair{uniform(spec, "epsilon", 0.0), uniform(spec, "sigma", -1.0)}));
    else if (n == "lj")
        e.add_force(std::make_unique<PairForce<D, LjPair>>(
            n, LjPair{uniform(spec, "epsilon", 0.0), uniform(spec, "sigma", -1.0),
                      uniform(spec, "cutoff", 2.5)}));
    else if (n == "self_propulsion")
        e.add_force(std::make_unique<SelfPropulsion<D>>(plugin_parameter(spec, "alpha", species)));
    else if (n == "polar_align")
        e.add_torque(
            std::make_unique<PolarAlign<D>>(uniform(spec, "J", 0.0), uniform(spec, "a", 0.0)));
    else if (n == "brownian")
        e.add_integrator(std::make_unique<BrownianIntegrator<D>>(
            plugin_parameter(spec, "T", species), plugin_parameter(spec, "gamma", species), seed));
    else if (n == "brownian_rotation")
        e.add_integrator(std::make_unique<BrownianRotationIntegrator<D>>(
            plugin_parameter(spec, "T", species), plugin_parameter(spec, "gamma", species), seed));
    else if (n == "langevin")
        e.add_integrator(std::make_unique<LangevinIntegrator<D>>(
            plugin_parameter(spec, "T", species), plugin_parameter(spec, "gamma", species), seed));
    else if (n == "nve")
        e.add_integrator(std::make_unique<VelocityVerletIntegrator<D>>());
    else
        throw InputError(spec.where + ": no plug-in '" + n + "' in this build");
}

template void add_plugin<2>(Evolver<2>&, const PluginSpec&, const std::vector<Species>&,
                            std::uint64_t);
template void add_plugin<3>(Evolver<3>&, const PluginSpec&, const std::vector<Species>&,
                            std::uint64_t);

} // namespace pedesis
