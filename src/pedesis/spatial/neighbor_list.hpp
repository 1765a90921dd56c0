#pragma once
// Verlet neighbour list for the soft / active engines: every pair closer than
// r_list = r_cut + skin, rebuilt only when a pair within r_cut could be missing from
// it (needs_rebuild), or, where other processes hold some of the pairs, when some
// particle has moved more than skin/2 (moved_half_skin).
//
// The list is HALF: each pair appears once, in the row of its lower storage index, so
// a force loop evaluates it once and adds it to both particles (Newton's third law).
// Rows lie in one array, each found by its start and length.
//
// Force loops must then write into neighbours' sums, and must do so in an order that
// does not depend on the threads (the project promises bit-identical results for any
// thread count). for_each_chunk gives that order: the cells are grouped into blocks,
// the blocks coloured (two or three colours per axis) so that two blocks of one colour
// are at least 2 r_list apart, and the colours swept one after another. A row writes
// only into its own block and at most r_list beyond it, so the blocks of one colour
// write disjoint particles and run in parallel in any order, and each particle
// receives its contributions in the fixed order (colour, then the position of the row
// in its one writing block).
// The row order is the cell-list scan order, which depends only on the positions.
#include "pedesis/core/box.hpp"
#include "pedesis/core/chunk_shares.hpp"
#include "pedesis/spatial/cell_list.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <vector>

namespace pedesis {

namespace detail {
// |d|^2 for the loops over list candidates. The same value as norm2 (which starts from
// 0.0, and adding +0 to a square changes nothing), without the addition the compiler
// must keep for it: one instruction of the ~20 per candidate.
template <int D> inline double squared_length(const Vec<D>& d) {
    double s = d[0] * d[0];
    for (int a = 1; a < D; ++a) s += d[a] * d[a];
    return s;
}
} // namespace detail

template <int D> class NeighborList {
  public:
    // Throws InputError naming the parameter (r_cut > 0, skin >= 0, both finite) or the
    // periodic axis shorter than 2 r_list (the minimum image would be ambiguous).
    NeighborList(const Box<D>& box, double r_cut, double skin);

    // Positions on periodic axes may lie outside the box by up to L/4 (the build bins
    // wrapped copies); a non-finite position, or one further out, throws RunError naming
    // the particle and leaves the previous list as it was.
    void build(const std::vector<Vec<D>>& pos);

    // True when a pair now closer than r_cut may be missing from the rows: when two
    // particles whose moves since the build (minimum image, so crossing a periodic
    // boundary is not motion) add up to more than the skin are now that close without
    // having been within r_list at the build; also when any particle has moved more than
    // the skin (which bounds the moves image_free_margin allows for), when the particle
    // count changed, or before the first build. Only particles that moved more than
    // skin/2 can be in such a pair, and at the extremes of 10^6 Brownian moves there are
    // few: the list lives on past the first of them (the old rule, moved_half_skin,
    // rebuilt there) until a missing pair is really near, or too many moved to check.
    bool needs_rebuild(const std::vector<Vec<D>>& pos) const;
    // True when any particle has moved more than skin/2 since the last build (then no
    // pair can be missing: the rule for lists whose pairs' partners another process
    // holds, where needs_rebuild cannot see them), when the particle count changed, or
    // before the first build.
    bool moved_half_skin(const std::vector<Vec<D>>& pos) const;
    // needs_rebuild where the box has been scaled along its axes since the build (a
    // barostat: soft/barostat.hpp) to `now`, by lambda_a = now_a / then_a. A pair's
    // separation is lambda times that of the positions scaled back, which moved by at
    // most u from the build: a pair missing from the rows is now at least
    // min lambda (r_list - 2u) apart, so the list holds every pair within r_cut while that
    // is r_cut or more; and a listed pair is at most max lambda (r_list + 2u) apart,
    // within the r_list + 2 skin that image_free_margin assumes. Not under shear.
    bool needs_rebuild_scaled(const std::vector<Vec<D>>& pos, const Box<D>& now) const;

    // Lees-Edwards shear (core/box.hpp): the box's offset now. A pair across the y faces
    // moves by the offset's change relative to each other, so under shear both rules
    // above ask for a rebuild once twice the largest move since the build plus that
    // change (to the nearest image) exceeds the skin.
    void set_shear_offset(double offset) { box_.set_shear_offset(offset); }
    // The offset the last build saw (a checkpoint restores the list with it).
    double build_shear_offset() const { return build_offset_; }

    // Follows a reordering of the particles' storage (new index i holds the particle that
    // was at old index order[i]) without a rebuild: every particle keeps the same
    // neighbours in the same row order, so forces summed over the rows do not change by a
    // bit. (A rebuild after the reordering would scan the cells in another order.)
    void reorder(const std::vector<std::uint32_t>& order);

    // Particles in the last build; rows below are valid for i < size().
    std::size_t size() const { return n_; }
    std::uint32_t count(std::size_t i) const {
        return static_cast<std::uint32_t>(rows_[i] & ((std::uint64_t{1} << length_bits) - 1));
    }
    const std::uint32_t* begin(std::size_t i) const {
        return neighbors_.get() + (rows_[i] >> length_bits);
    }
    const std::uint32_t* end(std::size_t i) const { return begin(i) + count(i); }
    // Calls rows(span of particle indices) for chunks that together hold every particle
    // i < size() once, in the colour order above: in parallel, and such that no two
    // concurrent calls write the same particle when each writes only to its particles
    // and the entries of their rows. Within a chunk the particles come in a fixed order.
    // Thread t takes the t-th of equal runs of each colour's chunks first, then helps
    // the others (core/chunk_shares.hpp). Call it from outside any parallel region.
    template <class Rows> void for_each_chunk(Rows&& rows) const {
        if (colour_chunk_.size() < 2) return; // before a build
        const std::vector<std::int64_t> bounds =
            thread_runs([](std::size_t c) { return static_cast<std::int64_t>(c); });
        ChunkShares shares(static_cast<std::int64_t>(chunk_start_.size()) - 1, 1, 1, bounds);
        // (a round per colour is what keeps the colours apart: never run them as one)
        if (shares.rounds() + 1 != static_cast<int>(colour_chunk_.size()))
            throw std::logic_error("for_each_chunk: the colours' runs do not fit the threads");
#pragma omp parallel
        for (int k = 0; k < shares.rounds(); ++k) {
            shares.run_round(k, [&](std::int64_t first, std::int64_t last) {
                for (std::int64_t c = first; c < last; ++c)
                    rows(chunk(static_cast<std::size_t>(c)));
            });
            // (the colours one after another)
#pragma omp barrier
        }
    }
    // Where the particles of the runs for_each_chunk gives each thread first lie in the
    // sweep order (sweep_order()): thread t's in colour k are [b[k T + t], b[k T + t + 1])
    // for T = omp_get_max_threads(). Storage in the sweep's order (after a sort) makes
    // them storage ranges, along which the per-particle loops share out their work, so
    // that each particle is integrated on the core that summed its force.
    std::vector<std::int64_t> thread_share_bounds() const {
        if (colour_chunk_.size() < 2) return {};
        return thread_runs(
            [this](std::size_t c) { return static_cast<std::int64_t>(chunk_start_[c]); });
    }
    // The colouring, for tests: the chunks of colour k are [first, last).
    int colours() const {
        return static_cast<int>(colour_block_.size()) - 1;
    }
    // Width of the colour blocks in cells (wider in large systems: set_grid).
    int block_width() const {
        return block_width_;
    }
    std::array<std::size_t, 2> chunks_of_colour(int k) const {
        return {colour_chunk_[k], colour_chunk_[k + 1]};
    }
    // Every particle once, in the order for_each_chunk visits the rows.
    const std::vector<std::uint32_t>& sweep_order() const {
        return sweep_;
    }
    std::span<const std::uint32_t> chunk(std::size_t c) const {
        return {sweep_.data() + chunk_start_[c], sweep_.data() + chunk_start_[c + 1]};
    }

    // Neighbour entries in all rows (each pair once).
    std::size_t entries() const {
        return entries_;
    }
    // The storage every row lies in (reused from build to build while it is large enough).
    const std::uint32_t* storage() const {
        return neighbors_.get();
    }

    // The positions of the last build, in storage order: building again from them gives
    // the same rows (a checkpoint restores the list this way).
    std::vector<Vec<D>> build_positions() const {
        return std::vector<Vec<D>>(home_.begin(), home_.begin() + static_cast<std::ptrdiff_t>(n_));
    }

    // Rows of particles further than this from every periodic face may use raw position
    // differences instead of the minimum image while the list is current: their
    // neighbours lie within r_list + 2 skin (no particle moves more than the skin between
    // builds), and positions are taken to lie within one step's largest move of the box
    // (the evolver wraps them after every step, and no step moves a particle further
    // than the skin, or r_cut without one).
    double image_free_margin() const {
        return r_list_ + 2.0 * skin_ + (skin_ > 0.0 ? skin_ : r_cut_);
    }

    double r_cut() const {
        return r_cut_;
    }
    double skin() const {
        return skin_;
    }
    double r_list() const {
        return r_list_;
    }
    const Box<D>& box() const {
        return box_;
    }
    std::uint64_t builds() const {
        return builds_;
    }
    std::size_t memory_bytes() const;

  private:
    Box<D> box_;
    double r_cut_, skin_, r_list_;
    CellList<D> cells_; // the grid and its stencils only: particles are binned below
    int reach_ = 1;     // stencil half-width in cells: cells of r_list / reach_
    // The colouring of for_each_chunk, fixed with the grid (set_grid says how wide the
    // blocks are and how many colours each axis has; the whole axis is one block where a
    // periodic axis is too short for a full colour cycle, which would make a block its
    // own neighbour). sweep_cells_ lists every cell colour by colour, block by
    // block; block_end_[b] is where the b-th block of that order ends in it, and blocks
    // [colour_block_[k], colour_block_[k + 1]) have colour k.
    std::vector<std::uint32_t> sweep_cells_, block_end_, colour_block_;
    // The build's stencil: with half_stencil_, a cell scans itself and the cells at the
    // offsets forward_ (half of the others: a pair of cells is scanned from one side
    // only); else (a periodic axis too short for that) the whole stencil, keeping the
    // neighbours of higher index.
    bool half_stencil_ = false;
    std::vector<std::array<int, D>> forward_;
    // The same half stencil as rows along axis 0: the cell itself and the forward cells
    // at x offsets x0 .. x1 and offsets o on the other axes (o[0] = x0), in forward_'s
    // order. Away from the faces of axis 0 a row's cells are consecutive, so a build
    // sets up a row with one index computation instead of one per cell.
    struct StencilRow {
        int x0, x1;
        std::array<int, D> o;
    };
    std::vector<StencilRow> stencil_rows_;
    void set_grid(int reach, double cell);
    // The cells' least width for `reach` and n particles: r_list / reach, or wider where
    // that would make a sparse system's grid hold more than grid_cells_per_particle cells
    // a particle (rounded up to a power of two, so that a count that wanders does not
    // remake the grid at every build), or min_grid_cells where that is more. A box 200
    // wide with free particles (r_list = skin = 0.5) took 406^3 cells, 256 MB and a pass
    // over 67 million cells per build, for any N. Wider cells hold the same pairs.
    double grid_cell(int reach, std::size_t n) const;
    static constexpr std::size_t grid_cells_per_particle = 4;
    static constexpr std::size_t min_grid_cells = 4096;
    double cell_ = 0.0; // the least width of the grid's cells (set_grid)
    // The colour blocks' width in cells for k colours per axis (set_grid).
    int choose_block_width(int k, int reach, double cell) const;
    static constexpr int max_block_width = 32;
    int block_width_ = 2;
    // Each build: the particles in that order (sweep_), cut at block boundaries into
    // chunks of about sweep_chunk particles: chunk c is sweep_[chunk_start_[c] ..
    // chunk_start_[c + 1]), and chunks [colour_chunk_[k], colour_chunk_[k + 1]) have
    // colour k.
    static constexpr std::size_t sweep_chunk = 64;
    std::vector<std::uint32_t> sweep_;
    std::vector<std::size_t> chunk_start_, colour_chunk_;
    void make_sweep();
    // For each colour k and thread t < T = omp_get_max_threads(), at(first chunk of the
    // t-th of T equal runs of k's chunks), then at(the chunk count).
    template <class At> std::vector<std::int64_t> thread_runs(At&& at) const {
        const auto threads = static_cast<std::size_t>(std::max(omp_get_max_threads(), 1));
        std::vector<std::int64_t> b;
        b.reserve((colour_chunk_.size() - 1) * threads + 1);
        for (std::size_t k = 0; k + 1 < colour_chunk_.size(); ++k)
            for (std::size_t t = 0; t < threads; ++t)
                b.push_back(
                    at(colour_chunk_[k] + (colour_chunk_[k + 1] - colour_chunk_[k]) * t / threads));
        b.push_back(at(colour_chunk_.back()));
        return b;
    }
    // needs_rebuild for particle i, which moved more than skin/2: whether a particle
    // binned at the build within `reach` of i's present position is now closer than
    // r_cut without having been a list partner.
    bool missing_partner(const std::vector<Vec<D>>& pos, std::size_t i, double reach) const;
    // Particles moved more than skin/2 that needs_rebuild checks one by one: beyond 16
    // plus one in 256, the checks of the steps until a missing pair comes near cost
    // more than the rebuilds they save (2D ABP, N = 36,000: with one in 32, 1.00 of the
    // old rule's speed; with one in 256, 1.06).
    static constexpr std::size_t checked_movers = 16;
    static constexpr std::size_t checked_movers_per = 256;
    // needs_rebuild's blocks of particles, marked where one moved more than skin/2.
    static constexpr std::size_t mover_block = 256;
    mutable std::vector<std::uint8_t> mover_blocks_;
    std::size_t n_ = 0;
    std::uint64_t builds_ = 0;
    double build_offset_ = 0.0; // the shear offset of the last build
    // Under shear: whether 2 (largest move since the build) + |offset change| > limit.
    bool sheared_moves_exceed(const std::vector<Vec<D>>& pos, double limit) const;
    // Under shear, where a cell's stencil crosses the y faces (neighbor_list.cpp): the
    // first x cell of a crossing row relative to the unsheared one, for a crossing
    // upward (+1) or downward (-1).
    int sheared_row_shift(int direction) const;
    // Under shear with the whole stencil: the distinct cells within reach of cell c,
    // the rows across the y faces shifted with the offset.
    void sheared_cells_within(std::int64_t c, std::vector<std::uint32_t>& out) const;
    // Row i: where it starts in neighbors_ (the high 40 bits: rows may lie anywhere, in
    // an order that depends on the threads) and its length (the low 24 bits), in one
    // word as the CSR offsets took. 40 bits: a dense 3D system with ~80 neighbours
    // passes 32 bits near 5e7 particles, which is a size people run.
    static constexpr int length_bits = 24;
    // Entries a thread claims at a time while it writes rows: at least chunk_entries, and
    // four times the most candidates of a row seen (so that a chunk, abandoned only when
    // the next row's candidates do not fit, is at least 3/4 used: what bounds the
    // storage a pass needs, neighbor_list.cpp).
    static constexpr std::size_t chunk_entries = 4096;
    // Relative margin on r_list^2 for rounding (neighbor_list.cpp): the rows hold every
    // pair closer than r_list and none further than r_list (1 + list_rounding / 2).
    static constexpr double list_rounding = 1e-12;
    std::size_t chunk_ = chunk_entries;
    std::vector<std::uint64_t> rows_;
    // Raw storage with its own capacity: std::vector::resize would zero every entry on
    // growth (wasted writes) and grows by doubling (wasted memory).
    std::unique_ptr<std::uint32_t[]> neighbors_;
    std::size_t entries_ = 0, capacity_ = 0;
    // The particles in cell order: those of cell c are
    // by_cell_[cell_start_[c] .. cell_start_[c + 1]), in increasing index, and ref_[k]
    // is the position of by_cell_[k] at the build. Scans then read contiguous memory.
    // home_ holds the same positions in storage order, the reference of needs_rebuild:
    // read in cell order it cost a cache miss per cell at 10^6 particles (7% of the 2D
    // ABP step), and in storage order it streams beside the positions. cell_of_ is each
    // particle's cell during the binning.
    std::vector<std::uint32_t> cell_start_, by_cell_, cell_of_;
    std::vector<Vec<D>> ref_, home_;
};

extern template class NeighborList<2>;
extern template class NeighborList<3>;

} // namespace pedesis
