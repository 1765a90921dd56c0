#pragma once
// The one error message of every integrator's blow-up check, so that a run that explodes
// reads the same whichever dynamics it used.
#include "pedesis/core/error.hpp"
#include "pedesis/soft/soft_state.hpp"

#include <sstream>
#include <string>

namespace pedesis::detail {

// Lowest storage index whose move was not finite or exceeded max_move; the caller throws.
template <int D>
[[noreturn]] inline void throw_bad_move(const SoftState<D>& s, std::size_t i, const Vec<D>& move,
                                        double max_move, const std::string& who) {
    std::ostringstream m;
    m << who << ": at step " << s.step << " particle " << s.p.tag[i];
    if (!all_finite(move))
        m << " got a non-finite displacement (the run blew up)";
    else
        m << " moved " << norm(move) << " in one step, more than " << max_move
          << " (the neighbour-list skin); reduce dt";
    throw RunError(m.str());
}

} // namespace pedesis::detail
