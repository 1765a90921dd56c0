#pragma once
// A wall that moves: vibrated (a sinusoid) or driven at a constant speed, always along its
// own normal and never out of the box. Its displacement W(t), inward from the face of the
// box it starts on, is
//   vibrated:  W(t) = A (1 - cos(omega t))   (at the face, at rest, at t = 0; it reaches 2A)
//   driven:    W(t) = u t                     (u >= 0: a piston pushing in)
// so that a run starts with the wall where the box's face is and every particle placed in
// the box is on the right side of it.
//
// When a particle meets it (moving_gap_time): the gap between the particle's contact plane
// and the wall is g(tau) = s + w tau + a tau^2 / 2 - (W(t0 + tau) - W(t0)), a quadratic
// minus a sinusoid, whose roots have no closed form. It is found by conservative
// advancement: since g'' >= a - A omega^2 =: m everywhere, g(tau + h) is at least the
// parabola g + g' h + m h^2 / 2, whose first zero (falling_gap_time) cannot lie beyond
// g's. Steps to that zero climb to g's first root from below and never past it, with
// Newton's speed near a crossing; so no contact is ever missed. The climb stops at the
// caller's horizon (an earlier event makes a later contact irrelevant), at contact, or
// after max_climbs steps (a graze that converges slowly): then the time reached is
// returned as a check, an event at which the engine finds no contact and predicts again.
#include "pedesis/event/falling_times.hpp"

#include <cmath>

namespace pedesis {

struct WallMotion {
    double amplitude = 0.0;         // A (vibrated)
    double angular_frequency = 0.0; // omega (vibrated)
    double speed = 0.0;             // u (driven)

    bool moves() const { return amplitude > 0.0 || speed != 0.0; }
    bool vibrated() const { return amplitude > 0.0; }
    double displacement(double t) const {
        if (vibrated()) return amplitude * (1.0 - std::cos(angular_frequency * t));
        return speed * t;
    }
    double velocity(double t) const {
        if (vibrated()) return amplitude * angular_frequency * std::sin(angular_frequency * t);
        return speed;
    }
    double acceleration(double t) const {
        if (vibrated())
            return amplitude * angular_frequency * angular_frequency *
                   std::cos(angular_frequency * t);
        return 0.0;
    }
    // The largest |W''|: what bounds the gap's curvature from below.
    double max_acceleration() const {
        return vibrated() ? amplitude * angular_frequency * angular_frequency : 0.0;
    }
};

// What moving_gap_time found: the time from t0 of a contact (the gap closed while closing),
// or of a check (no contact up to there; predict again then), or never (none before the
// horizon).
struct WallMeeting {
    double time = never;
    bool contact = false;
};

inline constexpr int max_climbs = 64;

// The particle's contact plane is a gap s ahead of the wall at time t0 (s >= 0 but for
// rounding); along the wall's inward normal the particle moves at w and accelerates at a
// (its gravity there); the wall moves as `motion`. `tolerance` is the gap taken as contact.
inline WallMeeting moving_gap_time(double s, double w, double a, const WallMotion& motion,
                                   double t0, double horizon, double tolerance) {
    if (!motion.vibrated()) {
        // a constant speed only shifts the relative velocity: exact
        const double t = falling_gap_time(s, w - motion.speed, a);
        return t <= horizon ? WallMeeting{t, true} : WallMeeting{};
    }
    const double w0 = motion.displacement(t0);
    const double lowest_curvature = a - motion.max_acceleration();
    double tau = 0.0;
    for (int climb = 0; climb < max_climbs; ++climb) {
        const double t = t0 + tau;
        const double gap = s + (w + 0.5 * a * tau) * tau - (motion.displacement(t) - w0);
        const double rate = w + a * tau - motion.velocity(t);
        if (gap <= tolerance && rate < 0.0) return {tau, true};
        // (touching but opening, as just after a bounce: the bound's return is next)
        const double step = falling_gap_time(gap > tolerance ? gap : 0.0, rate, lowest_curvature);
        if (!(step < never)) return {};
        // a zero step (opening at exactly zero rate) would not move: creep by the tolerance
        tau += step > 0.0 ? step : tolerance / (std::fabs(rate) + 1.0);
        if (tau > horizon) return {};
    }
    return {tau, false};
}

// The particle's velocity component v along the wall's inward normal after meeting the
// wall, which moves at u there, with restitution e in the wall's frame. It leaves at least
// at `least` relative to the wall: a particle carried by a rising wall (zero relative
// velocity, pressed on by the wall's acceleration) would otherwise meet it again at once,
// forever; it hops instead, each hop taking a time > 0.
inline double wall_rebound(double v, double u, double e, double least) {
    const double away = -e * (v - u);
    return u + (away > least ? away : least);
}

} // namespace pedesis
