#pragma once
// The one error message of every integrator's blow-up check, so that a run that explodes
// reads the same whichever dynamics it used.
#include "pedesis/core/error.hpp"
#include "pedesis/soft/soft_state.hpp"

#include <cstdint>
#include <limits>
#include <sstream>
#include <string>

namespace pedesis {

// A step that moved a particle further than the skin, or to a non-finite place: a
// RunError that the evolver completes with its likely cause (soft/blow_up_cause.hpp).
class BlowUp : public RunError {
  public:
    using RunError::RunError;
};

} // namespace pedesis

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
          << " (the neighbour-list skin)";
    throw BlowUp(m.str());
}

// The lowest storage index whose move was too long, and that move, gathered from the
// threads: each batch of particles notes its own and merges it once, after its loop. (A
// lock inside the particle loop would be a call there, after which the compiler loads
// every array's address again, on every particle: 2D Brownian moves took 1.6 times as
// long.)
template <int D> struct FirstBadMove {
    std::int64_t index = std::numeric_limits<std::int64_t>::max();
    Vec<D> move{};
    bool any() const { return index != std::numeric_limits<std::int64_t>::max(); }
    void note(std::int64_t i, const Vec<D>& m) {
        if (i < index) {
            index = i;
            move = m;
        }
    }
    void merge_into(FirstBadMove& all) const {
        if (!any()) return;
#pragma omp critical(pedesis_first_bad_move)
        all.note(index, move);
    }
};

} // namespace pedesis::detail
