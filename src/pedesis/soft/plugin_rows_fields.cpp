// The catalogue's rows of external fields (plugin_rows.hpp).
#include "pedesis/soft/plugin_rows.hpp"

namespace pedesis::rows {

std::vector<PluginInfo> external_field_rows() {
    return {};
}

} // namespace pedesis::rows
