#include "pedesis/stepped/stepped_engine.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/particle_checks.hpp"
#include "pedesis/core/stage.hpp"
#include "pedesis/event/collision_rules.hpp"
#include "pedesis/event/falling_times.hpp"
#include "pedesis/io/binary_stream.hpp"
#include "pedesis/stepped/rewind.hpp"
#include "pedesis/stepped/time_step.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pedesis {

namespace {

std::string tag_name(std::uint32_t tag) {
    return "particle " + std::to_string(tag);
}

void validate(const SteppedParams& p) {
    if (!(p.dt > 0.0 && std::isfinite(p.dt)))
        throw InputError("stepped.dt must be a positive finite number");
    if (!(p.max_move > 0.0 && p.max_move <= 1.0))
        throw InputError("stepped.max_move must lie in (0, 1]");
    if (p.max_events_per_step < 1) throw InputError("stepped engine: max_events_per_step < 1");
}

} // namespace

template <int D>
SteppedEngine<D>::SteppedEngine(ParticleStore<D> particles, const Box<D>& box,
                                const SteppedParams& params)
    : p_(std::move(particles)), box_(box), params_(params), dt_(params.dt) {
    enter_stage("setting up the stepped engine");
    if (p_.size() == 0) throw InputError("stepped engine: no particles (N = 0)");
    if (p_.size() > std::numeric_limits<std::uint32_t>::max() / 2)
        throw InputError("stepped engine: too many particles");
    validate(params_);
    double max_radius = 0.0;
    for (const auto& s : p_.species_table) {
        if (!(s.radius > 0.0 && std::isfinite(s.radius)))
            throw InputError("species '" + s.name + "': radius must be positive and finite");
        if (!(s.mass > 0.0) || std::isnan(s.mass))
            throw InputError("species '" + s.name +
                             "': mass must be positive (inf for a fixed obstacle)");
        max_radius = std::max(max_radius, s.radius);
    }
    for (int a = 0; a < D; ++a) {
        if (box_.length(a) < 2.0 * max_radius)
            throw InputError("box: length " + std::to_string(box_.length(a)) + " along axis " +
                             std::to_string(a) + " is smaller than one particle (diameter " +
                             std::to_string(2.0 * max_radius) + ")");
        // the minimum image of an overlapping pair must be unique
        if (box_.periodic(a) && !(box_.length(a) > 4.0 * max_radius))
            throw InputError("box: periodic length " + std::to_string(box_.length(a)) +
                             " must exceed twice the largest contact distance (" +
                             std::to_string(4.0 * max_radius) + ")");
    }
    for (std::size_t i = 0; i < p_.size(); ++i) {
        if (!all_finite(p_.position[i]) || !all_finite(p_.velocity[i]))
            throw InputError(tag_name(p_.tag[i]) + ": position or velocity is not a finite number");
        // m v^2 / 2 must stay a number (a speed of 1e200 ran forever with an infinite energy)
        if (norm2(p_.velocity[i]) > 1e200)
            throw InputError(tag_name(p_.tag[i]) + ": speed above 1e100 (the kinetic energy would "
                                                   "overflow)");
        if (std::isinf(p_.mass(i))) p_.velocity[i] = Vec<D>{}; // obstacles never move
        const double r = p_.radius(i);
        if (!box_.contains(p_.position[i], r * (1.0 - 1e-12)))
            throw InputError(fmt::format(
                "{} lies outside the walls (centre must be at least its radius {} from every "
                "wall)",
                tag_name(p_.tag[i]), r));
    }
    image_.assign(p_.size(), {});
    if (box_.sheared()) box_.shear_to_time(time());
    for (std::size_t i = 0; i < p_.size(); ++i) wrap_counting<D>(box_, p_.position[i], image_[i]);
    // the given velocities are peculiar: the flow starts linear
    if (box_.sheared())
        for (std::size_t i = 0; i < p_.size(); ++i)
            if (!std::isinf(p_.mass(i))) p_.velocity[i][0] += flow(p_.position[i][1]);
    setup();
    check_no_overlap(1e-10);
    if (box_.sheared()) track_flux_moments(); // the exact kinetic stress of the log's P_xy
}

// As the event engine's (event/event_driving.cpp): along walled axes only, and not with
// shear, fixed obstacles (which do not fall: pair flights relative to them would not be
// straight) or [transport].
template <int D> void SteppedEngine<D>::start_gravity() {
    falling_ = false;
    for (int a = 0; a < D; ++a) {
        gravity_[a] = params_.gravity[a];
        if (!(std::abs(gravity_[a]) <= 1e100))
            throw InputError("stepped.gravity must be finite numbers");
        if (gravity_[a] == 0.0) continue;
        falling_ = true;
        if (box_.periodic(a))
            throw InputError(fmt::format(
                "stepped.gravity: component {:g} along axis {} which is periodic: particles "
                "would fall for ever (no stationary state); make that axis a wall or give 0",
                gravity_[a], a));
    }
    if (!falling_) return;
    if (box_.sheared())
        throw InputError("stepped.gravity: not with Lees-Edwards shear ([box] shear_rate)");
    for (const auto& s : p_.species_table)
        if (std::isinf(s.mass))
            throw InputError("stepped.gravity: fixed obstacles (mass = inf) do not fall; not with "
                             "gravity");
}

template <int D> double SteppedEngine<D>::potential_energy() const {
    if (!falling_) return 0.0;
    double u = 0.0;
    for (std::size_t i = 0; i < p_.size(); ++i) {
        double h = 0.0;
        for (int a = 0; a < D; ++a)
            if (gravity_[a] != 0.0)
                h -= gravity_[a] *
                     (p_.position[i][a] - (gravity_[a] < 0.0 ? box_.lo(a) : box_.hi(a)));
        u += h / inv_mass_[p_.species[i]];
    }
    return u;
}

template <int D> void SteppedEngine<D>::setup() {
    start_gravity();
    radius_.clear();
    inv_mass_.clear();
    max_speed2_.clear();
    double max_radius = 0.0;
    for (const auto& s : p_.species_table) {
        radius_.push_back(s.radius);
        inv_mass_.push_back(s.inverse_mass());
        const double v = params_.max_move * s.radius / dt_;
        max_speed2_.push_back(v * v);
        max_radius = std::max(max_radius, s.radius);
    }
    any_periodic_ = false;
    for (int a = 0; a < D; ++a) {
        walled_[a] = !box_.periodic(a);
        any_periodic_ = any_periodic_ || box_.periodic(a);
    }
    shear_velocity_ = box_.shear_rate() * box_.length(1);
    shear_reach_ = 2.0 * max_radius * (1.0 + 1e-9) + 1e-9 * box_.length(1);
    if (box_.sheared()) check_shear_step(max_radius);
    // Cells at least one contact distance wide find every overlap in the 3^D cells around
    // a particle; in a dilute gas they are widened to about one particle per cell, so
    // that the scan does not visit mostly empty cells.
    const double per_particle = std::pow(box_.volume() / static_cast<double>(p_.size()), 1.0 / D);
    cells_ = CellList<D>(box_, std::max(2.0 * max_radius, per_particle));
    cells_.build(p_.position);
    segment_start_.assign(p_.size(), 0.0);
    events_.assign(p_.size(), 0);
    heap_.clear();
}

// The flow's velocity difference across a contact distance moves touching particles
// apart like a peculiar speed, which max_move bounds (the speed check sees only these).
template <int D> void SteppedEngine<D>::check_shear_step(double max_radius) const {
    double min_radius = max_radius;
    for (double r : radius_) min_radius = std::min(min_radius, r);
    const double streaming = box_.shear_rate() * 2.0 * max_radius * dt_;
    if (streaming > params_.max_move * min_radius)
        throw InputError(fmt::format(
            "[box] shear_rate = {:g} with [stepped] dt = {:g}: the flow alone moves touching "
            "particles {:.3g} radii past each other in one step, more than max_move = {:g}; "
            "lower dt to {:.2g} or less (or the rate)",
            box_.shear_rate(), dt_, streaming / min_radius, params_.max_move,
            params_.max_move * min_radius / (box_.shear_rate() * 2.0 * max_radius)));
}

template <int D> double SteppedEngine<D>::kinetic_energy() const {
    const ParticleStore<D>& p = particles();
    double k = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const double im = inv_mass_[p.species[i]];
        if (im > 0.0) k += 0.5 * norm2(p.velocity[i]) / im;
    }
    return k;
}

template <int D> const ParticleStore<D>& SteppedEngine<D>::peculiar_particles() const {
    if (peculiar_fresh_) return peculiar_;
    peculiar_ = p_;
    for (std::size_t i = 0; i < p_.size(); ++i)
        if (inv_mass_[p_.species[i]] > 0.0) peculiar_.velocity[i][0] -= flow(p_.position[i][1]);
    peculiar_fresh_ = true;
    return peculiar_;
}

// Independent speeds drawn in a run as long again as this one so far: N at the start
// and two per pair collision, doubled.
template <int D> double SteppedEngine<D>::speed_samples_so_far() const {
    return 2.0 *
           (static_cast<double>(p_.size()) + 2.0 * static_cast<double>(counters_.pair_collisions));
}

template <int D> void SteppedEngine<D>::check_speeds() const {
    // (under shear, the peculiar speed: the flow's is the neighbours' too)
    bool too_fast = false;
    for (std::size_t i = 0; i < p_.size(); ++i) {
        Vec<D> v = p_.velocity[i];
        if (inv_mass_[p_.species[i]] > 0.0) v[0] -= flow(p_.position[i][1]);
        too_fast = too_fast || norm2(v) > max_speed2_[p_.species[i]];
    }
    if (!too_fast) return;
    const FastestParticle f = fastest_particle(particles(), dt_);
    throw RunError(fmt::format(
        "stepped engine: at step {} {} (species '{}') would move {:.4g} = {:.3g} radii in one "
        "step of dt = {:g}, more than max_move = {:g} radii, so it could pass through another "
        "particle or a wall; reduce [stepped] dt to {:.2g} or less",
        step_, tag_name(p_.tag[f.index]), p_.species_table[p_.species[f.index]].name, f.speed * dt_,
        f.radii_per_step, dt_, params_.max_move,
        suggested_time_step(p_, params_.max_move, speed_samples_so_far())));
}

template <int D> void SteppedEngine<D>::step() {
    check_speeds();
    const auto n = static_cast<std::uint32_t>(p_.size());
    // the positions are those at the step's end, and so is the offset (time() after it)
    if (box_.sheared())
        box_.shear_to_time(time_base_ + static_cast<double>(step_ + 1 - step_base_) * dt_);
    peculiar_fresh_ = false;
    for (std::uint32_t i = 0; i < n; ++i) {
        if (falling_) [[unlikely]] {
            p_.position[i] += p_.velocity[i] * dt_ + gravity_ * (0.5 * dt_ * dt_);
            p_.velocity[i] += gravity_ * dt_;
        } else {
            p_.position[i] += p_.velocity[i] * dt_;
        }
        if (any_periodic_) wrap_particle(i);
        segment_start_[i] = 0.0;
        events_[i] = 0;
    }
    cells_.build(p_.position);
    heap_.clear();
    for (std::uint32_t i = 0; i < n; ++i) {
        find_wall_crossing(i);
        for_each_candidate(cells_, p_.position[i], [&](std::uint32_t j) {
            if (j > i) consider(i, j);
        });
    }
    while (!heap_.empty()) {
        std::pop_heap(heap_.begin(), heap_.end(), Later{});
        const Event e = heap_.back();
        heap_.pop_back();
        if (events_[e.i] != e.seen_i || events_[e.j] != e.seen_j) continue; // superseded
        if (e.wall == pair_event)
            collide(e);
        else
            bounce(e);
    }
    ++step_;
}

template <int D> void SteppedEngine<D>::push(const Event& e) {
    heap_.push_back(e);
    std::push_heap(heap_.begin(), heap_.end(), Later{});
}

// The earliest wall this particle's current segment has crossed. A centre past a wall
// but moving back in can only be a rounding error of an earlier mirror: it is put on
// the wall.
template <int D> void SteppedEngine<D>::find_wall_crossing(std::uint32_t i) {
    const double r = radius_[p_.species[i]];
    Event best{dt_ + 1.0, i, i, events_[i], events_[i], 0, false};
    for (int a = 0; a < D; ++a) {
        if (!walled_[a]) continue;
        double& x = p_.position[i][a];
        const double v = p_.velocity[i][a];
        const double lo = box_.lo(a) + r, hi = box_.hi(a) - r;
        int side;
        double overshoot;
        if (x > hi) {
            side = 1;
            overshoot = x - hi;
        } else if (x < lo) {
            side = 0;
            overshoot = lo - x;
        } else {
            continue;
        }
        double back; // how long before the step's end the centre crossed the plane
        if (gravity_[a] != 0.0) [[unlikely]] {
            // going back along the parabola, the outward distance overshoot - v_out tau +
            // g_out tau^2 / 2 first closes at the crossing (none in the segment: rounding)
            const double out = side == 1 ? 1.0 : -1.0;
            back = falling_gap_time(overshoot, -out * v, out * gravity_[a]);
            if (!(back <= dt_ - segment_start_[i])) {
                x = side == 1 ? hi : lo;
                continue;
            }
        } else {
            if (side == 1 ? !(v > 0.0) : !(v < 0.0)) {
                x = side == 1 ? hi : lo;
                continue;
            }
            back = overshoot / std::abs(v);
        }
        const double when = std::max(segment_start_[i], dt_ - back);
        if (when < best.when) {
            best.when = when;
            best.wall = 2 * a + side;
        }
    }
    if (best.when <= dt_) push(best);
}

template <int D> void SteppedEngine<D>::find_overlaps_of(std::uint32_t i, std::uint32_t skip) {
    for_each_candidate(cells_, p_.position[i], [&](std::uint32_t j) {
        if (j != i && j != skip) consider(i, j);
    });
}

// A centre within a contact distance of the top face touches the images above of
// particles near the bottom, displaced by the offset along x: their cells lie around the
// centre's image below, r - L_y e_y - offset e_x (and the reverse at the bottom face).
// The scans may overlap (a short box, the plain scan's wrap across y), so there the
// candidates are gathered, sorted and given once each.
template <int D>
template <class F>
void SteppedEngine<D>::for_each_candidate(const CellList<D>& cells, const Vec<D>& r, F&& f) const {
    const bool top = box_.sheared() && r[1] + shear_reach_ >= box_.hi(1);
    const bool bottom = box_.sheared() && r[1] - shear_reach_ <= box_.lo(1);
    if (!top && !bottom) [[likely]] {
        cells.for_each_near(r, f);
        return;
    }
    Vec<D> image{};
    image[0] = box_.shear_offset();
    image[1] = box_.length(1);
    candidates_.clear();
    const auto keep = [&](std::uint32_t j) { candidates_.push_back(j); };
    cells.for_each_near(r, keep);
    if (top) cells.for_each_near(r - image, keep);
    if (bottom) cells.for_each_near(r + image, keep);
    std::sort(candidates_.begin(), candidates_.end());
    candidates_.erase(std::unique(candidates_.begin(), candidates_.end()), candidates_.end());
    for (std::uint32_t j : candidates_) f(j);
}

// An overlapping pair collided when it entered the overlap, if that lies on the current
// segments of both; if the overlap was there already when the later segment began (a
// grazing collision missed in an earlier step or segment), it collides at that moment if
// it approaches then, and is left to separate otherwise.
template <int D>
void SteppedEngine<D>::overlapping(std::uint32_t i, std::uint32_t j, const Vec<D>& dr, double sigma,
                                   double dvx) {
    Vec<D> dv = p_.velocity[i] - p_.velocity[j];
    dv[0] += dvx;
    const double tau = contact_rewind_time(dr, dv, sigma);
    if (tau < 0.0) return; // no relative motion
    const double start = std::max(segment_start_[i], segment_start_[j]);
    double when = dt_ - tau;
    bool late = false;
    if (!(when >= start)) {
        if (dot(dr, dv) - norm2(dv) * (dt_ - start) >= 0.0) return;
        when = start;
        late = true;
    }
    const std::uint32_t a = std::min(i, j), b = std::max(i, j);
    push(Event{when, a, b, events_[a], events_[b], pair_event, late});
}

template <int D> void SteppedEngine<D>::collide(const Event& e) {
    const std::uint32_t i = e.i, j = e.j;
    const double back = dt_ - e.when;
    // under shear, j collides as the image nearest i, whose x velocity differs by -slide
    double slide = 0.0;
    Vec<D> dr = separation(p_.position[i] - p_.position[j], slide);
    const Vec<D> vi0 = p_.velocity[i];
    Vec<D> vj0 = p_.velocity[j];
    vj0[0] -= slide;
    dr -= (vi0 - vj0) * back; // the separation at the collision
    const double r = norm(dr);
    if (!(r > 0.0)) return; // coincident centres: no line of centres (never from a valid state)
    const Vec<D> n = dr * (1.0 / r);
    if (dot(vi0 - vj0, n) >= 0.0) return; // touching while separating, by rounding
    p_.velocity[j][0] -= slide;
    const PairImpulse imp = collide_pair(p_.velocity[i], p_.velocity[j], n,
                                         inv_mass_[p_.species[i]], inv_mass_[p_.species[j]], 1.0);
    const Vec<D> dvi = p_.velocity[i] - vi0, dvj = p_.velocity[j] - vj0;
    p_.velocity[j][0] += slide;
    add_collision_virial(counters_, imp.impulse, n, dr);
    if (moments_on_) [[unlikely]] {
        const double now = time() + e.when; // (step_ counts the steps before this one)
        if (box_.sheared()) {
            // peculiar velocities, at the heights of the collision (j's image has j's own)
            moments_.advance_sheared(now, box_.shear_rate());
            Vec<D> ci0 = vi0, cj0 = vj0;
            ci0[0] -= flow(p_.position[i][1] - vi0[1] * back);
            cj0[0] += slide - flow(p_.position[j][1] - vj0[1] * back);
            moments_.collision(mass_of(p_.species[i]), ci0, ci0 + dvi, mass_of(p_.species[j]), cj0,
                               cj0 + dvj, dr);
        } else {
            moments_.advance(now);
            moments_.collision(mass_of(p_.species[i]), vi0, p_.velocity[i], mass_of(p_.species[j]),
                               vj0, p_.velocity[j], dr);
        }
    }
    p_.position[i] += dvi * back;
    p_.position[j] += dvj * back;
    ++counters_.pair_collisions;
    if (e.late) ++stats_.late_collisions;
    moved(i, e.when);
    moved(j, e.when);
    find_wall_crossing(i);
    find_wall_crossing(j);
    find_overlaps_of(i, i);
    find_overlaps_of(j, i);
}

template <int D> void SteppedEngine<D>::track_flux_moments() {
    if (moments_on_) return;
    if (falling_)
        throw InputError("[transport] needs force-free flights: not with stepped.gravity");
    moments_ = FluxMoments<D>{};
    moments_.t = time();
    const ParticleStore<D>& p = particles(); // (peculiar under shear)
    for (std::size_t i = 0; i < p.size(); ++i)
        moments_.count(mass_of(p.species[i]), p.velocity[i], 1.0);
    moments_on_ = true;
}

template <int D> FluxMoments<D> SteppedEngine<D>::flux_moments() const {
    FluxMoments<D> m = moments_;
    if (box_.sheared())
        m.advance_sheared(time(), box_.shear_rate());
    else
        m.advance(time());
    return m;
}

template <int D> void SteppedEngine<D>::bounce(const Event& e) {
    const std::uint32_t i = e.i;
    const int a = e.wall / 2, side = e.wall % 2;
    const double r = radius_[p_.species[i]];
    double& x = p_.position[i][a];
    const double im = inv_mass_[p_.species[i]];
    if (gravity_[a] != 0.0) [[unlikely]] {
        // the velocity at the bounce reversed, and the parabola from the plane to the end
        const double back = dt_ - e.when;
        double& v = p_.velocity[i][a];
        v -= gravity_[a] * back;
        counters_.wall_impulse[a][side] += collide_wall(v, 1.0 / im, 1.0);
        x = (side == 1 ? box_.hi(a) - r : box_.lo(a) + r) + v * back +
            0.5 * gravity_[a] * back * back;
        v += gravity_[a] * back;
        ++counters_.wall_collisions;
        moved(i, e.when);
        find_wall_crossing(i);
        find_overlaps_of(i, i);
        return;
    }
    if (side == 1)
        x = 2.0 * (box_.hi(a) - r) - x;
    else
        x = 2.0 * (box_.lo(a) + r) - x;
    // under shear (walls on z only) the kinetic sums see the bounce
    Vec<D> c0 = p_.velocity[i];
    const bool recount = moments_on_ && box_.sheared();
    if (recount) {
        moments_.advance_sheared(time() + e.when, box_.shear_rate());
        c0[0] -= flow(p_.position[i][1] - c0[1] * (dt_ - e.when));
        moments_.count(1.0 / im, c0, -1.0);
    }
    counters_.wall_impulse[a][side] += collide_wall(p_.velocity[i][a], 1.0 / im, 1.0);
    if (recount) {
        c0[a] = p_.velocity[i][a];
        moments_.count(1.0 / im, c0, 1.0);
    }
    ++counters_.wall_collisions;
    moved(i, e.when);
    find_wall_crossing(i);
    find_overlaps_of(i, i);
}

// Bookkeeping after an event of particle i at `when`: a new segment, a new version of
// its events, its cell.
template <int D> void SteppedEngine<D>::wrap_particle(std::uint32_t i) {
    const Vec<D> shift = box_.wrap(p_.position[i]);
    for (int a = 0; a < D; ++a) image_[i][a] += static_cast<std::int32_t>(shift[a]);
    // (the image k boxes above moves k rate L_y faster: the same motion, told in the box)
    if (box_.sheared() && inv_mass_[p_.species[i]] > 0.0)
        p_.velocity[i][0] -= shift[1] * shear_velocity_;
}

template <int D> void SteppedEngine<D>::moved(std::uint32_t i, double when) {
    if (any_periodic_) wrap_particle(i);
    segment_start_[i] = when;
    ++events_[i];
    cells_.remove(i);
    cells_.insert(i, p_.position[i]);
    // a fixed obstacle is only hit: many hits in one step are no sign of a dt too large
    if (inv_mass_[p_.species[i]] == 0.0) return;
    if (events_[i] > 1) ++stats_.chained_events;
    stats_.most_events_in_step = std::max(stats_.most_events_in_step, events_[i]);
    if (events_[i] > params_.max_events_per_step)
        throw RunError(fmt::format(
            "stepped engine: at step {} {} had more than {} collisions in one step (the "
            "particles around it are packed too tightly for dt = {:g}); reduce [stepped] dt",
            step_, tag_name(p_.tag[i]), params_.max_events_per_step, dt_));
}

template <int D> void SteppedEngine<D>::check_no_overlap(double rel_tol) const {
    double max_radius = 0.0;
    for (double r : radius_) max_radius = std::max(max_radius, r);
    CellList<D> cells(box_, 2.0 * max_radius);
    cells.build(p_.position);
    for (std::uint32_t i = 0; i < p_.size(); ++i) {
        for_each_candidate(cells, p_.position[i], [&](std::uint32_t j) {
            if (j <= i) return;
            double unused = 0.0;
            const double d = norm(separation(p_.position[i] - p_.position[j], unused));
            const double c = contact(i, j);
            if (d < c * (1.0 - rel_tol)) {
                const std::string m = fmt::format(
                    "{} and {} overlap: centres {:g} apart, contact distance {:g} (overlap {:g})",
                    tag_name(p_.tag[i]), tag_name(p_.tag[j]), d, c, c - d);
                if (step_ == 0 && counters_.pair_collisions == 0) throw InputError(m);
                throw RunError(fmt::format("at step {} (t = {:g}): {}", step_, time(), m));
            }
        });
    }
}

namespace {
constexpr std::uint64_t checkpoint_magic = 0x5054535344455045ull; // "EPEDSSTP" in memory order
// 2: the collision virial's off-diagonal components; 3: image counts and the flux moments
// (version 2 is read with none crossed and no moments); 4: the shear rate (3 is read
// unsheared)
constexpr std::uint32_t checkpoint_version = 4;
constexpr std::uint32_t oldest_checkpoint_version = 2;
} // namespace

template <int D> void SteppedEngine<D>::save(std::ostream& out) const {
    using binary::put;
    binary::put_header(out, checkpoint_magic, checkpoint_version, D);
    put(out, p_.species_table);
    put(out, box_);
    put(out, dt_);
    put(out, step_);
    put(out, step_base_);
    put(out, time_base_);
    put(out, counters_);
    put(out, stats_);
    put(out, p_.position);
    put(out, p_.velocity);
    put(out, p_.tag);
    put(out, p_.species);
    put(out, image_);
    put<std::uint8_t>(out, moments_on_);
    put(out, moments_);
    put(out, box_.shear_rate());
}

template <int D>
SteppedEngine<D> SteppedEngine<D>::load(std::istream& in, const SteppedParams& params) {
    using binary::get;
    const std::uint32_t version = binary::get_header(in, checkpoint_magic, checkpoint_version, D,
                                                     "stepped", oldest_checkpoint_version);
    validate(params);
    SteppedEngine e;
    e.params_ = params;
    get(in, e.p_.species_table);
    const std::size_t ns = e.p_.species_table.size();
    get(in, e.box_);
    double saved_dt = 0.0;
    get(in, saved_dt);
    get(in, e.step_);
    get(in, e.step_base_);
    get(in, e.time_base_);
    get(in, e.counters_);
    get(in, e.stats_);
    get(in, e.p_.position);
    get(in, e.p_.velocity);
    get(in, e.p_.tag);
    get(in, e.p_.species);
    if (version >= 3) {
        get(in, e.image_);
        std::uint8_t on = 0;
        get(in, on);
        if (on > 1) throw InputError("checkpoint: corrupt flux moments");
        e.moments_on_ = on != 0;
        get(in, e.moments_);
    }
    if (version >= 4) {
        double rate = 0.0;
        get(in, rate);
        e.box_.set_shear_rate(rate); // (InputError if not a rate, or with walls across the flow)
        if (e.box_.sheared() && !e.moments_on_)
            throw InputError("checkpoint: a sheared run without its flux moments (corrupt)");
    }
    const std::size_t n = e.p_.position.size();
    if (version < 3) e.image_.assign(n, {});
    if (n == 0 || e.p_.velocity.size() != n || e.p_.tag.size() != n || e.p_.species.size() != n ||
        e.image_.size() != n || e.step_base_ > e.step_)
        throw InputError("checkpoint: inconsistent array sizes (corrupt file)");
    for (auto s : e.p_.species)
        if (s >= ns) throw InputError("checkpoint: corrupt species index");
    check_restored_particles(e.p_, e.box_, false); // before the cell list bins them
    e.dt_ = saved_dt;
    if (params.dt != saved_dt) {
        // a new dt: time goes on from here in steps of it
        e.time_base_ = e.time();
        e.step_base_ = e.step_;
        e.dt_ = params.dt;
    }
    if (e.box_.sheared()) e.box_.shear_to_time(e.time());
    e.setup();
    return e;
}

template class SteppedEngine<2>;
template class SteppedEngine<3>;

} // namespace pedesis
