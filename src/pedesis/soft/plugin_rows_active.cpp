// The catalogue's rows of the active models beyond ABPs (plugin_rows.hpp).
#include "pedesis/soft/plugin_rows.hpp"

namespace pedesis::rows {

std::vector<PluginInfo> active_model_rows() {
    return {};
}

} // namespace pedesis::rows
