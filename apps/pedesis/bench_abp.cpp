#include "bench_abp.hpp"

namespace pedesis::cli {
void add_bench_abp(CLI::App&) {}
} // namespace pedesis::cli
