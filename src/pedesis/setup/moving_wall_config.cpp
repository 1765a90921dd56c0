#include "pedesis/setup/moving_wall_config.hpp"

#include "pedesis/core/error.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace pedesis {

void read_moving_wall(ConfigTable& ev, RunConfig& c) {
    auto t = ev.table("moving_wall");
    if (!t) return;
    const auto axis_name = t->string("axis");
    if (!axis_name) throw InputError(t->location() + ": [event.moving_wall] needs axis");
    const std::string axes = c.dimension == 3 ? "xyz" : "xy";
    const auto axis = axes.find(*axis_name);
    if (axis_name->size() != 1 || axis == std::string::npos)
        throw InputError(t->where("axis") + ": must be one of \"" +
                         std::string(axes.begin(), axes.end()).insert(1, "\", \"") + "\"");
    if (axis < c.periodic.size() && c.periodic[axis])
        throw InputError(t->where("axis") + ": axis " + *axis_name +
                         " is periodic; a moving wall needs walls there ([box] boundary)");
    const std::string side = t->string("side").value_or("lower");
    if (side != "lower" && side != "upper")
        throw InputError(t->where("side") + ": must be \"lower\" or \"upper\"");
    const bool vibrated = t->has("amplitude") || t->has("frequency");
    if (vibrated == t->has("speed"))
        throw InputError(t->location() +
                         ": [event.moving_wall] takes amplitude and frequency (a vibrated wall) "
                         "or speed (a wall driven at constant speed), not both nor neither");
    WallMotion m;
    if (vibrated) {
        m.amplitude = t->required_number("amplitude");
        const double f = t->required_number("frequency");
        if (!(m.amplitude > 0.0 && m.amplitude <= 1e100))
            throw InputError(t->where("amplitude") + ": must be positive");
        if (!(f > 0.0 && f <= 1e100))
            throw InputError(t->where("frequency") + ": must be positive");
        m.angular_frequency = 2.0 * std::numbers::pi * f;
    } else {
        m.speed = t->required_number("speed");
        if (!(m.speed > 0.0 && m.speed <= 1e100))
            throw InputError(t->where("speed") +
                             ": must be positive (the wall moves into the box)");
    }
    if (c.growth_rate > 0.0)
        throw InputError(t->location() + ": a moving wall is not available with growth");
    if (c.shear_rate > 0.0)
        throw InputError(t->location() + ": a moving wall is not available with shear");
    t->finish();
    c.moving_wall_axis = static_cast<int>(axis);
    c.moving_wall_upper = side == "upper";
    c.moving_wall = m;
}

} // namespace pedesis
