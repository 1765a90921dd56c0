// The catalogue's rows of walls and containers (plugin_rows.hpp).
#include "pedesis/soft/plugin_rows.hpp"
#include "pedesis/soft/wall_force.hpp"

#include <string>

namespace pedesis::rows {

namespace {

WallPotential wall_potential(const std::string& word) {
    if (word == "lj93") return WallPotential::lj93;
    if (word == "harmonic") return WallPotential::harmonic;
    return WallPotential::wca;
}

template <int D> typename WallForce<D>::Shape wall_shape(const PluginSpec& s) {
    typename WallForce<D>::Shape shape;
    const std::string word = plugin_choice(s, "shape");
    shape.kind = word == "sphere"     ? WallShape::sphere
                 : word == "cylinder" ? WallShape::cylinder
                                      : WallShape::planes;
    const bool container = shape.kind != WallShape::planes;
    const auto radius = s.params.find("radius");
    if (container && radius == s.params.end())
        throw InputError(s.where + ": a " + word + " wall needs radius (the container's)");
    if (!container)
        for (const char* key : {"radius", "centre"})
            if (s.params.count(key))
                throw InputError(s.params.at(key).where +
                                 ": planes are the box's walled faces: no " + key +
                                 " (a container is shape = \"sphere\" or \"cylinder\")");
    if (!container && s.choices.count("axis"))
        throw InputError(s.where + ": axis is a cylinder's; planes are the box's walled faces");
    if (container) shape.radius = *radius->second.uniform;
    const std::vector<double> centre = plugin_axes(s, "centre", D, 0.0);
    for (int a = 0; a < D; ++a) shape.centre[a] = centre[a];
    const std::string axis = plugin_choice(s, "axis");
    shape.axis = axis.empty() ? D - 1 : axis_index(axis, D, s.where + ": axis");
    return shape;
}

} // namespace

std::vector<PluginInfo> wall_rows() {
    return {
        row({PluginKind::force,
             "wall",
             "Wall",
             {{"epsilon", optional, ParamLimit::non_negative, per_species,
               "energy scale of wca and lj93 (default 1)"},
              {"sigma", optional, ParamLimit::positive, per_species,
               "length scale: wca's and lj93's sigma, harmonic's range (default: the species' "
               "radius)"},
              {"k", optional, ParamLimit::non_negative, per_species,
               "harmonic's spring constant (needed by harmonic)"},
              {"cutoff", optional, ParamLimit::positive, shared,
               "lj93's cutoff in units of sigma (default 2.5)"},
              {"torque", optional, ParamLimit::any, shared,
               "c in tau_i = c n_i x F_i: the wall turns directors towards its push (default 0: "
               "torque-free)"},
              {"radius", optional, ParamLimit::positive, shared,
               "a container's radius (sphere, cylinder)"},
              {"centre", optional, ParamLimit::any, shared,
               "a container's centre, one number per axis (default: the origin)", false, true}},
             "U(h) of the distance h from the wall: wca 4 eps [(s/h)^12 - (s/h)^6] + eps for h < "
             "2^(1/6) s; lj93 eps [2/15 (s/h)^9 - (s/h)^3] shifted to 0 at cutoff s; harmonic "
             "k (s - h)^2 / 2 for h < s",
             false,
             {},
             {{"potential", {"wca", "lj93", "harmonic"}, "wca", "the wall potential"},
              {"shape",
               {"planes", "sphere", "cylinder"},
               "planes",
               "planes: the faces of the box's walled axes; sphere (2D: a circle) or cylinder: a "
               "container of the given radius"},
              {"axis", {"x", "y", "z"}, "", "a cylinder's axis (default: the last axis)"}}},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>& sp,
                               std::uint64_t) {
                const WallPotential potential = wall_potential(plugin_choice(s, "potential"));
                if (potential == WallPotential::harmonic && !s.params.count("k"))
                    throw InputError(s.where + ": a harmonic wall needs k (its spring constant)");
                if (potential != WallPotential::harmonic && s.params.count("k"))
                    throw InputError(s.params.at("k").where + ": k is the harmonic wall's; a " +
                                     plugin_choice(s, "potential") + " wall takes epsilon");
                std::optional<PerSpecies> sigma;
                if (s.params.count("sigma"))
                    sigma = plugin_parameter(s, "sigma", sp);
                else
                    for (const Species& species : sp)
                        if (!(species.radius > 0.0))
                            throw InputError(s.where + ": species '" + species.name +
                                             "' has radius 0, and the wall's sigma defaults to "
                                             "the radius: give sigma");
                const PerSpecies epsilon = s.params.count("epsilon")
                                               ? plugin_parameter(s, "epsilon", sp)
                                               : PerSpecies(1.0);
                const PerSpecies k =
                    s.params.count("k") ? plugin_parameter(s, "k", sp) : PerSpecies(0.0);
                e.add_force(std::make_unique<WallForce<D>>(potential, wall_shape<D>(s), epsilon,
                                                           sigma, k, uniform(s, "cutoff", 2.5),
                                                           uniform(s, "torque", 0.0)));
            })),
    };
}

} // namespace pedesis::rows
