#pragma once
// Time-stepped dynamics of hard disks (D = 2) and spheres (D = 3): the a-posteriori
// scheme of seeds 002 and 003, made exact for every collision it sees.
//
// One step of length dt:
// 1. every particle moves in a straight line for dt, walls or not;
// 2. the shared cell list finds every overlapping pair in O(N), and every centre that
//    ended past a wall;
// 3. each overlapping pair is rewound to the moment it entered the overlap (seed 002's
//    quadratic formula, stepped/rewind.hpp) and each wall crossing to the moment of
//    crossing; these events are processed in time order, earliest first. A pair goes
//    back to contact, collides elastically along the line of centres (unequal masses
//    and radii: the event engine's rule) and goes forward to the end of the step on its
//    new velocities; a particle past a wall is mirrored back and the wall's momentum
//    counted;
// 4. a particle that took part in an event moves on a new straight segment from that
//    moment, so its overlaps and wall crossings are found again on that segment, and
//    events computed before it changed are dropped. The loop ends when no overlap is
//    left that was entered during (or approaches at the start of) the current segments.
//
// So every event whose overlap lasts to the end of a step is resolved exactly and in
// the right order, however many events a particle has in one step. What is missed: a
// pair whose straight paths cross only the rim of the overlap (a grazing collision, in
// and out within one step). For relative speed g, contact distance sigma and
// x = g dt / sigma that is a fraction x^2 / 24 (2D) or x^2 / 12 (3D) of collisions, each
// missing a momentum transfer of at most mu g x / 2. A particle whose segment starts
// inside such a missed overlap collides at the segment start, from an overlapping
// position (a "late" collision). Energy is conserved by every collision, late or not,
// and momentum too apart from what the walls take, to rounding.
//
// Lees-Edwards shear (a sheared box, core/box.hpp; the event engine's design): the
// velocities inside are the laboratory ones, so every segment is still straight; a wrap
// across the y faces by k boxes takes k rate L_y off v_x. During a step the box holds
// the offset of the step's end, where the positions are: a pair's separation is that of
// the nearest image at that offset, whose x velocity differs by the slide, so the
// rewind finds the moment of contact exactly; the cell scan also looks around the
// images of a centre across the y faces. Nothing else depends on the offset's change
// within a step (the cells are rebuilt each step from the positions at its end), but the
// flow's own velocity difference across a contact distance must keep to max_move (the
// constructor refuses a rate and dt that do not). Out (particles(), kinetic_energy()):
// peculiar velocities, v - rate y e_x. The Helfand sums are always kept, of the peculiar
// velocities (FluxMoments::advance_sheared between events), so the kinetic stress is
// integrated exactly.
#include "pedesis/core/box.hpp"
#include "pedesis/core/collision_counters.hpp"
#include "pedesis/core/flux_moments.hpp"
#include "pedesis/core/image_count.hpp"
#include "pedesis/core/particles.hpp"
#include "pedesis/spatial/cell_list.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <iosfwd>
#include <vector>

namespace pedesis {

struct SteppedParams {
    double dt = 0.0;
    double max_move = 0.5; // largest distance moved in one step, in units of the own radius
    std::uint32_t max_events_per_step = 64; // per particle (pairs and walls); more stops the run
    // Uniform gravity, an acceleration (its first D components; zero: none), along walled
    // axes only. Each segment is a parabola; pairs fall alike, so their relative motion, and
    // the rewind, stay straight; a wall crossing is the root of a quadratic.
    std::array<double, 3> gravity{};
};

// Diagnostics of the approximation, since the engine was created (or restored).
struct SteppedStats {
    std::uint64_t late_collisions = 0;     // resolved from an overlap at a segment start
    std::uint64_t chained_events = 0;      // events of a particle that already had one that step
    std::uint32_t most_events_in_step = 0; // by one particle in one step
    // Checkpoints store the struct's bytes: a named, zeroed filler instead of padding, whose
    // bytes would be whatever memory held (the same run would write different files).
    std::uint32_t zero_ = 0;
};

template <int D> class SteppedEngine {
  public:
    SteppedEngine(ParticleStore<D> particles, const Box<D>& box, const SteppedParams& params);

    // One step of dt. Throws RunError before moving anything if a particle would move
    // more than max_move radii, and during the step if a particle has more than
    // max_events_per_step events.
    void step();

    std::uint64_t steps() const { return step_; }
    // base + (steps since base) x dt: a product, not a running sum
    double time() const { return time_base_ + static_cast<double>(step_ - step_base_) * dt_; }
    double dt() const { return dt_; }
    const SteppedParams& params() const { return params_; }
    const Box<D>& box() const { return box_; }
    // positions are those at time(), inside the walls and wrapped on periodic axes; under
    // shear the velocities are the peculiar ones (a copy made once a step, when asked)
    const ParticleStore<D>& particles() const { return box_.sheared() ? peculiar_particles() : p_; }
    // the periodic boxes each particle has crossed (unwrapped: position + image * L)
    const std::vector<ImageCount<D>>& images() const { return image_; }
    Vec<D> unwrapped_now(std::size_t i) const {
        return unwrapped<D>(box_, p_.position[i], image_[i]);
    }
    // (in the laboratory frame)
    const Vec<D>& velocity(std::size_t i) const { return p_.velocity[i]; }
    const EventCounters<D>& counters() const { return counters_; }
    // From now on, keeps the running integrals of the Helfand moments (core/flux_moments.hpp),
    // each collision at its own time within the step, for [transport]. Idempotent.
    void track_flux_moments();
    bool tracks_flux_moments() const { return moments_on_; }
    // Those integrals carried to time() (G's collisional part is counters().virial).
    // Under shear they are always kept, of the peculiar velocities, without the heat sums.
    FluxMoments<D> flux_moments() const;
    const SteppedStats& stats() const { return stats_; }
    std::size_t size() const { return p_.size(); }
    // Under shear, of the peculiar velocities: the heat, not the flow.
    double kinetic_energy() const;
    // In gravity, -sum m g . (r - r0), r0 the corner of the box that gravity points to (the
    // weight times each centre's height above the floor); 0 without.
    double potential_energy() const;
    bool falling() const { return falling_; }

    // Throws if two particles overlap by more than rel_tol of their contact distance:
    // InputError before the first step (a bad initial state), RunError after.
    void check_no_overlap(double rel_tol) const;

    // Exact state, so that a restored engine continues bit for bit. A restored engine
    // takes dt from `params`; if it differs from the saved one, time goes on from the
    // saved time in steps of the new dt.
    void save(std::ostream& out) const;
    static SteppedEngine load(std::istream& in, const SteppedParams& params);

  private:
    static constexpr std::int32_t pair_event = -1;

    struct Event {
        double when;                  // within the step, in [0, dt]
        std::uint32_t i, j;           // a pair: i < j; a wall: j = i
        std::uint32_t seen_i, seen_j; // events of i and j in this step when computed
        std::int32_t wall;            // pair_event, or 2 axis + side (0 low, 1 high)
        bool late;
    };
    struct Later {
        bool operator()(const Event& a, const Event& b) const {
            if (a.when != b.when) return a.when > b.when;
            if (a.i != b.i) return a.i > b.i;
            if (a.j != b.j) return a.j > b.j;
            return a.wall > b.wall;
        }
    };

    SteppedEngine() = default;
    void setup();
    void check_speeds() const;
    void check_shear_step(double max_radius) const;
    double speed_samples_so_far() const;
    void find_wall_crossing(std::uint32_t i);
    void find_overlaps_of(std::uint32_t i, std::uint32_t skip);
    // Most pairs of the cell scan do not touch: that test is here, small enough to inline
    // into the scan; the rest of the work is out of line.
    void consider(std::uint32_t i, std::uint32_t j) {
        // Two fixed obstacles never collide: neither can move, so the approach of their
        // sheared images would be re-found forever within the step.
        if (inv_mass_[p_.species[i]] == 0.0 && inv_mass_[p_.species[j]] == 0.0) return;
        double dvx = 0.0;
        const Vec<D> dr = separation(p_.position[i] - p_.position[j], dvx);
        const double sigma = contact(i, j);
        if (norm2(dr) < sigma * sigma) overlapping(i, j, dr, sigma, dvx);
    }
    // The separation r_i - r_j of j's nearest image, from d = r_i - r_j of positions in
    // the box; under shear, adds to `dvx` the change of the relative velocity's x
    // component for that image (k boxes above moves k rate L_y faster: -k rate L_y).
    Vec<D> separation(const Vec<D>& d, double& dvx) const {
        if (!any_periodic_) return d;
        const Vec<D> m = box_.minimum_image(d);
        if (box_.sheared()) [[unlikely]]
            dvx -= std::round((d[1] - m[1]) / box_.length(1)) * shear_velocity_;
        return m;
    }
    // f(j) once for every particle in the cells around r, and under shear also around r's
    // images across the y faces (where the particles it can touch there lie).
    template <class F>
    void for_each_candidate(const CellList<D>& cells, const Vec<D>& r, F&& f) const;
    void overlapping(std::uint32_t i, std::uint32_t j, const Vec<D>& dr, double sigma, double dvx);
    void push(const Event& e);
    void collide(const Event& e);
    void bounce(const Event& e);
    void moved(std::uint32_t i, double when);
    // Wraps i into the box, counting images; under shear its v_x follows a y crossing.
    void wrap_particle(std::uint32_t i);
    // The flow's x velocity at height y (0 without shear).
    double flow(double y) const { return box_.shear_rate() * y; }
    const ParticleStore<D>& peculiar_particles() const;
    double contact(std::uint32_t i, std::uint32_t j) const {
        return radius_[p_.species[i]] + radius_[p_.species[j]];
    }

    ParticleStore<D> p_;
    std::vector<ImageCount<D>> image_;
    Box<D> box_;
    SteppedParams params_;
    double dt_ = 0.0;
    std::uint64_t step_ = 0;
    std::uint64_t step_base_ = 0;
    double time_base_ = 0.0;

    std::vector<double> radius_;        // per species
    std::vector<double> inv_mass_;      // per species
    std::vector<double> max_speed2_;    // per species: (max_move r / dt)^2
    std::vector<double> segment_start_; // per particle: when its straight segment began
    std::vector<std::uint32_t> events_; // per particle: events in this step
    std::vector<Event> heap_;
    std::array<bool, D> walled_{};
    bool any_periodic_ = false;
    Vec<D> gravity_{};
    bool falling_ = false;
    void start_gravity();

    CellList<D> cells_;
    EventCounters<D> counters_;
    FluxMoments<D> moments_;
    bool moments_on_ = false;
    double mass_of(std::size_t species) const {
        return inv_mass_[species] > 0.0 ? 1.0 / inv_mass_[species] : 0.0; // obstacles: none
    }
    SteppedStats stats_;

    // shear
    double shear_velocity_ = 0.0; // rate L_y: how much faster the image above moves
    double shear_reach_ = 0.0;    // a centre this close to a y face meets images across it
    mutable std::vector<std::uint32_t> candidates_;
    mutable ParticleStore<D> peculiar_;
    mutable bool peculiar_fresh_ = false;
};

extern template class SteppedEngine<2>;
extern template class SteppedEngine<3>;

} // namespace pedesis
