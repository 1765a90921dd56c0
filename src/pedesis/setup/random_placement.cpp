#include "pedesis/setup/random_placement.hpp"

#include "pedesis/core/rng.hpp"
#include "pedesis/core/stage.hpp"
#include "pedesis/spatial/cell_list.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace pedesis {

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
        if (!placed)
            throw InputError(req.what + ": could not place particle " + std::to_string(k + 1) +
                             " of " + std::to_string(req.count) +
                             " at random without overlap after " + std::to_string(max_attempts) +
                             " attempts; the region is too crowded for random placement "
                             "(use a lattice, or a larger box)");
    }
}

template void place_randomly(std::vector<Vec<2>>&, std::vector<double>&, const Box<2>&,
                             const PlacementRequest<2>&, std::uint64_t);
template void place_randomly(std::vector<Vec<3>>&, std::vector<double>&, const Box<3>&,
                             const PlacementRequest<3>&, std::uint64_t);

} // namespace pedesis
