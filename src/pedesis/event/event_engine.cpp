#include "pedesis/event/event_engine.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/interrupt.hpp"
#include "pedesis/core/particle_checks.hpp"
#include "pedesis/core/stage.hpp"
#include "pedesis/event/collision_rules.hpp"
#include "pedesis/event/falling_times.hpp"
#include "pedesis/event/prediction.hpp"
#include "pedesis/io/binary_stream.hpp"
#include "pedesis/spatial/spatial_sort.hpp"

#include <fmt/format.h>

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
    if (!(p.growth_rate >= 0.0 && std::isfinite(p.growth_rate)))
        throw InputError("event.growth_rate must be a finite number >= 0");
    if (!(p.growth_packing_fraction >= 0.0 && p.growth_packing_fraction < 1.0))
        throw InputError("event.growth_packing_fraction must lie in (0, 1)");
    if (!(p.growth_max_pressure > 1.0))
        throw InputError("event.growth_max_pressure must exceed 1 (the ideal gas)");
    if (!(p.thermostat_temperature >= 0.0 && p.thermostat_temperature <= 1e100))
        throw InputError("event.temperature must be a finite number >= 0");
    if (p.thermostat_temperature > 0.0 &&
        !(p.thermostat_interval > 0.0 && std::isfinite(p.thermostat_interval)))
        throw InputError("event.thermostat_interval must be a positive finite number");
    for (double g : p.gravity)
        if (!(std::abs(g) <= 1e100)) throw InputError("event.gravity must be finite numbers");
    if (!(p.andersen_rate >= 0.0 && p.andersen_rate <= 1e100))
        throw InputError("event.thermostat_rate must be a finite number >= 0");
    if (p.andersen_rate > 0.0 && !(p.andersen_temperature > 0.0 && p.andersen_temperature <= 1e100))
        throw InputError("event.temperature must be a positive finite number");
    if (!(p.driving_rate >= 0.0 && p.driving_rate <= 1e100))
        throw InputError("event.driving_rate must be a finite number >= 0");
    if (p.driving_rate > 0.0 && !(p.driving_strength > 0.0 && p.driving_strength <= 1e100))
        throw InputError("event.driving_strength must be a positive finite number");
}

// The time of a periodic pass `interval` after now: RunError when the interval is below
// the clock's resolution (the pass would come again at the same instant, for ever).
double next_pass_time(double now, double interval, const char* what) {
    const double next = now + interval;
    if (!(next > now))
        throw RunError(fmt::format("event engine: at t = {:g} the {} interval {:g} is below the "
                                   "clock's resolution; raise it",
                                   now, what, interval));
    return next;
}

// Growth steps come at least this often in collisions per particle, so that the
// pressure that ends growth near jamming is measured while time hardly advances.
constexpr double growth_window_collisions = 4.0;
// ... and whenever the kinetic energy has drifted this far from the value held.
constexpr double growth_energy_tolerance = 0.05;

std::string tag_name(std::uint32_t tag) {
    return "particle " + std::to_string(tag);
}

} // namespace

template <int D>
EventEngine<D>::EventEngine(ParticleStore<D> particles, const Box<D>& box,
                            const EventParams& params)
    : p_(std::move(particles)), box_(box), params_(params) {
    enter_stage("setting up the event engine");
    if (p_.size() == 0) throw InputError("event engine: no particles (N = 0)");
    validate(params_);

    double max_radius = 0.0;
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
        // m v^2 / 2 must stay a number (a speed of 1e200 ran forever with an infinite energy)
        if (norm2(p_.velocity[i]) > 1e200)
            throw InputError(tag_name(p_.tag[i]) + ": speed above 1e100 (the kinetic energy would "
                                                   "overflow)");
        if (inv_mass_[p_.species[i]] == 0.0) p_.velocity[i] = Vec<D>{}; // obstacles never move
    }

    for (int a = 0; a < D; ++a)
        if (box_.length(a) < 2.0 * max_radius)
            throw InputError("box: length " + std::to_string(box_.length(a)) + " along axis " +
                             std::to_string(a) + " is smaller than one particle (diameter " +
                             std::to_string(2.0 * max_radius) + ")");

    for (std::size_t i = 0; i < p_.size(); ++i) {
        const double r = radius_[p_.species[i]];
        if (!box_.contains(p_.position[i], r * (1.0 - 1e-12))) {
            std::ostringstream m;
            m << tag_name(p_.tag[i])
              << " lies outside the walls (centre must be at least its radius " << r
              << " from every wall)";
            throw InputError(m.str());
        }
        image_.push_back(image_shift<D>(box_.wrap(p_.position[i])));
    }
    if (box_.sheared()) {
        if (params_.growth_rate > 0.0)
            throw InputError(
                "event.growth_rate: growth and Lees-Edwards shear cannot run together");
        box_.shear_to_time(now_);
        shear_velocity_ = box_.shear_rate() * box_.length(1);
        pair_times_ = nullptr; // the batch kernel knows no sliding images
        // the given velocities are peculiar: the flow starts linear
        for (std::size_t i = 0; i < p_.size(); ++i)
            if (inv_mass_[p_.species[i]] > 0.0)
                p_.velocity[i][0] += box_.shear_rate() * p_.position[i][1];
    }
    // Storage along a space-filling curve, so that a particle's neighbours lie in nearby
    // cache lines: events come in no spatial order, and at 10^6 particles a neighbour
    // stored far away costs a miss per array in every prediction. Only a fresh start is
    // sorted; a restored engine keeps its order and so continues bit for bit.
    const std::vector<std::uint32_t> order =
        space_filling_order(box_, p_.position, p_.tag, 2.0 * max_radius);
    p_.apply_order(order);
    std::vector<std::array<std::int32_t, D>> images(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) images[k] = image_[order[k]];
    image_.swap(images);

    take_flights(std::vector<double>(p_.size(), 0.0), std::vector<std::uint32_t>(p_.size(), 0),
                 std::vector<std::uint16_t>(p_.size(), 0));
    if (params_.tc > 0.0) last_collision_.assign(size(), -never);
    start_gravity();
    start_moving_wall();
    resum_kinetic_energy();
    if (params_.thermostat_temperature > 0.0 && params_.growth_rate > 0.0)
        throw InputError("event.thermostat: growth holds the kinetic energy itself; use one or "
                         "the other");

    radius_rate_.assign(radius_.size(), 0.0);
    if (params_.growth_rate > 0.0) start_growth();
    if (!choose_skin())
        throw InputError(fmt::format(
            "box: periodic length {:g} must be at least {:g} times the largest contact "
            "distance ({:g}): a pair meets one image only, and the neighbour lists need room "
            "between the two",
            min_periodic_length(), 2.0 * (1.0 + min_room_fraction), 2.0 * max_radius));
    make_grids();
    // before the lists exist: its copy of the positions then adds to less (the start is
    // the run's peak memory)
    check_no_overlap(1e-10);
    build_all_lists();
    setup();
    if (params_.thermostat_temperature > 0.0)
        next_rescale_ = next_pass_time(now_, params_.thermostat_interval, "thermostat");
    start_driving();
    if (box_.sheared()) {
        next_shear_relist_ = next_pass_time(now_, slide_ / shear_velocity_, "shear");
        track_flux_moments(); // the exact kinetic stress of the log's P_xy
    }
}

template <int D> double EventEngine<D>::min_periodic_length() const {
    double shortest = never;
    for (int a = 0; a < D; ++a)
        if (box_.periodic(a)) shortest = std::min(shortest, box_.length(a));
    return shortest;
}

// The minimum image of a colliding pair must be unique over a whole list lifetime:
// L/2 > contact + 2 skin, and with growth the contact may gain another skin/3 before
// the next growth step. Small periodic boxes get a smaller skin; false if none fits.
template <int D> bool EventEngine<D>::choose_skin() {
    double max_radius = 0.0, mean_diameter = 0.0;
    for (double r : radius_) max_radius = std::max(max_radius, r);
    for (auto s : p_.species) mean_diameter += 2.0 * radius_[s];
    mean_diameter /= static_cast<double>(size());
    skin_ = params_.skin >= 0.0 ? params_.skin : default_skin(mean_diameter);
    // The lists' skin must fit between the largest contact and half the periodic length
    // (one image per pair). A box barely wider than that leaves a skin so thin that the
    // lists are rebuilt every 1e-16 time units and the run stalls (one particle in a
    // square of 4 radii + 1 ulp, found by the brute-force tests): half the length must
    // exceed the contact by a tenth of it, so that the skin is at least 0.045 contacts.
    const double contact = 2.0 * max_radius;
    const double room = 0.5 * min_periodic_length() - contact;
    if (!(room >= min_room_fraction * contact)) return false;
    // (growth takes another third of the skin between passes; under shear the slide's
    // allowance needs room too, choose_slide)
    skin_ = std::min(skin_, (growth_.growing || box_.sheared() ? 0.4 : 0.45) * room);
    if (!(skin_ > 0.0)) throw InputError("event.skin must be positive");
    shell_ = growth_.growing ? skin_ / 3.0 : 0.5 * skin_;
    choose_slide();
    return true;
}

// How far the offset may move between shear passes: one list reach (contact + skin), but
// less in a short box, where a pair's nearest image along x must stay the one that may
// collide: contact + 2 skin + slide < L_x / 2 (choose_skin's cap leaves at least a fifth
// of the room between contact and L/2 for it).
template <int D> void EventEngine<D>::choose_slide() {
    if (!box_.sheared()) return;
    const double contact = 2.0 * *std::max_element(radius_.begin(), radius_.end());
    const double room = 0.5 * box_.length(0) - contact - 2.0 * skin_;
    slide_ = std::min(contact + skin_, (1.0 - 1e-9) * room);
}

template <int D> double EventEngine<D>::packing_fraction() const {
    const double ball = D == 2 ? std::numbers::pi : 4.0 / 3.0 * std::numbers::pi;
    double volume = 0.0;
    for (auto s : p_.species) volume += ball * std::pow(radius_now(s), D);
    return volume / box_.volume();
}

// Radii grow linearly, each in proportion to its size, so that the size ratios hold:
// the largest diameter gains growth_rate per unit time.
template <int D> void EventEngine<D>::start_growth() {
    for (double im : inv_mass_)
        if (im == 0.0)
            throw InputError("event.growth_rate: every species must be mobile (a fixed obstacle "
                             "cannot make room for growing neighbours)");
    if (!(kinetic_ > 0.0))
        throw InputError("event.growth_rate: the particles must move (zero kinetic energy)");
    const double target = params_.growth_packing_fraction;
    if (target > 0.0 && target <= packing_fraction())
        throw InputError("event.growth_packing_fraction (" + std::to_string(target) +
                         ") must exceed the starting packing fraction (" +
                         std::to_string(packing_fraction()) + ")");
    set_radius_rates();
    radius_time_ = now_;
    growth_kinetic_ = kinetic_;
    growth_.growing = true;
    window_time_ = now_;
    window_collisions_ = counters_.pair_collisions;
    window_virial_ = virial_trace(counters_);
}

template <int D> void EventEngine<D>::set_radius_rates() {
    const double largest = *std::max_element(radius_.begin(), radius_.end());
    for (std::size_t s = 0; s < radius_.size(); ++s)
        radius_rate_[s] = 0.5 * params_.growth_rate * radius_[s] / largest;
}

template <int D> bool EventEngine<D>::pressure_window_full() const {
    return static_cast<double>(counters_.pair_collisions - window_collisions_) >=
           growth_window_collisions * static_cast<double>(size());
}

template <int D> bool EventEngine<D>::growth_due() const {
    return pressure_window_full() ||
           std::abs(kinetic_ - growth_kinetic_) > growth_energy_tolerance * growth_kinetic_;
}

// The next growth step: when the contact distances have used up the part of the skin
// the lists leave them (see choose_skin), or when the target packing fraction is due.
template <int D> void EventEngine<D>::schedule_growth_step() {
    double contact_rate = 0.0, largest = 0.0, largest_rate = 0.0;
    for (std::size_t s = 0; s < radius_.size(); ++s) {
        contact_rate = std::max(contact_rate, 2.0 * radius_rate_[s]);
        if (radius_[s] > largest) largest = radius_[s], largest_rate = radius_rate_[s];
    }
    next_growth_step_ = now_ + (skin_ - 2.0 * shell_) / contact_rate;
    const double target = params_.growth_packing_fraction;
    if (target > 0.0) {
        const double scale = std::pow(target / packing_fraction(), 1.0 / D);
        next_growth_step_ =
            std::min(next_growth_step_, now_ + largest * (scale - 1.0) / largest_rate);
    }
}

// A whole-system pass at now_: every particle brought to now_, the growth's end
// tested, the kinetic energy rescaled to the value held and every event predicted
// anew. A full step (the lists' allowance used up, or growth over) also moves the
// radii's reference to now_ and rebuilds the lists; a thermostat step keeps both.
template <int D> void EventEngine<D>::growth_step(bool full) {
    for (std::uint32_t i = 0; i < size(); ++i) {
        advance(i);
        wrap_flight(i);
    }
    ++growth_.steps;
    if (pressure_window_full() && now_ > window_time_) {
        // Z = PV/(NkT) = 1 + W/(2K dt) with the collision virial W over the window
        const double w = virial_trace(counters_) - window_virial_;
        growth_.last_pressure = 1.0 + w / (2.0 * growth_kinetic_ * (now_ - window_time_));
        window_time_ = now_;
        window_collisions_ = counters_.pair_collisions;
        window_virial_ = virial_trace(counters_);
        if (growth_.last_pressure >= params_.growth_max_pressure) end_growth(GrowthEnd::pressure);
    }
    const double target = params_.growth_packing_fraction;
    if (growth_.growing && target > 0.0 && packing_fraction() >= target * (1.0 - 1e-12))
        end_growth(GrowthEnd::packing_fraction);

    const double scale = std::sqrt(growth_kinetic_ / kinetic_);
    for (auto& f : f_) f.v *= scale;
    resum_kinetic_energy();

    if (!full && growth_.growing) {
        queue_.build_from(size(), [&](std::uint32_t i) { return predict(i); });
        return;
    }
    for (std::size_t s = 0; s < radius_.size(); ++s) {
        radius_[s] = radius_now(s);
        p_.species_table[s].radius = radius_[s];
    }
    radius_time_ = now_;
    std::fill(radius_rate_.begin(), radius_rate_.end(), 0.0); // until growth resumes below
    if (growth_.growing) set_radius_rates();
    if (!choose_skin()) {
        std::ostringstream m;
        m << "event engine: at t = " << now_ << " the particles have grown to a contact distance "
          << 2.0 * *std::max_element(radius_.begin(), radius_.end())
          << ", and the periodic box length " << min_periodic_length() << " must be at least "
          << 2.0 * (1.0 + min_room_fraction) << " times that; use a larger box (more particles)";
        throw RunError(m.str());
    }
    relist();
}

// The radii stop at their current values: growth_step(), which calls this, then moves
// their reference to now_ before any rate is cleared.
template <int D> void EventEngine<D>::end_growth(GrowthEnd why) {
    growth_.growing = false;
    growth_.ended = why;
    next_growth_step_ = never;
}

template <int D> void EventEngine<D>::relist() {
    make_grids();
    build_all_lists();
    setup();
}

// A skin that holds about 8 (2D) or 12 (3D) neighbours per list, and at least half a
// diameter: in dense fluids that is the 1.5-diameter shell of Smallenburg's code; in
// dilute gases it grows with the mean free path, so lists are not rebuilt several
// times per free flight.
template <int D> double EventEngine<D>::default_skin(double mean_diameter) const {
    const double n = static_cast<double>(size()) / box_.volume();
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
    // how far each class's particles scan in each grid: the two classes' largest
    // radii + skin (CellList's margins keep a class's own reach at the 3-cell stencil)
    const std::size_t classes = class_radius_.size();
    reach_.assign(classes * classes, 0.0);
    for (std::size_t c = 0; c < classes; ++c)
        for (std::size_t k = 0; k < classes; ++k)
            reach_[c * classes + k] = class_radius_[c] + class_radius_[k] + skin_;
}

// Calls f(j) for every particle whose list centre may lie within contact + skin of i's:
// in each class's grid, the cells within reach of i's class, less those wholly beyond
// it (CellList::for_each_reaching: about a quarter of a 3^3 stencil, at the corners,
// whose chains and centres are cache misses at 10^6). The particles come in the
// whole stencil's order, so the lists are those a scan of every cell would build.
template <int D>
template <class F>
void EventEngine<D>::for_each_candidate(std::uint32_t i, F&& f) const {
    if (box_.sheared()) [[unlikely]] {
        for_each_candidate_sheared(i, f);
        return;
    }
    const std::size_t classes = grids_.size();
    const std::size_t c = class_of_[f_[i].species];
    for (std::size_t k = 0; k < classes; ++k)
        grids_[k].for_each_reaching(ev_[i].centre, reach_[c * classes + k], f);
}

// A centre within reach of the top face meets the images above of particles near the
// bottom, displaced by the offset along x: their cells lie around the centre's image
// below, c - L_y e_y - offset e_x (and the reverse at the bottom face), out to the reach
// plus the slide's allowance along x (list_partners). The scans may overlap (a short box,
// the plain scan's wrap across y): a stamp per particle gives each candidate once, in
// the order first met.
template <int D>
template <class F>
void EventEngine<D>::for_each_candidate_sheared(std::uint32_t i, F&& f) const {
    const std::size_t classes = grids_.size();
    const std::size_t c = class_of_[f_[i].species];
    const Vec<D>& centre = ev_[i].centre;
    const double margin = 1e-9 * box_.length(1);
    const double widest = *std::max_element(reach_.begin(), reach_.end());
    if (centre[1] + widest + margin < box_.hi(1) && centre[1] - widest - margin > box_.lo(1)) {
        // away from the faces: the plain scan, each particle once
        for (std::size_t k = 0; k < classes; ++k)
            grids_[k].for_each_reaching(centre, reach_[c * classes + k], f);
        return;
    }
    if (seen_.size() != size() || ++stamp_ == 0) {
        seen_.assign(size(), 0);
        stamp_ = 1;
    }
    const auto once = [&](std::uint32_t j) {
        if (seen_[j] == stamp_) return;
        seen_[j] = stamp_;
        f(j);
    };
    Vec<D> image_shift{};
    image_shift[0] = box_.shear_offset();
    image_shift[1] = box_.length(1);
    for (std::size_t k = 0; k < classes; ++k) {
        const double reach = reach_[c * classes + k];
        grids_[k].for_each_reaching(centre, reach, once);
        Vec<D> half{};
        for (int a = 0; a < D; ++a) half[a] = reach;
        half[0] += slide_;
        if (centre[1] + reach + margin >= box_.hi(1))
            grids_[k].for_each_in_box(centre - image_shift, half, once);
        if (centre[1] - reach - margin <= box_.lo(1))
            grids_[k].for_each_in_box(centre + image_shift, half, once);
    }
}

template <int D> std::size_t EventEngine<D>::grids_memory() const {
    std::size_t bytes = 0;
    for (const auto& grid : grids_) bytes += grid.memory_bytes();
    return bytes;
}

template <int D> void EventEngine<D>::build_all_lists() {
    const auto n = static_cast<std::uint32_t>(size());
    ev_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) ev_[i] = {f_[i].x, no_event, 0};
    for (std::size_t k = 0; k < grids_.size(); ++k) {
        grids_[k].clear(n);
        for (std::uint32_t i = n; i-- > 0;)
            if (class_of_[f_[i].species] == k) grids_[k].insert(i, ev_[i].centre);
    }
    // size the lists from the real counts, with room to grow as the fluid moves
    std::uint32_t max_count = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        std::uint32_t c = 0;
        for_each_candidate(i, [&](std::uint32_t j) {
            if (j != i && list_partners(i, j)) ++c;
        });
        max_count = std::max(max_count, c);
    }
    stride_ = std::max<std::uint32_t>(8, max_count + max_count / 2 + 2);
    for (auto& f : f_) f.n_nbr = 0;
    nbr_.assign(static_cast<std::size_t>(n) * stride_, 0);
    for (std::uint32_t i = 0; i < n; ++i) {
        for_each_candidate(i, [&](std::uint32_t j) {
            if (j > i && list_partners(i, j)) add_neighbor(i, j);
        });
    }
}

template <int D> void EventEngine<D>::setup() {
    const auto n = static_cast<std::uint32_t>(size());
    queue_.build_from(n, [&](std::uint32_t i) { return predict(i); });
    if (growth_.growing) schedule_growth_step();
}

template <int D> void EventEngine<D>::add_neighbor(std::uint32_t i, std::uint32_t j) {
    if (f_[i].n_nbr == stride_ || f_[j].n_nbr == stride_) grow_lists();
    nbr_[static_cast<std::size_t>(i) * stride_ + f_[i].n_nbr++] = j;
    nbr_[static_cast<std::size_t>(j) * stride_ + f_[j].n_nbr++] = i;
}

template <int D> void EventEngine<D>::remove_neighbor(std::uint32_t i, std::uint32_t j) {
    std::uint32_t* list = &nbr_[static_cast<std::size_t>(i) * stride_];
    const std::uint16_t n = f_[i].n_nbr;
    for (std::uint16_t k = 0; k < n; ++k) {
        if (list[k] == j) {
            list[k] = list[n - 1];
            f_[i].n_nbr = n - 1;
            return;
        }
    }
}

template <int D> void EventEngine<D>::grow_lists() {
    const std::uint32_t new_stride = stride_ + stride_ / 2 + 4;
    if (new_stride > 65535)
        throw RunError("event engine: a neighbour list exceeds 65535 entries; reduce event.skin");
    std::vector<std::uint32_t> grown(size() * static_cast<std::size_t>(new_stride));
    for (std::size_t i = 0; i < size(); ++i)
        std::copy_n(&nbr_[i * stride_], f_[i].n_nbr, &grown[i * new_stride]);
    nbr_ = std::move(grown);
    stride_ = new_stride;
}

// A row is read first by the prediction that follows every event, and missed the caches
// there; asked for before the event's own work, it arrives meanwhile.
template <int D> void EventEngine<D>::prefetch_list(std::uint32_t i) const {
    const std::uint32_t* row = &nbr_[static_cast<std::size_t>(i) * stride_];
    __builtin_prefetch(row);
    __builtin_prefetch(row + std::min<std::uint32_t>(16, stride_ - 1)); // the next line
}

template <int D> void EventEngine<D>::advance(std::uint32_t i) {
    const double dt = now_ - f_[i].t;
    if (dt != 0.0) {
        if (falling_) [[unlikely]] {
            f_[i].x += f_[i].v * dt + gravity_ * (0.5 * dt * dt);
            f_[i].v += gravity_ * dt;
        } else {
            f_[i].x += f_[i].v * dt;
        }
        f_[i].t = now_;
    }
}

template <int D> double EventEngine<D>::predict(std::uint32_t i) {
    if (falling_ || moving_) [[unlikely]]
        return predict_falling(i);
    return growth_.growing ? predict_with<true>(i) : predict_with<false>(i);
}

// predict_with in gravity (no growth, no shear, no batch kernel): the pair times are
// those of straight flights from now_, since both particles fall alike; the walls' and
// the shell's are falling_times.hpp's.
template <int D> double EventEngine<D>::predict_falling(std::uint32_t i) {
    const Vec<D> vi = v_now(i);
    const Vec<D> xi = x_now(i);
    const double ri = radius_[f_[i].species];
    double best =
        falling_shell_exit_time(box_.minimum_image(xi - ev_[i].centre), vi, gravity_, shell_);
    std::int32_t partner = shell_event;
    for (int a = 0; a < D; ++a) {
        if (box_.periodic(a)) continue;
        bool upper = false;
        double tw = falling_wall_time(xi[a], vi[a], gravity_[a], box_.lo(a), box_.hi(a), ri, upper);
        if (moving_ && a == moving_axis_) [[unlikely]] {
            // the fixed face only here; the moving one last, with the earliest horizon
            upper = moving_side_ == 0;
            tw = upper ? falling_gap_time((box_.hi(a) - ri) - xi[a], -vi[a], -gravity_[a])
                       : falling_gap_time(xi[a] - (box_.lo(a) + ri), vi[a], gravity_[a]);
        }
        if (tw < best) {
            best = tw;
            partner = wall_event_base - (2 * a + (upper ? 1 : 0));
        }
    }
    const std::uint32_t* list = &nbr_[static_cast<std::size_t>(i) * stride_];
    for (std::uint16_t k = 0; k < f_[i].n_nbr; ++k) {
        const std::uint32_t j = list[k];
        const Vec<D> dr = box_.minimum_image(xi - x_now(j));
        const double tc =
            pair_collision_time_before(dr, vi - v_now(j), ri + radius_[f_[j].species], best);
        if (tc < best) {
            best = tc;
            partner = static_cast<std::int32_t>(j);
        }
    }
    if (moving_) [[unlikely]]
        meet_moving_wall(xi, vi, ri, best, partner);
    return settle_event(i, best, partner);
}

// The earliest event of particle i. While the radii grow (Growing), contact and wall
// distances move; the other branch is the plain hot loop.
template <int D> template <bool Growing> double EventEngine<D>::predict_with(std::uint32_t i) {
    const Vec<D> vi = f_[i].v;
    const Vec<D> xi = f_[i].x + vi * (now_ - f_[i].t);
    const std::size_t si = f_[i].species;
    const double ri = Growing ? radius_now(si) : radius_[si];

    double best = shell_exit_time(box_.minimum_image(xi - ev_[i].centre), vi, shell_);
    std::int32_t partner = shell_event;
    for (int a = 0; a < D; ++a) {
        if (box_.periodic(a)) continue;
        bool upper = vi[a] > 0.0;
        const double tw = Growing
                              ? growing_wall_collision_time(xi[a], vi[a], box_.lo(a), box_.hi(a),
                                                            ri, radius_rate_[si], upper)
                              : wall_collision_time(xi[a], vi[a], box_.lo(a), box_.hi(a), ri);
        if (tw < best) {
            best = tw;
            partner = wall_event_base - (2 * a + (upper ? 1 : 0));
        }
    }
    const std::uint32_t* list = &nbr_[static_cast<std::size_t>(i) * stride_];
    const std::uint16_t n = f_[i].n_nbr;
    // Every neighbour's data is asked for before any is used: the loop below branches on
    // whether each pair approaches, which no predictor guesses, and each miss of a branch
    // would otherwise discard the loads started for the neighbours after it.
    for (std::uint16_t k = 0; k < n; ++k) {
        const std::uint32_t j = list[k];
        __builtin_prefetch(&f_[j]);
    }
    if (!Growing && pair_times_ != nullptr) {
        earliest_listed_lanes(i, xi, vi, ri, best, partner);
    } else {
        for (std::uint16_t k = 0; k < n; ++k) {
            const std::uint32_t j = list[k];
            const std::size_t sj = f_[j].species;
            const Vec<D> xj = f_[j].x + f_[j].v * (now_ - f_[j].t);
            Vec<D> dv = vi - f_[j].v;
            const Vec<D> dr = pair_separation(xi - xj, dv[0]);
            double tc;
            if constexpr (Growing)
                tc = growing_pair_collision_time(dr, dv, ri + radius_now(sj),
                                                 radius_rate_[si] + radius_rate_[sj]);
            else
                tc = pair_collision_time_before(dr, dv, ri + radius_[sj], best);
            if (tc < best) {
                best = tc;
                partner = static_cast<std::int32_t>(j);
            }
        }
    }
    return settle_event(i, best, partner);
}

// predict_with's scan of the list with the batch kernel of the AVX2 and AVX-512 sets.
// It picks what the scalar loop picks: the first neighbour whose time is below the
// earliest so far, where pair_collision_time_before with that bound would not have
// returned `never` early (c > -2 b bound); that test is rarely reached, so the scan's
// one branch is rarely taken.
template <int D>
void EventEngine<D>::earliest_listed_lanes(std::uint32_t i, const Vec<D>& xi, const Vec<D>& vi,
                                           double ri, double& best, std::int32_t& partner) {
    const std::uint32_t* list = &nbr_[static_cast<std::size_t>(i) * stride_];
    const std::size_t n = f_[i].n_nbr;
    const std::size_t room = pair_times_room(n);
    if (lane_scratch_.size() < 3 * room) lane_scratch_.resize(3 * room);
    const PairTimes out{lane_scratch_.data(), lane_scratch_.data() + room,
                        lane_scratch_.data() + 2 * room};
    PairTimesInput<D> in{f_.data(), radius_.data(), list, n, xi, vi, ri, now_, {}, {}};
    for (int a = 0; a < D; ++a) {
        in.half[a] = box_.periodic(a) ? box_.hi(a) : never;
        in.length[a] = box_.length(a);
    }
    pair_times_(in, out);
    for (std::size_t k = 0; k < n; ++k) {
        if (out.time[k] < best && !(out.c[k] > -2.0 * out.b[k] * best)) {
            best = out.time[k];
            partner = static_cast<std::int32_t>(list[k]);
        }
    }
}

template <int D> void EventEngine<D>::set_restitution(double xi) {
    EventParams p = params_;
    p.restitution = xi;
    validate(p);
    params_ = p;
}

template <int D> void EventEngine<D>::set_wall_restitution(double xi) {
    EventParams p = params_;
    p.wall_restitution = xi;
    validate(p);
    params_ = p;
}

template <int D> void EventEngine<D>::process_pair(std::uint32_t i, std::uint32_t j) {
    advance(i);
    advance(j);
    // under shear, j collides as the image nearest i, whose x velocity differs by -slide
    double slide = 0.0;
    const Vec<D> dr = pair_separation(f_[i].x - f_[j].x, slide);
    f_[j].v[0] -= slide;
    const double dist = norm(dr);
    const Vec<D> n = dr * (1.0 / dist);
    double xi = params_.restitution;
    if (params_.tc > 0.0) {
        if (now_ - last_collision_[i] < params_.tc || now_ - last_collision_[j] < params_.tc)
            xi = 1.0;
        last_collision_[i] = last_collision_[j] = now_;
    }
    const std::size_t si = f_[i].species, sj = f_[j].species;
    const Vec<D> vi0 = f_[i].v, vj0 = f_[j].v;
    const PairImpulse res =
        growth_.growing ? collide_growing_pair(f_[i].v, f_[j].v, n, inv_mass_[si], inv_mass_[sj],
                                               xi, radius_rate_[si] + radius_rate_[sj])
                        : collide_pair(f_[i].v, f_[j].v, n, inv_mass_[si], inv_mass_[sj], xi);
    f_[j].v[0] += slide;
    add_collision_virial(counters_, res.impulse, n, dr);
    if (moments_on_) [[unlikely]] {
        if (box_.sheared()) {
            // peculiar velocities (a change of velocity is the same in both frames; j's
            // image has j's peculiar velocity)
            moments_.advance_sheared(now_, box_.shear_rate());
            Vec<D> flow_i{}, flow_j{};
            flow_i[0] = flow_velocity(i);
            flow_j[0] = flow_velocity(j);
            Vec<D> vj0_own = vj0; // (the image's velocity: j's own less the slide)
            vj0_own[0] += slide;
            moments_.collision(mass_of(si), vi0 - flow_i, f_[i].v - flow_i, mass_of(sj),
                               vj0_own - flow_j, f_[j].v - flow_j, dr);
        } else {
            moments_.advance(now_);
            moments_.collision(mass_of(si), vi0, f_[i].v, mass_of(sj), vj0, f_[j].v, dr);
        }
    }
    kinetic_ += res.energy_change;
    if (kinetic_ < 0.5 * kinetic_exact_) resum_kinetic_energy();
    counters_.energy_lost -= res.energy_change;
    ++counters_.pair_collisions;
    ++f_[i].count;
    ++f_[j].count;
}

template <int D> void EventEngine<D>::process_wall(std::uint32_t i, std::int32_t code) {
    const int k = wall_event_base - code;
    const int a = k / 2, side = k % 2;
    if (moving_ && a == moving_axis_ && side == moving_side_) [[unlikely]]
        return process_moving_wall(i, side);
    advance(i);
    double xi = params_.wall_restitution;
    if (params_.tc > 0.0) {
        if (now_ - last_collision_[i] < params_.tc) xi = 1.0;
        last_collision_[i] = now_;
    }
    // pin the particle exactly onto the contact plane so rounding never lets it leak out
    const std::size_t s = f_[i].species;
    const double r = radius_now(s);
    f_[i].x[a] = side ? box_.hi(a) - r : box_.lo(a) + r;
    const double before = f_[i].v[a];
    const double m = 1.0 / inv_mass_[s];
    double lost = 0.5 * m * (1.0 - xi * xi) * before * before;
    if (growth_.growing) {
        counters_.wall_impulse[a][side] +=
            collide_growing_wall(f_[i].v[a], m, xi, radius_rate_[s], side ? 1.0 : -1.0);
        lost = 0.5 * m * (before * before - f_[i].v[a] * f_[i].v[a]);
    } else {
        counters_.wall_impulse[a][side] += collide_wall(f_[i].v[a], m, xi);
    }
    kinetic_ -= lost;
    if (kinetic_ < 0.5 * kinetic_exact_) resum_kinetic_energy();
    counters_.energy_lost += lost;
    ++counters_.wall_collisions;
    ++f_[i].count;
}

template <int D> double EventEngine<D>::peculiar_kinetic_energy() const {
    double k = 0.0;
    for (std::uint32_t i = 0; i < size(); ++i) {
        const double inv_m = inv_mass_[f_[i].species];
        if (inv_m == 0.0) continue;
        Vec<D> c = f_[i].v;
        c[0] -= flow_velocity(i);
        k += 0.5 * norm2(c) / inv_m;
    }
    return k;
}

// Every particle at now_; the thermostat's rescaling if due; under shear, once the offset
// has moved the lists' allowance slide_, every list that may hold a pair across the y
// faces rebuilt. Only those pairs slide against each other, and only centres within the
// lists' reach of a face can have partners across it: a band of about 2 reach / L_y of
// the particles. Then the events of those particles are predicted anew, or all of them
// after a rescaling.
template <int D> void EventEngine<D>::periodic_pass() {
    for (std::uint32_t i = 0; i < size(); ++i) advance(i);
    const bool rescaled = now_ >= next_rescale_;
    if (rescaled) {
        rescale_temperature();
        next_rescale_ = next_pass_time(now_, params_.thermostat_interval, "thermostat");
    }
    band_.clear();
    if (now_ >= next_shear_relist_) {
        const double reach = *std::max_element(reach_.begin(), reach_.end());
        const double edge = box_.hi(1) - reach - 1e-9 * box_.length(1);
        for (std::uint32_t i = 0; i < size(); ++i)
            if (std::abs(ev_[i].centre[1]) >= edge) band_.push_back(i);
        for (std::uint32_t i : band_) rebuild_list(i);
        next_shear_relist_ = next_pass_time(now_, slide_ / shear_velocity_, "shear");
    }
    if (rescaled)
        queue_.build_from(size(), [&](std::uint32_t i) { return predict(i); });
    else
        for (std::uint32_t i : band_) queue_.update(i, predict(i));
}

// Scales the velocities relative to the flow and to the centre of mass (along the axes
// whose momentum the dynamics keeps, as observe/thermo.hpp counts the degrees of
// freedom) so that their temperature is the thermostat's. Needs every flight at now_.
template <int D> void EventEngine<D>::rescale_temperature() {
    bool obstacle = false;
    Vec<D> momentum{};
    double mass = 0.0;
    std::size_t mobile = 0;
    for (std::uint32_t i = 0; i < size(); ++i) {
        const double inv_m = inv_mass_[f_[i].species];
        if (inv_m == 0.0) {
            obstacle = true;
            continue;
        }
        Vec<D> c = f_[i].v;
        c[0] -= flow_velocity(i);
        momentum += c * (1.0 / inv_m);
        mass += 1.0 / inv_m;
        ++mobile;
    }
    int conserved = 0;
    Vec<D> mean{};
    for (int a = 0; a < D; ++a)
        if (!obstacle && box_.periodic(a) && mass > 0.0) {
            ++conserved;
            mean[a] = momentum[a] / mass;
        }
    double thermal = 0.0;
    for (std::uint32_t i = 0; i < size(); ++i) {
        const double inv_m = inv_mass_[f_[i].species];
        if (inv_m == 0.0) continue;
        Vec<D> c = f_[i].v;
        c[0] -= flow_velocity(i);
        thermal += 0.5 * norm2(c - mean) / inv_m;
    }
    const double freedom = D * static_cast<double>(mobile) - conserved;
    if (!(thermal > 0.0) || !(freedom > 0.0)) return; // nothing moves: nothing to scale
    const double scale = std::sqrt(params_.thermostat_temperature * freedom / (2.0 * thermal));
    for (std::uint32_t i = 0; i < size(); ++i) {
        if (inv_mass_[f_[i].species] == 0.0) continue;
        const double flow = flow_velocity(i);
        Vec<D> c = f_[i].v;
        c[0] -= flow;
        f_[i].v = mean + (c - mean) * scale;
        f_[i].v[0] += flow;
    }
    thermostat_.energy_removed += thermal * (1.0 - scale * scale);
    ++thermostat_.rescales;
    resum_kinetic_energy();
    if (moments_on_) {
        if (box_.sheared())
            moments_.advance_sheared(now_, box_.shear_rate());
        else
            moments_.advance(now_);
        recount_kinetic_moments();
    }
}

template <int D> void EventEngine<D>::track_flux_moments() {
    if (moments_on_) return;
    if (falling_ || params_.andersen_rate > 0.0 || params_.driving_rate > 0.0)
        throw InputError("[transport] needs force-free, deterministic flights: not with "
                         "event.gravity, thermostat = \"andersen\" or event.driving");
    moments_ = FluxMoments<D>{};
    moments_.t = now_;
    recount_kinetic_moments();
    moments_on_ = true;
}

// Σ m v v afresh (peculiar velocities under shear), with every flight at now_ or not.
template <int D> void EventEngine<D>::recount_kinetic_moments() {
    moments_.kinetic = SymTensor{};
    moments_.heat = Vec<D>{};
    for (std::uint32_t i = 0; i < size(); ++i) {
        Vec<D> v = f_[i].v;
        if (box_.sheared() && inv_mass_[f_[i].species] > 0.0) v[0] -= flow_velocity(i);
        moments_.count(mass_of(f_[i].species), v, 1.0);
    }
}

template <int D> FluxMoments<D> EventEngine<D>::flux_moments() const {
    FluxMoments<D> m = moments_;
    if (box_.sheared())
        m.advance_sheared(now_, box_.shear_rate());
    else
        m.advance(now_);
    return m;
}

// The running kinetic energy carries a rounding error of order 1e-16 of the energy it
// started from; in a gas that cools by many decades that error would dominate (and can
// turn negative), so the sum is redone from the velocities each time it halves.
template <int D> void EventEngine<D>::resum_kinetic_energy() {
    double k = 0.0;
    for (std::size_t i = 0; i < size(); ++i)
        if (inv_mass_[f_[i].species] > 0.0) k += 0.5 * norm2(f_[i].v) / inv_mass_[f_[i].species];
    if (falling_)
        for (std::size_t i = 0; i < size(); ++i) k += height_energy(f_[i].species, f_[i].x);
    kinetic_ = kinetic_exact_ = k;
}

template <int D> double EventEngine<D>::falling_kinetic_energy() const {
    double k = 0.0;
    for (std::size_t i = 0; i < size(); ++i)
        if (inv_mass_[f_[i].species] > 0.0) k += 0.5 * norm2(v_now(i)) / inv_mass_[f_[i].species];
    return k;
}

template <int D> double EventEngine<D>::potential_energy() const {
    if (!falling_) return 0.0;
    double u = 0.0;
    for (std::size_t i = 0; i < size(); ++i) u += height_energy(f_[i].species, x_now(i));
    return u;
}

// Most of a particle's neighbours stay neighbours when it rebuilds its list, and their
// rows are cache misses: only the rows of partners that leave or join are touched
// (the rebuilt row and a joining partner's row end as a full rebuild would leave them;
// a staying partner's row keeps its order, which matters only for exactly tied events).
template <int D> void EventEngine<D>::wrap_flight(std::uint32_t i) {
    if (box_.sheared()) [[unlikely]] {
        // (at f_[i].t = now_, whose offset the box holds) the image k boxes above moves
        // k rate L_y faster: the same motion, told in the box's frame
        const Vec<D> shift = box_.wrap(f_[i].x);
        for (int a = 0; a < D; ++a) image_[i][a] += static_cast<std::int32_t>(shift[a]);
        f_[i].v[0] -= shift[1] * shear_velocity_;
        return;
    }
    wrap_counting<D>(box_, f_[i].x, image_[i]);
}

template <int D> void EventEngine<D>::rebuild_list(std::uint32_t i) {
    advance(i);
    wrap_flight(i);
    CellList<D>& grid = grids_[class_of_[f_[i].species]];
    grid.remove(i);
    ev_[i].centre = f_[i].x;
    grid.insert(i, ev_[i].centre);
    // the cells' chains first, every candidate's centre asked for on the way, then the
    // distances (as in predict_with: no mispredicted branch discards the loads)
    candidates_.clear();
    for_each_candidate(i, [&](std::uint32_t j) {
        __builtin_prefetch(&ev_[j].centre);
        candidates_.push_back(j);
    });
    // Branch-free (about one candidate in six is a partner, at random): each candidate
    // is stored and the cursor advances on a partner.
    fresh_list_.resize(candidates_.size());
    std::size_t partners = 0;
    for (std::uint32_t j : candidates_) {
        fresh_list_[partners] = j;
        partners += j != i && list_partners(i, j);
    }
    fresh_list_.resize(partners);
    // (every entry compared, no early exit: which rows hold whom is as random)
    const auto holds = [](const std::uint32_t* first, std::size_t n, std::uint32_t j) {
        bool found = false;
        for (std::size_t k = 0; k < n; ++k) found |= first[k] == j;
        return found;
    };
    const std::uint32_t* row = &nbr_[static_cast<std::size_t>(i) * stride_];
    old_list_.assign(row, row + f_[i].n_nbr);
    for (std::uint32_t j : old_list_)
        if (!holds(fresh_list_.data(), fresh_list_.size(), j)) remove_neighbor(j, i);
    while (fresh_list_.size() > stride_) grow_lists();
    for (std::uint32_t j : fresh_list_) {
        if (holds(old_list_.data(), old_list_.size(), j)) continue;
        if (f_[j].n_nbr == stride_) grow_lists();
        nbr_[static_cast<std::size_t>(j) * stride_ + f_[j].n_nbr++] = i;
    }
    std::copy(fresh_list_.begin(), fresh_list_.end(), &nbr_[static_cast<std::size_t>(i) * stride_]);
    f_[i].n_nbr = static_cast<std::uint16_t>(fresh_list_.size());
    ++counters_.list_rebuilds;
}

// Why events pile up at one instant: growing particles that have jammed (they touch in
// a cage, or a wall, and cannot grow further), or inelastic collapse; with elastic
// collisions and no growth, particles wedged against each other and the walls.
template <int D> std::string EventEngine<D>::stall_cause() const {
    if (growth_.growing)
        return fmt::format("the growing particles have jammed at packing fraction {:.6g} and "
                           "cannot grow further: ask for less (event.growth_packing_fraction, "
                           "event.growth_max_pressure) or grow more slowly",
                           packing_fraction());
    if (falling_ && params_.tc == 0.0)
        return "a particle has come to rest on a wall or another particle under gravity, or "
               "bounces ever faster on it (inelastic collapse): set event.tc > 0 (TC model) "
               "or start the particles moving";
    if (params_.restitution < 1.0 || params_.wall_restitution < 1.0)
        return "this is inelastic collapse: set event.tc > 0 (TC model) or raise the "
               "restitution";
    return "the particles are wedged against each other and the walls (all collisions are "
           "elastic): start them further apart";
}

template <int D> StopReason EventEngine<D>::run(const StopLimits& limits) {
    // a signal is looked for every 4096 events: microseconds apart, and no cost per event
    for (std::uint32_t since_check = 0;; ++since_check) {
        if ((since_check & 4095u) == 4095u && interrupt_requested()) return StopReason::interrupted;
        const std::uint32_t i = queue_.top();
        const double te = queue_.top_time();
        if (next_growth_step_ < te && next_growth_step_ <= limits.time) {
            set_now(next_growth_step_);
            growth_step(true);
            if (!growth_.growing) return StopReason::grown;
            continue;
        }
        if (const double pass = std::min(next_shear_relist_, next_rescale_);
            pass < te && pass <= limits.time) [[unlikely]] {
            set_now(pass);
            periodic_pass();
            continue;
        }
        if (const double kick = std::min(next_andersen_, next_kick_);
            kick < te && kick <= limits.time) [[unlikely]] {
            set_now(kick);
            stochastic_event();
            continue;
        }
        if (te == never) return StopReason::no_events; // nothing moves: time is meaningless
        if (te > limits.time) {
            if (std::isfinite(limits.time)) set_now(std::max(now_, limits.time));
            return StopReason::time;
        }
        // Inelastic collapse shows as unbounded events at one instant.
        if (te - now_ <= 1e-13 * (1.0 + std::abs(te))) {
            // Growing particles have no collapse to tell apart from a jam, and each of
            // their events may rescale and re-predict everything (the thermostat): a
            // tenth of the allowance ends a jam in a tenth of the time (fuzz_run found
            // 68 jammed disks taking 15 s under the sanitizers to reach the full one).
            const std::uint64_t allowance = growth_.growing ? 20 : 200;
            if (++stalled_events_ > 1000 + allowance * static_cast<std::uint64_t>(size())) {
                std::ostringstream m;
                m << "event engine: time stopped advancing at t = " << te << " (" << stalled_events_
                  << " events at the same instant, last at " << tag_name(p_.tag[i]) << "); "
                  << stall_cause();
                throw RunError(m.str());
            }
        } else {
            stalled_events_ = 0;
        }
        set_now(te);
        const std::int32_t partner = ev_[i].partner;
        prefetch_list(i);
        if (partner >= 0) {
            const auto j = static_cast<std::uint32_t>(partner);
            prefetch_list(j);
            if (f_[j].count != ev_[i].count) {
                ++counters_.stale_events;
                queue_.update(i, predict(i));
                continue;
            }
            process_pair(i, j);
            if (params_.check_overlaps) {
                check_particle_overlap(i, 1e-9);
                check_particle_overlap(j, 1e-9);
            }
            queue_.update(i, predict(i));
            queue_.update(j, predict(j));
            if (growth_.growing && growth_due()) {
                growth_step(false);
                if (!growth_.growing) return StopReason::grown;
            }
            if (counters_.pair_collisions >= limits.pair_collisions) return StopReason::collisions;
            if (kinetic_ <= limits.min_kinetic_energy) return StopReason::energy;
            continue;
        }
        if (partner == shell_event)
            rebuild_list(i);
        else
            process_wall(i, partner);
        queue_.update(i, predict(i));
        if (growth_.growing && partner != shell_event && growth_due()) {
            growth_step(false);
            if (!growth_.growing) return StopReason::grown;
        }
        if (partner != shell_event && kinetic_ <= limits.min_kinetic_energy)
            return StopReason::energy;
    }
}

template <int D> Vec<D> EventEngine<D>::position_now(std::size_t i) const {
    Vec<D> r = x_now(i);
    box_.wrap(r);
    return r;
}

template <int D> std::array<std::int32_t, D> EventEngine<D>::image_now(std::size_t i) const {
    Vec<D> r = x_now(i);
    std::array<std::int32_t, D> image = image_shift<D>(box_.wrap(r));
    for (int a = 0; a < D; ++a) image[a] += image_[i][a];
    return image;
}

template <int D>
void EventEngine<D>::take_flights(const std::vector<double>& t,
                                  const std::vector<std::uint32_t>& counts,
                                  const std::vector<std::uint16_t>& row_lengths) {
    const std::size_t n = p_.size();
    f_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
        f_[i] = {p_.position[i], t[i], p_.velocity[i], counts[i], p_.species[i], row_lengths[i]};
    // from here on f_ holds them; lazy_particles() copies them back when asked
    std::vector<Vec<D>>().swap(p_.position);
    std::vector<Vec<D>>().swap(p_.velocity);
}

template <int D> const ParticleStore<D>& EventEngine<D>::lazy_particles() const {
    p_.position.resize(size());
    p_.velocity.resize(size());
    for (std::size_t i = 0; i < size(); ++i) {
        p_.position[i] = f_[i].x;
        p_.velocity[i] = v_now(i);
        if (box_.sheared() && inv_mass_[f_[i].species] > 0.0) p_.velocity[i][0] -= flow_velocity(i);
    }
    return p_;
}

template <int D> std::vector<Vec<D>> EventEngine<D>::unwrapped_now() const {
    std::vector<Vec<D>> u(size());
    for (std::size_t i = 0; i < size(); ++i) u[i] = unwrapped_now(i);
    return u;
}

template <int D>
ParticleStore<D> EventEngine<D>::snapshot(std::vector<std::array<std::int32_t, D>>* images) const {
    ParticleStore<D> s;
    s.tag = p_.tag;
    s.species = p_.species;
    s.species_table = p_.species_table;
    s.position.resize(size());
    s.velocity.resize(size());
    for (std::size_t i = 0; i < size(); ++i) {
        s.position[i] = position_now(i);
        s.velocity[i] = v_now(i);
        if (box_.sheared() && inv_mass_[f_[i].species] > 0.0) s.velocity[i][0] -= flow_velocity(i);
    }
    if (images) {
        images->resize(size());
        for (std::size_t i = 0; i < size(); ++i) (*images)[i] = image_now(i);
    }
    for (std::size_t k = 0; k < radius_.size(); ++k) s.species_table[k].radius = radius_now(k);
    return s;
}

template <int D>
void EventEngine<D>::check_particle_overlap(std::uint32_t i, double rel_tol) const {
    const Vec<D> xi = x_now(i);
    const std::uint32_t* list = &nbr_[static_cast<std::size_t>(i) * stride_];
    for (std::uint16_t k = 0; k < f_[i].n_nbr; ++k) {
        const std::uint32_t j = list[k];
        const Vec<D> xj = x_now(j);
        double unused = 0.0;
        const double d = norm(pair_separation(xi - xj, unused));
        const double s = contact_now(i, j);
        if (d < s * (1.0 - rel_tol)) {
            std::ostringstream m;
            m << "overlap at t = " << now_ << ": " << tag_name(p_.tag[i]) << " and "
              << tag_name(p_.tag[j]) << " are " << d << " apart, contact distance " << s;
            throw RunError(m.str());
        }
    }
}

template <int D> void EventEngine<D>::check_no_overlap(double rel_tol) const {
    // Fresh cell lists on current positions, independent of the neighbour lists: one per
    // size class with cells of the class's diameter, scanned as far as each pair of
    // classes can touch (so small particles do not scan cells sized by the largest).
    // (positions only, not a whole snapshot: at the start this is the run's peak memory)
    std::vector<Vec<D>> pos(size());
    for (std::size_t i = 0; i < size(); ++i) pos[i] = position_now(i);
    const std::size_t classes = class_radius_.size();
    std::vector<double> largest(classes, 0.0);
    for (std::size_t k = 0; k < radius_.size(); ++k)
        largest[class_of_[k]] = std::max(largest[class_of_[k]], radius_now(k));
    std::vector<CellList<D>> cells;
    for (std::size_t k = 0; k < classes; ++k) {
        cells.emplace_back(box_, 2.0 * largest[k]);
        cells.back().clear(pos.size());
    }
    for (std::uint32_t i = pos.size(); i-- > 0;) cells[class_of_[f_[i].species]].insert(i, pos[i]);
    for (std::uint32_t i = 0; i < pos.size(); ++i) {
        const std::size_t c = class_of_[f_[i].species];
        for (std::size_t k = 0; k < classes; ++k) {
            const int reach = cells[k].cells_to_reach(largest[c] + largest[k]);
            cells[k].for_each_within(pos[i], reach, [&](std::uint32_t j) {
                if (j <= i) return;
                const double d = norm(box_.minimum_image(pos[i] - pos[j]));
                const double contact = contact_now(i, j);
                if (d < contact * (1.0 - rel_tol)) {
                    std::ostringstream m;
                    // the lower tag first, whatever the storage order
                    m << tag_name(std::min(p_.tag[i], p_.tag[j])) << " and "
                      << tag_name(std::max(p_.tag[i], p_.tag[j])) << " overlap: centres " << d
                      << " apart, contact distance " << contact << " (overlap " << contact - d
                      << ")";
                    if (now_ == 0.0 && counters_.pair_collisions == 0) throw InputError(m.str());
                    throw RunError("at t = " + std::to_string(now_) + ": " + m.str());
                }
            });
        }
    }
}

template <int D> std::size_t EventEngine<D>::memory_bytes() const {
    auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    // (the lazy copies of positions and velocities only while an observer holds them)
    return bytes(f_) + bytes(p_.position) + bytes(p_.velocity) + bytes(p_.tag) + bytes(p_.species) +
           bytes(ev_) + bytes(image_) + bytes(last_collision_) + bytes(nbr_) + grids_memory() +
           queue_.memory_bytes();
}

namespace {
constexpr std::uint64_t checkpoint_magic = 0x4b43455344455045ull; // "EPEDSECK" in memory order
// 2: one cell list per size class; 3: growth state; 4: the collision virial's
// off-diagonal components; 5: image counts and the flux moments (version 4 is read with
// none crossed and no moments); 6: Lees-Edwards shear and the rescaling thermostat;
// 7: gravity, the Andersen thermostat and the white-noise driving; 8: the moving wall's work
constexpr std::uint32_t checkpoint_version = 8;
constexpr std::uint32_t oldest_checkpoint_version = 4;
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
    put(out, params_.growth_rate);
    put(out, radius_rate_);
    put(out, radius_time_);
    put(out, next_growth_step_);
    put(out, growth_kinetic_);
    put(out, window_time_);
    put(out, window_collisions_);
    put(out, window_virial_);
    // field by field: the struct's padding bytes are not part of the state
    put<std::uint8_t>(out, growth_.growing);
    put(out, growth_.ended);
    put(out, growth_.last_pressure);
    put(out, growth_.steps);
    // the layout of the versions with one array per field (the file does not change)
    const std::size_t n = size();
    std::vector<Vec<D>> positions(n), velocities(n), centres(n);
    std::vector<double> flight_times(n);
    std::vector<std::uint32_t> collision_counts(n);
    std::vector<std::uint16_t> row_lengths(n);
    for (std::size_t i = 0; i < n; ++i) {
        positions[i] = f_[i].x;
        velocities[i] = f_[i].v;
        flight_times[i] = f_[i].t;
        collision_counts[i] = f_[i].count;
        row_lengths[i] = f_[i].n_nbr;
        centres[i] = ev_[i].centre;
    }
    put(out, positions);
    put(out, velocities);
    put(out, p_.tag);
    put(out, p_.species);
    put(out, flight_times);
    put(out, centres);
    put(out, collision_counts);
    // the layout of versions with three arrays (the file does not change with the records)
    std::vector<double> times(n);
    std::vector<std::int32_t> partners(n);
    std::vector<std::uint32_t> counts(n);
    for (std::uint32_t i = 0; i < n; ++i) {
        times[i] = queue_.time(i);
        partners[i] = ev_[i].partner;
        counts[i] = ev_[i].count;
    }
    put(out, times);
    put(out, partners);
    put(out, counts);
    put(out, last_collision_);
    put(out, stride_);
    put(out, row_lengths);
    put(out, nbr_);
    for (const auto& grid : grids_) grid.save([&](const auto& v) { put(out, v); });
    put(out, image_);
    put<std::uint8_t>(out, moments_on_);
    put(out, moments_);
    put(out, box_.shear_rate());
    put(out, next_shear_relist_);
    put(out, next_rescale_);
    put(out, thermostat_.rescales);
    put(out, thermostat_.energy_removed);
    for (int a = 0; a < D; ++a) put(out, gravity_[a]);
    put(out, next_andersen_);
    put(out, next_kick_);
    put(out, driving_.andersen_events);
    put(out, driving_.andersen_energy);
    put(out, driving_.kicks);
    put(out, driving_.injected_energy);
    put(out, wall_work_);
    put(out, wall_checks_);
}

template <int D> EventEngine<D> EventEngine<D>::load(std::istream& in, const EventParams& params) {
    using binary::get;
    const std::uint32_t version = binary::get_header(in, checkpoint_magic, checkpoint_version, D,
                                                     "event", oldest_checkpoint_version);
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
    get(in, e.kinetic_);
    get(in, e.kinetic_exact_);
    get(in, e.stalled_events_);
    get(in, e.counters_);
    // lengths that size the cell grids and neighbour shells: a crafted value must not
    // reach an int conversion (fuzzing found a skin of 3.6e76)
    double shortest = std::numeric_limits<double>::infinity();
    for (int a = 0; a < D; ++a) shortest = std::min(shortest, e.box_.length(a));
    if (!(std::isfinite(e.skin_) && e.skin_ > 0.0 && e.skin_ < shortest))
        throw InputError("checkpoint: corrupt neighbour-list skin");
    for (const auto& s : e.p_.species_table)
        if (!(s.radius < shortest)) throw InputError("checkpoint: corrupt species radius");
    if (!(std::isfinite(e.now_) && e.now_ >= 0.0)) throw InputError("checkpoint: corrupt time");
    get(in, e.params_.growth_rate); // the checkpoint's, whatever the config now says
    if (!(e.params_.growth_rate >= 0.0 && std::isfinite(e.params_.growth_rate)))
        throw InputError("checkpoint: corrupt growth rate");
    get(in, e.radius_rate_);
    get(in, e.radius_time_);
    get(in, e.next_growth_step_);
    get(in, e.growth_kinetic_);
    get(in, e.window_time_);
    get(in, e.window_collisions_);
    get(in, e.window_virial_);
    std::uint8_t growing = 0;
    get(in, growing);
    e.growth_.growing = growing != 0;
    get(in, e.growth_.ended);
    if (growing > 1 || static_cast<std::uint8_t>(e.growth_.ended) > 2)
        throw InputError("checkpoint: corrupt growth state");
    get(in, e.growth_.last_pressure);
    get(in, e.growth_.steps);
    if (e.radius_rate_.size() != e.radius_.size())
        throw InputError("checkpoint: inconsistent array sizes (corrupt file)");
    e.shell_ = e.growth_.growing ? e.skin_ / 3.0 : 0.5 * e.skin_;
    get(in, e.p_.position);
    get(in, e.p_.velocity);
    get(in, e.p_.tag);
    get(in, e.p_.species);
    std::vector<double> flight_times;
    std::vector<std::uint32_t> collision_counts;
    std::vector<std::uint16_t> row_lengths;
    get(in, flight_times);
    std::vector<Vec<D>> centres;
    get(in, centres);
    get(in, collision_counts);
    std::vector<double> times;
    std::vector<std::int32_t> partners;
    std::vector<std::uint32_t> counts;
    get(in, times);
    get(in, partners);
    get(in, counts);
    get(in, e.last_collision_);
    get(in, e.stride_);
    get(in, row_lengths);
    get(in, e.nbr_);
    const std::size_t n = e.p_.position.size();
    if (n == 0 || e.p_.velocity.size() != n || e.p_.tag.size() != n || e.p_.species.size() != n ||
        flight_times.size() != n || centres.size() != n || collision_counts.size() != n ||
        times.size() != n || partners.size() != n || counts.size() != n ||
        row_lengths.size() != n || e.nbr_.size() != n * e.stride_)
        throw InputError("checkpoint: inconsistent array sizes (corrupt file)");
    if (params.tc > 0.0 && e.last_collision_.size() != n) e.last_collision_.assign(n, -never);
    for (auto s : e.p_.species)
        if (s >= e.p_.species_table.size()) throw InputError("checkpoint: corrupt species index");
    check_restored_particles(e.p_, e.box_, false); // before anything is built from them
    for (std::size_t i = 0; i < n; ++i) {
        if (row_lengths[i] > e.stride_) throw InputError("checkpoint: corrupt neighbour list");
        for (std::uint16_t k = 0; k < row_lengths[i]; ++k)
            if (e.nbr_[i * e.stride_ + k] >= n)
                throw InputError("checkpoint: corrupt neighbour list");
        // a particle, no event, the shell or one of the 2 D walls (a code below them would
        // index a wall that does not exist)
        if (partners[i] < wall_event_base - (2 * D - 1) ||
            partners[i] >= static_cast<std::int32_t>(n))
            throw InputError("checkpoint: corrupt event");
    }
    e.take_flights(flight_times, collision_counts, row_lengths);
    e.make_grids();
    for (auto& grid : e.grids_) grid.load([&](auto& v) { get(in, v); });
    if (version >= 5) {
        get(in, e.image_);
        if (e.image_.size() != n) throw InputError("checkpoint: corrupt image counts");
        std::uint8_t on = 0;
        get(in, on);
        if (on > 1) throw InputError("checkpoint: corrupt flux moments");
        e.moments_on_ = on != 0;
        get(in, e.moments_);
    } else {
        e.image_.assign(n, {});
    }
    if (version >= 6) {
        double rate = 0.0;
        get(in, rate);
        get(in, e.next_shear_relist_);
        get(in, e.next_rescale_);
        get(in, e.thermostat_.rescales);
        get(in, e.thermostat_.energy_removed);
        // passes before now_ would repeat at one instant (NaN never comes)
        if (!(e.next_shear_relist_ >= e.now_) || !(e.next_rescale_ >= e.now_))
            throw InputError("checkpoint: corrupt pass times");
        if (!(std::isfinite(rate) && rate >= 0.0) ||
            (rate > 0.0) == (e.next_shear_relist_ == never))
            throw InputError("checkpoint: corrupt shear rate");
        if (rate > 0.0) {
            if (e.growth_.growing) throw InputError("checkpoint: corrupt shear rate");
            e.box_.set_shear_rate(rate); // (refuses walls across x or y)
            e.box_.shear_to_time(e.now_);
            e.shear_velocity_ = rate * e.box_.length(1);
            e.pair_times_ = nullptr;
            e.choose_slide();
        }
    }
    // the config's thermostat from now on (the checkpoint's schedule if it had one)
    if (!(params.thermostat_temperature > 0.0))
        e.next_rescale_ = never;
    else if (e.next_rescale_ == never)
        e.next_rescale_ = next_pass_time(e.now_, params.thermostat_interval, "thermostat");
    Vec<D> gravity{};
    if (version >= 7) {
        for (int a = 0; a < D; ++a) get(in, gravity[a]);
        get(in, e.next_andersen_);
        get(in, e.next_kick_);
        get(in, e.driving_.andersen_events);
        get(in, e.driving_.andersen_energy);
        get(in, e.driving_.kicks);
        get(in, e.driving_.injected_energy);
        if (!(e.next_andersen_ >= e.now_) || !(e.next_kick_ >= e.now_))
            throw InputError("checkpoint: corrupt driving times");
    }
    for (int a = 0; a < D; ++a)
        if (!(gravity[a] == params.gravity[a]))
            throw InputError("event.gravity differs from the checkpoint's (the energy it keeps "
                             "counts the potential energy of its gravity): give the same");
    e.start_gravity();
    e.start_moving_wall();
    if (version >= 8) {
        get(in, e.wall_work_);
        get(in, e.wall_checks_);
    }
    e.ev_.resize(n);
    for (std::size_t i = 0; i < n; ++i) e.ev_[i] = {centres[i], partners[i], counts[i]};
    e.start_driving();
    e.queue_.build(times);
    return e;
}

template class EventEngine<2>;
template class EventEngine<3>;

} // namespace pedesis
