#include "pedesis/soft/integrator_set.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/soft/plugin_registry.hpp"

#include <algorithm>

namespace pedesis {

namespace {

constexpr const char* rotation = "brownian_rotation";

// The integrators that turn the directors instead of moving the particles: beside the
// one position integrator, each at most once, for the reason given.
struct DirectorIntegrator {
    const char* name;
    const char* twice; // what a second one would do
};
constexpr DirectorIntegrator director_integrators[] = {
    {rotation, "the directors would turn twice per step"},
    {"run_and_tumble", "the particles would tumble at the sum of the rates"},
};

const DirectorIntegrator* turning(const std::string& name) {
    for (const DirectorIntegrator& d : director_integrators)
        if (name == d.name) return &d;
    return nullptr;
}

std::string named(const std::string& name, PluginNaming naming) {
    if (naming == PluginNaming::config) return "'" + name + "'";
    for (const PluginInfo& info : plugin_catalogue())
        if (info.kind == PluginKind::integrator && name == info.name)
            return std::string(info.python_class) + " ('" + name + "')";
    return "'" + name + "'";
}

} // namespace

bool moves_positions(const PluginSpec& integrator) {
    return turning(integrator.name) == nullptr;
}

std::string position_integrators(PluginNaming naming) {
    std::string s;
    for (const PluginInfo& info : plugin_catalogue())
        if (info.kind == PluginKind::integrator && !turning(info.name))
            s += (s.empty() ? "" : ", ") +
                 std::string(naming == PluginNaming::config ? info.name : info.python_class);
    return s;
}

void check_integrator_added(const std::vector<PluginSpec>& present, const PluginSpec& added,
                            PluginNaming naming) {
    for (const PluginSpec& p : present) {
        if (const DirectorIntegrator* d = turning(added.name); d && p.name == added.name)
            throw InputError(added.where + ": a second " + named(added.name, naming) +
                             " integrator (" + d->twice + "); give one");
        if (moves_positions(added) && moves_positions(p))
            throw InputError(added.where + ": a second position integrator (" +
                             named(p.name, naming) +
                             " is already there, and both would move the particles every step); "
                             "give exactly one of " +
                             position_integrators(naming));
    }
}

void check_integrators_complete(const std::vector<PluginSpec>& integrators,
                                const std::vector<PluginSpec>& torques, const std::string& missing,
                                PluginNaming naming) {
    if (std::none_of(integrators.begin(), integrators.end(), moves_positions))
        throw InputError(missing);
    const bool rotates = std::any_of(integrators.begin(), integrators.end(),
                                     [](const PluginSpec& i) { return i.name == rotation; });
    if (!torques.empty() && !rotates)
        throw InputError(torques.front().where + ": a torque turns nothing without a " +
                         named(rotation, naming) + " integrator");
}

} // namespace pedesis
