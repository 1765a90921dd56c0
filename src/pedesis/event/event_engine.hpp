#pragma once
// Exact event-driven dynamics of hard disks (D = 2) and spheres (D = 3).
//
// Design (after Smallenburg, Eur. Phys. J. E 45, 22 (2022), rewritten here):
// - one pending event per particle: its earliest pair collision, wall collision or
//   neighbour-shell exit, in a bucket calendar (event_queue.hpp);
// - positions are advanced lazily: particle i stores r_i at its own time t_i;
// - each particle keeps a neighbour list of everyone whose list centre lies within
//   sigma_ij + skin of its own; a particle rebuilds its list (alone) when it has moved
//   skin/2 from its centre, which keeps the lists exact without global rebuilds;
// - a collision counter per particle invalidates events whose partner has collided
//   since the prediction (no event is ever removed from the calendar);
// - optional Lees-Edwards shear (the box's shear rate, core/box.hpp): velocities are kept
//   in the laboratory frame, so flights stay straight; a particle wrapped across the y
//   faces by k boxes loses k rate L_y of its x velocity, and a pair's nearest image k
//   boxes above moves k rate L_y faster (pair_separation). The slide moves the images
//   across the y faces against each other: pairs across them are listed as if slide_
//   closer along x, and the lists near the faces are rebuilt each time the offset has
//   moved another slide_ (periodic_pass);
// - optional Lubachevsky-Stillinger growth: every radius grows linearly in time (ratios
//   kept), with the exact collision time and rule for growing spheres; the lists, the
//   radii and a velocity rescaling (which holds the kinetic energy) are renewed at
//   "growth steps" (growth_step()), a whole-system pass every time the contact distances
//   have grown by a third of the skin, the kinetic energy has drifted 2%, or N
//   collisions have passed.
#include "pedesis/core/box.hpp"
#include "pedesis/core/collision_counters.hpp"
#include "pedesis/core/flux_moments.hpp"
#include "pedesis/core/image_count.hpp"
#include "pedesis/core/particles.hpp"
#include "pedesis/core/rng.hpp"
#include "pedesis/event/event_queue.hpp"
#include "pedesis/event/flight.hpp"
#include "pedesis/event/moving_wall.hpp"
#include "pedesis/event/pair_times.hpp"
#include "pedesis/spatial/cell_list.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <iosfwd>
#include <limits>
#include <vector>

namespace pedesis {

struct EventParams {
    double restitution = 1.0;      // particle-particle, xi in [0, 1]
    double wall_restitution = 1.0; // particle-wall
    double tc = 0.0;               // TC model: collisions within tc of a particle's last
                                   // collision are elastic (0 disables)
    double skin = -1.0;            // neighbour-list skin; < 0 chooses one from the density
    bool check_overlaps = false;   // debug: verify no overlap after every collision
    // Lubachevsky-Stillinger growth (0: none): the largest species' diameter grows by
    // growth_rate per unit time, all others in proportion; it stops at the packing fraction
    // growth_packing_fraction (0: no target) or when the reduced pressure PV/(NkT) over the
    // last N collisions exceeds growth_max_pressure.
    double growth_rate = 0.0;
    double growth_packing_fraction = 0.0;
    double growth_max_pressure = 1e3;
    // Velocity rescaling ([event] thermostat = "rescale"): every thermostat_interval the
    // velocities relative to the flow (peculiar velocities under shear) are scaled so that
    // the temperature (the log's: the centre of mass's motion left out) is
    // thermostat_temperature. 0: no thermostat.
    double thermostat_temperature = 0.0;
    double thermostat_interval = 0.0;
    // Uniform gravity, an acceleration (its first D components; zero: none), along walled
    // axes only: flights are parabolas (event/falling_times.hpp).
    std::array<double, 3> gravity{};
    // Andersen thermostat ([event] thermostat = "andersen"): at the times of a Poisson
    // process of rate andersen_rate per particle (N times that for the system) one particle,
    // chosen at random, gets a new velocity from the Maxwell-Boltzmann distribution at
    // andersen_temperature. 0: none.
    double andersen_rate = 0.0;
    double andersen_temperature = 0.0;
    // White-noise driving ([event] driving = "white_noise", van Noije & Ernst): at rate
    // driving_rate / 2 per particle a random pair of particles receives equal and opposite
    // momentum kicks dp, each component normal with variance driving_strength m_i m_j, so
    // that each particle is kicked at driving_rate and, of equal masses, its velocity
    // changes by driving_strength in variance per component; the momentum is kept. 0: none.
    double driving_rate = 0.0;
    double driving_strength = 0.0;
    std::uint64_t seed = 1; // of the thermostat's and the driving's random numbers
    // One wall that moves along its normal ([event.moving_wall]; event/moving_wall.hpp):
    // the face of axis moving_wall_axis (-1: none), the upper one if moving_wall_upper.
    // Its collisions have restitution wall_restitution in the wall's frame.
    int moving_wall_axis = -1;
    bool moving_wall_upper = false;
    WallMotion moving_wall{};
};

// What the Andersen thermostat and the white-noise driving have done.
struct DrivingStatus {
    std::uint64_t andersen_events = 0;
    double andersen_energy = 0.0; // kinetic energy the redraws added (negative: took)
    std::uint64_t kicks = 0;      // pair kicks
    double injected_energy = 0.0; // kinetic energy the kicks added
};

// What the rescaling thermostat has done, for logs and summaries.
struct ThermostatStatus {
    std::uint64_t rescales = 0;
    double energy_removed = 0.0; // sum of the kinetic energy each rescaling took away
};

enum class GrowthEnd : std::uint8_t { none, packing_fraction, pressure };

// State of Lubachevsky-Stillinger growth, for logs and summaries.
struct GrowthStatus {
    bool growing = false;
    GrowthEnd ended = GrowthEnd::none;
    double last_pressure = 0.0; // reduced pressure Z over the last window (0: none yet)
    std::uint64_t steps = 0;    // growth steps (whole-system list rebuilds) so far
};

// interrupted: a signal arrived (core/interrupt.hpp); the state is whole and can go on.
enum class StopReason { time, collisions, energy, no_events, grown, interrupted };

struct StopLimits {
    double time = std::numeric_limits<double>::infinity();
    std::uint64_t pair_collisions = std::numeric_limits<std::uint64_t>::max();
    double min_kinetic_energy = -1.0;
};

template <int D> class EventEngine {
  public:
    EventEngine(ParticleStore<D> particles, const Box<D>& box, const EventParams& params);

    StopReason run(const StopLimits& limits);

    double time() const { return now_; }
    const Box<D>& box() const { return box_; }
    const EventParams& params() const { return params_; }
    // From the next collision on (a change while it runs: pedesis run --view, --steering).
    // Collision times do not depend on it, so the predicted events stay valid. InputError
    // outside [0, 1].
    void set_restitution(double xi);
    void set_wall_restitution(double xi);
    const EventCounters<D>& counters() const { return counters_; }
    // From now on, keeps the running integrals of the Helfand moments (core/flux_moments.hpp)
    // for [transport]: a few multiplications per collision. Idempotent.
    void track_flux_moments();
    bool tracks_flux_moments() const { return moments_on_; }
    // Those integrals carried to the current time (G's collisional part is counters().virial).
    // Under shear they are always kept, of the peculiar velocities, without the heat sums.
    FluxMoments<D> flux_moments() const;
    // Under shear, of the peculiar velocities (v - rate y e_x): the heat, not the flow.
    // Under gravity, summed afresh (kinetic and potential energy trade in flight).
    double kinetic_energy() const {
        if (falling_) [[unlikely]]
            return falling_kinetic_energy();
        return box_.sheared() ? peculiar_kinetic_energy() : kinetic_;
    }
    // In gravity: -sum m g . (r - r0), r0 the corner of the box that gravity points to
    // (along each axis, the wall it points to), so that it is the weight times the height
    // of each centre above the floor(s) and never negative. 0 without gravity.
    double potential_energy() const;
    bool falling() const { return falling_; }
    // The moving wall: whether there is one, its face's coordinate now, the work it has
    // done on the particles (the energy it injected, less nothing: what the restitution
    // takes is in counters().energy_lost), and the times a prediction's climb stopped
    // short of a contact (event/moving_wall.hpp's checks).
    bool wall_moves() const { return moving_; }
    double moving_wall_position() const;
    double wall_work() const { return wall_work_; }
    std::uint64_t wall_checks() const { return wall_checks_; }
    const DrivingStatus& driving() const { return driving_; }
    std::size_t size() const { return f_.size(); }
    double skin() const { return skin_; }
    // Volume fraction of the particles at the current time (radii grow with growth).
    double packing_fraction() const;
    const GrowthStatus& growth() const { return growth_; }
    const ThermostatStatus& thermostat() const { return thermostat_; }

    // Position of particle i (storage index) at the current time, wrapped into the box.
    Vec<D> position_now(std::size_t i) const;
    // The periodic boxes particle i has crossed by the current time (the soft engine's
    // meaning: its unwrapped position is position_now(i) + image * L).
    std::array<std::int32_t, D> image_now(std::size_t i) const;
    // Every particle's unwrapped position now, in storage order; one particle's.
    std::vector<Vec<D>> unwrapped_now() const;
    Vec<D> unwrapped_now(std::size_t i) const { return unwrapped<D>(box_, x_now(i), image_[i]); }
    // Particle i's current velocity (in the laboratory frame).
    Vec<D> velocity(std::size_t i) const { return v_now(i); }
    // All particles at the current time, wrapped, in storage order; with `images`, their
    // image counts too. Under shear the velocities are the peculiar ones (the soft
    // engine's frames give the same).
    ParticleStore<D> snapshot(std::vector<std::array<std::int32_t, D>>* images = nullptr) const;
    // Particle data whose velocities (peculiar under shear), tags and species are current
    // (positions are not: each is at the particle's own time): copies the engine fills at
    // each call and keeps (48 bytes per particle in 3D).
    const ParticleStore<D>& lazy_particles() const;

    // Throws RunError naming the pair if any two particles overlap by more than a
    // relative tolerance (debug and tests).
    void check_no_overlap(double rel_tol = 1e-9) const;

    std::size_t memory_bytes() const;

    // Half the shortest periodic length must exceed the largest contact by this fraction
    // of it (choose_skin): room for the lists' skin.
    static constexpr double min_room_fraction = 0.1;

    // Exact state, so that a restored engine continues bit for bit.
    void save(std::ostream& out) const;
    static EventEngine load(std::istream& in, const EventParams& params);

  private:
    EventEngine() = default;
    static constexpr double never_time = std::numeric_limits<double>::infinity();
    static constexpr std::int32_t no_event = -1;
    static constexpr std::int32_t shell_event = -2;
    static constexpr std::int32_t wall_event_base = -3; // -3 - (2 axis + side)

    void setup();
    // Particle i at now_: its flight carried from its own time (a parabola in gravity).
    Vec<D> x_now(std::size_t i) const {
        const double dt = now_ - f_[i].t;
        if (falling_) [[unlikely]]
            return f_[i].x + f_[i].v * dt + gravity_ * (0.5 * dt * dt);
        return f_[i].x + f_[i].v * dt;
    }
    Vec<D> v_now(std::size_t i) const {
        if (falling_) [[unlikely]]
            return f_[i].v + gravity_ * (now_ - f_[i].t);
        return f_[i].v;
    }
    // In gravity: m |g_a| times the height of x above the floor along each axis (see
    // potential_energy()).
    double height_energy(std::size_t species, const Vec<D>& x) const {
        double u = 0.0;
        for (int a = 0; a < D; ++a)
            if (gravity_[a] != 0.0)
                u -= gravity_[a] * (x[a] - (gravity_[a] < 0.0 ? box_.lo(a) : box_.hi(a)));
        return u * mass_of(species);
    }
    double falling_kinetic_energy() const;
    void start_gravity();
    // The Andersen thermostat's and the driving's events (event/event_driving.cpp):
    // draws(stream, k)'s first number gives the wait before event k, the rest its choices.
    void start_driving();
    void stochastic_event();
    void andersen_event();
    void kick_event();
    double next_stochastic_time(RngStream stream, std::uint64_t k, double rate) const;
    // A particle's velocity set to v at now_ (its flight brought there), with the energy
    // accounting of a collision; returns the change of its kinetic energy.
    double set_velocity(std::uint32_t i, const Vec<D>& v);
    std::uint32_t random_mobile(CounterRng& rng) const;
    // now_ moves to t; under shear the box's offset follows it.
    void set_now(double t) {
        now_ = t;
        if (box_.sheared()) [[unlikely]]
            box_.shear_to_time(t);
    }
    // The separation r_i - r_j of the nearest image of j at now_, from d = r_i - r_j of
    // the flights (which may lie up to a shell outside the box); under shear, adds to
    // `dvx` the change of the relative velocity's x component for that image.
    Vec<D> pair_separation(Vec<D> d, double& dvx) const {
        if (!box_.sheared()) return box_.minimum_image(d);
        const double k = std::round(d[1] / box_.length(1));
        d[1] -= k * box_.length(1);
        d[0] -= k * box_.shear_offset();
        d[0] -= box_.length(0) * std::round(d[0] / box_.length(0));
        dvx -= k * shear_velocity_;
        return box_.minimum_image(d); // the other axes
    }
    double peculiar_kinetic_energy() const;
    void recount_kinetic_moments();
    // x velocity of the flow at particle i's position now (0 without shear)
    double flow_velocity(std::uint32_t i) const {
        return box_.shear_rate() * (f_[i].x[1] + f_[i].v[1] * (now_ - f_[i].t));
    }
    // The whole-system passes of shear and the thermostat, at now_: a rescaling of the
    // velocities and/or a rebuild of every list, then every event predicted anew.
    void periodic_pass();
    void rescale_temperature();
    void schedule_passes();
    double default_skin(double mean_diameter) const;
    void build_all_lists();
    void add_neighbor(std::uint32_t i, std::uint32_t j);
    void remove_neighbor(std::uint32_t i, std::uint32_t j);
    void grow_lists();
    // The time of i's next event (its partner and the partner's count go to ev_[i]).
    double predict(std::uint32_t i);
    void advance(std::uint32_t i);
    void prefetch_list(std::uint32_t i) const;
    void process_pair(std::uint32_t i, std::uint32_t j);
    void process_wall(std::uint32_t i, std::int32_t code);
    void rebuild_list(std::uint32_t i);
    // Wraps f_[i].x into the box and counts the boxes crossed in image_[i].
    void wrap_flight(std::uint32_t i);
    void resum_kinetic_energy();
    void check_particle_overlap(std::uint32_t i, double rel_tol) const;
    // Contact distance at the last growth step (the lists' reference; all times
    // without growth) and now.
    double contact(std::uint32_t i, std::uint32_t j) const {
        return radius_[p_.species[i]] + radius_[p_.species[j]];
    }
    // The one criterion of every list build: list centres within contact + skin.
    // Under shear a pair across the y faces (its nearest image taken across them) counts
    // as if it were slide_ closer along x: the offset moves it by up to that much before
    // the next shear pass decides again.
    bool list_partners(std::uint32_t i, std::uint32_t j) const {
        const double cut = contact(i, j) + skin_;
        Vec<D> d = box_.minimum_image(ev_[i].centre - ev_[j].centre);
        if (box_.sheared() && std::abs(ev_[i].centre[1] - ev_[j].centre[1]) > box_.hi(1))
            d[0] = std::max(0.0, std::abs(d[0]) - slide_);
        return norm2(d) < cut * cut;
    }
    double radius_now(std::size_t species) const {
        return radius_[species] + radius_rate_[species] * (now_ - radius_time_);
    }
    double contact_now(std::uint32_t i, std::uint32_t j) const {
        return radius_now(p_.species[i]) + radius_now(p_.species[j]);
    }
    void start_growth();
    void growth_step(bool full);
    void set_radius_rates();
    void end_growth(GrowthEnd why);
    bool choose_skin();
    double min_periodic_length() const;
    std::string stall_cause() const;
    void relist();
    bool growth_due() const;
    bool pressure_window_full() const;
    void schedule_growth_step();
    template <bool Growing> double predict_with(std::uint32_t i);
    double predict_falling(std::uint32_t i);
    // The moving wall (event/event_moving_wall.cpp): its checks at set-up, its meeting
    // with particle i (on i's flight from now_) if before `best`, and a contact or check.
    void start_moving_wall();
    void meet_moving_wall(const Vec<D>& xi, const Vec<D>& vi, double ri, double& best,
                          std::int32_t& partner);
    void process_moving_wall(std::uint32_t i, int side);
    // A prediction's end: i's event is `partner` (its count noted) after `best`, or none.
    double settle_event(std::uint32_t i, double best, std::int32_t partner) {
        if (best == never_time) partner = no_event;
        ev_[i].partner = partner;
        ev_[i].count = partner >= 0 ? f_[partner].count : 0;
        return now_ + best;
    }
    void earliest_listed_lanes(std::uint32_t i, const Vec<D>& xi, const Vec<D>& vi, double ri,
                               double& best, std::int32_t& partner);

    // Tags, species and the species table; positions and velocities only as
    // lazy_particles() fills them (the engine's own are in f_).
    mutable ParticleStore<D> p_;
    std::vector<Flight<D>> f_;
    // f_ from p_'s positions, velocities and species and the rest given; frees p_'s
    // positions and velocities.
    void take_flights(const std::vector<double>& t, const std::vector<std::uint32_t>& counts,
                      const std::vector<std::uint16_t>& row_lengths);
    Box<D> box_;
    EventParams params_;
    double now_ = 0.0;
    double skin_ = 0.0;
    double shell_ = 0.0; // skin / 2: how far a particle may stray from its centre
    double kinetic_ = 0.0;
    double kinetic_exact_ = 0.0; // kinetic_ when last summed from the velocities

    // gravity (falling_: it is not zero); kinetic_ then holds every particle's kinetic plus
    // potential energy at its own flight time, which a flight keeps and only collisions,
    // kicks and redraws change
    Vec<D> gravity_{};
    bool falling_ = false;
    // the moving wall (moving_: there is one; predictions then take predict_falling's way)
    bool moving_ = false;
    WallMotion motion_{};
    int moving_axis_ = 0, moving_side_ = 0;
    double wall_tolerance_ = 0.0; // a gap taken as contact: 1e-12 of the axis's length
    double largest_radius_ = 0.0;
    double wall_work_ = 0.0;
    std::uint64_t wall_checks_ = 0;
    // the Andersen thermostat and the white-noise driving: the next event of each (never
    // without) and what they have done; mobile_: storage indices of the mobile particles
    double next_andersen_ = never_time;
    double next_kick_ = never_time;
    DrivingStatus driving_;
    std::vector<std::uint32_t> mobile_;

    std::vector<double> radius_;   // per species, at radius_time_
    std::vector<double> inv_mass_; // per species

    // growth (radius_rate_ all zero and next_growth_step_ = never without it)
    std::vector<double> radius_rate_; // per species, d radius / dt
    double radius_time_ = 0.0;
    double next_growth_step_ = never_time;
    double growth_kinetic_ = 0.0; // the kinetic energy growth holds
    double window_time_ = 0.0;    // pressure window: start time, collisions and virial
    std::uint64_t window_collisions_ = 0;
    double window_virial_ = 0.0;
    GrowthStatus growth_;

    // shear and the thermostat (never_time without them)
    double shear_velocity_ = 0.0; // rate L_y: how much faster the image above moves
    double slide_ = 0.0;          // the offset's move the lists allow between shear passes
    void choose_slide();
    double next_shear_relist_ = never_time;
    double next_rescale_ = never_time;
    ThermostatStatus thermostat_;

    // Each particle's neighbour-list centre and pending event (its time is the calendar's,
    // queue_.time; the partner's collision count when it was predicted tells a stale
    // event). One record: the run loop reads the partner, and the prediction that follows
    // reads the centre (the shell's exit time), in one cache line.
    struct ListAndEvent {
        Vec<D> centre;
        std::int32_t partner;
        std::uint32_t count;
    };
    std::vector<ListAndEvent> ev_;
    // Per particle: the periodic boxes crossed up to its flight's position f_[i].x (apart
    // from the record: touched only when a particle is wrapped, at its list rebuilds).
    std::vector<std::array<std::int32_t, D>> image_;
    std::vector<double> last_collision_; // only with the TC model
    FluxMoments<D> moments_;
    bool moments_on_ = false;
    double mass_of(std::size_t species) const {
        return inv_mass_[species] > 0.0 ? 1.0 / inv_mass_[species] : 0.0; // obstacles: none
    }

    std::uint32_t stride_ = 0; // neighbour slots per particle
    std::vector<std::uint32_t> nbr_;
    std::vector<std::uint32_t> candidates_, fresh_list_, old_list_; // rebuild_list's scratch
    // predict_with's batch kernel (core/simd_level.hpp; nullptr: the scalar loop) and
    // its output
    PairTimesKernel<D> pair_times_ = pair_times_for<D>(simd_level());
    std::vector<double> lane_scratch_;

    // Cell lists over the list centres, one per size class (species whose radii lie
    // within a factor 2 of the class's largest), each with cells of the class's own
    // contact distance plus the skin: a small particle's list rebuild then scans small
    // cells for small partners instead of cells sized by the largest particle.
    std::vector<CellList<D>> grids_;
    std::vector<std::uint8_t> class_of_; // per species
    std::vector<double> class_radius_;   // per class: its largest radius
    std::vector<double> reach_;          // [class of i][class of grid]: the list reach
    void make_grids();
    template <class F> void for_each_candidate(std::uint32_t i, F&& f) const;
    // Under shear: also the cells around the images of i's centre across the y faces.
    template <class F> void for_each_candidate_sheared(std::uint32_t i, F&& f) const;
    mutable std::vector<std::uint32_t> seen_; // its stamps (the last scan that met each)
    mutable std::uint32_t stamp_ = 0;
    std::vector<std::uint32_t> band_; // periodic_pass's particles near the y faces
    std::size_t grids_memory() const;
    EventQueue queue_;
    EventCounters<D> counters_;
    std::uint64_t stalled_events_ = 0;
};

extern template class EventEngine<2>;
extern template class EventEngine<3>;

} // namespace pedesis
