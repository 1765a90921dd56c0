#include "pedesis/run/hard_run_output.hpp"

#include "pedesis/core/ball_volume.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/binary_stream.hpp"
#include "pedesis/observe/pressure.hpp"
#include "pedesis/observe/theory.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace pedesis {

namespace {

// What follows the speed histogram in a checkpoint's run record: 1, the MSD's origin and
// the transport measurement; 2, then the shear record (1 is read with none).
constexpr std::uint32_t record_extension = 2;

// Which definition the run-averaged pressure uses, for the printed summary.
template <int D> const char* pressure_method(const Box<D>& box) {
    bool wall = false, periodic = false;
    for (int a = 0; a < D; ++a) (box.periodic(a) ? periodic : wall) = true;
    if (wall && periodic) return "walls on walled axes, collision virial on periodic axes";
    return wall ? "momentum delivered to the walls" : "collision virial";
}

} // namespace

template <int D> void HardRunRecord<D>::save(std::ostream& out) const {
    binary::put(out, initial_kinetic);
    binary::put(out, integral_T_dt);
    binary::put(out, last_log_time);
    binary::put(out, last_temperature);
    binary::put(out, integral_thermal_dt);
    binary::put(out, last_thermal);
    binary::put(out, last_counters);
    binary::put(out, frames);
    histogram.save(out);
    binary::put<std::uint32_t>(out, record_extension);
    binary::put(out, start);
    binary::put<std::uint8_t>(out, transport.has_value());
    if (transport) transport->save(out);
    binary::put(out, shear.velocity_sum);
    binary::put(out, shear.count);
    binary::put(out, shear.shear_stress);
    binary::put(out, last_kinetic_integral);
}

template <int D> void HardRunRecord<D>::load(std::istream& in) {
    binary::get(in, initial_kinetic);
    binary::get(in, integral_T_dt);
    binary::get(in, last_log_time);
    binary::get(in, last_temperature);
    binary::get(in, integral_thermal_dt);
    binary::get(in, last_thermal);
    binary::get(in, last_counters);
    binary::get(in, frames);
    histogram.load(in);
    start.clear();
    transport.reset();
}

template <int D> void HardRunRecord<D>::load_extension(std::istream& in) {
    std::uint32_t extension = 0;
    binary::get(in, extension);
    if (extension != record_extension && extension != 1)
        throw InputError("checkpoint: unknown run record extension " + std::to_string(extension));
    binary::get(in, start);
    std::uint8_t measured = 0;
    binary::get(in, measured);
    if (measured > 1) throw InputError("checkpoint: corrupt run record");
    transport.reset();
    if (measured) transport.emplace(TransportMeasurement<D>::load(in, "checkpoint"));
    shear = ShearRecord{};
    if (extension >= 2) {
        binary::get(in, shear.velocity_sum);
        binary::get(in, shear.count);
        binary::get(in, shear.shear_stress);
        binary::get(in, last_kinetic_integral);
        if (shear.velocity_sum.size() != shear.count.size())
            throw InputError("checkpoint: corrupt shear record");
    }
}

template <int D>
double mean_squared_displacement(const ParticleStore<D>& p, const std::vector<Vec<D>>& unwrapped,
                                 const std::vector<Vec<D>>& start) {
    double sum = 0.0;
    std::size_t mobile = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (std::isinf(p.mass(i))) continue;
        sum += norm2(unwrapped[i] - start[i]);
        ++mobile;
    }
    return mobile ? sum / static_cast<double>(mobile) : 0.0;
}

template <int D> std::vector<std::string> HardRunOutput<D>::log_columns() const {
    std::vector<std::string> c = {"time",
                                  "collisions",
                                  "collisions_per_particle",
                                  "wall_collisions",
                                  "kinetic_energy",
                                  "energy_fraction",
                                  "temperature"};
    for (const auto& s : c_.species) {
        c.push_back("temperature_" + s.name);
        c.push_back("kinetic_energy_" + s.name);
    }
    c.push_back("pressure");
    c.push_back("pressure_ideal");
    for (int slot : sym_slots<D>()) c.push_back(std::string("pressure_") + sym_suffix(slot));
    c.push_back("compressibility");
    c.push_back("mean_free_time");
    c.push_back("msd");
    return c;
}

template <int D>
HardMeasurement HardRunOutput<D>::measure(const ParticleStore<D>& p, const Box<D>& box, double t,
                                          const EventCounters<D>& counters, double msd,
                                          std::vector<double>& values,
                                          const SymTensor* kinetic_integral) {
    HardMeasurement m;
    m.kinetics = measure_kinetics(p, box, hard_particle_dynamics);
    const auto& k = m.kinetics;
    const double T = k.temperature();
    const double dt = t - record_.last_log_time;
    const double meanT = 0.5 * (T + record_.last_temperature);
    SymTensor mean_thermal = sym_midpoint(k.thermal_tensor, record_.last_thermal);
    if (kinetic_integral) {
        if (dt > 0)
            for (int c = 0; c < 6; ++c)
                mean_thermal[c] = ((*kinetic_integral)[c] - record_.last_kinetic_integral[c]) / dt;
        record_.last_kinetic_integral = *kinetic_integral;
    }
    for (int c = 0; c < 6; ++c) record_.integral_thermal_dt[c] += mean_thermal[c] * dt;
    const SymTensor tensor =
        interval_pressure_tensor(box, record_.last_counters, counters, dt, mean_thermal);
    const double P = sym_trace<D>(tensor) / D;
    record_.integral_T_dt += meanT * dt;
    const double n = static_cast<double>(p.size());
    const auto C = static_cast<double>(counters.pair_collisions);
    const double P_ideal = static_cast<double>(k.total_mobile) * meanT / box.volume();
    values.insert(values.end(),
                  {t, C, C / n, static_cast<double>(counters.wall_collisions), k.total_kinetic,
                   record_.initial_kinetic > 0 ? k.total_kinetic / record_.initial_kinetic : 0.0,
                   T});
    for (std::size_t s = 0; s < c_.species.size(); ++s)
        values.insert(values.end(), {k.temperature(s), k.kinetic[s]});
    const double mft = C > 0 ? static_cast<double>(k.total_mobile) * t / (2.0 * C)
                             : std::numeric_limits<double>::infinity();
    values.insert(values.end(), {dt > 0 ? P : 0.0, P_ideal});
    for (int slot : sym_slots<D>()) values.push_back(tensor[slot]);
    values.insert(values.end(), {dt > 0 && P_ideal > 0 ? P / P_ideal : 0.0, mft, msd});
    if (box.sheared() && dt > 0) record_.shear.shear_stress.push_back(tensor[sym_slot(0, 1)]);
    if (c_.histogram_start && t >= *c_.histogram_start) record_.histogram.add(p);
    record_.last_log_time = t;
    record_.last_temperature = T;
    record_.last_thermal = k.thermal_tensor;
    record_.last_counters = counters;
    m.temperature = T;
    m.pressure = P;
    m.has_pressure = dt > 0;
    return m;
}

template <int D> void HardRunOutput<D>::write_speed_histogram(const ParticleStore<D>& final_state) {
    SpeedHistogram histogram = record_.histogram;
    if (!c_.histogram_start) histogram.add(final_state);
    std::vector<std::string> names;
    std::vector<double> masses;
    for (const auto& s : c_.species) {
        names.push_back(s.name);
        masses.push_back(s.mass);
    }
    write_file_atomically(o_.out_dir / "speed_histogram.csv",
                          [&](std::ostream& out) { histogram.write_csv(out, D, names, masses); });
}

template <int D>
nlohmann::json HardRunOutput<D>::summary(const ParticleStore<D>& p, const Box<D>& box, double t,
                                         const EventCounters<D>& counters) const {
    const auto k = measure_kinetics(p, box, hard_particle_dynamics);
    const double V = box.volume();
    const double T_avg = t > 0 ? record_.integral_T_dt / t : k.temperature();
    const SymTensor tensor =
        interval_pressure_tensor(box, EventCounters<D>{}, counters, t, record_.mean_thermal(t));
    const double P = sym_trace<D>(tensor) / D;
    const double P_ideal = static_cast<double>(k.total_mobile) * T_avg / V;
    const double eta = packing_fraction(p, box);
    const auto C = counters.pair_collisions;
    nlohmann::json j;
    j["dimension"] = D;
    j["particles"] = p.size();
    j["time"] = t;
    j["pair_collisions"] = C;
    j["collisions_per_particle"] = static_cast<double>(C) / static_cast<double>(p.size());
    j["wall_collisions"] = counters.wall_collisions;
    j["packing_fraction"] = eta;
    j["temperature"] = k.temperature();
    j["degrees_of_freedom"] = k.total_freedom;
    j["time_averaged_temperature"] = T_avg;
    j["energy_fraction"] =
        record_.initial_kinetic > 0 ? k.total_kinetic / record_.initial_kinetic : 0.0;
    for (std::size_t s = 0; s < c_.species.size(); ++s)
        j["species"][c_.species[s].name] = {{"temperature", k.temperature(s)},
                                            {"kinetic_energy", k.kinetic[s]}};
    j["pressure"] = P;
    for (int slot : sym_slots<D>()) j["pressure_tensor"][sym_suffix(slot)] = tensor[slot];
    j["pressure_ideal_gas"] = P_ideal;
    j["compressibility"] = P_ideal > 0 ? P / P_ideal : 0.0;
    j["compressibility_equation_of_state"] = theory::compressibility_factor(D, eta);
    if (C)
        j["mean_free_time"] =
            static_cast<double>(k.total_mobile) * t / (2.0 * static_cast<double>(C));
    else
        j["mean_free_time"] = nullptr; // infinite: no collision yet
    return j;
}

template <int D>
void HardRunOutput<D>::print_summary(std::ostream& console, const nlohmann::json& j,
                                     const Box<D>& box) const {
    const double P = j["pressure"].template get<double>();
    const double P_ideal = j["pressure_ideal_gas"].template get<double>();
    console << fmt::format("  temperature        {:.6g} (time average {:.6g}, {:g} degrees of "
                           "freedom); energy remaining {:.4g} of initial\n",
                           j["temperature"].template get<double>(),
                           j["time_averaged_temperature"].template get<double>(),
                           j["degrees_of_freedom"].template get<double>(),
                           j["energy_fraction"].template get<double>());
    if (c_.species.size() > 1)
        for (const auto& s : c_.species)
            console << fmt::format("  temperature of {:<4s} {:.6g}\n", s.name,
                                   j["species"][s.name]["temperature"].template get<double>());
    console << fmt::format("  pressure           {:.6g} ({})\n", P, pressure_method(box));
    console << fmt::format("  ideal gas N T / V  {:.6g}  ->  Z = P V / (N T) = {:.4f}\n", P_ideal,
                           P_ideal > 0 ? P / P_ideal : 0.0);
    console << fmt::format("  {} at eta = {:.4f}: Z = {:.4f}{}\n",
                           D == 2 ? "hard-disk EOS (Henderson)"
                                  : "hard-sphere EOS (Carnahan-Starling)",
                           j["packing_fraction"].template get<double>(),
                           j["compressibility_equation_of_state"].template get<double>(),
                           box.any_wall() ? " (walls shift this by O(sigma/L))" : "");
    if (!j["mean_free_time"].is_null())
        console << fmt::format("  mean free time     {:.6g}\n",
                               j["mean_free_time"].template get<double>());
}

template <int D> std::string box_text(const Box<D>& box) {
    std::string s;
    for (int a = 0; a < D; ++a)
        s += fmt::format("{}{:g}{}", a ? " x " : "", box.length(a), box.periodic(a) ? "p" : "w");
    return s;
}

template <int D> double packing_fraction(const ParticleStore<D>& p, const Box<D>& box) {
    double v = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        v += ball_volume(p.radius(i), D);
    }
    return v / box.volume();
}

template <int D>
void check_checkpoint_matches(const std::vector<Species>& table, const Box<D>& box,
                              const RunConfig& c) {
    if (table.size() != c.species.size()) throw InputError("species do not match " + c.file);
    for (std::size_t k = 0; k < table.size(); ++k)
        if (table[k].name != c.species[k].name || table[k].radius != c.species[k].radius ||
            !(table[k].mass == c.species[k].mass))
            throw InputError("species '" + table[k].name + "' does not match " + c.file);
    for (int a = 0; a < D; ++a)
        if (box.length(a) != c.box_lengths[static_cast<std::size_t>(a)] ||
            box.periodic(a) != c.periodic[static_cast<std::size_t>(a)])
            throw InputError("box does not match " + c.file);
}

template struct HardRunRecord<2>;
template struct HardRunRecord<3>;
template class HardRunOutput<2>;
template class HardRunOutput<3>;
template std::string box_text(const Box<2>&);
template std::string box_text(const Box<3>&);
template double packing_fraction(const ParticleStore<2>&, const Box<2>&);
template double packing_fraction(const ParticleStore<3>&, const Box<3>&);
template double mean_squared_displacement(const ParticleStore<2>&, const std::vector<Vec<2>>&,
                                          const std::vector<Vec<2>>&);
template double mean_squared_displacement(const ParticleStore<3>&, const std::vector<Vec<3>>&,
                                          const std::vector<Vec<3>>&);
template void check_checkpoint_matches(const std::vector<Species>&, const Box<2>&,
                                       const RunConfig&);
template void check_checkpoint_matches(const std::vector<Species>&, const Box<3>&,
                                       const RunConfig&);

} // namespace pedesis
