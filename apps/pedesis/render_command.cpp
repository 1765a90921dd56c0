#include "render_command.hpp"

namespace pedesis::cli {
void add_render_command(CLI::App&) {}
} // namespace pedesis::cli
