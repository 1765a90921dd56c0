// The catalogue's row of active Ornstein-Uhlenbeck particles (plugin_rows.hpp).
#include "pedesis/soft/active_ou.hpp"
#include "pedesis/soft/plugin_rows.hpp"

namespace pedesis::rows {

std::vector<PluginInfo> active_ou_rows() {
    return {
        row({PluginKind::force,
             "active_ou",
             "ActiveOU",
             {{"tau", required, ParamLimit::positive, per_species,
               "persistence time of the active velocity"},
              {"D_a", required, ParamLimit::non_negative, per_species, "active diffusivity"}},
             "F_i = gamma p_i, tau dp_i = -p_i dt + sqrt(2 D_a) dW per axis (gamma: the "
             "position integrator's friction)"},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>& sp,
                               std::uint64_t seed) {
                add_active_ou(e, plugin_parameter(s, "tau", sp), plugin_parameter(s, "D_a", sp),
                              seed);
            })),
    };
}

} // namespace pedesis::rows
