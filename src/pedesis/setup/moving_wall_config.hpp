#pragma once
// [event.moving_wall]: one wall of the box that moves along its normal, vibrated
// (amplitude and frequency) or driven at a constant speed (event/moving_wall.hpp gives the
// motion; docs/config.md the keys).
#include "pedesis/io/config_table.hpp"
#include "pedesis/setup/run_config.hpp"

namespace pedesis {

// Reads the table if `ev` ([event]) has it, into c.moving_wall_*; the axis must be walled.
void read_moving_wall(ConfigTable& ev, RunConfig& c);

} // namespace pedesis
