#include "bench_stepped.hpp"

namespace pedesis::cli {
void add_bench_stepped(CLI::App&) {}
} // namespace pedesis::cli
