#pragma once
// How many OpenMP threads a run uses. Results do not depend on it (the engines are
// bit-identical for any thread count), only the speed does: OpenMP's threads spin while
// they wait, so a thread that shares its core with another busy process makes every
// step wait for it (measured: 2 threads beside one busy process ran at 0.4-0.7 of one
// thread). So, unless the user chose (--threads, or OMP_NUM_THREADS), a run takes the
// cores that are idle now, and says so when that is fewer than all.
#include <iosfwd>
#include <optional>

namespace pedesis::cli {

// `requested`: --threads, if given (>= 1). Sets OpenMP's thread count and returns it;
// prints a note to `console` when cores are busy and fewer threads are used.
int choose_threads(std::optional<int> requested, std::ostream& console);

} // namespace pedesis::cli
