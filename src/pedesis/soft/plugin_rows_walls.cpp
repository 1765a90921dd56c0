// The catalogue's rows of walls and containers (plugin_rows.hpp).
#include "pedesis/soft/plugin_rows.hpp"

namespace pedesis::rows {

std::vector<PluginInfo> wall_rows() {
    return {};
}

} // namespace pedesis::rows
