#include "pedesis/setup/random_placement.hpp"

#include "pedesis/core/ball_volume.hpp"
#include "pedesis/core/rng.hpp"
#include "pedesis/core/stage.hpp"
#include "pedesis/spatial/cell_list.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace pedesis {

namespace {

// Why random placement gave up, from what it was asked: the space each particle keeps
// free (its diameter, or min_distance where that is larger) and the share of the
// region those spaces cover, against the limit where random sequential addition jams.
template <int D>
std::string crowded_message(const PlacementRequest<D>& req, std::size_t k, std::size_t total,
                            int attempts) {
    const double keep = std::max(2.0 * req.radius, req.min_distance);
    double region = 1.0;
    for (int a = 0; a < D; ++a) region *= req.hi[a] - req.lo[a];
    const double n = static_cast<double>(total);
    const char* ball = D == 2 ? "disk" : "sphere";
    const char* lattice = D == 2 ? "hexagonal" : "fcc";
    const double close_packing = D == 2 ? 0.9069 : 0.7405;
    const std::string head =
        fmt::format("{}: could not place particle {} of {} at random without overlap after {} "
                    "attempts",
                    req.what, k + 1, req.count, attempts);
    // the particles themselves do not fit: no placement and no min_distance helps
    const double body = 2.0 * (req.body_radius >= 0.0 ? req.body_radius : req.radius);
    const double filled = n * ball_volume(0.5 * body, D) / region;
    if (filled > close_packing)
        return fmt::format("{}: the particles themselves, {}s of diameter {:g} (twice the "
                           "species' radius), would fill {:.3g} of the region, more than close "
                           "packing ({}) allows; give a larger box or fewer particles",
                           head, ball, body, filled, close_packing);
    const double covered = n * ball_volume(0.5 * keep, D) / region;
    const double jams = D == 2 ? 0.547 : 0.38; // random sequential addition's limit
    const bool min_distance_binds = req.min_distance > 2.0 * req.radius;
    std::string m = fmt::format(
        "{}: each keeps a {} of diameter {:g} free of other centres ({}), and {} of them "
        "would cover {:.3g} of the region, where random placement jams near {} (or sooner, "
        "with other species). Place them on a lattice (positions = \"{}\"), which holds them "
        "up to close packing",
        head, ball, keep, min_distance_binds ? "[initial] min_distance" : "its diameter", total,
        covered, jams, lattice);
    // a smaller min_distance that random placement reaches, no smaller than a hard
    // particle's contact
    const double lower =
        std::max(2.0 * req.radius, keep * std::pow(0.8 * jams / std::max(covered, jams), 1.0 / D));
    if (min_distance_binds && lower < keep)
        m += fmt::format(", or lower [initial] min_distance to about {:.2g}{}", lower,
                         req.radius > 0.0 ? ""
                                          : " (soft particles then start closer than that: "
                                            "the first steps push them apart, given a small dt)");
    return m + ", or give a larger box";
}

} // namespace

template <int D>
void place_randomly(std::vector<Vec<D>>& pos, std::vector<double>& radii, const Box<D>& box,
                    const PlacementRequest<D>& req, std::uint64_t seed) {
    enter_stage("placing particles at random");
    double max_radius = req.radius, min_radius = req.radius;
    for (double r : radii) {
        max_radius = std::max(max_radius, r);
        min_radius = std::min(min_radius, r);
    }
    // Cells sized by the smallest particle (but no more cells than particles), scanned
    // as far as this request's particles reach: a small particle placed among large
    // ones then looks at cells near it, not at cells the size of the largest contact.
    const std::size_t total = pos.size() + req.count;
    const double spacing = std::pow(box.volume() / static_cast<double>(total), 1.0 / D);
    CellList<D> cells(box, std::max({2.0 * min_radius, req.min_distance, spacing}));
    const int reach_cells =
        cells.cells_to_reach(std::max(req.radius + max_radius, req.min_distance));
    cells.clear(total);
    for (std::size_t j = 0; j < pos.size(); ++j)
        cells.insert(static_cast<std::uint32_t>(j), pos[j]);

    constexpr int max_attempts = 20000;
    for (std::size_t k = 0; k < req.count; ++k) {
        CounterRng rng(seed, RngStream::placement, req.first_tag + static_cast<std::uint32_t>(k));
        bool placed = false;
        for (int attempt = 0; attempt < max_attempts && !placed; ++attempt) {
            Vec<D> r;
            for (int a = 0; a < D; ++a) r[a] = rng.uniform(req.lo[a], req.hi[a]);
            if (req.allowed && !req.allowed(r)) continue;
            bool free = true;
            cells.for_each_within(r, reach_cells, [&](std::uint32_t j) {
                if (!free) return;
                const double dmin = std::max(req.radius + radii[j], req.min_distance);
                if (norm2(box.minimum_image(r - pos[j])) < dmin * dmin) free = false;
            });
            if (!free) continue;
            const auto idx = static_cast<std::uint32_t>(pos.size());
            pos.push_back(r);
            radii.push_back(req.radius);
            cells.insert(idx, r);
            placed = true;
        }
        if (!placed) throw InputError(crowded_message(req, k, total, max_attempts));
    }
}

template void place_randomly(std::vector<Vec<2>>&, std::vector<double>&, const Box<2>&,
                             const PlacementRequest<2>&, std::uint64_t);
template void place_randomly(std::vector<Vec<3>>&, std::vector<double>&, const Box<3>&,
                             const PlacementRequest<3>&, std::uint64_t);

} // namespace pedesis
