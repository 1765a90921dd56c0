// The catalogue's rows of the active models beyond ABPs (plugin_rows.hpp).
#include "pedesis/soft/plugin_rows.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/soft/active_torque.hpp"
#include "pedesis/soft/nematic_align.hpp"
#include "pedesis/soft/run_and_tumble.hpp"
#include "pedesis/soft/velocity_align.hpp"

#include <memory>
#include <string>

namespace pedesis::rows {

namespace {

// active_torque's `torque`: a number (or one per species) about z, or in 3D a list of
// three, one lab-frame vector for every species.
template <int D>
std::unique_ptr<ActiveTorque<D>> active_torque(const PluginSpec& spec,
                                               const std::vector<Species>& species) {
    const PluginParam& p = spec.params.at("torque");
    if (p.components.empty())
        return std::make_unique<ActiveTorque<D>>(plugin_parameter(spec, "torque", species));
    if (D == 2 || p.components.size() != 3)
        throw InputError(p.where + ": a " + std::to_string(D) + "D torque is one number (about z)" +
                         (D == 3 ? " or a list of three (a lab-frame vector), not a list of " +
                                       std::to_string(p.components.size())
                                 : std::string(", not a list")));
    TorqueVec<D> lab{};
    if constexpr (D == 3)
        for (int a = 0; a < 3; ++a) lab[a] = p.components[a];
    return std::make_unique<ActiveTorque<D>>(1.0, lab);
}

// The alignments' shared parameters.
std::vector<ParamInfo> alignment_params() {
    return {{"J", required, ParamLimit::any, shared, "alignment strength"},
            {"a", required, ParamLimit::positive, shared, "alignment range"}};
}

template <template <int> class Align> auto alignment_builders() {
    return builders(
        []<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>&, std::uint64_t) {
            e.add_torque(std::make_unique<Align<D>>(uniform(s, "J", 0.0), uniform(s, "a", 0.0)));
        });
}

} // namespace

std::vector<PluginInfo> active_model_rows() {
    return {
        row({PluginKind::torque,
             "active_torque",
             "ActiveTorque",
             {{"torque", required, ParamLimit::any, per_species,
               "torque c_s about z (with brownian_rotation of friction gamma: omega = c_s / "
               "gamma); in 3D also a list of three numbers, one lab-frame torque vector for "
               "every species",
               false, true}},
             "tau_i = c_s (2D; 3D: c_s e_z, or the lab-frame vector given); with "
             "brownian_rotation omega = tau / gamma"},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>& sp,
                               std::uint64_t) { e.add_torque(active_torque<D>(s, sp)); })),
        row({PluginKind::torque, "nematic_align", "NematicAlign", alignment_params(),
             "tau_i = J sum_{r_ij < a} (n_i . n_j) n_i x n_j (2D: (J/2) sum sin 2(theta_j - "
             "theta_i))"},
            alignment_builders<NematicAlign>()),
        row({PluginKind::torque, "velocity_align", "VelocityAlign", alignment_params(),
             "tau_i = J sum_{r_ij < a, j = i included} n_i x v_j / |v_j| (v_j = 0 adds "
             "nothing)"},
            alignment_builders<VelocityAlign>()),
        row({PluginKind::integrator,
             "run_and_tumble",
             "RunAndTumble",
             {{"rate", required, ParamLimit::non_negative, per_species,
               "tumble rate lambda (tumbles per unit time)"}},
             "each step n_i is drawn anew, uniformly on the circle (sphere), with probability "
             "1 - exp(-lambda dt)"},
            builders([]<int D>(Evolver<D>& e, const PluginSpec& s, const std::vector<Species>& sp,
                               std::uint64_t seed) {
                e.add_integrator(
                    std::make_unique<RunAndTumble<D>>(plugin_parameter(s, "rate", sp), seed));
            })),
    };
}

} // namespace pedesis::rows
