#pragma once
// What the two hard-particle engines, event and stepped, measure alike, so that a plot
// made from one run works for the other: the log.csv columns both share, the speed
// histogram, and the common part of summary.json and of the printed summary. Each
// engine's run adds its own columns and keys; the Simulation writes the files.
#include "pedesis/core/box.hpp"
#include "pedesis/core/collision_counters.hpp"
#include "pedesis/core/particles.hpp"
#include "pedesis/observe/shear_flow.hpp"
#include "pedesis/observe/speed_histogram.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/run/run_options.hpp"
#include "pedesis/run/transport_measurement.hpp"
#include "pedesis/setup/run_config.hpp"

#include <nlohmann/json.hpp>

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

namespace pedesis {

// Collisions, elastic or not, conserve momentum: only walls and fixed obstacles (which
// thermo.hpp sees in the box and the masses) take degrees of freedom back.
inline constexpr Momentum hard_particle_dynamics = Momentum::conserving;

// What the run directory accumulates, kept in checkpoints so that a continued run
// writes what the uninterrupted one would have.
template <int D> struct HardRunRecord {
    double initial_kinetic = 0.0;
    double integral_T_dt = 0.0; // for the kinetic part of the run-averaged pressure
    double last_log_time = 0.0;
    double last_temperature = 0.0;
    SymTensor integral_thermal_dt{}; // for the run-averaged pressure tensor
    SymTensor last_thermal{};        // sum m u_a u_b at the last row (thermo.hpp)
    EventCounters<D> last_counters{};
    std::uint64_t frames = 0;
    SpeedHistogram histogram;
    // Unwrapped positions at t = 0 in the engine's storage order: the MSD's origin. (A
    // checkpoint written before image counts had none: the origin is then the restart.)
    std::vector<Vec<D>> start;
    // [transport]'s measurement so far (none without the table)
    std::optional<TransportMeasurement<D>> transport;
    // under Lees-Edwards shear: the velocity profile and P_xy of every row after t = 0, and
    // the engine's exact ∫ Σ m c c dt at the last row
    ShearRecord shear;
    SymTensor last_kinetic_integral{};

    // the kinetic state at t = 0 of a fresh run
    void start_from(const SpeciesKinetics& k) {
        last_temperature = k.temperature();
        last_thermal = k.thermal_tensor;
    }
    // The time mean of sum m u_a u_b over the run so far (its value now at t = 0).
    SymTensor mean_thermal(double t) const {
        if (!(t > 0)) return last_thermal;
        SymTensor m;
        for (int c = 0; c < 6; ++c) m[c] = integral_thermal_dt[c] / t;
        return m;
    }
    void save(std::ostream& out) const;
    // The fields up to the histogram; then, in checkpoints since issue 51, the extension
    // (the MSD's origin, the transport measurement and, since extension 2, the shear).
    void load(std::istream& in);
    void load_extension(std::istream& in);
};

// The mean over the mobile particles (finite mass) of |r(t) - r(0)|^2, from unwrapped
// positions in storage order.
template <int D>
double mean_squared_displacement(const ParticleStore<D>& p, const std::vector<Vec<D>>& unwrapped,
                                 const std::vector<Vec<D>>& start);

// What a measurement of the shared log columns gives the engines besides the values.
struct HardMeasurement {
    SpeciesKinetics kinetics;
    double temperature = 0.0;
    double pressure = 0.0; // over the interval since the previous row
    bool has_pressure = false;
};

template <int D> class HardRunOutput {
  public:
    HardRunOutput(const RunConfig& c, const RunOptions& o, HardRunRecord<D>& record)
        : c_(c), o_(o), record_(record) {}

    // The log columns both engines share, in order (two per species).
    std::vector<std::string> log_columns() const;

    // Measures those columns at time t (velocities of p must be current), appending their
    // values; samples the speed histogram if asked, and moves the record on.
    // msd: the mean squared displacement since t = 0, for its column. kinetic_integral:
    // the engine's exact ∫ Σ m v v dt so far (the event engine under shear), for the
    // kinetic part of the interval's pressure tensor instead of the mean of its two ends.
    HardMeasurement measure(const ParticleStore<D>& p, const Box<D>& box, double t,
                            const EventCounters<D>& counters, double msd,
                            std::vector<double>& values,
                            const SymTensor* kinetic_integral = nullptr);

    // speed_histogram.csv from the samples, plus `final_state` when the histogram is of
    // the final state only. Not in the record, so a continued run does not count it twice.
    void write_speed_histogram(const ParticleStore<D>& final_state);

    // The summary fields both engines share: temperatures, run-averaged pressure against
    // the ideal gas and the hard-disk / hard-sphere equation of state, collisions.
    nlohmann::json summary(const ParticleStore<D>& p, const Box<D>& box, double t,
                           const EventCounters<D>& counters) const;
    // The printed lines for those fields, from the temperature to the mean free time.
    void print_summary(std::ostream& console, const nlohmann::json& j, const Box<D>& box) const;

  private:
    const RunConfig& c_;
    const RunOptions& o_;
    HardRunRecord<D>& record_;
};

// "30w x 20p": the box for the first printed line.
template <int D> std::string box_text(const Box<D>& box);

// Volume fraction of the particles in the box.
template <int D> double packing_fraction(const ParticleStore<D>& p, const Box<D>& box);

// Throws InputError if a checkpoint's species or box differ from the config's.
template <int D>
void check_checkpoint_matches(const std::vector<Species>& table, const Box<D>& box,
                              const RunConfig& c);

extern template class HardRunOutput<2>;
extern template class HardRunOutput<3>;

} // namespace pedesis
