#pragma once
// The trigger of a script's writer, callback or recording: every `steps` steps or every
// `time` of simulated time, one of them, checked as the message names `what`.
#include "pedesis/run/trigger.hpp"

#include <cstdint>
#include <optional>
#include <string>

namespace pedesis::python {

Trigger make_trigger(std::optional<std::uint64_t> steps, std::optional<double> time,
                     const std::string& what, bool has_steps);

} // namespace pedesis::python
