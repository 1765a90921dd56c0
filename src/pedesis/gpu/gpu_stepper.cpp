#include "pedesis/gpu/gpu_stepper.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/gpu/device_system.hpp"
#include "pedesis/soft/blow_up.hpp"
#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/langevin.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"
#include "pedesis/soft/polar_align.hpp"
#include "pedesis/soft/self_propulsion.hpp"
#include "pedesis/soft/velocity_verlet.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace pedesis {

std::string gpu_unavailable_reason() {
    if (!gpu::cuda_built())
        return "this pedesis was built without CUDA (configure with -DPEDESIS_CUDA=ON where "
               "CUDA's compiler is installed; see docs/gpu.md)";
    const std::string why = gpu::unavailable_reason();
    return why.empty() ? why : "no GPU to run on: " + why;
}

namespace {

template <int D, class Pair>
bool read_pair(const ForceTerm<D>& f, std::size_t ns, std::vector<Pair>& table) {
    const auto* term = dynamic_cast<const PairForce<D, Pair>*>(&f);
    if (!term) return false;
    table.clear();
    for (std::size_t a = 0; a < ns; ++a)
        for (std::size_t b = 0; b < ns; ++b) table.push_back(term->pair(a, b));
    return true;
}

// The device kernels draw Gaussian noise only.
void gaussian_noise_only(detail::NoiseShape shape, const char* integrator) {
    if (shape != detail::NoiseShape::gaussian)
        throw InputError(std::string("device = \"gpu\" draws Gaussian noise only: ") + integrator +
                         "'s uniform_noise runs on the CPU (device = \"cpu\")");
}

} // namespace

template <int D> gpu::Model gpu_model(const SoftState<D>& s, Evolver<D>& evolver) {
    gpu::Model m;
    m.dim = D;
    m.particles = s.size();
    m.species = s.p.species_table.size();
    if (s.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
        throw InputError(fmt::format("device = \"gpu\" runs at most {} particles",
                                     std::numeric_limits<int>::max()));
    for (const auto& sp : s.p.species_table) m.radius.push_back(sp.radius);
    const double reach = evolver.interaction_reach();
    m.skin = evolver.skin();
    m.r_cut = evolver.list_cutoff();
    // (its kernels know no sliding images, nor SLLOD's peculiar velocities)
    if (s.box.sheared())
        throw InputError("device = \"gpu\" does not run Lees–Edwards shear ([box] shear_rate); "
                         "run it on the CPU");
    for (int a = 0; a < D; ++a) {
        if (!s.box.periodic(a))
            throw InputError("device = \"gpu\" runs periodic boxes only (axis " +
                             std::to_string(a) + " is a wall)");
        // one image of each neighbour within the list's range, by the minimum image
        if (!(s.box.length(a) > 2.0 * reach))
            throw InputError(fmt::format(
                "device = \"gpu\" needs the box longer than twice the list's range "
                "(cutoff + skin = {:g}) on every axis, and axis {} is {:g} long; use a larger "
                "box, or the CPU",
                reach, a, s.box.length(a)));
        m.box[a] = s.box.length(a);
    }
    const std::size_t ns = m.species;
    int pair_terms = 0;
    for (const auto& f : evolver.forces()) {
        if (read_pair<D>(*f, ns, m.harmonic))
            m.pair = gpu::PairKind::harmonic;
        else if (read_pair<D>(*f, ns, m.wca))
            m.pair = gpu::PairKind::wca;
        else if (read_pair<D>(*f, ns, m.lj))
            m.pair = gpu::PairKind::lj;
        else if (dynamic_cast<const SelfPropulsion<D>*>(f.get())) {
            m.propulsion = true;
            continue;
        } else
            throw InputError("device = \"gpu\" does not run the force '" + f->name() + "'");
        if (++pair_terms > 1)
            throw InputError("device = \"gpu\" runs one pair force per run; this config has more "
                             "(run it on the CPU)");
    }
    int aligners = 0;
    for (const auto& t : evolver.torques()) {
        const auto* a = dynamic_cast<const PolarAlign<D>*>(t.get());
        if (!a) throw InputError("device = \"gpu\" does not run the torque '" + t->name() + "'");
        if (++aligners > 1)
            throw InputError("device = \"gpu\" runs one polar_align per run; this config has more");
        m.align = true;
        m.align_range = a->range(s);
    }
    for (const auto& i : evolver.integrators()) {
        gpu::Mover mover = gpu::Mover::none;
        if (const auto* b = dynamic_cast<const BrownianIntegrator<D>*>(i.get())) {
            mover = gpu::Mover::brownian;
            m.seed = b->seed();
            gaussian_noise_only(b->noise_shape(), "brownian");
        } else if (const auto* l = dynamic_cast<const LangevinIntegrator<D>*>(i.get())) {
            mover = gpu::Mover::langevin;
            m.seed = l->seed();
            gaussian_noise_only(l->noise_shape(), "langevin");
        } else if (dynamic_cast<const VelocityVerletIntegrator<D>*>(i.get())) {
            mover = gpu::Mover::nve;
        } else if (const auto* r = dynamic_cast<const BrownianRotationIntegrator<D>*>(i.get())) {
            if (m.rotation) throw InputError("device = \"gpu\" runs one brownian_rotation per run");
            m.rotation = true;
            m.rotation_seed = r->seed();
            continue;
        } else
            throw InputError("device = \"gpu\" does not run the integrator '" + i->name() + "'");
        if (m.mover != gpu::Mover::none)
            throw InputError("device = \"gpu\" runs one position integrator per run");
        m.mover = mover;
    }
    return m;
}

template <int D>
gpu::StepCoefficients gpu_coefficients(const SoftState<D>& s, const Evolver<D>& evolver, double dt,
                                       double max_move) {
    const auto& table = s.p.species_table;
    const std::size_t ns = table.size();
    gpu::StepCoefficients c;
    c.species.assign(ns, gpu::SpeciesCoefficients{});
    c.dt = dt;
    c.max_move = max_move;
    for (const auto& f : evolver.forces())
        if (const auto* p = dynamic_cast<const SelfPropulsion<D>*>(f.get()))
            for (std::size_t k = 0; k < ns; ++k) c.species[k].alpha += p->alpha().at(k, ns);
    for (const auto& t : evolver.torques())
        if (const auto* a = dynamic_cast<const PolarAlign<D>*>(t.get())) c.J = a->coupling();
    for (const auto& i : evolver.integrators()) {
        if (const auto* b = dynamic_cast<const BrownianIntegrator<D>*>(i.get())) {
            detail::OverdampedCoefficients o;
            o.update(b->temperature(), b->gamma(), ns, dt);
            for (std::size_t k = 0; k < ns; ++k) {
                c.species[k].drift = o.drift[k];
                c.species[k].kick = o.kick[k];
            }
            c.noisy = o.noisy;
        } else if (const auto* r = dynamic_cast<const BrownianRotationIntegrator<D>*>(i.get())) {
            detail::OverdampedCoefficients o;
            o.update(r->temperature(), r->gamma(), ns, dt);
            for (std::size_t k = 0; k < ns; ++k) {
                c.species[k].rot_drift = o.drift[k];
                c.species[k].rot_kick = o.kick[k];
            }
            c.rot_noisy = o.noisy;
        } else if (const auto* l = dynamic_cast<const LangevinIntegrator<D>*>(i.get())) {
            detail::LangevinCoefficients o;
            o.update(l->temperature(), l->gamma(), table, dt);
            for (std::size_t k = 0; k < ns; ++k) {
                c.species[k].half_kick = o.kick[k];
                c.species[k].half_drift = o.half_drift[k];
                c.species[k].damp = o.damp[k];
                c.species[k].noise = o.noise[k];
            }
            c.noisy = o.noisy;
        } else if (dynamic_cast<const VelocityVerletIntegrator<D>*>(i.get())) {
            std::vector<double> kick, drift;
            VelocityVerletIntegrator<D>::tabulate(table, dt, kick, drift);
            for (std::size_t k = 0; k < ns; ++k) {
                c.species[k].half_kick = kick[k];
                c.species[k].half_drift = drift[k];
            }
        }
    }
    return c;
}

namespace {

template <int D> class GpuStepper final : public DeviceStepper<D> {
  public:
    GpuStepper(SoftState<D>& s, Evolver<D>& evolver, const std::vector<Vec<D>>& reference)
        : s_(s), evolver_(evolver), system_(gpu_model(s, evolver)) {
        if (s.ghosts != 0) throw InputError("device = \"gpu\" runs on one process");
        if (!reference.empty() && reference.size() != s.size())
            throw std::logic_error("gpu: a list reference of another size");
        guarded(
            [&] { system_.upload(arrays(), reference.empty() ? nullptr : reference[0].c.data()); });
        description_ = gpu::device_description();
    }

    std::string description() const override { return description_; }

    std::uint64_t step(double dt, double max_move) override {
        std::uint64_t builds = 0;
        guarded([&] {
            system_.set_coefficients(gpu_coefficients(s_, evolver_, dt, max_move));
            const auto step = static_cast<std::uint32_t>(s_.step);
            check_move(system_.prestep(step), max_move);
            builds = system_.compute_forces() ? 1 : 0;
            check_move(system_.poststep(step), max_move);
        });
        return builds;
    }

    std::uint64_t compute_forces() override {
        std::uint64_t builds = 0;
        guarded([&] {
            // J and alpha of the current parameters (a step sets them again anyway)
            system_.set_coefficients(gpu_coefficients(s_, evolver_, 1.0, evolver_.skin()));
            builds = system_.compute_forces() ? 1 : 0;
        });
        return builds;
    }

    PairTotals pair_totals() override {
        gpu::Totals t;
        guarded([&] { t = system_.totals(); });
        PairTotals p{t.energy, t.virial, {}};
        std::copy(std::begin(t.virial_tensor), std::end(t.virial_tensor), p.virial_tensor.begin());
        return p;
    }

    void download() override {
        guarded([&] { system_.download(arrays()); });
    }

    std::vector<Vec<D>> list_reference() override {
        std::vector<Vec<D>> r(s_.size());
        bool built = false;
        guarded([&] { built = r.empty() || system_.download_reference(r[0].c.data()); });
        if (!built) r.clear();
        return r;
    }

    std::size_t device_bytes() const override { return system_.device_bytes(); }

  private:
    gpu::HostArrays arrays() {
        static_assert(sizeof(Vec<D>) == D * sizeof(double) &&
                      sizeof(TorqueVec<D>) == (D == 2 ? 1 : 3) * sizeof(double));
        if (s_.p.size() != s_.director.size() || s_.force.size() != s_.size() ||
            s_.torque.size() != s_.size() || s_.image.size() != s_.size())
            throw std::logic_error("gpu: the state's arrays differ in size");
        gpu::HostArrays a;
        if (s_.size() == 0) return a;
        a.position = s_.p.position[0].c.data();
        a.velocity = s_.p.velocity[0].c.data();
        a.director = s_.director[0].c.data();
        a.force = s_.force[0].c.data();
        a.torque = s_.torque[0].c.data();
        a.image = s_.image[0].data();
        a.tag = s_.p.tag.data();
        a.species = s_.p.species.data();
        return a;
    }

    // The device's errors (CUDA's, out of memory) as the run's.
    template <class F> void guarded(F&& f) {
        try {
            f();
        } catch (const std::runtime_error& e) {
            if (dynamic_cast<const InputError*>(&e) || dynamic_cast<const RunError*>(&e)) throw;
            throw RunError(std::string("gpu: ") + e.what());
        }
    }

    void check_move(const gpu::StepStatus& st, double max_move) const {
        if (!st.bad_move) return;
        std::string who = "gpu";
        for (const auto& i : evolver_.integrators())
            if (i->name() != "brownian_rotation") who = i->name();
        throw BlowUp(fmt::format("{}: at step {} particle {} moved more than {:g} in one step "
                                 "(the neighbour-list skin), or to a non-finite place (the run "
                                 "blew up)",
                                 who, s_.step, st.bad_tag, max_move));
    }

    SoftState<D>& s_;
    Evolver<D>& evolver_;
    gpu::DeviceSystem system_;
    std::string description_;
};

} // namespace

template <int D>
std::unique_ptr<DeviceStepper<D>> make_gpu_stepper(SoftState<D>& state, Evolver<D>& evolver,
                                                   const std::vector<Vec<D>>& reference) {
    gpu_model(state, evolver); // a config the GPU cannot run is an input error anywhere
    if (const std::string why = gpu_unavailable_reason(); !why.empty())
        throw InputError("device = \"gpu\": " + why);
    return std::make_unique<GpuStepper<D>>(state, evolver, reference);
}

template gpu::Model gpu_model<2>(const SoftState<2>&, Evolver<2>&);
template gpu::Model gpu_model<3>(const SoftState<3>&, Evolver<3>&);
template gpu::StepCoefficients gpu_coefficients<2>(const SoftState<2>&, const Evolver<2>&, double,
                                                   double);
template gpu::StepCoefficients gpu_coefficients<3>(const SoftState<3>&, const Evolver<3>&, double,
                                                   double);
template std::unique_ptr<DeviceStepper<2>> make_gpu_stepper<2>(SoftState<2>&, Evolver<2>&,
                                                               const std::vector<Vec<2>>&);
template std::unique_ptr<DeviceStepper<3>> make_gpu_stepper<3>(SoftState<3>&, Evolver<3>&,
                                                               const std::vector<Vec<3>>&);

} // namespace pedesis
