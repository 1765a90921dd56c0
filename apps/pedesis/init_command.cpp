#include "init_command.hpp"

namespace pedesis::cli {
void add_init_command(CLI::App&) {}
} // namespace pedesis::cli
