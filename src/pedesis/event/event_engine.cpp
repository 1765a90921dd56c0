#include "pedesis/event/event_engine.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/event/collision_rules.hpp"
#include "pedesis/event/prediction.hpp"
#include "pedesis/io/binary_stream.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace pedesis {

namespace {

void validate(const EventParams& p) {
    if (!(p.restitution >= 0.0 && p.restitution <= 1.0))
        throw InputError("event.restitution must lie in [0, 1]");
    if (!(p.wall_restitution >= 0.0 && p.wall_restitution <= 1.0))
        throw InputError("event.wall_restitution must lie in [0, 1]");
    if (!(p.tc >= 0.0 && std::isfinite(p.tc)))
        throw InputError("event.tc must be a finite number >= 0");
}

std::string tag_name(std::uint32_t tag) {
    return "particle " + std::to_string(tag);
}

} // namespace

template <int D>
EventEngine<D>::EventEngine(ParticleStore<D> particles, const Box<D>& box,
                            const EventParams& params)
    : p_(std::move(particles)), box_(box), params_(params) {
    if (p_.size() == 0) throw InputError("event engine: no particles (N = 0)");
    validate(params_);

    double max_radius = 0.0, mean_diameter = 0.0;
    for (const auto& s : p_.species_table) {
        if (!(s.radius > 0.0 && std::isfinite(s.radius)))
            throw InputError("species '" + s.name + "': radius must be positive and finite");
        if (!(s.mass > 0.0) || std::isnan(s.mass))
            throw InputError("species '" + s.name +
                             "': mass must be positive (inf for a fixed obstacle)");
        radius_.push_back(s.radius);
        inv_mass_.push_back(s.inverse_mass());
        max_radius = std::max(max_radius, s.radius);
    }
    for (std::size_t i = 0; i < p_.size(); ++i) {
        if (!all_finite(p_.position[i]) || !all_finite(p_.velocity[i]))
            throw InputError(tag_name(p_.tag[i]) + ": position or velocity is not a finite number");
        if (inv_mass_[p_.species[i]] == 0.0) p_.velocity[i] = Vec<D>{}; // obstacles never move
        mean_diameter += 2.0 * radius_[p_.species[i]];
    }
    mean_diameter /= static_cast<double>(p_.size());

    double min_periodic = never;
    for (int a = 0; a < D; ++a) {
        if (box_.length(a) < 2.0 * max_radius)
            throw InputError("box: length " + std::to_string(box_.length(a)) + " along axis " +
                             std::to_string(a) + " is smaller than one particle (diameter " +
                             std::to_string(2.0 * max_radius) + ")");
        if (box_.periodic(a)) min_periodic = std::min(min_periodic, box_.length(a));
    }
    // The minimum image of a colliding pair must be unique over a whole list
    // lifetime: L/2 > contact + 2 skin. Small periodic boxes get a smaller skin.
    skin_ = params_.skin >= 0.0 ? params_.skin : default_skin(mean_diameter);
    const double max_contact = 2.0 * max_radius;
    if (std::isfinite(min_periodic)) {
        const double room = 0.5 * min_periodic - max_contact;
        if (room <= 0.0)
            throw InputError("box: periodic length " + std::to_string(min_periodic) +
                             " must exceed twice the largest contact distance (" +
                             std::to_string(2.0 * max_contact) + ")");
        skin_ = std::min(skin_, 0.45 * room);
    }
    if (!(skin_ > 0.0)) throw InputError("event.skin must be positive");
    shell_ = 0.5 * skin_;

    for (std::size_t i = 0; i < p_.size(); ++i) {
        const double r = radius_[p_.species[i]];
        if (!box_.contains(p_.position[i], r * (1.0 - 1e-12))) {
            std::ostringstream m;
            m << tag_name(p_.tag[i])
              << " lies outside the walls (centre must be at least its radius " << r
              << " from every wall)";
            throw InputError(m.str());
        }
        box_.wrap(p_.position[i]);
    }

    t_.assign(p_.size(), 0.0);
    count_.assign(p_.size(), 0);
    if (params_.tc > 0.0) last_collision_.assign(p_.size(), -never);
    kinetic_ = 0.0;
    for (std::size_t i = 0; i < p_.size(); ++i)
        if (inv_mass_[p_.species[i]] > 0.0)
            kinetic_ += 0.5 * norm2(p_.velocity[i]) / inv_mass_[p_.species[i]];
    kinetic_exact_ = kinetic_;

    make_grids();
    build_all_lists();
    check_no_overlap(1e-10);
    setup();
}

// A skin that holds about 8 (2D) or 12 (3D) neighbours per list, and at least half a
// diameter: in dense fluids that is the 1.5-diameter shell of Smallenburg's code; in
// dilute gases it grows with the mean free path, so lists are not rebuilt several
// times per free flight.
template <int D> double EventEngine<D>::default_skin(double mean_diameter) const {
    const double n = static_cast<double>(p_.size()) / box_.volume();
    const double wanted = D == 2 ? 8.0 : 12.0;
    const double ball = D == 2 ? std::numbers::pi : 4.0 / 3.0 * std::numbers::pi;
    const double reach = std::pow(wanted / (ball * n), 1.0 / D);
    return std::max(0.5 * mean_diameter, reach - mean_diameter);
}

// Size classes: species sorted by radius, largest first; a class takes every species
// whose radius is at least half of its largest. One class (the usual case) gives one
// grid with cells of the largest contact distance plus the skin.
template <int D> void EventEngine<D>::make_grids() {
    std::vector<double> radii = radius_;
    std::sort(radii.begin(), radii.end(), std::greater<>());
    class_radius_.clear();
    constexpr std::size_t most_classes = 8; // the last takes every smaller radius
    for (double r : radii)
        if (class_radius_.empty() ||
            (r < 0.5 * class_radius_.back() && class_radius_.size() < most_classes))
            class_radius_.push_back(r);
    class_of_.assign(radius_.size(), 0);
    for (std::size_t s = 0; s < radius_.size(); ++s)
        for (std::size_t k = 0; k < class_radius_.size(); ++k)
            if (radius_[s] >= 0.5 * class_radius_[k] || k + 1 == class_radius_.size()) {
                class_of_[s] = static_cast<std::uint8_t>(k);
                break;
            }
    grids_.clear();
    for (double r : class_radius_) grids_.emplace_back(box_, 2.0 * r + skin_);
    // cells each class's particles scan in each grid: reach = the two classes' largest
    // radii + skin (a hair below the exact ratio, so that rounding never widens the
    // usual 3-cell stencil of a grid whose cells are exactly the reach)
    const std::size_t classes = class_radius_.size();
    reach_cells_.assign(classes * classes, 1);
    for (std::size_t c = 0; c < classes; ++c)
        for (std::size_t k = 0; k < classes; ++k)
            reach_cells_[c * classes + k] = grids_[k].cells_to_reach(
                (class_radius_[c] + class_radius_[k] + skin_) * (1.0 - 1e-12));
}

// Calls f(j) for every particle whose list centre may lie within contact + skin of i's:
// in each class's grid, the cells within reach of i's class.
template <int D>
template <class F>
void EventEngine<D>::for_each_candidate(std::uint32_t i, F&& f) const {
    const std::size_t classes = grids_.size();
    const std::size_t c = class_of_[p_.species[i]];
    for (std::size_t k = 0; k < classes; ++k)
        grids_[k].for_each_within(centre_[i], reach_cells_[c * classes + k], f);
}

template <int D> std::size_t EventEngine<D>::grids_memory() const {
    std::size_t bytes = 0;
    for (const auto& grid : grids_) bytes += grid.memory_bytes();
    return bytes;
}

template <int D> void EventEngine<D>::build_all_lists() {
    const auto n = static_cast<std::uint32_t>(p_.size());
    centre_ = p_.position;
    for (std::size_t k = 0; k < grids_.size(); ++k) {
        grids_[k].clear(n);
        for (std::uint32_t i = n; i-- > 0;)
            if (class_of_[p_.species[i]] == k) grids_[k].insert(i, centre_[i]);
    }
    // size the lists from the real counts, with room to grow as the fluid moves
    std::vector<std::uint16_t> counts(n, 0);
    std::uint32_t max_count = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        std::uint32_t c = 0;
        for_each_candidate(i, [&](std::uint32_t j) {
            if (j == i) return;
            const double cut = contact(i, j) + skin_;
            if (norm2(box_.minimum_image(centre_[i] - centre_[j])) < cut * cut) ++c;
        });
        max_count = std::max(max_count, c);
    }
    stride_ = std::max<std::uint32_t>(8, max_count + max_count / 2 + 2);
    n_nbr_.assign(n, 0);
    nbr_.assign(static_cast<std::size_t>(n) * stride_, 0);
    for (std::uint32_t i = 0; i < n; ++i) {
        for_each_candidate(i, [&](std::uint32_t j) {
            if (j <= i) return;
            const double cut = contact(i, j) + skin_;
            if (norm2(box_.minimum_image(centre_[i] - centre_[j])) < cut * cut) add_neighbor(i, j);
        });
    }
}

template <int D> void EventEngine<D>::setup() {
    const auto n = static_cast<std::uint32_t>(p_.size());
    ev_time_.assign(n, never);
    ev_partner_.assign(n, no_event);
    ev_count_.assign(n, 0);
    for (std::uint32_t i = 0; i < n; ++i) predict(i);
    queue_.build(ev_time_);
}

template <int D> void EventEngine<D>::add_neighbor(std::uint32_t i, std::uint32_t j) {
    if (n_nbr_[i] == stride_ || n_nbr_[j] == stride_) grow_lists();
    nbr_[static_cast<std::size_t>(i) * stride_ + n_nbr_[i]++] = j;
    nbr_[static_cast<std::size_t>(j) * stride_ + n_nbr_[j]++] = i;
}

template <int D> void EventEngine<D>::remove_neighbor(std::uint32_t i, std::uint32_t j) {
    std::uint32_t* list = &nbr_[static_cast<std::size_t>(i) * stride_];
    const std::uint16_t n = n_nbr_[i];
    for (std::uint16_t k = 0; k < n; ++k) {
        if (list[k] == j) {
            list[k] = list[n - 1];
            n_nbr_[i] = n - 1;
            return;
        }
    }
}

template <int D> void EventEngine<D>::grow_lists() {
    const std::uint32_t new_stride = stride_ + stride_ / 2 + 4;
    if (new_stride > 65535)
        throw RunError("event engine: a neighbour list exceeds 65535 entries; reduce event.skin");
    std::vector<std::uint32_t> grown(p_.size() * static_cast<std::size_t>(new_stride));
    for (std::size_t i = 0; i < p_.size(); ++i)
        std::copy_n(&nbr_[i * stride_], n_nbr_[i], &grown[i * new_stride]);
    nbr_ = std::move(grown);
    stride_ = new_stride;
}

template <int D> void EventEngine<D>::advance(std::uint32_t i) {
    const double dt = now_ - t_[i];
    if (dt != 0.0) {
        p_.position[i] += p_.velocity[i] * dt;
        t_[i] = now_;
    }
}

template <int D> void EventEngine<D>::predict(std::uint32_t i) {
    const Vec<D> vi = p_.velocity[i];
    const Vec<D> xi = p_.position[i] + vi * (now_ - t_[i]);
    const double ri = radius_[p_.species[i]];

    double best = shell_exit_time(box_.minimum_image(xi - centre_[i]), vi, shell_);
    std::int32_t partner = shell_event;
    for (int a = 0; a < D; ++a) {
        if (box_.periodic(a)) continue;
        const double tw = wall_collision_time(xi[a], vi[a], box_.lo(a), box_.hi(a), ri);
        if (tw < best) {
            best = tw;
            partner = wall_event_base - (2 * a + (vi[a] > 0.0 ? 1 : 0));
        }
    }
    const std::uint32_t* list = &nbr_[static_cast<std::size_t>(i) * stride_];
    const std::uint16_t n = n_nbr_[i];
    for (std::uint16_t k = 0; k < n; ++k) {
        const std::uint32_t j = list[k];
        const Vec<D> xj = p_.position[j] + p_.velocity[j] * (now_ - t_[j]);
        const Vec<D> dr = box_.minimum_image(xi - xj);
        const Vec<D> dv = vi - p_.velocity[j];
        const double tc = pair_collision_time_before(dr, dv, ri + radius_[p_.species[j]], best);
        if (tc < best) {
            best = tc;
            partner = static_cast<std::int32_t>(j);
        }
    }
    if (best == never) partner = no_event;
    ev_time_[i] = now_ + best;
    ev_partner_[i] = partner;
    ev_count_[i] = partner >= 0 ? count_[partner] : 0;
}

template <int D> void EventEngine<D>::process_pair(std::uint32_t i, std::uint32_t j) {
    advance(i);
    advance(j);
    const Vec<D> dr = box_.minimum_image(p_.position[i] - p_.position[j]);
    const double dist = norm(dr);
    const Vec<D> n = dr * (1.0 / dist);
    double xi = params_.restitution;
    if (params_.tc > 0.0) {
        if (now_ - last_collision_[i] < params_.tc || now_ - last_collision_[j] < params_.tc)
            xi = 1.0;
        last_collision_[i] = last_collision_[j] = now_;
    }
    const PairImpulse res = collide_pair(p_.velocity[i], p_.velocity[j], n,
                                         inv_mass_[p_.species[i]], inv_mass_[p_.species[j]], xi);
    for (int a = 0; a < D; ++a) counters_.virial[a] += res.impulse * n[a] * dr[a];
    kinetic_ += res.energy_change;
    if (kinetic_ < 0.5 * kinetic_exact_) resum_kinetic_energy();
    counters_.energy_lost -= res.energy_change;
    ++counters_.pair_collisions;
    ++count_[i];
    ++count_[j];
}

template <int D> void EventEngine<D>::process_wall(std::uint32_t i, std::int32_t code) {
    advance(i);
    const int k = wall_event_base - code;
    const int a = k / 2, side = k % 2;
    double xi = params_.wall_restitution;
    if (params_.tc > 0.0) {
        if (now_ - last_collision_[i] < params_.tc) xi = 1.0;
        last_collision_[i] = now_;
    }
    // pin the particle exactly onto the contact plane so rounding never lets it leak out
    const double r = radius_[p_.species[i]];
    p_.position[i][a] = side ? box_.hi(a) - r : box_.lo(a) + r;
    const double before = p_.velocity[i][a];
    const double m = 1.0 / inv_mass_[p_.species[i]];
    counters_.wall_impulse[a][side] += collide_wall(p_.velocity[i][a], m, xi);
    kinetic_ -= 0.5 * m * (1.0 - xi * xi) * before * before;
    if (kinetic_ < 0.5 * kinetic_exact_) resum_kinetic_energy();
    counters_.energy_lost += 0.5 * m * (1.0 - xi * xi) * before * before;
    ++counters_.wall_collisions;
    ++count_[i];
}

// The running kinetic energy carries a rounding error of order 1e-16 of the energy it
// started from; in a gas that cools by many decades that error would dominate (and can
// turn negative), so the sum is redone from the velocities each time it halves.
template <int D> void EventEngine<D>::resum_kinetic_energy() {
    double k = 0.0;
    for (std::size_t i = 0; i < p_.size(); ++i)
        if (inv_mass_[p_.species[i]] > 0.0)
            k += 0.5 * norm2(p_.velocity[i]) / inv_mass_[p_.species[i]];
    kinetic_ = kinetic_exact_ = k;
}

template <int D> void EventEngine<D>::rebuild_list(std::uint32_t i) {
    advance(i);
    box_.wrap(p_.position[i]);
    const std::uint32_t* list = &nbr_[static_cast<std::size_t>(i) * stride_];
    for (std::uint16_t k = 0; k < n_nbr_[i]; ++k) remove_neighbor(list[k], i);
    n_nbr_[i] = 0;
    CellList<D>& grid = grids_[class_of_[p_.species[i]]];
    grid.remove(i);
    centre_[i] = p_.position[i];
    grid.insert(i, centre_[i]);
    for_each_candidate(i, [&](std::uint32_t j) {
        if (j == i) return;
        const double cut = contact(i, j) + skin_;
        if (norm2(box_.minimum_image(centre_[i] - centre_[j])) < cut * cut) add_neighbor(i, j);
    });
    ++counters_.list_rebuilds;
}

template <int D> StopReason EventEngine<D>::run(const StopLimits& limits) {
    while (true) {
        const std::uint32_t i = queue_.top();
        const double te = queue_.top_time();
        if (te == never) return StopReason::no_events; // nothing moves: time is meaningless
        if (te > limits.time) {
            if (std::isfinite(limits.time)) now_ = std::max(now_, limits.time);
            return StopReason::time;
        }
        // Inelastic collapse shows as unbounded events at one instant.
        if (te - now_ <= 1e-13 * (1.0 + std::abs(te))) {
            if (++stalled_events_ > 1000 + 200 * static_cast<std::uint64_t>(p_.size())) {
                std::ostringstream m;
                m << "event engine: time stopped advancing at t = " << te << " (" << stalled_events_
                  << " events at the same instant, last at " << tag_name(p_.tag[i])
                  << "); this is inelastic collapse: set event.tc > 0 (TC model) or raise the "
                     "restitution";
                throw RunError(m.str());
            }
        } else {
            stalled_events_ = 0;
        }
        now_ = te;
        const std::int32_t partner = ev_partner_[i];
        if (partner >= 0) {
            const auto j = static_cast<std::uint32_t>(partner);
            if (count_[j] != ev_count_[i]) {
                ++counters_.stale_events;
                predict(i);
                queue_.update(i, ev_time_[i]);
                continue;
            }
            process_pair(i, j);
            if (params_.check_overlaps) {
                check_particle_overlap(i, 1e-9);
                check_particle_overlap(j, 1e-9);
            }
            predict(i);
            predict(j);
            queue_.update(i, ev_time_[i]);
            queue_.update(j, ev_time_[j]);
            if (counters_.pair_collisions >= limits.pair_collisions) return StopReason::collisions;
            if (kinetic_ <= limits.min_kinetic_energy) return StopReason::energy;
            continue;
        }
        if (partner == shell_event)
            rebuild_list(i);
        else
            process_wall(i, partner);
        predict(i);
        queue_.update(i, ev_time_[i]);
        if (partner != shell_event && kinetic_ <= limits.min_kinetic_energy)
            return StopReason::energy;
    }
}

template <int D> Vec<D> EventEngine<D>::position_now(std::size_t i) const {
    Vec<D> r = p_.position[i] + p_.velocity[i] * (now_ - t_[i]);
    box_.wrap(r);
    return r;
}

template <int D> ParticleStore<D> EventEngine<D>::snapshot() const {
    ParticleStore<D> s = p_;
    for (std::size_t i = 0; i < s.size(); ++i) s.position[i] = position_now(i);
    return s;
}

template <int D>
void EventEngine<D>::check_particle_overlap(std::uint32_t i, double rel_tol) const {
    const Vec<D> xi = p_.position[i] + p_.velocity[i] * (now_ - t_[i]);
    const std::uint32_t* list = &nbr_[static_cast<std::size_t>(i) * stride_];
    for (std::uint16_t k = 0; k < n_nbr_[i]; ++k) {
        const std::uint32_t j = list[k];
        const Vec<D> xj = p_.position[j] + p_.velocity[j] * (now_ - t_[j]);
        const double d = norm(box_.minimum_image(xi - xj));
        const double s = contact(i, j);
        if (d < s * (1.0 - rel_tol)) {
            std::ostringstream m;
            m << "overlap at t = " << now_ << ": " << tag_name(p_.tag[i]) << " and "
              << tag_name(p_.tag[j]) << " are " << d << " apart, contact distance " << s;
            throw RunError(m.str());
        }
    }
}

template <int D> void EventEngine<D>::check_no_overlap(double rel_tol) const {
    // Uses a fresh cell list on current positions: independent of the neighbour lists.
    const ParticleStore<D> s = snapshot();
    double max_radius = 0.0;
    for (double r : radius_) max_radius = std::max(max_radius, r);
    CellList<D> cells(box_, 2.0 * max_radius);
    cells.build(s.position);
    for (std::uint32_t i = 0; i < s.size(); ++i) {
        cells.for_each_near(s.position[i], [&](std::uint32_t j) {
            if (j <= i) return;
            const double d = norm(box_.minimum_image(s.position[i] - s.position[j]));
            const double c = contact(i, j);
            if (d < c * (1.0 - rel_tol)) {
                std::ostringstream m;
                m << tag_name(s.tag[i]) << " and " << tag_name(s.tag[j]) << " overlap: centres "
                  << d << " apart, contact distance " << c << " (overlap " << c - d << ")";
                if (now_ == 0.0 && counters_.pair_collisions == 0) throw InputError(m.str());
                throw RunError("at t = " + std::to_string(now_) + ": " + m.str());
            }
        });
    }
}

template <int D> std::size_t EventEngine<D>::memory_bytes() const {
    auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    return bytes(p_.position) + bytes(p_.velocity) + bytes(p_.tag) + bytes(p_.species) + bytes(t_) +
           bytes(centre_) + bytes(count_) + bytes(ev_time_) + bytes(ev_partner_) +
           bytes(ev_count_) + bytes(last_collision_) + bytes(n_nbr_) + bytes(nbr_) +
           grids_memory() + queue_.memory_bytes();
}

namespace {
constexpr std::uint64_t checkpoint_magic = 0x4b43455344455045ull; // "EPEDSECK" in memory order
constexpr std::uint32_t checkpoint_version = 2;                   // 2: one cell list per size class
} // namespace

template <int D> void EventEngine<D>::save(std::ostream& out) const {
    using binary::put;
    binary::put_header(out, checkpoint_magic, checkpoint_version, D);
    put(out, p_.species_table);
    put(out, box_);
    put(out, now_);
    put(out, skin_);
    put(out, kinetic_);
    put(out, kinetic_exact_);
    put(out, stalled_events_);
    put(out, counters_);
    put(out, p_.position);
    put(out, p_.velocity);
    put(out, p_.tag);
    put(out, p_.species);
    put(out, t_);
    put(out, centre_);
    put(out, count_);
    put(out, ev_time_);
    put(out, ev_partner_);
    put(out, ev_count_);
    put(out, last_collision_);
    put(out, stride_);
    put(out, n_nbr_);
    put(out, nbr_);
    for (const auto& grid : grids_) grid.save([&](const auto& v) { put(out, v); });
}

template <int D> EventEngine<D> EventEngine<D>::load(std::istream& in, const EventParams& params) {
    using binary::get;
    binary::get_header(in, checkpoint_magic, checkpoint_version, D, "event");
    validate(params);
    EventEngine e;
    e.params_ = params;
    get(in, e.p_.species_table);
    for (const auto& s : e.p_.species_table) {
        e.radius_.push_back(s.radius);
        e.inv_mass_.push_back(s.inverse_mass());
    }
    get(in, e.box_);
    get(in, e.now_);
    get(in, e.skin_);
    e.shell_ = 0.5 * e.skin_;
    get(in, e.kinetic_);
    get(in, e.kinetic_exact_);
    get(in, e.stalled_events_);
    get(in, e.counters_);
    get(in, e.p_.position);
    get(in, e.p_.velocity);
    get(in, e.p_.tag);
    get(in, e.p_.species);
    get(in, e.t_);
    get(in, e.centre_);
    get(in, e.count_);
    get(in, e.ev_time_);
    get(in, e.ev_partner_);
    get(in, e.ev_count_);
    get(in, e.last_collision_);
    get(in, e.stride_);
    get(in, e.n_nbr_);
    get(in, e.nbr_);
    const std::size_t n = e.p_.position.size();
    if (n == 0 || e.p_.velocity.size() != n || e.p_.tag.size() != n || e.p_.species.size() != n ||
        e.t_.size() != n || e.centre_.size() != n || e.count_.size() != n ||
        e.ev_time_.size() != n || e.ev_partner_.size() != n || e.ev_count_.size() != n ||
        e.n_nbr_.size() != n || e.nbr_.size() != n * e.stride_)
        throw InputError("checkpoint: inconsistent array sizes (corrupt file)");
    if (params.tc > 0.0 && e.last_collision_.size() != n) e.last_collision_.assign(n, -never);
    for (auto s : e.p_.species)
        if (s >= e.p_.species_table.size()) throw InputError("checkpoint: corrupt species index");
    for (std::size_t i = 0; i < n; ++i) {
        if (e.n_nbr_[i] > e.stride_) throw InputError("checkpoint: corrupt neighbour list");
        for (std::uint16_t k = 0; k < e.n_nbr_[i]; ++k)
            if (e.nbr_[i * e.stride_ + k] >= n)
                throw InputError("checkpoint: corrupt neighbour list");
        if (e.ev_partner_[i] >= static_cast<std::int32_t>(n))
            throw InputError("checkpoint: corrupt event");
    }
    e.make_grids();
    for (auto& grid : e.grids_) grid.load([&](auto& v) { get(in, v); });
    e.queue_.build(e.ev_time_);
    return e;
}

template class EventEngine<2>;
template class EventEngine<3>;

} // namespace pedesis
