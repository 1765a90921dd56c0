#pragma once
// The named quantities a run can log: one row each, with its unit and meaning. log.csv's
// columns, `pedesis run --list-quantities`, `[log] quantities` and docs/formats.md all
// go by these names. An engine measures the quantities it has (its RunEngine lists them);
// adding a quantity is its row here and the line of the engine that measures it.
#include <string>
#include <string_view>
#include <vector>

namespace pedesis {

struct QuantityInfo {
    // The column name; "<species>" in it stands for each species' name, one column each.
    const char* name;
    const char* unit; // in the run's units (k_B = 1)
    const char* meaning;
    const char* engines; // which engines measure it
    bool count = false;  // an integer count, written without exponent or decimals
    // +inf is one of its values (a mean time between collisions before the first one);
    // any other quantity that is not finite means a broken state and stops the run
    bool may_be_infinite = false;
};

const std::vector<QuantityInfo>& quantity_catalogue();

// The row of a column name: exact, or a per-species pattern whose "<species>" matches any
// non-empty name. Null if none.
const QuantityInfo* find_quantity(std::string_view column);

// "time, collisions, ...": every name, for messages.
std::string quantity_names();

} // namespace pedesis
