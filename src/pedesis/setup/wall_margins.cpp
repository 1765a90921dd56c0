#include "pedesis/setup/wall_margins.hpp"

#include "pedesis/soft/plugin_registry.hpp"

#include <algorithm>
#include <cmath>

namespace pedesis {

template <int D>
bool WallMargins<D>::inside(const Vec<D>& r, std::size_t s, const Box<D>& box) const {
    for (const Container& k : containers) {
        Vec<D> d = box.minimum_image(r - k.centre);
        if (k.cylinder) d[k.axis] = 0.0;
        if (!(norm(d) < k.radius - k.margin[s])) return false;
    }
    return true;
}

template <int D> WallMargins<D> wall_margins(const RunConfig& c) {
    WallMargins<D> m;
    std::vector<Species> table;
    for (const auto& s : c.species) {
        table.push_back(Species{s.name, s.radius, s.mass});
        m.face.push_back(s.radius);
    }
    if (!c.soft()) return m;
    for (const PluginSpec& spec : c.forces) {
        if (spec.name != "wall") continue;
        const std::string potential = plugin_choice(spec, "potential");
        const double core_fraction = potential == "wca"    ? 1.0
                                     : potential == "lj93" ? std::pow(2.0 / 15.0, 1.0 / 6.0)
                                                           : 0.0;
        std::vector<double> margin;
        const bool sigma_given = spec.params.count("sigma") > 0;
        for (std::size_t s = 0; s < table.size(); ++s) {
            const double sigma = sigma_given
                                     ? plugin_parameter(spec, "sigma", table).at(s, table.size())
                                     : table[s].radius;
            margin.push_back(std::max(table[s].radius, core_fraction * sigma));
        }
        const std::string shape = plugin_choice(spec, "shape");
        if (shape == "planes") {
            for (std::size_t s = 0; s < table.size(); ++s)
                m.face[s] = std::max(m.face[s], margin[s]);
            continue;
        }
        // (a container the wall's builder will refuse is none here)
        if (!spec.params.count("radius") || (shape == "cylinder" && D == 2)) continue;
        typename WallMargins<D>::Container k;
        k.cylinder = shape == "cylinder";
        const std::string axis = plugin_choice(spec, "axis");
        k.axis = axis.empty() ? D - 1 : axis_index(axis, D, spec.where);
        k.radius = *spec.params.at("radius").uniform;
        const std::vector<double> centre = plugin_axes(spec, "centre", D, 0.0);
        for (int a = 0; a < D; ++a) k.centre[a] = centre[static_cast<std::size_t>(a)];
        k.margin = std::move(margin);
        m.containers.push_back(std::move(k));
    }
    return m;
}

template struct WallMargins<2>;
template struct WallMargins<3>;
template WallMargins<2> wall_margins<2>(const RunConfig&);
template WallMargins<3> wall_margins<3>(const RunConfig&);

} // namespace pedesis
