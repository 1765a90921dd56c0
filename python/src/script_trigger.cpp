#include "script_trigger.hpp"

#include "pedesis/core/error.hpp"

#include <cmath>

namespace pedesis::python {

Trigger make_trigger(std::optional<std::uint64_t> steps, std::optional<double> time,
                     const std::string& what, bool has_steps) {
    if (steps.has_value() == time.has_value())
        throw InputError(what + ": give steps or time, one of them");
    if (steps) {
        if (*steps == 0) throw InputError(what + ": steps must be positive");
        if (!has_steps)
            throw InputError(what + ": the event engine has no steps; give time instead");
        return Trigger::every_steps(*steps);
    }
    if (!(std::isfinite(*time) && *time > 0))
        throw InputError(what + ": time must be a positive finite number");
    return Trigger::every_time(*time);
}

} // namespace pedesis::python
