#include "analyze_command.hpp"

namespace pedesis::cli {
void add_analyze_command(CLI::App&) {}
} // namespace pedesis::cli
