// The catalogue's rows of external fields (plugin_rows.hpp).
#include "pedesis/soft/external_fields.hpp"
#include "pedesis/soft/plugin_rows.hpp"

namespace pedesis::rows {

namespace {

constexpr bool per_axis = true;

// The axis a field acts along: the word given, else the last (y in 2D, z in 3D).
int field_axis(const PluginSpec& spec, int dimension) {
    const std::string word = plugin_choice(spec, "axis");
    return word.empty() ? dimension - 1 : axis_index(word, dimension, spec.where + ": axis");
}

} // namespace

std::vector<PluginInfo> external_field_rows() {
    return {
        row({PluginKind::force,
             "gravity",
             "Gravity",
             {{"force", required, ParamLimit::any, per_species,
               "weight: the force along -axis on each particle (negative: upwards)"}},
             "F_i = -w_i e_axis; U = sum_i w_i x_i,axis (heights from the box's centre)",
             false,
             {},
             {{"axis",
               {"x", "y", "z"},
               "",
               "the axis the weight acts along (default: the last, y in 2D, z in 3D)"}}},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>& sp,
                               std::uint64_t) {
                e.add_force(std::make_unique<Gravity<D>>(plugin_parameter(s, "force", sp),
                                                         field_axis(s, D)));
            })),
        row({PluginKind::force,
             "harmonic_trap",
             "HarmonicTrap",
             {{"k", required, ParamLimit::non_negative, per_species,
               "stiffness: one number, one per species, or a list of one per axis (then the "
               "same for every species)",
               false, per_axis},
              {"centre", optional, ParamLimit::any, shared,
               "the trap's centre, a list of one number per axis (default: the box's centre, "
               "the origin)",
               false, per_axis}},
             "F_i,a = -k_a (x_i,a - c_a), nearest image of c on periodic axes; U = sum_i sum_a "
             "k_a (x_i,a - c_a)^2 / 2"},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>& sp,
                               std::uint64_t) {
                const bool by_axis = !s.params.at("k").components.empty();
                const std::vector<double> c = plugin_axes(s, "centre", D, 0.0);
                Vec<D> centre;
                for (int a = 0; a < D; ++a) centre[a] = c[static_cast<std::size_t>(a)];
                e.add_force(std::make_unique<HarmonicTrap<D>>(
                    by_axis ? PerSpecies(0.0) : plugin_parameter(s, "k", sp),
                    by_axis ? plugin_axes(s, "k", D, 0.0) : std::vector<double>{}, centre));
            })),
    };
}

} // namespace pedesis::rows
