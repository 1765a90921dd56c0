// The event engine's moving wall: one face of the box, vibrated or driven along its
// normal (event/moving_wall.hpp has the motion, the meeting and the rebound). Its position
// is a function of time alone, so a restored engine moves it as the uninterrupted one.
#include "pedesis/core/error.hpp"
#include "pedesis/event/event_engine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pedesis {

// A wall on a walled axis; not with growth (its contact planes move too) nor shear (walls
// there are on z only, and the flow would need them at rest).
template <int D> void EventEngine<D>::start_moving_wall() {
    moving_ = params_.moving_wall_axis >= 0 && params_.moving_wall.moves();
    if (!moving_) return;
    const int a = params_.moving_wall_axis;
    if (a >= D || box_.periodic(a))
        throw InputError(fmt::format("event.moving_wall: axis {} is not walled", "xyz"[a % 3]));
    if (params_.growth_rate > 0.0 || growth_.growing)
        throw InputError("event.moving_wall: not with growth (event.growth_rate)");
    if (box_.sheared())
        throw InputError("event.moving_wall: not with Lees-Edwards shear ([box] shear_rate)");
    for (double im : inv_mass_)
        if (im == 0.0)
            throw InputError("event.moving_wall: fixed obstacles (mass = inf) cannot be pushed "
                             "by the wall; not with a moving wall");
    motion_ = params_.moving_wall;
    largest_radius_ = *std::max_element(radius_.begin(), radius_.end());
    moving_axis_ = a;
    moving_side_ = params_.moving_wall_upper ? 1 : 0;
    wall_tolerance_ = 1e-12 * box_.length(a);
    pair_times_ = nullptr; // predict_falling's way, which knows the wall
}

template <int D> double EventEngine<D>::moving_wall_position() const {
    if (!moving_) return 0.0;
    const double w = motion_.displacement(now_);
    return moving_side_ ? box_.hi(moving_axis_) - w : box_.lo(moving_axis_) + w;
}

template <int D>
void EventEngine<D>::meet_moving_wall(const Vec<D>& xi, const Vec<D>& vi, double ri, double& best,
                                      std::int32_t& partner) {
    const int a = moving_axis_;
    const double inward = moving_side_ ? -1.0 : 1.0;
    const double w = motion_.displacement(now_);
    // a driven wall may not crush the particles against the opposite one
    if (!motion_.vibrated() && w > box_.length(a) - 2.0 * largest_radius_)
        throw RunError(fmt::format(
            "event.moving_wall: at t = {:g} the driven wall has come within a diameter of "
            "the opposite wall; stop the run earlier (run.time) or lower its speed",
            now_));
    const double face = moving_side_ ? box_.hi(a) - w : box_.lo(a) + w;
    const double gap = inward * (xi[a] - face) - ri;
    const WallMeeting m = moving_gap_time(gap, inward * vi[a], inward * gravity_[a], motion_, now_,
                                          best, wall_tolerance_);
    if (m.time < best) {
        best = m.time;
        partner = wall_event_base - (2 * a + moving_side_);
    }
}

// At a contact the particle is put on the wall and rebounds in the wall's frame; at a
// check (the gap still open, or opening) only its next event is predicted again.
template <int D> void EventEngine<D>::process_moving_wall(std::uint32_t i, int side) {
    advance(i);
    const int a = moving_axis_;
    const double inward = side ? -1.0 : 1.0;
    const std::size_t s = f_[i].species;
    const double r = radius_[s];
    const double w = motion_.displacement(now_), u = motion_.velocity(now_);
    const double face = side ? box_.hi(a) - w : box_.lo(a) + w;
    const double gap = inward * (f_[i].x[a] - face) - r;
    const double vn = inward * f_[i].v[a];
    if (gap > 16.0 * wall_tolerance_ || vn - u >= 0.0) {
        ++wall_checks_;
        return;
    }
    double xi = params_.wall_restitution;
    if (params_.tc > 0.0) {
        if (now_ - last_collision_[i] < params_.tc) xi = 1.0;
        last_collision_[i] = now_;
    }
    const double m = mass_of(s);
    // pinned onto the contact plane (rounding never lets it leak), its height energy kept
    const double pinned = face + inward * r;
    if (falling_) kinetic_ -= height_energy(s, f_[i].x);
    f_[i].x[a] = pinned;
    if (falling_) kinetic_ += height_energy(s, f_[i].x);
    // the least separation speed: a hop of at least ~1e-6 of the time to fall the axis
    const double pull = std::abs(gravity_[a]) + motion_.max_acceleration();
    const double least = std::sqrt(2.0 * pull * wall_tolerance_);
    const double after = wall_rebound(vn, u, xi, least);
    const double impulse = m * (after - vn); // on the particle, along the inward normal
    const double before_kinetic = 0.5 * m * f_[i].v[a] * f_[i].v[a];
    f_[i].v[a] = inward * after;
    const double change = 0.5 * m * f_[i].v[a] * f_[i].v[a] - before_kinetic;
    kinetic_ += change;
    if (kinetic_ < 0.5 * kinetic_exact_) resum_kinetic_energy();
    // the wall's work is the impulse times its speed; what of it the particle did not
    // gain, the restitution took
    const double work = impulse * u;
    wall_work_ += work;
    counters_.energy_lost += work - change;
    counters_.wall_impulse[a][side] += impulse;
    ++counters_.wall_collisions;
    ++f_[i].count;
}

#define PEDESIS_EVENT_MOVING_WALL(D)                                                               \
    template void EventEngine<D>::start_moving_wall();                                             \
    template double EventEngine<D>::moving_wall_position() const;                                  \
    template void EventEngine<D>::meet_moving_wall(const Vec<D>&, const Vec<D>&, double, double&,  \
                                                   std::int32_t&);                                 \
    template void EventEngine<D>::process_moving_wall(std::uint32_t, int);

PEDESIS_EVENT_MOVING_WALL(2)
PEDESIS_EVENT_MOVING_WALL(3)

} // namespace pedesis
