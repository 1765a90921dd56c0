#include "pedesis/soft/blow_up_cause.hpp"

#include "pedesis/core/ball_volume.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pedesis {

namespace {

// A start whose pairs overlap blows up in its first steps; later the start is not the
// cause any more.
constexpr std::uint64_t start_steps = 10;

} // namespace

template <int D>
StartFacts measure_start(const SoftState<D>& s, const NeighborList<D>& list,
                         const std::vector<std::unique_ptr<ForceTerm<D>>>& forces) {
    StartFacts f;
    f.measured = true;
    f.step = s.step;
    const std::size_t n = s.p.species_table.size();
    // the largest core of each species pair over the terms, and whose it is
    std::vector<double> core(n * n, 0.0);
    std::vector<std::size_t> whose(n * n, 0);
    for (std::size_t t = 0; t < forces.size(); ++t)
        for (std::size_t a = 0; a < n; ++a)
            for (std::size_t b = 0; b < n; ++b) {
                const double c = forces[t]->core(s, a, b);
                if (c > core[a * n + b]) {
                    core[a * n + b] = c;
                    whose[a * n + b] = t;
                }
            }
    for (std::size_t i = 0; i < list.size(); ++i)
        for (const std::uint32_t* j = list.begin(i); j != list.end(i); ++j) {
            const std::size_t k = s.p.species[i] * n + s.p.species[*j];
            if (!(core[k] > 0.0)) continue;
            const double r = norm(s.box.minimum_image(s.p.position[i] - s.p.position[*j]));
            if (r / core[k] < f.closest_ratio) {
                f.closest_ratio = r / core[k];
                f.closest = r;
                f.core = core[k];
                f.tag_a = std::min(s.p.tag[i], s.p.tag[*j]);
                f.tag_b = std::max(s.p.tag[i], s.p.tag[*j]);
                f.core_term = forces[whose[k]]->name();
            }
        }
    std::vector<double> count(n, 0.0);
    for (std::size_t i = 0; i < s.size(); ++i) count[s.p.species[i]] += 1.0;
    std::size_t most = 0;
    for (std::size_t a = 0; a < n; ++a) {
        f.packing += count[a] * ball_volume(0.5 * core[a * n + a], D) / s.box.volume();
        if (count[a] > count[most]) most = a;
    }
    if (n > 0 && !forces.empty()) {
        f.packing_core = core[most * n + most];
        f.packing_term = forces[whose[most * n + most]]->name();
    }
    for (const auto& term : forces)
        if (f.one_body.empty()) f.one_body = term->start_overlap(s);
    return f;
}

std::string blow_up_cause(const StartFacts& start, std::uint64_t failed_step, double dt, int dim) {
    const double close_packing = dim == 2 ? 0.9069 : 0.7405;
    if (start.measured && start.packing > close_packing)
        return fmt::format(
            ". Likely cause: the density. Taken as {} of diameter {:g} ({}'s core), the "
            "particles fill {:.3g} of the box, more than close packing ({}) allows, so they "
            "overlap whatever dt is: give a larger box or fewer particles",
            dim == 2 ? "disks" : "spheres", start.packing_core, start.packing_term, start.packing,
            close_packing);
    if (start.measured && failed_step < start.step + start_steps && start.closest_ratio < 1.0)
        return fmt::format(
            ". Likely cause: the start. Particles {} and {} began {:.3g} apart, inside {}'s "
            "core ({:g}), and the force there is too strong for dt = {:g}: start them further "
            "apart ([initial] min_distance = {:g}, or a lattice), or take the first steps with "
            "a smaller dt",
            start.tag_a, start.tag_b, start.closest, start.core_term, start.core, dt, start.core);
    if (start.measured && failed_step < start.step + start_steps && !start.one_body.empty())
        return fmt::format(". Likely cause: the start. {}, and the force there is too strong for "
                           "dt = {:g}",
                           start.one_body, dt);
    return fmt::format("; reduce dt (now {:g})", dt);
}

template StartFacts measure_start<2>(const SoftState<2>&, const NeighborList<2>&,
                                     const std::vector<std::unique_ptr<ForceTerm<2>>>&);
template StartFacts measure_start<3>(const SoftState<3>&, const NeighborList<3>&,
                                     const std::vector<std::unique_ptr<ForceTerm<3>>>&);

} // namespace pedesis
