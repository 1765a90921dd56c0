#include "pedesis/spatial/neighbor_list.hpp"

#include "pedesis/core/chunk_shares.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/particles.hpp"
#include "pedesis/core/stage.hpp"
#include "pedesis/spatial/block_moves.hpp"
#include "pedesis/spatial/near_rows.hpp"

#include <fmt/format.h>

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace pedesis {

namespace {

// Below this many particles a parallel region costs more than the loop it splits.
constexpr std::int64_t parallel_min = 4096;

// Cells of r_list / reach, scanned reach deep: 1 or 2 (build()).
constexpr int max_stencil_reach = 2;

// The cell list links particles with int32 (-1 = none).
constexpr std::size_t max_particles = std::numeric_limits<std::int32_t>::max();

// Headroom on the first allocation and on growth: the pair count fluctuates by a few
// per cent between builds, and a reallocation mid-run would briefly double the memory.
constexpr std::size_t grow(std::size_t needed) {
    return needed + needed / 8 + 64;
}

} // namespace

template <int D>
NeighborList<D>::NeighborList(const Box<D>& box, double r_cut, double skin)
    : box_(box), r_cut_(r_cut), skin_(skin), r_list_(r_cut + skin) {
    if (!(std::isfinite(r_cut) && r_cut > 0.0))
        throw InputError(
            fmt::format("neighbour list: r_cut must be a positive finite number (got {})", r_cut));
    if (!(std::isfinite(skin) && skin >= 0.0))
        throw InputError(
            fmt::format("neighbour list: skin must be a finite number >= 0 (got {})", skin));
    for (int a = 0; a < D; ++a)
        if (box.periodic(a) && box.length(a) < 2.0 * r_list_)
            throw InputError(fmt::format(
                "neighbour list: box too small for the cutoff: periodic axis {} has length {} "
                "but the minimum image needs at least 2 r_list = {} (r_list = r_cut + skin = {})",
                a, box.length(a), 2.0 * r_list_, r_list_));
    set_grid(1, grid_cell(1, 0));
}

template <int D> double NeighborList<D>::grid_cell(int reach, std::size_t n) const {
    std::size_t most = min_grid_cells;
    while (most < grid_cells_per_particle * n && most < (std::size_t{1} << 40)) most *= 2;
    double volume = 1.0;
    for (int a = 0; a < D; ++a) volume *= box_.length(a);
    return std::max(r_list_ / reach, std::pow(volume / static_cast<double>(most), 1.0 / D));
}

template <int D> int NeighborList<D>::choose_block_width(int k, int reach, double cell) const {
    const int narrowest = (2 * reach + k - 2) / (k - 1);
    // In a large system the colour sweep is what brings particles through the caches:
    // each colour visits its blocks and the cells round them, so with blocks of w cells
    // a colour pass touches ((w + 1) / 2w)^D of the box at reach 1: 2.25 box-sweeps per
    // step in 2D with w = 2 against 1.27 with w = 8 and 1.06 with w = 32. Once the state
    // outgrows the caches (2D ABP at 10^6) that is the likely reason the pair loop was a
    // third slower per particle than at 36,000 (w = 8: 1.20x; stored in sweep order,
    // Evolver::sort_storage, each block is one run of memory and its forward halo is
    // what misses: w = 32 another 1.19x, docs/performance.md). Wider blocks are taken
    // only where every axis keeps 8 blocks of each colour or more (threads stay balanced;
    // small systems keep the narrowest width) and the periodic multiple widens the cells
    // by 5% at most (a list build scans more).
    // In 3D the halo is a larger share, ((w + 1) / w)^3, and 8 blocks of a colour along
    // every axis would leave 3D systems of 10^5 particles at the narrowest width: there a
    // block needs 2 of each colour along every axis (8 blocks a colour, even work for two
    // threads) and cells no wider than the narrowest width makes them. In.lj's fluid and
    // a 3D WCA fluid (32,000) keep their cells, and the pair rows missed a simulated 1 MB
    // cache 22% and 48% less often (docs/performance.md).
    std::array<int, D> along{};
    int fewest = CellList<D>::max_cells_along;
    for (int a = 0; a < D; ++a) {
        along[a] = clamped_int(box_.length(a) / (cell * (1.0 + CellList<D>::width_margin)), 1,
                               CellList<D>::max_cells_along);
        fewest = std::min(fewest, along[a]);
    }
    // the cells along an axis once the periodic multiple m is taken (CellList)
    auto rounded = [](int n, int m) { return n >= m ? n - n % m : n; };
    const int per_colour = D == 3 ? 2 : 8;
    for (int w = std::min(max_block_width, fewest / (per_colour * k)); w > narrowest; --w) {
        bool cheap = true;
        for (int a = 0; a < D; ++a) {
            if (!box_.periodic(a)) continue;
            if constexpr (D == 3)
                cheap = cheap && rounded(along[a], k * w) >= rounded(along[a], k * narrowest);
            else
                cheap = cheap && along[a] % (k * w) <= along[a] / 20;
        }
        if (cheap) return w;
    }
    return narrowest;
}

template <int D> void NeighborList<D>::set_grid(int reach, double cell) {
    reach_ = reach;
    cell_ = cell;
    // Blocks w cells wide, k colours per axis: two blocks of one colour have (k - 1) w
    // cells between them and a row writes at most reach cells beyond its block, so
    // (k - 1) w >= 2 reach keeps their writes apart. Each colour costs the sweep a
    // barrier, while larger blocks spread a block's writes further: measured best were
    // k = 2, w = 2 for cells of r_list (4 colours in 2D, 8 in 3D: 2/1 threads 1.85
    // against 1.79, wca3d 1.07x) and k = 3, w = reach for half-width cells (lj3d 7%
    // faster than k = 2, w = 4).
    const int k = reach == 1 ? 2 : 3;
    const int w = choose_block_width(k, reach, cell);
    block_width_ = w;
    cells_ = CellList<D>(box_, cell, k * w);
    std::array<int, D> along, width, blocks_along, colours_along;
    std::size_t n_blocks = 1;
    for (int a = 0; a < D; ++a) {
        along[a] = cells_.cells_along(a);
        // A periodic axis of k w cells or more has a multiple of k w (CellList's
        // periodic_multiple), so its blocks come in whole colour cycles round the wrap;
        // a shorter one is one block, which every stencil on that axis stays within.
        width[a] = box_.periodic(a) && along[a] < k * w ? along[a] : w;
    }
    // Under shear a row at the y faces writes across them into cells shifted along x by
    // the offset, which may be another block of its colour where y is one block (with
    // whole colour cycles along y the faces' rows differ in colour): x is one block then.
    if (box_.sheared() && width[1] == along[1]) width[0] = along[0];
    for (int a = 0; a < D; ++a) {
        blocks_along[a] = (along[a] + width[a] - 1) / width[a];
        colours_along[a] = std::min(k, blocks_along[a]);
        n_blocks *= static_cast<std::size_t>(blocks_along[a]);
    }
    // The half stencil: the offsets whose last non-zero component is positive, one of
    // each pair o, -o. Usable when every periodic axis has 2 reach + 1 cells or more, so
    // that o and -o never name the same cell.
    half_stencil_ = true;
    for (int a = 0; a < D; ++a)
        half_stencil_ = half_stencil_ && !(box_.periodic(a) && along[a] < 2 * reach + 1);
    // (a row across the sheared y faces spans 2 reach + 2 cells along x: none twice)
    if (box_.sheared()) half_stencil_ = half_stencil_ && along[0] >= 2 * reach + 2;
    // (an odometer over D coordinates, axis 0 fastest; false once it wraps round)
    auto next = [](std::array<int, D>& c, const std::array<int, D>& lo,
                   const std::array<int, D>& hi, const std::array<int, D>& step) {
        for (int a = 0; a < D; ++a) {
            c[a] += step[a];
            if (c[a] < hi[a]) return true;
            c[a] = lo[a];
        }
        return false;
    };
    std::array<int, D> zero{}, one, first, past;
    one.fill(1);
    first.fill(-reach);
    past.fill(reach + 1);
    forward_.clear();
    std::array<int, D> o = first;
    do {
        int last = D - 1;
        while (last >= 0 && o[last] == 0) --last;
        if (last >= 0 && o[last] > 0) forward_.push_back(o);
    } while (next(o, first, past, one));
    stencil_rows_.assign(1, StencilRow{0, 0, zero}); // the cell itself
    for (const auto& f : forward_) {
        StencilRow& row = stencil_rows_.back();
        bool continues = f[0] == row.x1 + 1;
        for (int a = 1; a < D; ++a) continues = continues && f[a] == row.o[a];
        if (continues)
            row.x1 = f[0];
        else
            stencil_rows_.push_back(StencilRow{f[0], f[0], f});
    }
    sweep_cells_.clear();
    sweep_cells_.reserve(cells_.cell_count());
    block_end_.clear();
    block_end_.reserve(n_blocks);
    colour_block_.assign(1, 0);
    std::array<int, D> colour{};
    do {
        std::array<int, D> block = colour; // this colour's blocks: every colours_along-th
        do {
            std::array<int, D> lo, hi;
            for (int a = 0; a < D; ++a) {
                lo[a] = block[a] * width[a];
                hi[a] = std::min(lo[a] + width[a], along[a]);
            }
            std::array<int, D> cell = lo;
            do {
                std::size_t id = 0;
                for (int a = D - 1; a >= 0; --a)
                    id =
                        id * static_cast<std::size_t>(along[a]) + static_cast<std::size_t>(cell[a]);
                sweep_cells_.push_back(static_cast<std::uint32_t>(id));
            } while (next(cell, lo, hi, one));
            block_end_.push_back(static_cast<std::uint32_t>(sweep_cells_.size()));
        } while (next(block, colour, blocks_along, colours_along));
        colour_block_.push_back(static_cast<std::uint32_t>(block_end_.size()));
    } while (next(colour, zero, colours_along, one));
}

template <int D> void NeighborList<D>::make_sweep() {
    sweep_.resize(by_cell_.size());
    chunk_start_.assign(1, 0);
    colour_chunk_.assign(1, 0);
    std::size_t w = 0, b = 0, c = 0;
    for (std::size_t k = 0; k + 1 < colour_block_.size(); ++k) {
        for (; b < colour_block_[k + 1]; ++b) {
            for (; c < block_end_[b]; ++c)
                for (std::uint32_t q = cell_start_[sweep_cells_[c]];
                     q < cell_start_[sweep_cells_[c] + 1]; ++q)
                    sweep_[w++] = by_cell_[q];
            if (w - chunk_start_.back() >= sweep_chunk) chunk_start_.push_back(w);
        }
        if (w != chunk_start_.back()) chunk_start_.push_back(w);
        colour_chunk_.push_back(chunk_start_.size() - 1);
    }
}

template <int D> void NeighborList<D>::build(const std::vector<Vec<D>>& pos) {
    enter_stage("building the neighbour list");
    const std::size_t n = pos.size();
    if (n > max_particles)
        throw InputError(
            fmt::format("neighbour list: {} particles exceed the limit of {}", n, max_particles));
    const auto sn = static_cast<std::int64_t>(n);

    // Checked before binning: a NaN would make the cell index undefined, and since
    // minimum_image is exact only within 1.5 L, a position further than 0.75 L from the
    // centre would silently lose pairs.
    std::array<double, D> reach;
    for (int a = 0; a < D; ++a)
        reach[a] = box_.periodic(a) ? 0.75 * box_.length(a) : std::numeric_limits<double>::max();
    // Positions outside the box (but within reach) are allowed: the evolver builds after
    // its integrators' first half-step and wraps only at the end of the step. The build
    // bins and scans wrapped copies (ref_), so that every cell's particles lie inside
    // it, which the shortcuts below rely on.
    std::int64_t bad = sn;
    // (min is exact, so the schedule cannot change the result)
#pragma omp parallel for reduction(min : bad) if (sn >= parallel_min)
    for (std::int64_t i = 0; i < sn; ++i)
        for (int a = 0; a < D; ++a)
            if (!(std::abs(pos[i][a]) <= reach[a])) bad = std::min(bad, i);
    if (bad < sn) {
        std::string where = "(";
        for (int a = 0; a < D; ++a) where += fmt::format("{}{}", a ? ", " : "", pos[bad][a]);
        where += ")";
        throw RunError(fmt::format("neighbour list: particle {} (storage index) is at {}, which "
                                   "is not finite or not wrapped into the periodic box",
                                   bad, where));
    }
    n_ = 0; // until the rows below are complete
    build_offset_ = box_.shear_offset();

    // Binning: the cell of every particle in parallel, then a counting sort into cell
    // order (serial, about 3 ns per particle), each cell's particles in increasing index
    // as the shared cell list's linked lists had them. Building those lists was serial
    // (about 8 ns per particle, floor and modulo included), which two threads felt; and
    // chasing them (and the scattered positions they point to) for every stencil cost
    // more than the distance tests.
    // Cells of r_list / 2 scanned two deep when a full cell would hold many particles
    // (long cutoffs in dense systems, like Lennard-Jones at 2.5 sigma): the 5^D stencil
    // covers (5/6)^D of the 3^D one's volume, 42% fewer candidates in 3D. With few
    // particles per cell the extra, mostly empty, cells would cost more than they save.
    double cell_volume = 1.0;
    for (int a = 0; a < D; ++a) cell_volume *= r_list_;
    const int stencil_reach = static_cast<double>(n) / box_.volume() * cell_volume >= 8.0 ? 2 : 1;
    if (const double cell = grid_cell(stencil_reach, n); stencil_reach != reach_ || cell != cell_)
        set_grid(stencil_reach, cell);
    const std::size_t n_cells = cells_.cell_count();
    const auto sc = static_cast<std::int64_t>(n_cells);
    cell_of_.resize(n);
    by_cell_.resize(n);
    ref_.resize(n);
    home_.resize(n);
    auto wrapped = [&](std::size_t i) {
        Vec<D> r = pos[i];
        box_.wrap(r);
        return r;
    };
#pragma omp parallel for schedule(static) if (sn >= parallel_min)
    for (std::int64_t i = 0; i < sn; ++i)
        cell_of_[i] = static_cast<std::uint32_t>(cells_.cell_index(wrapped(i)));
    cell_start_.assign(n_cells + 1, 0);
    for (std::size_t i = 0; i < n; ++i) ++cell_start_[cell_of_[i] + 1];
    for (std::size_t c = 0; c < n_cells; ++c) cell_start_[c + 1] += cell_start_[c];
    for (std::size_t i = 0; i < n; ++i) { // cell_start_[c] is c's cursor here
        const std::uint32_t k = cell_start_[cell_of_[i]]++;
        by_cell_[k] = static_cast<std::uint32_t>(i);
        home_[i] = ref_[k] = wrapped(i);
    }
    // each cursor now stands at the next cell's start: shift them back
    for (std::size_t c = n_cells; c > 0; --c) cell_start_[c] = cell_start_[c - 1];
    cell_start_[0] = 0;

    // A pair at r_list to within rounding is listed: the by-image difference (ri + image
    // - rj) and the minimum image round the same pair's r^2 differently, by a few ulps,
    // and a pair the force loop finds inside r_cut = r_list (skin 0) must be in the list.
    // (A cubic lattice with a site one ulp inside L/2 has pairs at 3 - 4e-15 that the
    // shifted difference put at exactly 3.)
    const double rl2 = r_list_ * r_list_ * (1.0 + list_rounding);
    // Wrap is a std::bool_constant, true only with the whole stencil (a periodic axis too
    // short for the half one) for the cells next to a periodic face; with the half
    // stencil each range carries its image (by_image below). Elsewhere a raw difference
    // within 2 cells is the minimum image whenever it is shorter than r_list (a longer
    // one is not a pair either way: every position of ref_ lies in the box).
    auto near = [&](auto wrap, const Vec<D>& ri, const Vec<D>& rj) {
        if constexpr (decltype(wrap)::value)
            return detail::squared_length(box_.minimum_image(ri - rj)) < rl2;
        else
            return detail::squared_length(ri - rj) < rl2;
    };
    std::array<bool, D> periodic;
    std::array<int, D> along;
    Vec<D> length;
    for (int a = 0; a < D; ++a) {
        periodic[a] = box_.periodic(a);
        along[a] = cells_.cells_along(a);
        length[a] = box_.length(a);
    }
    // With the half stencil (and every position of ref_ in the box), the image of a neighbour
    // cell across a periodic face is known from the stencil offset: the whole range is
    // shifted by it (ri + image - rj), and no candidate needs minimum_image, whose
    // branches a scan through the faces mispredicts often (the build of a periodic
    // Lennard-Jones fluid took more than twice that of the same one between walls).
    // The pairs are the same: with 2 reach + 1 cells or more on the axis, each pair of
    // cells is related by one stencil offset, a particle of a cell across the face is
    // further than r_list in the direct difference, and a shifted difference shorter
    // than r_list <= L/2 is the minimum image.
    const bool by_image = half_stencil_;
    // Lees-Edwards shear: the offset of the image above, and where a row across the y
    // faces starts along x (sheared_row_shift).
    const bool sheared = box_.sheared();
    const double offset = box_.shear_offset();
    const int shift_up = sheared ? sheared_row_shift(1) : 0;
    const int shift_down = sheared ? sheared_row_shift(-1) : 0;
    // For the scans' trimming (trim_segments below): the cells' widths, and a margin far
    // above the rounding of a position's offset in its cell or of its binning.
    if (reach_ > max_stencil_reach) throw std::logic_error("neighbour list: stencil reach above 2");
    std::array<double, D> cell_width;
    double trim_margin = 0.0;
    for (int a = 0; a < D; ++a) {
        cell_width[a] = cells_.cell_width(a);
        trim_margin = std::max(trim_margin, 1e-9 * box_.length(a));
    }
    auto wraps = [&](std::int64_t c) {
        for (int a = 0; a < D; ++a) {
            const auto ca = static_cast<int>(c % along[a]);
            c /= along[a];
            if (periodic[a] &&
                (along[a] < 2 * reach_ + 1 || ca < reach_ || ca >= along[a] - reach_))
                return true;
        }
        return false;
    };
    const auto near_row = detail::near_row_for<D>(simd_level());
    const std::uint32_t* const idx = by_cell_.data();
    const Vec<D>* const ref = ref_.data();
    using Range = std::array<std::uint32_t, 2>;
    constexpr int stencil_max = D == 2 ? 25 : 125; // cells of a 5^D stencil

    // One pass over the cells writes every row. Each thread claims chunks of the row
    // storage (an atomic cursor) and appends the rows of its cells there, each row
    // starting where the chunk still has room for all its candidates (else in a fresh
    // chunk), so that the scan stores without bound checks. Rows lie in an order that
    // depends on the threads, but each row's content and order depend only on the
    // positions (the cell scan), so every sum over a row is the same for any thread
    // count. (An earlier build counted the rows in a first pass and filled them in a
    // second, in particle order: twice the distance tests.)
    rows_.resize(n);
    std::vector<std::uint32_t>& lengths = cell_of_; // free after the binning above
    // At most two passes: a pass that runs out of storage still counts every row, and the
    // second has storage that provably suffices (below).
    for (int pass = 0;; ++pass) {
        if (pass == 2) throw std::logic_error("neighbour list: the second pass ran out of storage");
        std::atomic<std::size_t> claimed{0};
        std::atomic<bool> overflow{false};
        std::size_t max_candidates = 0; // the most candidates of any particle
        std::uint32_t* const out = neighbors_.get();
        const std::size_t capacity = capacity_, chunk = chunk_;
#pragma omp parallel if (sn >= parallel_min)
        {
            std::size_t cur = 0, lim = 0;    // this thread's chunk: [cur, lim)
            std::vector<std::uint32_t> sink; // rows go here once storage ran out (counted only)
            std::vector<std::uint32_t> sheared_cells; // sheared_cells_within's
            // Where a row of at most `cand` entries goes: the chunk if it has room, else a
            // new chunk; nullptr once the storage is full (the pass is then repeated).
            auto place_row = [&](std::size_t cand) -> std::uint32_t* {
                if (cur + cand <= lim) return out + cur;
                if (!overflow.load(std::memory_order_relaxed)) {
                    const std::size_t size = std::max(chunk, cand);
                    const std::size_t at = claimed.fetch_add(size, std::memory_order_relaxed);
                    if (at + size <= capacity) {
                        cur = at;
                        lim = at + size;
                        return out + cur;
                    }
                    overflow.store(true, std::memory_order_relaxed);
                }
                if (sink.size() < cand) sink.resize(cand);
                return nullptr;
            };
#pragma omp for schedule(dynamic, 64) reduction(max : max_candidates)
            for (std::int64_t c = 0; c < sc; ++c) {
                const std::uint32_t cb = cell_start_[c], ce = cell_start_[c + 1];
                if (cb == ce) continue;
                std::array<Range, stencil_max> range;
                // what each range adds to ri - rj: the periodic image of its cell (a plain
                // array: an array of Vec would be zeroed, 3 kB, for every cell)
                double image[stencil_max][D];
                // With the half stencil each range is one segment of a stencil row: cells
                // at x offsets seg_x[r][0] .. seg_x[r][1] from this cell (consecutive
                // cell indices), at the offsets seg_o[r] on the other axes.
                std::array<std::array<int, 2>, stencil_max> seg_x;
                std::array<std::array<int, D>, stencil_max> seg_o;
                // seg_start[r][k]: where the segment's k-th cell starts (k = its length:
                // where it ends), copied here once per cell rather than read from
                // cell_start_ for each particle
                std::array<std::array<std::uint32_t, 2 * max_stencil_reach + 2>, stencil_max>
                    seg_start;
                int nr = 0;
                std::size_t cand = 0; // candidates of each particle of this cell (at most)
                // the particles [b, e) of cell order, of one or more consecutive cells
                auto add_range = [&](std::uint32_t b, std::uint32_t e, const Vec<D>& im) {
                    cand += e - b;
                    // Ranges that touch are concatenated (the cells between are empty):
                    // consecutive cells of a stencil row become one range, and one loop
                    // of ~8 candidates mispredicts its exit less often than three of ~3.
                    bool same_image = nr > 0;
                    for (int a = 0; a < D && same_image; ++a)
                        same_image = image[nr - 1][a] == im[a];
                    if (same_image && range[nr - 1][1] == b)
                        range[nr - 1][1] = e;
                    else if (b != e) {
                        for (int a = 0; a < D; ++a) image[nr][a] = im[a];
                        range[nr++] = {b, e};
                    }
                };
                auto add_cell = [&](std::size_t nc, const Vec<D>& im) {
                    add_range(cell_start_[nc], cell_start_[nc + 1], im);
                };
                std::array<int, D> cc; // this cell's coordinates
                {
                    std::int64_t rest = c;
                    for (int a = 0; a < D; ++a) {
                        cc[a] = static_cast<int>(rest % along[a]);
                        rest /= along[a];
                    }
                }
                // a cell at offset o joins the last segment where it continues it along x
                std::size_t seg_end_cell = 0; // the cell after the last segment's last
                auto add_segment_cell = [&](std::size_t nc, const Vec<D>& im,
                                            const std::array<int, D>& o) {
                    const std::uint32_t b = cell_start_[nc], e = cell_start_[nc + 1];
                    cand += e - b;
                    bool continues = nr > 0 && seg_x[nr - 1][1] + 1 == o[0] && seg_end_cell == nc;
                    for (int a = 1; a < D && continues; ++a) continues = seg_o[nr - 1][a] == o[a];
                    for (int a = 0; a < D && continues; ++a) continues = image[nr - 1][a] == im[a];
                    seg_end_cell = nc + 1;
                    if (continues) {
                        seg_x[nr - 1][1] = o[0];
                        seg_start[nr - 1][o[0] - seg_x[nr - 1][0] + 1] = e;
                        range[nr - 1][1] = e;
                        return;
                    }
                    for (int a = 0; a < D; ++a) image[nr][a] = im[a];
                    seg_x[nr] = {o[0], o[0]};
                    seg_o[nr] = o;
                    seg_start[nr][0] = b;
                    seg_start[nr][1] = e;
                    range[nr++] = {b, e};
                };
                // A whole row of consecutive cells, nc first: what add_segment_cell gives
                // cell by cell (a row never continues the segment before it: that one
                // ends at an x offset of reach, or is the cell's own row, which is first)
                auto add_segment_row = [&](std::size_t nc, const StencilRow& t, const Vec<D>& im) {
                    const int cells = t.x1 - t.x0 + 1;
                    for (int k = 0; k <= cells; ++k) seg_start[nr][k] = cell_start_[nc + k];
                    cand += seg_start[nr][cells] - seg_start[nr][0];
                    for (int a = 0; a < D; ++a) image[nr][a] = im[a];
                    seg_x[nr] = {t.x0, t.x1};
                    seg_o[nr] = t.o;
                    range[nr] = {seg_start[nr][0], seg_start[nr][cells]};
                    ++nr;
                    seg_end_cell = nc + static_cast<std::size_t>(cells);
                };
                // Each particle scans, of each segment, only the cells its sphere of
                // r_list reaches (trim_segments below), with half-width cells only: with
                // cells of r_list (reach 1) that trims a smaller share (a fifth of the
                // cells in 3D, a tenth in 2D), and ABP in 2D ran 0.94x.
                // (not under shear: the shifted rows across the y faces are not at the
                // offsets trim_segments measures)
                const bool trim = reach_ == max_stencil_reach && !sheared;
                if (half_stencil_) {
                    // Row by row (stencil_rows_): the axes above 0 give the row's image
                    // and first cell once; a row that stays inside axis 0 is consecutive
                    // cells, taken as one piece, and one across its faces goes cell by
                    // cell as a scan over forward_ would. The ranges are the same.
                    for (const StencilRow& t : stencil_rows_) {
                        std::size_t upper = 0; // the row's index on the axes above 0
                        bool inside = true;
                        Vec<D> im{};
                        int x0 = t.x0, x1 = t.x1;
                        for (int a = D - 1; a >= 1; --a) {
                            int x = cc[a] + t.o[a];
                            if (periodic[a]) {
                                // a neighbour cell across the face lies one box length
                                // away from where its particles are stored
                                if (x < 0) {
                                    x += along[a];
                                    im[a] = length[a];
                                } else if (x >= along[a]) {
                                    x -= along[a];
                                    im[a] = -length[a];
                                }
                                // Across the sheared y faces the image slides by the
                                // offset: the row's cells shift along x with it, one
                                // more to cover the offset's part of a cell. (Such a
                                // row has every x offset -reach .. reach.)
                                if (sheared && a == 1 && im[1] != 0.0) {
                                    const bool up = im[1] < 0.0;
                                    im[0] = up ? -offset : offset;
                                    x0 = up ? shift_up : shift_down;
                                    x1 = x0 + 2 * reach_ + 1;
                                }
                            } else {
                                inside = inside && x >= 0 && x < along[a];
                            }
                            upper = upper * static_cast<std::size_t>(along[a]) +
                                    static_cast<std::size_t>(x);
                        }
                        if (!inside) continue;
                        const int x_first = cc[0] + x0, x_last = cc[0] + x1;
                        if (x_first >= 0 && x_last < along[0]) {
                            const std::size_t nc = upper * static_cast<std::size_t>(along[0]) +
                                                   static_cast<std::size_t>(x_first);
                            if (trim)
                                add_segment_row(nc, t, im);
                            else
                                add_range(cell_start_[nc], cell_start_[nc + (x1 - x0) + 1], im);
                            continue;
                        }
                        for (int dx = x0; dx <= x1; ++dx) {
                            int x = cc[0] + dx;
                            Vec<D> imx = im;
                            if (periodic[0]) {
                                if (x < 0) {
                                    x += along[0];
                                    imx[0] = im[0] + length[0];
                                } else if (x >= along[0]) {
                                    x -= along[0];
                                    imx[0] = im[0] - length[0];
                                }
                            } else if (x < 0 || x >= along[0]) {
                                continue;
                            }
                            const std::size_t nc = upper * static_cast<std::size_t>(along[0]) +
                                                   static_cast<std::size_t>(x);
                            std::array<int, D> o = t.o;
                            o[0] = dx;
                            if (trim)
                                add_segment_cell(nc, imx, o);
                            else
                                add_cell(nc, imx);
                        }
                    }
                } else if (sheared && wraps(c)) {
                    sheared_cells_within(c, sheared_cells);
                    for (const std::uint32_t nc : sheared_cells) add_cell(nc, Vec<D>{});
                } else {
                    cells_.for_each_cell_within(
                        static_cast<std::int32_t>(c), reach_,
                        [&](std::int32_t nc) { add_cell(static_cast<std::size_t>(nc), Vec<D>{}); });
                }
                max_candidates = std::max(max_candidates, cand);
                // With the half stencil a particle at k in its cell starts after itself
                // and keeps every candidate in range; with the full one it keeps those of
                // higher index.
                const bool half = half_stencil_;
                // The cells of a segment that a particle's sphere of r_list reaches: about
                // two thirds of a 5^3 half stencil's cells. Those left out hold no pair, so
                // the rows are the same. gap2[a][d + reach] is the squared distance along
                // axis a from the particle to the cells at offset d, less a margin for
                // positions binned by rounding.
                std::array<Range, stencil_max> reached;
                const detail::NearRowInput<D> near_input{
                    ref, idx, trim ? reached.data() : range.data(), image, nr, rl2};
                auto trim_segments = [&](const Vec<D>& ri) {
                    // (branch-free: the branches of a first version mispredicted so often
                    // that they cost what the shorter scans saved)
                    // (trimming runs at reach 2 only)
                    constexpr int R = max_stencil_reach;
                    double gap2[D][2 * R + 1];
                    for (int a = 0; a < D; ++a) {
                        const double u = ri[a] - (box_.lo(a) + cc[a] * cell_width[a]);
                        for (int d = -R; d <= R; ++d) {
                            const double g =
                                CellList<D>::gap_to_cell(u, cell_width[a], d, trim_margin);
                            gap2[a][R + d] = g * g;
                        }
                    }
                    for (int r = 0; r < nr; ++r) {
                        double across = 0.0;
                        for (int a = 1; a < D; ++a) across += gap2[a][seg_o[r][a] + R];
                        const double left = rl2 - across;
                        // the x offsets reached form [-behind, ahead] (the gaps grow with
                        // the offset's size); none where left <= 0
                        int behind = 0, ahead = 0;
                        for (int d = 1; d <= R; ++d) {
                            behind += gap2[0][R - d] < left;
                            ahead += gap2[0][R + d] < left;
                        }
                        const int x0 = seg_x[r][0], x1 = seg_x[r][1];
                        const int lo = std::min(std::max(x0, -behind), x1 + 1);
                        const int hi = std::max(left > 0.0 ? std::min(x1, ahead) : lo - 1, lo - 1);
                        reached[r] = {seg_start[r][lo - x0], seg_start[r][hi - x0 + 1]};
                    }
                };
                auto row = [&](auto wrap, std::uint32_t kk, std::uint32_t i, const Vec<D>& ri) {
                    // Branch-free: about a sixth of the candidates hit, at random. Every
                    // candidate is stored and the cursor advances only on a hit; the row
                    // has room for all of them.
                    // (the SIMD scans may write a few entries past the row's
                    // candidates: room for them too)
                    std::uint32_t* dst = place_row(cand + detail::near_row_slack);
                    const bool stored = dst != nullptr;
                    if (!stored) dst = sink.data();
                    std::size_t w = 0;
                    if (half) {
                        // (the half stencil never wraps: each range carries its image;
                        // the particle's own cell is always reached)
                        if (trim) trim_segments(ri);
                        w = near_row(near_input, kk + 1, ri, dst);
                    } else {
                        for (int r = 0; r < nr; ++r) {
                            Vec<D> rs = ri;
                            for (int a = 0; a < D; ++a) rs[a] += image[r][a];
                            for (std::uint32_t k = range[r][0]; k < range[r][1]; ++k) {
                                const std::uint32_t j = idx[k];
                                dst[w] = j;
                                w += (j > i) & near(wrap, rs, ref[k]);
                            }
                        }
                    }
                    lengths[i] = static_cast<std::uint32_t>(w);
                    if (stored) {
                        rows_[i] = (static_cast<std::uint64_t>(cur) << length_bits) | w;
                        cur += w;
                    }
                };
                if (!by_image && wraps(c))
                    for (std::uint32_t k = cb; k < ce; ++k)
                        row(std::true_type{}, k, idx[k], ref[k]);
                else
                    for (std::uint32_t k = cb; k < ce; ++k)
                        row(std::false_type{}, k, idx[k], ref[k]);
            }
        }
        std::size_t total = 0, longest = 0;
        // (integer sums and maxima: exact in any order)
#pragma omp parallel for reduction(+ : total) reduction(max : longest) if (sn >= parallel_min)
        for (std::int64_t i = 0; i < sn; ++i) {
            total += lengths[i];
            longest = std::max<std::size_t>(longest, lengths[i]);
        }
        if (longest >= (std::size_t{1} << length_bits))
            throw RunError(fmt::format("neighbour list: a row of {} neighbours exceeds the limit "
                                       "of {}; reduce the cutoff or the skin",
                                       longest, (std::size_t{1} << length_bits) - 1));
        entries_ = total;
        if (!overflow.load()) break;
        // Storage too small (the first build, or the system grew denser). A thread leaves
        // a chunk only when the next row's candidates and the scans' slack (at most
        // max_candidates + near_row_slack) do not fit in what is left of it, so with chunks
        // of at least 4 times that every chunk it leaves is at least 3/4 used: the pass claims at
        // most 4/3 of the total plus one unfinished chunk per thread. (Room for the total plus a
        // chunk per thread was not enough: in a perfect lattice every row has the most candidates,
        // and with LJ's 2.5 cutoff in in.lj's fcc crystal, 2300 candidates against chunks of 4096
        // left half of every chunk empty, so the pass overflowed again, the same
        // capacity was computed from the same total, and the build repeated for ever.)
        chunk_ = std::max(chunk_entries, 4 * (max_candidates + detail::near_row_slack));
        capacity_ =
            grow(total + total / 3 + static_cast<std::size_t>(omp_get_max_threads() + 1) * chunk_);
        neighbors_.reset(); // free first so that old and new never coexist
        neighbors_ = std::make_unique_for_overwrite<std::uint32_t[]>(capacity_);
    }
    make_sweep();
    n_ = n;
    ++builds_;
}

template <int D> int NeighborList<D>::sheared_row_shift(int direction) const {
    // A neighbour across the upper y face is the image of a particle stored at x less the
    // offset (across the lower one, plus it): from a cell at x index c its cells within
    // r_list <= reach cell widths run from c - reach + floor(-+offset / w) to one beyond
    // c + reach + that floor. (Cells are wider than r_list / reach by a margin far above
    // the rounding of the floor and of the binning.)
    const double w = cells_.cell_width(0);
    return static_cast<int>(
               std::floor((direction > 0 ? -box_.shear_offset() : box_.shear_offset()) / w)) -
           reach_;
}

template <int D>
void NeighborList<D>::sheared_cells_within(std::int64_t c, std::vector<std::uint32_t>& out) const {
    std::array<int, D> along, cc;
    for (int a = 0; a < D; ++a) {
        along[a] = cells_.cells_along(a);
        cc[a] = static_cast<int>(c % along[a]);
        c /= along[a];
    }
    const int m = reach_;
    const int up = sheared_row_shift(1), down = sheared_row_shift(-1);
    auto wrapped = [](int x, int n) { return ((x % n) + n) % n; };
    out.clear();
    // every offset on the axes above x, odometer fashion (axis 1 fastest)
    std::array<int, D> o;
    o.fill(-m);
    while (true) {
        const int y = cc[1] + o[1];
        // images across the y faces: one at most for a pair within r_list <= L_y / 2
        const int images = y < 0 ? -1 : y >= along[1] ? 1 : 0;
        bool inside = y >= -along[1] && y < 2 * along[1];
        std::size_t upper = static_cast<std::size_t>(wrapped(y, along[1]));
        std::size_t stride = static_cast<std::size_t>(along[1]);
        for (int a = 2; a < D; ++a) {
            int z = cc[a] + o[a];
            if (box_.periodic(a))
                z = wrapped(z, along[a]);
            else
                inside = inside && z >= 0 && z < along[a];
            upper += stride * static_cast<std::size_t>(std::clamp(z, 0, along[a] - 1));
            stride *= static_cast<std::size_t>(along[a]);
        }
        if (inside) {
            const int first = images == 0 ? cc[0] - m : cc[0] + (images > 0 ? up : down);
            const int count = std::min(images == 0 ? 2 * m + 1 : 2 * m + 2, along[0]);
            for (int k = 0; k < count; ++k)
                out.push_back(static_cast<std::uint32_t>(
                    upper * static_cast<std::size_t>(along[0]) +
                    static_cast<std::size_t>(wrapped(first + k, along[0]))));
        }
        int a = 1;
        while (a < D && ++o[a] > m) o[a++] = -m;
        if (a == D) break;
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

template <int D> void NeighborList<D>::reorder(const std::vector<std::uint32_t>& order) {
    if (order.size() != n_)
        throw RunError(
            fmt::format("neighbour list: reorder of {} particles, list has {}", order.size(), n_));
    std::vector<std::uint32_t> new_index(n_);
    for (std::size_t i = 0; i < n_; ++i) new_index[order[i]] = static_cast<std::uint32_t>(i);
    // Rows stay where they are; the particle each belongs to and the entries are renamed.
    permute_by(rows_, order);
    for (std::size_t i = 0; i < n_; ++i)
        for (std::uint32_t* j = neighbors_.get() + (rows_[i] >> length_bits);
             j != neighbors_.get() + (rows_[i] >> length_bits) + count(i); ++j)
            *j = new_index[*j];
    // ref_ stays in cell order; only the particle each entry belongs to is renamed
    for (auto& k : by_cell_) k = new_index[k];
    permute_by(home_, order);
    for (auto& k : sweep_) k = new_index[k];
}

template <int D> bool NeighborList<D>::needs_rebuild(const std::vector<Vec<D>>& pos) const {
    if (builds_ == 0 || n_ != pos.size()) return true;
    if (box_.sheared()) return sheared_moves_exceed(pos, skin_);
    const double half2 = 0.25 * skin_ * skin_, skin2 = skin_ * skin_;
    // the particles in blocks, each marked when one of its particles moved more than
    // skin/2: the inner loops stay free of branches, and only marked blocks are read again
    const std::size_t blocks = (n_ + mover_block - 1) / mover_block;
    mover_blocks_.resize(blocks);
    const auto sb = static_cast<std::int64_t>(blocks);
    bool too_far = false;
    double most2 = 0.0;
    std::size_t movers = 0;
    detail::BlockMovesInput<D> in{pos.data(), home_.data(), {}, {}, skin2, half2};
    for (int a = 0; a < D; ++a) {
        const bool periodic = box_.periodic(a);
        in.half[a] = periodic ? box_.hi(a) : std::numeric_limits<double>::infinity();
        in.length[a] = periodic ? box_.length(a) : 0.0;
    }
    const auto block_moves = detail::block_moves_for<D>(simd_level());
    ChunkShares shares(sb, 4);
#pragma omp parallel reduction(|| : too_far) reduction(max : most2) reduction(+ : movers) \
    if (static_cast<std::int64_t>(n_) >= parallel_min)
    shares.run([&](std::int64_t first_block, std::int64_t last_block) {
        for (std::int64_t b = first_block; b < last_block; ++b) {
            const std::size_t first = static_cast<std::size_t>(b) * mover_block;
            const detail::BlockMoves m = block_moves(in, first, std::min(n_, first + mover_block));
            too_far = too_far || m.far;
            most2 = std::max(most2, m.most2);
            movers += m.movers;
            mover_blocks_[static_cast<std::size_t>(b)] = m.movers > 0 ? 1 : 0;
        }
    });
    if (too_far) return true;
    if (movers == 0) return false;
    if (movers > checked_movers + n_ / checked_movers_per) return true;
    // A pair missing from the rows was at least r_list apart at the build; closer than
    // r_cut now, its two moves add up to more than the skin, so one of them moved more
    // than skin/2, and the other was at the build within r_cut + its own move (at most
    // the largest) of where that one is now.
    const double most = std::sqrt(most2);
    bool missing = false;
#pragma omp parallel for schedule(dynamic, 1) reduction(|| : missing) if (movers >= 64)
    for (std::int64_t b = 0; b < sb; ++b) {
        if (missing || mover_blocks_[static_cast<std::size_t>(b)] == 0) continue;
        const std::size_t first = static_cast<std::size_t>(b) * mover_block;
        for (std::size_t k = first; k < std::min(n_, first + mover_block); ++k) {
            const double d2 = norm2(box_.minimum_image(pos[k] - home_[k]));
            if (d2 > half2 && missing_partner(pos, k, r_cut_ + most)) missing = true;
        }
    }
    return missing;
}

template <int D>
bool NeighborList<D>::missing_partner(const std::vector<Vec<D>>& pos, std::size_t i,
                                      double reach) const {
    // relative margins far above the rounding of the squared distances: a pair at the
    // edge of the cutoff counts as close, one at the edge of r_list as possibly missing
    const double close2 = r_cut_ * r_cut_ * (1.0 + 1e-9);
    const double listed2 = r_list_ * r_list_ * (1.0 - 1e-9);
    const int m = cells_.cells_to_reach(reach * (1.0 + 1e-9));
    bool missing = false;
    // (a position off the box is binned as the build bins: wrapped, or clamped to a
    // wall, which brings it no further from any particle inside)
    cells_.for_each_cell_within(cells_.cell_index(pos[i]), m, [&](std::int32_t c) {
        for (std::uint32_t q = cell_start_[c]; q < cell_start_[c + 1]; ++q) {
            const std::uint32_t j = by_cell_[q];
            if (j == i || !(norm2(box_.minimum_image(pos[i] - pos[j])) < close2)) continue;
            if (!(norm2(box_.minimum_image(home_[i] - ref_[q])) < listed2)) missing = true;
        }
    });
    return missing;
}

template <int D> bool NeighborList<D>::moved_half_skin(const std::vector<Vec<D>>& pos) const {
    if (builds_ == 0 || n_ != pos.size()) return true;
    if (box_.sheared()) return sheared_moves_exceed(pos, skin_);
    const double lim2 = 0.25 * skin_ * skin_;
    const auto sn = static_cast<std::int64_t>(n_);
    bool moved = false;
#pragma omp parallel for schedule(static) reduction(|| : moved) if (sn >= parallel_min)
    for (std::int64_t k = 0; k < sn; ++k) {
        // written as !(<=) so that a NaN position asks for a rebuild (which reports it)
        if (!(norm2(box_.minimum_image(pos[k] - home_[k])) <= lim2)) moved = true;
    }
    return moved;
}

template <int D>
bool NeighborList<D>::sheared_moves_exceed(const std::vector<Vec<D>>& pos, double limit) const {
    // A pair unlisted at the build was r_list or more apart in some image; each move
    // (measured by the minimum image now, so that a crossing of the y faces counts as
    // if made at the present offset) and, across the y faces, the offset's change since
    // the build bring it closer by at most their sum. The old skin/2 rule with the
    // offset's change in: a sheared list is rebuilt often anyway (the streaming moves
    // particles near the y faces by rate L_y / 2 per unit time).
    const double lx = box_.length(0);
    double change = box_.shear_offset() - build_offset_;
    change -= lx * std::nearbyint(change / lx);
    const auto sn = static_cast<std::int64_t>(n_);
    double most2 = 0.0;
    bool bad = false;
#pragma omp parallel for schedule(static) reduction(max                                            \
                                                    : most2)                                       \
    reduction(||                                                                                   \
              : bad) if (sn >= parallel_min)
    for (std::int64_t k = 0; k < sn; ++k) {
        const double d2 = norm2(box_.minimum_image(pos[k] - home_[k]));
        // (a NaN position asks for a rebuild, which reports it)
        if (!(d2 >= 0.0))
            bad = true;
        else
            most2 = std::max(most2, d2);
    }
    return bad || !(2.0 * std::sqrt(most2) + std::abs(change) <= limit);
}

template <int D> std::size_t NeighborList<D>::memory_bytes() const {
    return cells_.memory_bytes() +
           (cell_start_.capacity() + by_cell_.capacity() + cell_of_.capacity()) *
               sizeof(std::uint32_t) +
           rows_.capacity() * sizeof(std::uint64_t) + capacity_ * sizeof(std::uint32_t) +
           (ref_.capacity() + home_.capacity()) * sizeof(Vec<D>) +
           (sweep_cells_.capacity() + block_end_.capacity() + colour_block_.capacity() +
            sweep_.capacity()) *
               sizeof(std::uint32_t) +
           (chunk_start_.capacity() + colour_chunk_.capacity()) * sizeof(std::size_t);
}

template <int D>
bool NeighborList<D>::needs_rebuild_scaled(const std::vector<Vec<D>>& pos,
                                           const Box<D>& now) const {
    if (builds_ == 0 || n_ != pos.size()) return true;
    Vec<D> back;
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (int a = 0; a < D; ++a) {
        const double lambda = now.length(a) / box_.length(a);
        back[a] = 1.0 / lambda;
        lo = std::min(lo, lambda);
        hi = std::max(hi, lambda);
    }
    double most2 = 0.0;
    for (std::size_t i = 0; i < n_; ++i) {
        Vec<D> r;
        for (int a = 0; a < D; ++a) r[a] = pos[i][a] * back[a];
        most2 = std::max(most2, norm2(box_.minimum_image(r - home_[i])));
    }
    const double u = std::sqrt(most2);
    return !(lo * (r_list_ - 2.0 * u) >= r_cut_ &&
             hi * (r_list_ + 2.0 * u) <= r_list_ + 2.0 * skin_);
}

template class NeighborList<2>;
template class NeighborList<3>;

} // namespace pedesis
