#include "pedesis/setup/barostat_config.hpp"

#include "pedesis/core/error.hpp"

#include <cmath>

namespace pedesis {

void read_barostat_config(ConfigTable& root, const std::string& dynamics, BarostatConfig& b) {
    auto t = root.table("barostat");
    if (!t) return;
    b.on = true;
    b.where = t->location() + ": table 'barostat'";
    if (dynamics != "nve" && dynamics != "langevin")
        throw InputError(b.where +
                         ": the barostat moves the box of the inertial soft engine; "
                         "set dynamics = \"nve\" (constant enthalpy) or \"langevin\" "
                         "(constant temperature), not \"" +
                         dynamics + "\"");
    if (!t->has("pressure")) throw InputError(b.where + ": needs pressure (the target, > 0)");
    b.pressure = t->required_number("pressure");
    if (!(b.pressure > 0.0 && std::isfinite(b.pressure)))
        throw InputError(t->where("pressure") + ": must be a positive finite number");
    if (!t->has("tau"))
        throw InputError(b.where + ": needs tau (the barostat's time constant, e.g. 1000 dt)");
    b.tau = t->required_number("tau");
    if (!(b.tau > 0.0 && std::isfinite(b.tau)))
        throw InputError(t->where("tau") + ": must be a positive finite time");
    const std::string coupling = t->string("coupling").value_or("isotropic");
    if (coupling != "isotropic" && coupling != "anisotropic")
        throw InputError(t->where("coupling") + ": '" + coupling +
                         "' is not \"isotropic\" (one strain rate for every axis) or "
                         "\"anisotropic\" (one per axis)");
    b.anisotropic = coupling == "anisotropic";
    t->finish();
}

} // namespace pedesis
