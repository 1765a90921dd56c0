#include "pedesis/soft/evolver.hpp"

#include "pedesis/core/chunk_shares.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/core/inside_box.hpp"
#include "pedesis/core/interrupt.hpp"
#include "pedesis/soft/blow_up.hpp"
#include "pedesis/spatial/spatial_sort.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace pedesis {

template <int D>
Evolver<D>::Evolver(SoftState<D>& state, double skin, double r_cut)
    : s_(state), skin_(skin), r_cut_request_(r_cut) {
    if (!(skin >= 0.0 && std::isfinite(skin)))
        throw InputError("neighbor_list.skin must be a finite number >= 0");
    if (!(r_cut >= 0.0 && std::isfinite(r_cut)))
        throw InputError("neighbor_list.r_cut must be a finite number >= 0");
}

template <int D> void Evolver<D>::add_force(std::unique_ptr<ForceTerm<D>> f) {
    forces_.push_back(std::move(f));
    nl_.reset(); // the cutoff may have grown
    forces_current_ = false;
}

template <int D> void Evolver<D>::add_torque(std::unique_ptr<TorqueTerm<D>> t) {
    torques_.push_back(std::move(t));
    nl_.reset();
    forces_current_ = false;
}

template <int D> void Evolver<D>::add_integrator(std::unique_ptr<Integrator<D>> i) {
    if (domain_) i->set_communicator(&domain_->comm());
    integrators_.push_back(std::move(i));
}

template <int D> void Evolver<D>::make_list() {
    // shared among processes, the cells cover this process's region only
    make_list(domain_ ? domain_->local_box(skin_) : s_.box);
}

template <int D> bool Evolver<D>::box_changed() const {
    for (int a = 0; a < D; ++a)
        if (nl_->box().length(a) != s_.box.length(a)) return true;
    return false;
}

template <int D> bool Evolver<D>::list_stale() const {
    if (domain_ || !box_changed()) return nl_->needs_rebuild(s_.p.position);
    return nl_->needs_rebuild_scaled(s_.p.position, s_.box);
}

template <int D> void Evolver<D>::make_list(const Box<D>& box) {
    double range = r_cut_request_;
    for (const auto& f : forces_) range = std::max(range, f->range(s_));
    for (const auto& t : torques_) range = std::max(range, t->range(s_));
    if (range <= 0.0) range = 1e-3; // only one-body terms: an (almost) empty list
    r_list_cut_ = range;
    nl_ = std::make_unique<NeighborList<D>>(box, range, skin_);
}

template <int D> double Evolver<D>::interaction_reach() {
    if (!nl_) make_list();
    return r_list_cut_ + skin_;
}

template <int D> void Evolver<D>::ensure_list(bool for_totals) {
    if (!nl_) make_list();
    if (domain_) {
        // every process rebuilds when one must: a rebuild moves particles between them
        domain_->local_positions(s_.p.position, local_, skin_);
        // (a pair's partner may be another process's: the rule that needs only one's own)
        const bool rebuild = domain_->any(nl_->moved_half_skin(local_));
        if (rebuild) {
            domain_->redistribute(s_);
            build_local();
        } else {
            domain_->refresh_ghosts(s_);
        }
        // A rebuild for the log's totals is counted at the next step, where one process
        // rebuilds (it builds a separate list for the totals instead), so that the
        // count is the same.
        if (for_totals)
            rebuild_for_totals_ = rebuild_for_totals_ || rebuild;
        else if (rebuild || rebuild_for_totals_) {
            ++builds_;
            rebuild_for_totals_ = false;
        }
        return;
    }
    if (list_stale()) {
        if (box_changed()) make_list(); // cells and images for the box of now
        nl_->build(s_.p.position);
        ++builds_;
    }
}

template <int D> const NeighborList<D>& Evolver<D>::neighbor_list() {
    ensure_list();
    return *nl_;
}

template <int D> std::vector<Vec<D>> Evolver<D>::list_reference() const {
    if (device_) return device_->list_reference();
    // (a shared run's list holds one process's particles: a restart rebuilds)
    return nl_ && !domain_ ? nl_->build_positions() : std::vector<Vec<D>>{};
}

template <int D> std::vector<double> Evolver<D>::list_box_lengths() const {
    const Box<D>& box = nl_ ? nl_->box() : s_.box;
    std::vector<double> lengths(D);
    for (int a = 0; a < D; ++a) lengths[static_cast<std::size_t>(a)] = box.length(a);
    return lengths;
}

template <int D> double Evolver<D>::list_shear_offset() const {
    return nl_ ? nl_->build_shear_offset() : 0.0;
}

template <int D>
void Evolver<D>::restore_list(const std::vector<Vec<D>>& reference, std::uint64_t builds,
                              double shear_offset, const std::vector<double>& build_lengths) {
    // (only a barostat's box differs from the build's: a box of the present lengths is the
    // state's own, with its shear)
    bool other_box = false;
    if (build_lengths.size() == static_cast<std::size_t>(D) && !domain_)
        for (int a = 0; a < D; ++a)
            other_box = other_box || build_lengths[static_cast<std::size_t>(a)] != s_.box.length(a);
    if (other_box) {
        Vec<D> lengths;
        std::array<bool, D> periodic{};
        for (int a = 0; a < D; ++a) {
            lengths[a] = build_lengths[static_cast<std::size_t>(a)];
            periodic[a] = s_.box.periodic(a);
        }
        make_list(Box<D>(lengths, periodic));
    } else {
        make_list();
    }
    if (!reference.empty()) {
        // the rows of the build, across the sheared faces too, then the offset of now
        if (s_.box.sheared()) nl_->set_shear_offset(shear_offset);
        nl_->build(reference);
        if (s_.box.sheared()) nl_->set_shear_offset(s_.box.shear_offset());
    }
    builds_ = builds;
}

template <int D> void Evolver<D>::slide_images(double dt) {
    // By increments rather than from the time: a restart's clock (t0 + steps dt from the
    // checkpoint) rounds otherwise than the continuous run's, and the offset must not.
    const double g = s_.box.shear_rate() * s_.box.length(1);
    s_.box.set_shear_offset(s_.box.shear_offset() + g * dt);
    if (nl_) nl_->set_shear_offset(s_.box.shear_offset());
}

template <int D> void Evolver<D>::wrap_all() {
    const auto n = static_cast<std::int64_t>(s_.owned());
    // Bounds on the periodic axes only (a walled axis takes +-infinity): most particles
    // are inside, tested block by block without branches (detail::all_inside, SIMD), and
    // only the blocks with one outside are gone through again, to wrap those and count
    // their images.
    detail::BoxBounds<D> bounds;
    for (int a = 0; a < D; ++a) {
        const bool periodic = s_.box.periodic(a);
        bounds.lo[a] = periodic ? s_.box.lo(a) : -std::numeric_limits<double>::infinity();
        bounds.hi[a] = periodic ? s_.box.hi(a) : std::numeric_limits<double>::infinity();
    }
    const auto all_inside = detail::all_inside_for<D>(simd_level());
    constexpr std::int64_t block = 256;
    const Vec<D>* pos = s_.p.position.data();
    ChunkShares shares(n, 4, block, s_.thread_shares);
#pragma omp parallel
    shares.run([&](std::int64_t first_block, std::int64_t last_block) {
        for (std::int64_t b = first_block; b < last_block; ++b) {
            const auto first = static_cast<std::size_t>(b * block);
            const auto last = static_cast<std::size_t>(std::min(n, (b + 1) * block));
            if (all_inside(bounds, pos, first, last)) continue;
            for (std::size_t i = first; i < last; ++i) {
                if (detail::inside_bounds<D>(bounds, pos[i])) continue;
                const Vec<D> shift = s_.box.wrap(s_.p.position[i]);
                for (int a = 0; a < D; ++a) s_.image[i][a] += static_cast<std::int32_t>(shift[a]);
            }
        }
    });
}

template <int D> void Evolver<D>::reorder_storage() {
    if (domain_ || device_)
        throw std::logic_error("sort_storage: the domain decomposition or the device sorts");
    if (!nl_) make_list();
    // Along the curve first: the order is then a function of the positions and tags
    // alone, whatever it was before, and the build below reads memory in cell order.
    s_.apply_order(space_filling_order(s_.box, s_.p.position, s_.p.tag, r_list_cut_ + skin_));
    nl_->build(s_.p.position);
    // Then in the order the force loops visit the rows (colour, block, cell): a block's
    // rows, particles and their forces lie together in memory instead of in pieces of the
    // curve. Once the state outgrows the caches that is what the pair loop waits on
    // (2D ABP at 10^6: 1.14x the rate, docs/performance.md).
    const std::vector<std::uint32_t> order = nl_->sweep_order();
    s_.apply_order(order);
    // A fresh list from the final storage, as a restart builds it from the checkpoint:
    // renumbering the rows instead would sum a particle's forces in another order where
    // a pair's row is that of its lower storage index (the full stencil of narrow boxes).
    nl_->build(s_.p.position);
    // (its sweep is the storage order now)
    s_.thread_shares = nl_->thread_share_bounds();
}

template <int D> void Evolver<D>::sort_storage() {
    reorder_storage();
    ++builds_;
}

template <int D> void Evolver<D>::sort_storage_at_start() {
    reorder_storage();
    builds_ = std::max<std::uint64_t>(builds_, 1);
}

template <int D> bool Evolver<D>::in_tag_order() const {
    for (std::size_t i = 0; i < s_.size(); ++i)
        if (s_.p.tag[i] != i) return false;
    return true;
}

template <int D> std::vector<std::uint32_t> Evolver<D>::restore_tag_order() {
    if (in_tag_order()) return {};
    std::vector<std::uint32_t> order(s_.size());
    for (std::size_t i = 0; i < s_.size(); ++i) {
        if (s_.p.tag[i] >= s_.size()) throw RunError("restore_tag_order: tags are not 0..N-1");
        order[s_.p.tag[i]] = static_cast<std::uint32_t>(i);
    }
    reorder(order);
    return order;
}

template <int D> void Evolver<D>::reorder(const std::vector<std::uint32_t>& order) {
    s_.apply_order(order);
    if (nl_ && nl_->size() == s_.size()) nl_->reorder(order);
}

template <int D> bool Evolver<D>::needs_initial_forces() const {
    return std::any_of(integrators_.begin(), integrators_.end(),
                       [](const auto& i) { return i->needs_initial_forces(); });
}

template <int D> void Evolver<D>::compute_forces() {
    if (device_) {
        builds_ += device_->compute_forces();
        host_current_ = false;
        forces_current_ = true;
        return;
    }
    ensure_list();
    // in parallel like every per-particle loop of a step: serial, it would cap the speed-up
    // with threads
    const auto n = static_cast<std::int64_t>(s_.size());
    parallel_for_each_index(n, s_.thread_shares, [&](std::int64_t i) {
        s_.force[i] = Vec<D>{};
        s_.torque[i] = TorqueVec<D>{};
    });
    for (const auto& f : forces_) f->add_forces(s_, *nl_);
    for (const auto& t : torques_) t->add_torques(s_, *nl_);
    forces_current_ = true;
}

template <int D> void Evolver<D>::evolve(double dt) {
    if (!(dt > 0.0 && std::isfinite(dt))) throw InputError("dt must be a positive finite number");
    // what a blow-up's message will need, once, at the first step (under a decomposition
    // each process holds a share only, and the blow-up comes back as the agreed message)
    if (!start_.measured && !domain_) {
        if (!nl_) ensure_list();
        start_ = measure_start(s_, *nl_, forces_);
    }
    try {
        step(dt);
    } catch (const BlowUp& e) {
        throw BlowUp(e.what() + blow_up_cause(start_, s_.step, dt, D));
    }
}

template <int D> void Evolver<D>::step(double dt) {
    if (domain_) {
        evolve_shared(dt);
        return;
    }
    if (device_) {
        if (!forces_current_ && needs_initial_forces()) compute_forces();
        host_current_ = false;
        builds_ += device_->step(dt, skin_ > 0.0 ? skin_ : r_list_cut_);
        ++s_.step;
        s_.time += dt;
        return;
    }
    if (!nl_) ensure_list();
    if (sort_interval_ > 0 && s_.step > 0 && s_.step % sort_interval_ == 0) sort_storage();
    if (!forces_current_ && needs_initial_forces()) compute_forces();
    // A step longer than the skin is a blow-up (tunnelling through neighbours), as in
    // the tutorial's guidance on choosing the pad; with no skin, the cutoff is the scale.
    const double max_move = skin_ > 0.0 ? skin_ : r_list_cut_;
    for (auto& i : integrators_) i->prestep(s_, dt, max_move);
    // Under shear the images slide to where they are at the step's end when the
    // positions get there: before the forces of an inertial step's new positions, after
    // an overdamped step's move (its forces are those of the positions it starts from).
    const bool sheared = s_.box.sheared();
    const bool overdamped =
        sheared && std::any_of(integrators_.begin(), integrators_.end(),
                               [](const auto& i) { return i->overdamped_positions(); });
    if (sheared && !overdamped) slide_images(dt);
    // checked after the pre-steps, so that velocity-Verlet drifts are covered too
    compute_forces();
    for (auto& i : integrators_) i->poststep(s_, dt, max_move);
    if (overdamped) slide_images(dt);
    wrap_all();
    ++s_.step;
    s_.time += dt;
}

template <int D> void Evolver<D>::set_device(std::unique_ptr<DeviceStepper<D>> device) {
    if (domain_) throw InputError("device = \"gpu\" runs on one process (not under mpirun)");
    if (!nl_) make_list(); // the cutoff and skin the device's list uses
    device_ = std::move(device);
    host_current_ = true;
}

template <int D> void Evolver<D>::sync_host() {
    if (device_ && !host_current_) {
        device_->download();
        host_current_ = true;
    }
}

template <int D> void Evolver<D>::set_domain(DomainDecomposition<D>* domain) {
    domain_ = domain;
    nl_.reset(); // its cells cover another region now
    for (auto& i : integrators_) i->set_communicator(domain ? &domain->comm() : nullptr);
}

template <int D> void Evolver<D>::build_local() {
    domain_->local_positions(s_.p.position, local_, skin_);
    nl_->build(local_);
}

template <int D> void Evolver<D>::evolve_shared(double dt) {
    // The serial step, with the points where the processes must agree: an integrator's
    // error on one process is held until all meet, so that none waits for it forever.
    auto held = [](std::string& error, auto&& act) {
        try {
            act();
        } catch (const RunError& e) {
            error = e.what();
        }
    };
    if (!nl_) make_list();
    if (sort_interval_ > 0 && s_.step > 0 && s_.step % sort_interval_ == 0) {
        // as sort_particles: a fresh list after the sort, so rebuilds count the same
        domain_->redistribute(s_, r_list_cut_ + skin_);
        build_local();
        ++builds_;
    }
    if (!forces_current_ && needs_initial_forces()) compute_forces();
    const double max_move = skin_ > 0.0 ? skin_ : r_list_cut_;
    std::string error;
    held(error, [&] {
        for (auto& i : integrators_) i->prestep(s_, dt, max_move);
    });
    agree(error, false);
    compute_forces();
    held(error, [&] {
        for (auto& i : integrators_) i->poststep(s_, dt, max_move);
    });
    wrap_all();
    ++s_.step;
    s_.time += dt;
    interrupted_ = agree(error, interrupt_requested());
}

template <int D> bool Evolver<D>::agree(const std::string& error, bool stop) {
    Communicator& comm = domain_->comm();
    // [the lowest process with an error, counted from the top (0: none), stop]
    double flags[2] = {error.empty() ? 0.0 : static_cast<double>(comm.size() - comm.rank()),
                       stop ? 1.0 : 0.0};
    comm.max(flags);
    if (flags[0] > 0.0) {
        const int from = comm.size() - static_cast<int>(flags[0]);
        throw RunError(comm.broadcast(error, from));
    }
    return flags[1] > 0.0;
}

template <int D> bool Evolver<D>::interrupted() const {
    return domain_ ? interrupted_ : interrupt_requested();
}

template <int D> PairTotals Evolver<D>::pair_totals() {
    PairTotals t = pair_totals_within_cutoff();
    add_tail_corrections(t);
    return t;
}

template <int D>
bool Evolver<D>::heat_flux(std::vector<double>& energy, Vec<D>& flux, SymTensor* virial_tensor) {
    if (device_ || domain_) return false;
    if (!nl_) ensure_list();
    // (a list of its own when this one is due a rebuild, as pair_totals_within_cutoff)
    std::optional<NeighborList<D>> fresh;
    const NeighborList<D>* list = nl_.get();
    if (list_stale()) {
        fresh.emplace(s_.box, r_list_cut_, skin_);
        fresh->build(s_.p.position);
        list = &*fresh;
    }
    energy.assign(s_.size(), 0.0);
    flux = Vec<D>{};
    PairTotals t; // (only its virial tensor, summed as pair_totals sums it)
    for (const auto& f : forces_)
        if (!f->add_heat_flux(s_, *list, energy, flux, t.virial_tensor)) return false;
    if (virial_tensor) {
        add_tail_corrections(t);
        *virial_tensor = t.virial_tensor;
    }
    for (std::size_t i = 0; i < s_.size(); ++i) {
        const double m = s_.p.mass(i);
        if (!std::isfinite(m)) continue;
        const Vec<D>& v = s_.p.velocity[i];
        flux += v * (0.5 * m * norm2(v) + energy[i]);
    }
    return true;
}

template <int D> void Evolver<D>::add_tail_corrections(PairTotals& t) {
    const auto& table = s_.p.species_table;
    std::vector<double> counts(table.size(), 0.0);
    for (std::size_t i = 0; i < s_.owned(); ++i) counts[s_.p.species[i]] += 1.0;
    if (domain_) domain_->comm().sum(counts); // (pair_totals is collective there already)
    for (const auto& f : forces_) {
        const PairTotals tail = f->tail(table, counts, s_.box.volume());
        t.energy += tail.energy;
        t.virial += tail.virial;
        for (int c = 0; c < 6; ++c) t.virial_tensor[c] += tail.virial_tensor[c];
    }
}

template <int D> PairTotals Evolver<D>::pair_totals_within_cutoff() {
    if (device_) return device_->pair_totals();
    if (!nl_) ensure_list();
    PairTotals t;
    if (domain_) {
        // the ghosts must be where their owners are (and a rebuild here is shared)
        ensure_list(true);
        for (const auto& f : forces_) f->add_totals(s_, *nl_, t);
        std::array<double, 8> sums{t.energy, t.virial};
        std::copy(t.virial_tensor.begin(), t.virial_tensor.end(), sums.begin() + 2);
        domain_->comm().sum(sums);
        t.energy = sums[0];
        t.virial = sums[1];
        std::copy(sums.begin() + 2, sums.end(), t.virial_tensor.begin());
        return t;
    }
    if (!list_stale()) {
        for (const auto& f : forces_) f->add_totals(s_, *nl_, t);
        return t;
    }
    // A rebuild here would change the rows, hence the summation order of the next
    // forces: how often a run is logged must not change its trajectory. A list of its
    // own serves the totals instead.
    NeighborList<D> fresh(s_.box, r_list_cut_, skin_);
    fresh.build(s_.p.position);
    for (const auto& f : forces_) f->add_totals(s_, fresh, t);
    return t;
}

template class Evolver<2>;
template class Evolver<3>;

} // namespace pedesis
