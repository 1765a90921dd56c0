#include "pedesis/run/soft_run.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/simd_level.hpp"
#include "pedesis/gpu/gpu_stepper.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/observe/soft_observables.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/run/shear_output.hpp"
#include "pedesis/run/simulation.hpp"
#include "pedesis/run/soft_checkpoint.hpp"
#include "pedesis/run/soft_minimize.hpp"
#include "pedesis/run/transport_plan.hpp"
#include "pedesis/setup/build_soft_state.hpp"
#include "pedesis/setup/build_system.hpp"
#include "pedesis/soft/active_ou.hpp"
#include "pedesis/soft/barostat.hpp"
#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/domain_decomposition.hpp"
#include "pedesis/soft/integrator_set.hpp"
#include "pedesis/soft/langevin.hpp"
#include "pedesis/soft/plugin_registry.hpp"
#include "pedesis/soft/polar_align.hpp"
#include "pedesis/soft/run_and_tumble.hpp"
#include "pedesis/soft/self_propulsion.hpp"
#include "pedesis/soft/wall_force.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <sstream>

namespace pedesis {

namespace {

// Two particles at the same place (coinciding lattices of two species, a file with a
// repeated position) have pair forces without a direction: 0/0, and the run would stop
// at its first log row on a NaN. Bad input, named at set-up. The message names the pair
// of lowest tags (the lower tag first, then the higher), so that it does not depend on
// the order of the list nor on how many processes share the run: under a domain
// decomposition each process checks its share and ghosts (every pair lies in some
// process's list), and two reductions find that pair, so that every process stops with
// the same message (exit 2) and none waits for another.
template <int D>
void refuse_coincident_particles(const SoftState<D>& s, const NeighborList<D>& list,
                                 const std::string& file, Communicator* comm) {
    constexpr double none = std::numeric_limits<double>::infinity();
    // the least key(lower tag, higher tag) over the coincident pairs (none: no pair)
    const auto least = [&](auto&& key) {
        double best = none;
        for (std::size_t i = 0; i < list.size(); ++i)
            for (const std::uint32_t* j = list.begin(i); j != list.end(i); ++j)
                if (norm2(s.box.minimum_image(s.p.position[i] - s.p.position[*j])) == 0.0)
                    best = std::min(best, key(std::min(s.p.tag[i], s.p.tag[*j]),
                                              std::max(s.p.tag[i], s.p.tag[*j])));
        return comm && comm->size() > 1 ? -comm->max(-best) : best;
    };
    const double lower = least([](std::uint32_t a, std::uint32_t) { return double(a); });
    if (lower == none) return;
    const double higher =
        least([&](std::uint32_t a, std::uint32_t b) { return a == lower ? double(b) : none; });
    throw InputError(fmt::format(
        "{}: particles {} and {} start at the same position: the force between them has no "
        "direction; move one of them (two lattices of different species in the same region "
        "coincide: give each its own region)",
        file, static_cast<std::uint32_t>(lower), static_cast<std::uint32_t>(higher)));
}

std::vector<Species> species_table(const RunConfig& c) {
    std::vector<Species> t;
    for (const auto& s : c.species) t.push_back(Species{s.name, s.radius, s.mass});
    return t;
}

// The soft/active engine (state, evolver, plug-ins) as the Simulation drives it.
template <int D> class SoftRunEngine final : public RunEngine<D> {
  public:
    SoftRunEngine(const RunConfig& c, const RunOptions& o, std::ostream& console)
        : SoftRunEngine(c, o, console, read_start(c, o)) {}

  private:
    // The [initial] file, read once for the config's completion and the state (a
    // 10^6-particle JSON takes seconds to parse), when either needs it.
    static std::optional<ParticleFile<D>> read_start(const RunConfig& c, const RunOptions& o) {
        const bool incomplete = c.box_lengths.empty() || c.species.empty();
        if (!c.initial_file || (o.restart && !incomplete)) return std::nullopt;
        return read_initial_file<D>(c);
    }

    SoftRunEngine(const RunConfig& c, const RunOptions& o, std::ostream& console,
                  std::optional<ParticleFile<D>> start)
        : c_(complete_from_initial_file<D>(c, start ? &*start : nullptr)), o_(o),
          console_(console) {
        if (c_.dynamics == "minimize") SoftMinimization<D>::refuse(c_, o_, on_gpu());
        const std::vector<Species> table = species_table(c_);
        if (!o_.restart) {
            state_ = build_soft_state<D>(c_, start ? &*start : nullptr);
            if (c_.shear_rate > 0.0) {
                state_.box.set_shear_rate(c_.shear_rate);
                state_.box.shear_to_time(state_.time);
            }
        }
        start.reset(); // (the state holds the particles now)
        evolver_ = std::make_unique<Evolver<D>>(state_, c_.list_skin, c_.list_r_cut);
        evolver_->set_sort_interval(c_.sort_every);
        for (const auto* list : {&c_.forces, &c_.torques, &c_.integrators})
            for (const auto& spec : *list) {
                if (c_.barostat.on && list == &c_.integrators && moves_positions(spec))
                    evolver_->add_integrator(make_mtk_integrator<D>(
                        c_.barostat, spec, table, c_.seed,
                        [this] { return evolver_->pair_totals().virial_tensor; },
                        state_.box.volume()));
                else
                    add_plugin(*evolver_, spec, table, c_.seed);
            }
        if (c_.dynamics == "minimize") minimize_.emplace(c_, state_, *evolver_);
        // (under MPI the list is built after the decomposition, on each process's share)
        if (!o_.restart && !(o_.comm && o_.comm->size() > 1))
            refuse_coincident_particles(state_, evolver_->neighbor_list(), c_.file, nullptr);
        if (o_.restart) {
            load_soft_checkpoint(*o_.restart, c_, state_, *evolver_, book_);
            if (state_.step >= c_.steps)
                throw InputError(fmt::format(
                    "{}: the checkpoint {} is at step {}, and run.steps = {} asks for no more; "
                    "raise run.steps to continue",
                    c_.file, o_.restart->string(), state_.step, c_.steps));
        } else {
            book_.start.resize(state_.size());
            for (std::size_t i = 0; i < state_.size(); ++i)
                book_.start[state_.p.tag[i]] = state_.unwrapped(i);
        }
        state_.pair_precision = c_.precision;
        check_walls(); // (a restored state has its box from here on)
        check_barostat();
        check_active_ou();
        check_thermostat();
        check_shear();
        read_observable_parameters(table);
        read_swim_forces();
        start_transport_if_asked(); // (after the above: it asks whether the run is inertial)
        particles_ = state_.size();
        if (o_.comm && o_.comm->size() > 1) {
            // what measured_shared needs of the whole system, which does not change
            conserved_ = conserved_momentum_axes(state_.p, state_.box, momentum_);
            species_count_.assign(table.size(), 0.0);
            for (std::size_t i = 0; i < state_.size(); ++i)
                species_count_[state_.p.species[i]] += 1.0;
            // every process built or loaded the whole state, and keeps its domain's share
            const double reach = evolver_->interaction_reach();
            domain_ = std::make_unique<DomainDecomposition<D>>(*o_.comm, state_.box, reach);
            domain_->scatter(state_);
            evolver_->set_domain(domain_.get());
        }
        if (on_gpu()) {
            if (c_.precision == Precision::mixed)
                throw InputError(c_.precision_where +
                                 " = \"mixed\" runs on the CPU (the GPU path computes in double "
                                 "only): set device = \"cpu\" or precision = \"double\"");
            if (domain_)
                throw InputError((o_.device || c_.device_where.empty() ? c_.file + ": device"
                                                                       : c_.device_where) +
                                 " = \"gpu\" runs on one process; start it without mpirun");
            // a restored run's list reference makes the device's first list the same
            evolver_->set_device(
                make_gpu_stepper<D>(state_, *evolver_, evolver_->list_reference()));
        } else if (!o_.restart || domain_) {
            // built here so that a box too small for the cutoff is reported before any
            // output exists; a restored run has its list already (building now could
            // rebuild it at another point of the step than the continuous run did)
            evolver_->neighbor_list();
            if (domain_ && !o_.restart)
                refuse_coincident_particles(state_, evolver_->neighbor_list(), c_.file, o_.comm);
            // as LAMMPS sorts its atoms at a run's set-up: the first sort_every steps would
            // otherwise run in the input's order (a restored run keeps the checkpoint's)
            if (!domain_ && !o_.restart && c_.sort_every > 0) evolver_->sort_storage_at_start();
        }
    }

  public:
    Schedule schedule() const {
        return {Trigger::every_steps(c_.log_every),
                c_.snapshot_every ? Trigger::every_steps(c_.snapshot_every) : Trigger::never(),
                c_.checkpoint_every ? Trigger::every_steps(c_.checkpoint_every) : Trigger::never()};
    }

    std::uint64_t step() const override { return state_.step; }
    double time() const override { return state_.time; }

    bool interrupted() const override { return evolver_->interrupted(); }

    Advance advance(std::uint64_t until_step, double until_time) override {
        whole_current_ = false;
        // the stepping alone (no output), and its share of communication: benchmarks
        const auto begin = std::chrono::steady_clock::now();
        const double comm_begin = o_.comm ? o_.comm->seconds() : 0.0;
        const double bytes_begin = o_.comm ? o_.comm->bytes_sent() : 0.0;
        const std::uint64_t last = std::min<std::uint64_t>(until_step, c_.steps);
        // [transport]'s samples fall on their own steps, between the Simulation's
        for (;;) {
            const std::uint64_t target = book_.transport ? std::min(last, transport_step()) : last;
            const SoftClock clock{clock_t0_, clock_step0_, c_.dt};
            if (state_.step < target && minimize_)
                minimize_->advance(state_, *evolver_, clock, target, until_time);
            else if (state_.step < target)
                evolve_until(state_, *evolver_, clock, target, until_time);
            if (state_.step < target) break; // a signal, or until_time
            if (book_.transport && state_.step == transport_step()) sample_transport();
            if (state_.step >= last) break;
        }
        stepping_.seconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
        if (o_.comm) {
            stepping_.communication_seconds += o_.comm->seconds() - comm_begin;
            stepping_.bytes_sent += o_.comm->bytes_sent() - bytes_begin;
        }
        if (minimize_ && minimize_->stopped_by()) return {minimize_->stopped_by(), false};
        return {state_.step >= c_.steps ? "steps" : nullptr, false};
    }

    Frame<D> frame() override { return whole().frame(); }
    std::uint64_t frames() const override { return book_.frames; }
    void frame_written() override { ++book_.frames; }

    void save_checkpoint(const std::filesystem::path& path) override {
        const SoftState<D>& s = whole();
        on_process_zero(o_.comm, [&] { save_soft_checkpoint(path, s, *evolver_, book_); });
        // Shared, the run goes on from what a restart from a checkpoint of its step grid
        // starts from (the whole state in tag order, scattered, a fresh list), since the
        // processes' storage orders, which their force sums follow, are not in it: a run
        // resumed there then steps as this one does, bit for bit. Only on the grid, so
        // that checkpoints on the wall clock or on a signal change no trajectory.
        if (domain_ && c_.checkpoint_every > 0 && state_.step % c_.checkpoint_every == 0) {
            domain_->settle_in_tag_order(state_);
            evolver_->set_domain(domain_.get());
            evolver_->neighbor_list();
        }
    }

    std::vector<const char*> stale_results() const override {
        if (c_.shear_rate > 0.0) return {"summary.json", "velocity_profile.csv"};
        if (c_.transport.on) return {"summary.json", "transport.csv"};
        return {"summary.json"};
    }

    std::vector<std::string> log_columns() const override {
        std::vector<std::string> c = {"step", "time", "polar_order", "msd", "potential_energy"};
        if (inertial()) c.insert(c.end(), {"kinetic_energy", "temperature", "total_energy"});
        if (thermostat_) c.push_back("conserved_energy");
        c.insert(c.end(), {"pressure", "pressure_ideal", "pressure_virial", "pressure_active"});
        for (int slot : sym_slots<D>()) c.push_back(std::string("pressure_") + sym_suffix(slot));
        for (const auto& f : evolver_->forces())
            for (std::string& name : f->log_columns(state_)) c.push_back(std::move(name));
        if (c_.barostat.on) c.push_back("volume");
        if (minimize_)
            for (std::string& name : SoftMinimization<D>::log_columns())
                c.push_back(std::move(name));
        c.push_back("list_rebuilds");
        return c;
    }

    void measure(std::vector<double>& values) override {
        const PairTotals pair = evolver_->pair_totals(); // (collective under a decomposition)
        evolver_->sync_host();
        const Measured m = domain_ ? measured_shared() : measured_here();
        const double V = state_.box.volume();
        const double virial = pair.virial / (D * V);
        const double pressure = m.ideal + virial + m.active;
        values.insert(values.end(),
                      {static_cast<double>(state_.step), state_.time, m.order, m.msd, pair.energy});
        if (inertial())
            values.insert(values.end(), {m.kinetic, m.temperature, pair.energy + m.kinetic});
        if (thermostat_) values.push_back(pair.energy + m.kinetic + thermostat_->bath_energy());
        values.insert(values.end(), {pressure, m.ideal, virial, m.active});
        for (int slot : sym_slots<D>())
            values.push_back(m.ideal_tensor[slot] + pair.virial_tensor[slot] / V +
                             m.active_tensor[slot]);
        add_term_values(values);
        if (c_.barostat.on) values.push_back(V);
        if (minimize_) minimize_->add_values(values);
        values.push_back(static_cast<double>(evolver_->list_builds()));
        if (state_.step > 0) {
            if (state_.box.sheared()) {
                // (one process: shear is refused under a decomposition)
                book_.shear.add_profile(state_.p, state_.box);
                book_.shear.shear_stress.push_back(m.ideal_tensor[3] + pair.virial_tensor[3] / V +
                                                   m.active_tensor[3]);
            }
            ++book_.samples;
            book_.sum_pressure += pressure;
            book_.sum_polar_order += m.order;
            book_.sum_temperature += m.temperature;
        }
        progress(m, pressure);
    }

    void start(bool fresh) override {
        console_ << fmt::format(
            "pedesis: {}D {} run, N = {}, box {}, dt = {:g}, {} steps, list cutoff {:g} + "
            "skin {:g}, output in {}\n",
            D, c_.dynamics, particles_, box_text(), c_.dt, c_.steps, evolver_->list_cutoff(),
            evolver_->skin(), o_.out_dir.string());
        if (domain_) {
            std::string grid;
            for (int a = 0; a < D; ++a)
                grid += fmt::format("{}{}", a ? " x " : "", domain_->grid()[a]);
            console_ << fmt::format("  {} MPI processes, domains {}\n", o_.comm->size(), grid);
        }
        if (const auto* device = evolver_->device())
            console_ << fmt::format("  on the GPU: {}\n", device->description());
        else
            console_ << fmt::format("  CPU kernels: {}, pair math in {}{}\n",
                                    simd_name(simd_level()), precision_name(pair_precision()),
                                    c_.precision == pair_precision()
                                        ? ""
                                        : " (precision = \"mixed\" needs one radius and one "
                                          "evaluator per force, and the avx2 or avx512 kernels)");
        if (state_.box.sheared())
            console_ << fmt::format("  Lees–Edwards shear at rate {:g}: flow along x, gradient "
                                    "along y, velocities peculiar\n",
                                    state_.box.shear_rate());
        if (fresh) evolver_->compute_forces(); // so that frame 0 shows them; the step reuses them
        if (minimize_) minimize_->start(state_);
        whole_current_ = false;
        wall_start_ = std::chrono::steady_clock::now();
        step_start_ = state_.step;
        // The clock of a run that kept its dt from step 0 is step * dt: a restart (or a
        // --resume at any step) that finds its time there keeps that origin, so that its
        // times are bit for bit those of the run that never stopped; a time elsewhere (dt
        // changed at an earlier restart) starts the clock from the checkpoint.
        const bool on_the_clock = static_cast<double>(state_.step) * c_.dt == state_.time;
        clock_t0_ = on_the_clock ? 0.0 : state_.time;
        clock_step0_ = on_the_clock ? 0 : state_.step;
    }

    nlohmann::json summary(const char* /*stopped_by*/) override {
        const double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
        const SoftState<D>& whole_state = whole();
        nlohmann::json j;
        if (domain_) {
            // for benchmarks, over the steps (outputs excluded): seconds, seconds in MPI
            // calls (waiting for the others included) and bytes sent, with the ghosts held
            const double steps = std::max(1.0, static_cast<double>(state_.step - step_start_));
            double per_process[4] = {stepping_.seconds, stepping_.communication_seconds,
                                     stepping_.bytes_sent, static_cast<double>(state_.ghosts)};
            double total[4] = {per_process[0], per_process[1], per_process[2], per_process[3]};
            o_.comm->sum(total);
            o_.comm->max(per_process);
            const double p = o_.comm->size();
            j["mpi"] = {{"processes", o_.comm->size()},
                        {"domain_grid", domain_->grid()},
                        {"stepping_seconds_max", per_process[0]},
                        {"communication_seconds_mean", total[1] / p},
                        {"communication_seconds_max", per_process[1]},
                        {"bytes_sent_per_step", total[2] / steps},
                        {"ghosts", total[3]}};
        }
        if (!writer()) return j;
        j["dimension"] = D;
        j["dynamics"] = c_.dynamics;
        j["device"] = on_gpu() ? "gpu" : "cpu";
        if (!on_gpu()) j["cpu_kernels"] = simd_name(simd_level());
        j["precision"] = precision_name(pair_precision());
        j["particles"] = particles_;
        j["steps"] = state_.step;
        j["time"] = state_.time;
        j["dt"] = c_.dt;
        j["polar_order"] = polar_order(whole_state);
        j["msd"] = mean_squared_displacement(whole_state, book_.start);
        j["mean_pressure"] = book_.samples ? book_.sum_pressure / book_.samples : 0.0;
        j["mean_polar_order"] = book_.samples ? book_.sum_polar_order / book_.samples : 0.0;
        j["logged_samples"] = book_.samples;
        if (inertial()) {
            const SpeciesKinetics k = measure_kinetics(whole_state.p, whole_state.box, momentum_);
            j["temperature"] = k.temperature();
            j["mean_temperature"] = book_.samples ? book_.sum_temperature / book_.samples : 0.0;
            j["degrees_of_freedom"] = k.total_freedom;
        }
        if (state_.box.sheared()) j["shear"] = book_.shear.summary(state_.box.shear_rate());
        if (book_.transport)
            j["transport"] = book_.transport->summary(transport_scales(
                c_, state_.box, whole_state.p, j["mean_temperature"].template get<double>()));
        if (minimize_) minimize_->add_summary(j);
        j["list_rebuilds"] = evolver_->list_builds();
        j["frames"] = book_.frames;
        j["wall_seconds"] = wall;
        j["particle_steps_per_second"] = rate(wall); // the same window as wall_seconds
        j["stepping_seconds"] = stepping_.seconds;
        return j;
    }

    void finish(const nlohmann::json& j) override {
        if (!writer()) return;
        const bool interrupted = j["stopped_by"] == "interrupted";
        console_ << fmt::format("pedesis: {} at step {} (t = {:.6g}) in {:.3g} s, {:.3g} "
                                "particle-steps/s, {} list rebuilds\n",
                                interrupted ? "stopped" : "done", state_.step, state_.time,
                                j["wall_seconds"].template get<double>(),
                                j["particle_steps_per_second"].template get<double>(),
                                evolver_->list_builds());
        const double msd = j["msd"].template get<double>();
        const double mean_pressure = j["mean_pressure"].template get<double>();
        // the quantities this system has: directors only where the dynamics moves or
        // uses them, a temperature only where particles have velocities
        const nlohmann::json& last = j.at("final");
        if (directors_matter())
            console_ << fmt::format("  polar order {:.4f} (run mean {:.4f}), MSD {:.6g}, mean "
                                    "pressure {:.6g}\n",
                                    j["polar_order"].template get<double>(),
                                    j["mean_polar_order"].template get<double>(), msd,
                                    mean_pressure);
        else if (inertial())
            console_ << fmt::format(
                "  temperature {:.6g} (run mean {:.6g}), potential energy {:.6g}, total energy "
                "{:.6g}, MSD {:.6g}, mean pressure {:.6g}\n",
                j["temperature"].template get<double>(),
                j["mean_temperature"].template get<double>(),
                last.at("potential_energy").template get<double>(),
                last.at("total_energy").template get<double>(), msd, mean_pressure);
        else
            console_ << fmt::format("  potential energy {:.6g}, MSD {:.6g}, mean pressure {:.6g}\n",
                                    last.at("potential_energy").template get<double>(), msd,
                                    mean_pressure);
        if (state_.box.sheared())
            write_shear_results(o_.out_dir, book_.shear, state_.box, j, console_);
        if (book_.transport) {
            book_.transport->write_csv(
                o_.out_dir / "transport.csv",
                transport_scales(c_, state_.box, whole().p,
                                 j["mean_temperature"].template get<double>()));
            print_transport(console_, j["transport"]);
        }
        if (minimize_) minimize_->print_end(console_, j, o_.out_dir);
        console_ << fmt::format("  outputs            {}\n", o_.out_dir.string());
    }

    OutputChoice outputs() const {
        return {c_.formats, c_.log_quantities, c_.log_quantities_where};
    }

    // temperature: of the position integrators (brownian, langevin), every species;
    // alpha: of self_propulsion, every species; J: of polar_align.
    std::vector<std::pair<std::string, double>> steerable() const override {
        std::vector<std::pair<std::string, double>> out;
        const std::size_t ns = state_.p.species_table.size();
        for (const auto& i : evolver_->integrators()) {
            if (const auto* b = dynamic_cast<const BrownianIntegrator<D>*>(i.get()))
                out.emplace_back("temperature", b->temperature().at(0, ns));
            else if (const auto* l = dynamic_cast<const LangevinIntegrator<D>*>(i.get()))
                out.emplace_back("temperature", l->temperature().at(0, ns));
            if (!out.empty()) break;
        }
        for (const auto& f : evolver_->forces())
            if (const auto* p = dynamic_cast<const SelfPropulsion<D>*>(f.get())) {
                out.emplace_back("alpha", p->alpha().at(0, ns));
                break;
            }
        for (const auto& t : evolver_->torques())
            if (const auto* a = dynamic_cast<const PolarAlign<D>*>(t.get())) {
                out.emplace_back("J", a->coupling());
                break;
            }
        return out;
    }

    void steer(const std::string& name, double value) override {
        bool found = false;
        if (name == "temperature")
            for (const auto& i : evolver_->integrators()) {
                if (auto* b = dynamic_cast<BrownianIntegrator<D>*>(i.get())) {
                    b->set_temperature(value);
                    found = true;
                } else if (auto* l = dynamic_cast<LangevinIntegrator<D>*>(i.get())) {
                    l->set_temperature(value);
                    found = true;
                }
            }
        else if (name == "alpha")
            for (const auto& f : evolver_->forces()) {
                if (auto* p = dynamic_cast<SelfPropulsion<D>*>(f.get())) {
                    p->set_alpha(value);
                    found = true;
                }
            }
        else if (name == "J")
            for (const auto& t : evolver_->torques())
                if (auto* a = dynamic_cast<PolarAlign<D>*>(t.get())) {
                    a->set_coupling(value);
                    found = true;
                }
        if (!found) RunEngine<D>::steer(name, value);
        // the logged ideal pressure of an overdamped run is n T of its bath
        read_observable_parameters(state_.p.species_table);
        read_swim_forces();
    }

  private:
    // A walled axis keeps its particles in by a wall force, and a planes wall needs a
    // walled axis; two terms must not log the same column.
    void check_walls() const {
        bool planes = false;
        for (const auto& f : evolver_->forces())
            if (const auto* w = dynamic_cast<const WallForce<D>*>(f.get()))
                planes = planes || w->shape() == WallShape::planes;
        const std::string where = c_.boundary_where.empty() ? c_.file : c_.boundary_where;
        if (!planes) {
            for (int a = 0; a < D; ++a)
                if (!state_.box.periodic(a))
                    throw InputError(fmt::format(
                        "{}: axis {} is a wall, and the {} engine keeps particles in by a wall "
                        "force: add [[force]] name = \"wall\" (potential = \"wca\", \"lj93\" "
                        "or \"harmonic\")",
                        where, "xyz"[a], c_.dynamics));
        } else if (!state_.box.any_wall()) {
            throw InputError(c_.file + ": a wall of shape \"planes\" stands on the box's walled "
                                       "faces, and every axis is periodic: set [box] boundary = "
                                       "\"wall\" on an axis, or give the wall shape = \"sphere\" "
                                       "or \"cylinder\"");
        }
        if (!o_.restart)
            for (const auto& f : evolver_->forces())
                if (const auto* w = dynamic_cast<const WallForce<D>*>(f.get());
                    w && w->first_outside(state_) >= 0) {
                    const auto i = static_cast<std::size_t>(w->first_outside(state_));
                    throw InputError(fmt::format(
                        "{}: particle {} starts on or beyond a wall (at {}), where a wca or lj93 "
                        "wall cannot push it back: place the particles inside (a [[species]] "
                        "region within the container), or use potential = \"harmonic\"",
                        c_.file, state_.p.tag[i], fmt::join(state_.p.position[i].c, ", ")));
                }
        std::vector<std::string> seen;
        for (const auto& f : evolver_->forces())
            for (const std::string& column : f->log_columns(state_)) {
                if (std::find(seen.begin(), seen.end(), column) != seen.end())
                    throw InputError(c_.file + ": two " + f->name() + " forces would both log " +
                                     column + ": give one [[force]] of each kind and shape");
                seen.push_back(column);
            }
    }

    // [transport]: D, eta and kappa of inertial dynamics, on one process on the CPU,
    // without shear (under shear summary.json's "shear" gives eta); the measurement
    // starts now unless the checkpoint carries one.
    void start_transport_if_asked() {
        if (!c_.transport.on) {
            book_.transport.reset();
            return;
        }
        const std::string& where = c_.transport.where;
        if (!inertial())
            throw InputError(where + ": transport coefficients need dynamics that carry "
                                     "momentum (langevin or nve); a brownian run's D is the "
                                     "slope of its msd column");
        if ((o_.comm && o_.comm->size() > 1) || on_gpu())
            throw InputError(where + ": [transport] runs on one process, on the CPU");
        if (state_.box.sheared())
            throw InputError(where + ": not under shear: summary.json's \"shear\" gives the "
                                     "viscosity of a sheared run");
        if (!book_.transport) {
            double contact = 0.0; // the potential's core between like particles
            for (const auto& f : evolver_->forces())
                contact = std::max(contact, f->core(state_, 0, 0));
            // the heat flux needs energy conservation and pair energies only
            Vec<D> probe{};
            const bool heat = c_.dynamics == "nve" && evolver_->heat_flux(particle_energy_, probe);
            book_.transport.emplace(
                start_transport<D>(c_, state_.p, state_.box, state_.time, c_.dt, contact, heat));
        }
        const auto& plan = book_.transport->plan();
        per_sample_ = static_cast<std::uint64_t>(std::max(1.0, std::round(plan.interval / c_.dt)));
        // (a run's clock is step x dt from its start: the measurement's start is a step)
        first_sample_ = static_cast<std::uint64_t>(std::max(0.0, std::round(plan.start / c_.dt)));
    }
    std::uint64_t transport_step() const {
        return first_sample_ + book_.transport->samples() * per_sample_;
    }
    // The pressure tensor times V (kinetic and pair virial), and the followed particles by
    // tag (the storage order changes with sorting).
    void sample_transport() {
        auto& m = *book_.transport;
        // (with the heat flux, its pass gives the pair virial too)
        SymTensor vp{};
        Vec<D> heat{};
        const bool with_heat = m.plan().heat && evolver_->heat_flux(particle_energy_, heat, &vp);
        if (!with_heat) vp = evolver_->pair_totals().virial_tensor;
        for (std::size_t i = 0; i < state_.size(); ++i) {
            const double mass = state_.p.mass(i);
            if (std::isfinite(mass))
                add_sym_outer<D>(vp, state_.p.velocity[i], state_.p.velocity[i], mass);
        }
        const std::size_t k = m.plan().particles;
        positions_.assign(m.positions_due() ? k : 0, Vec<D>{});
        velocities_.assign(m.velocities_due() ? k : 0, Vec<D>{});
        for (std::size_t i = 0; i < state_.size(); ++i) {
            const std::uint32_t tag = state_.p.tag[i];
            if (tag >= k) continue;
            if (!positions_.empty()) positions_[tag] = state_.unwrapped(i);
            if (!velocities_.empty()) velocities_[tag] = state_.p.velocity[i];
        }
        m.add_flux(vp, with_heat ? &heat : nullptr, positions_, velocities_);
    }

    // Lees–Edwards shear runs on one process, on the CPU (gpu_model refuses it), and needs
    // the streaming at the y faces, rate L_y / 2 per unit time, to move particles less
    // than half the list's skin a step (else every step would rebuild the list, and the
    // move check would call the flow a blow-up).
    void check_shear() {
        if (!state_.box.sheared()) return;
        const std::string where = c_.shear_where.empty() ? c_.file : c_.shear_where;
        if (o_.comm && o_.comm->size() > 1)
            throw InputError(where + ": Lees–Edwards shear runs on one process: start it "
                                     "without mpirun");
        const double stream = 0.5 * state_.box.shear_rate() * state_.box.length(1) * c_.dt;
        // (with no skin, the cutoff bounds a step's move: Evolver::step)
        const double skin =
            evolver_->skin() > 0.0 ? evolver_->skin() : evolver_->interaction_reach();
        if (!(stream < 0.5 * skin))
            throw InputError(fmt::format(
                "{}: the flow moves particles at the y faces by shear_rate L_y dt / 2 = {:g} a "
                "step, not less than half the neighbour list's skin ({:g}): lower dt or "
                "shear_rate, or raise [neighbor_list] skin",
                where, stream, skin));
    }

    // The log's one-body quantities at this instant; the tensors are pressure parts.
    struct Measured {
        double order = 0.0, msd = 0.0, kinetic = 0.0, temperature = 0.0, ideal = 0.0, active = 0.0;
        SymTensor ideal_tensor{}, active_tensor{};
    };

    // The forces' own columns (ForceTerm::log_values): sums over each process's particles.
    void add_term_values(std::vector<double>& values) {
        term_values_.clear();
        for (const auto& f : evolver_->forces()) f->log_values(state_, term_values_);
        if (domain_) o_.comm->sum(std::span<double>(term_values_));
        values.insert(values.end(), term_values_.begin(), term_values_.end());
    }

    // The active force along the director of each species (for the swim pressure's sums).
    void read_swim_forces() {
        const std::size_t species = state_.p.species_table.size();
        swim_alpha_.assign(species, 0.0);
        for (std::size_t sp = 0; sp < species; ++sp)
            for (const auto& f : evolver_->forces()) swim_alpha_[sp] += f->swim_force(sp, species);
    }

    // active_ou's force is gamma p with the position integrator's friction, and its active
    // velocities stay on one process: both refused at set-up rather than at the first step.
    // An NVT thermostat (bussi, nose_hoover) measures the temperature as the log does
    // (under a decomposition it sums over the processes: Evolver::set_domain).
    void check_thermostat() {
        thermostat_ = nullptr;
        for (const auto& i : evolver_->integrators())
            if (!std::isnan(i->bath_energy())) thermostat_ = i.get();
        if (thermostat_)
            thermostat_->set_conserved_momentum(
                conserved_momentum_axes(state_.p, state_.box, momentum_));
    }

    void check_active_ou() const {
        for (const auto& f : evolver_->forces())
            if (const auto* ou = dynamic_cast<const ActiveOU<D>*>(f.get())) {
                try {
                    ou->frictions(state_);
                } catch (const InputError& e) {
                    throw InputError(c_.file + ": " + e.what());
                }
                if (o_.comm && o_.comm->size() > 1)
                    throw InputError(c_.file + ": active_ou runs on one process: its particles' "
                                               "active velocities do not travel between "
                                               "processes; start it without mpirun");
            }
    }

    // The active forces beyond the directors' (active_ou), per owned particle, or none.
    const std::vector<Vec<D>>& active_forces() const {
        active_forces_.clear();
        for (const auto& f : evolver_->forces()) f->add_active_forces(state_, active_forces_);
        return active_forces_;
    }

    // An overdamped run's ideal part is the bath's n T, isotropic.
    void isotropic_ideal(Measured& m) const {
        for (int a = 0; a < D; ++a) m.ideal_tensor[a] = m.ideal;
    }

    // From the whole state, on one process.
    Measured measured_here() const {
        const auto& s = state_;
        const double V = s.box.volume();
        Measured m;
        if (inertial()) {
            // the kinetic part of P V is 2 K / d in the centre-of-mass frame, f T / d
            const SpeciesKinetics k = measure_kinetics(s.p, s.box, momentum_);
            m.ideal = 2.0 * k.total_thermal / (D * V);
            m.kinetic = k.total_kinetic;
            m.temperature = k.temperature();
            for (int c = 0; c < 6; ++c) m.ideal_tensor[c] = k.thermal_tensor[c] / V;
        } else {
            for (std::size_t i = 0; i < s.size(); ++i) m.ideal += bath_T_[s.p.species[i]];
            m.ideal /= V;
            isotropic_ideal(m);
        }
        for (const auto& f : evolver_->forces()) m.active += f->swim_pressure(s, book_.start);
        const SymTensor swim =
            swim_tensor_of(soft_log_sums(s, book_.start, swim_alpha_, active_forces()));
        for (int c = 0; c < 6; ++c) m.active_tensor[c] = swim[c] / V;
        m.order = polar_order(s);
        m.msd = mean_squared_displacement(s, book_.start);
        return m;
    }

    // The same from the sums of every process's particles (collective): the formulas of
    // measured_here, rearranged so that each is a function of sums (SoftLogSums).
    Measured measured_shared() const {
        const SoftLogSums<D> mine =
            soft_log_sums(state_, book_.start, swim_alpha_, active_forces());
        auto flat = mine.flat();
        o_.comm->sum(flat);
        const SoftLogSums<D> t = SoftLogSums<D>::from_flat(flat);
        const double V = state_.box.volume(), n = t.particles;
        Measured m;
        m.order = norm(t.director) / n;
        m.msd = t.squared_displacement / n;
        // sum alpha n . (dr - drift), with drift the mean displacement
        m.active = (t.swim - dot(t.displacement * (1.0 / n), t.swim_direction)) / (D * V);
        const SymTensor swim = swim_tensor_of(t);
        for (int c = 0; c < 6; ++c) m.active_tensor[c] = swim[c] / V;
        if (inertial()) {
            // sum m (v - V)^2 / 2 along the conserved axes is sum m v^2 / 2 - P^2 / 2M
            double thermal = t.kinetic;
            int conserved = 0;
            for (int a = 0; a < D; ++a)
                if (conserved_[a]) {
                    ++conserved;
                    if (t.mass > 0.0) thermal -= 0.5 * t.momentum[a] * t.momentum[a] / t.mass;
                }
            const double freedom = t.mobile > 0.0 ? D * t.mobile - conserved : 0.0;
            m.kinetic = t.kinetic;
            m.temperature = freedom > 0.0 ? 2.0 * thermal / freedom : 0.0;
            m.ideal = 2.0 * thermal / (D * V);
            const SymTensor k = thermal_tensor_of<D>(t, conserved_);
            for (int c = 0; c < 6; ++c) m.ideal_tensor[c] = k[c] / V;
        } else {
            for (std::size_t sp = 0; sp < species_count_.size(); ++sp)
                m.ideal += species_count_[sp] * bath_T_[sp];
            m.ideal /= V;
            isotropic_ideal(m);
        }
        return m;
    }

    // The barostat scales a periodic box, on one process and on the CPU.
    void check_barostat() const {
        if (!c_.barostat.on) return;
        const std::string& where = c_.barostat.where;
        if (o_.comm && o_.comm->size() > 1)
            throw InputError(where + ": the barostat runs on one process (the domains would "
                                     "have to follow the box); start it without mpirun");
        if (on_gpu())
            throw InputError(where + ": the barostat runs on the CPU; set device = \"cpu\"");
        if (state_.box.any_wall())
            throw InputError(where + ": the barostat scales a periodic box, and this one has "
                                     "walls ([box] boundary)");
        if (c_.shear_rate > 0.0)
            throw InputError(where + ": the barostat and Lees-Edwards shear ([box] shear_rate) "
                                     "cannot run together");
    }

    // The plug-ins say what the logs need: an overdamped position integrator (its bath
    // temperature gives the ideal-gas pressure) and the forces' swim pressure.
    void read_observable_parameters(const std::vector<Species>& table) {
        overdamped_ = nullptr;
        for (const auto& i : evolver_->integrators())
            if (i->overdamped_positions()) overdamped_ = i.get();
        if (overdamped_) {
            bath_T_.resize(table.size());
            for (std::size_t s = 0; s < table.size(); ++s)
                bath_T_[s] = overdamped_->bath_temperature(s, table.size());
        }
    }

    std::string box_text() const {
        std::string s;
        for (int a = 0; a < D; ++a)
            s += fmt::format("{}{:g}", a ? " x " : "", state_.box.length(a));
        return s;
    }

    bool inertial() const { return overdamped_ == nullptr; }
    bool on_gpu() const { return o_.device.value_or(c_.device) == "gpu"; }
    // The precision the pair math runs in: mixed where every pair force's rows are
    // (PairForce::rows_precision), double otherwise.
    Precision pair_precision() const {
        bool mixed = c_.precision == Precision::mixed && !on_gpu(), any = false;
        for (const auto& f : evolver_->forces())
            if (const auto p = f->rows_precision(state_)) {
                mixed = mixed && *p == Precision::mixed;
                any = true;
            }
        return mixed && any ? Precision::mixed : Precision::full;
    }

    // Whether this process writes and prints (process 0, or the only one).
    bool writer() const { return !domain_ || o_.comm->rank() == 0; }

    // The whole state in tag order: this process's own on one process; under a domain
    // decomposition gathered on process 0 once per state (collective).
    const SoftState<D>& whole() {
        if (!domain_) {
            evolver_->sync_host();
            return state_;
        }
        if (!whole_current_) {
            domain_->gather(state_, whole_);
            if (writer() && whole_.size() != particles_)
                throw std::logic_error(fmt::format("domain decomposition: {} particles of {} "
                                                   "were gathered",
                                                   whole_.size(), particles_));
        }
        whole_current_ = true;
        return whole_;
    }

    void progress(const Measured& m, double pressure) {
        if (!c_.progress) return;
        const auto now = std::chrono::steady_clock::now();
        if (last_progress_ && now - *last_progress_ < std::chrono::seconds(1)) return;
        last_progress_ = now;
        // as at the end of the run: what this system has (see finish)
        const std::string shown = minimize_ ? minimize_->progress()
                                  : directors_matter()
                                      ? fmt::format("polar order = {:<8.4f}", m.order)
                                  : inertial() ? fmt::format("T = {:<10.5g}", m.temperature)
                                               : fmt::format("MSD = {:<10.5g}", m.msd);
        console_ << fmt::format("  step {:<10} t = {:<10.5g} {} P = {:<10.5g} "
                                "{:.3g} particle-steps/s\n",
                                state_.step, state_.time, shown, pressure, rate());
    }

    // Whether the directors take part in the dynamics: a self-propulsion force, a torque
    // or rotational diffusion. Only then is their polar order a property of the run; a
    // passive system (LJ, WCA) keeps the random directors of its start, and their order
    // would only measure the size of the sample.
    bool directors_matter() const {
        if (!evolver_->torques().empty()) return true;
        for (const auto& f : evolver_->forces())
            if (dynamic_cast<const SelfPropulsion<D>*>(f.get())) return true;
        for (const auto& i : evolver_->integrators())
            if (dynamic_cast<const BrownianRotationIntegrator<D>*>(i.get()) ||
                dynamic_cast<const RunAndTumble<D>*>(i.get()))
                return true;
        return false;
    }

    double rate() const {
        return rate(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count());
    }
    double rate(double wall) const {
        return wall > 0 ? static_cast<double>(state_.step - step_start_) *
                              static_cast<double>(particles_) / wall
                        : 0.0;
    }

    const RunConfig c_;
    const RunOptions& o_;
    std::ostream& console_;
    SoftState<D> state_; // under a domain decomposition: this process's share and ghosts
    std::unique_ptr<Evolver<D>> evolver_;
    std::unique_ptr<DomainDecomposition<D>> domain_;
    // FIRE's stopping and columns, for dynamics = "minimize"
    std::optional<SoftMinimization<D>> minimize_;
    SoftState<D> whole_; // gathered, on process 0
    bool whole_current_ = false;
    std::size_t particles_ = 0; // in the whole system
    // for measured_shared: the axes of conserved momentum, the particles of each species,
    // and each species's active force
    std::array<bool, D> conserved_{};
    std::vector<double> species_count_; // of the whole system
    std::vector<double> swim_alpha_;
    mutable std::vector<Vec<D>> active_forces_; // (reused at every log row)
    std::vector<double> term_values_;           // add_term_values' scratch
    struct {
        double seconds = 0.0, communication_seconds = 0.0, bytes_sent = 0.0;
    } stepping_; // by this invocation
    SoftRunBook<D> book_;
    const Integrator<D>* overdamped_ = nullptr;
    Integrator<D>* thermostat_ = nullptr; // bussi or nose_hoover: the bath of conserved_energy
    std::vector<double> bath_T_;          // per species, of the overdamped integrator
    const Momentum momentum_ = momentum_of(c_);
    std::uint64_t step_start_ = 0; // of this invocation, for its speed
    double clock_t0_ = 0.0;        // the origin of the clock (SoftClock)
    std::uint64_t clock_step0_ = 0;
    std::uint64_t per_sample_ = 1, first_sample_ = 0; // [transport]'s steps
    std::vector<Vec<D>> positions_, velocities_;      // a sample's followed particles
    std::vector<double> particle_energy_;             // the heat flux's scratch
    std::chrono::steady_clock::time_point wall_start_ = std::chrono::steady_clock::now();
    std::optional<std::chrono::steady_clock::time_point> last_progress_;
};

} // namespace

template <int D>
EngineSetup<D> soft_engine_setup(const RunConfig& config, const RunOptions& options,
                                 std::ostream& console) {
    std::unique_ptr<SoftRunEngine<D>> engine;
    try {
        engine = std::make_unique<SoftRunEngine<D>>(config, options, console);
    } catch (const InputError& e) {
        // the neighbour list knows the box and the cutoff, not the file they came from
        const std::string what = e.what();
        if (!what.starts_with("neighbour list:")) throw;
        const bool box_from_file = config.box_lengths.empty() && config.initial_file;
        throw InputError(fmt::format(
            "{}: {}; make the box{} larger, or the cutoff ([neighbor_list] r_cut, the forces' "
            "ranges) or [neighbor_list] skin smaller",
            box_from_file || config.lengths_where.empty() ? config.file : config.lengths_where,
            what,
            box_from_file ? " (of the [initial] file " + *config.initial_file + ")"
                          : std::string(" ([box] length)")));
    }
    EngineSetup<D> setup{nullptr, engine->schedule(), engine->outputs()};
    setup.engine = std::move(engine);
    return setup;
}

template EngineSetup<2> soft_engine_setup<2>(const RunConfig&, const RunOptions&, std::ostream&);
template EngineSetup<3> soft_engine_setup<3>(const RunConfig&, const RunOptions&, std::ostream&);

} // namespace pedesis
