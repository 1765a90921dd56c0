#pragma once
// A cell list shared by every engine. Cells are at least `min_cell` wide, so all
// pairs closer than min_cell sit in the same or adjacent cells: wider by a relative
// 1e-10, because binning a position rounds ((x - lo) and its product with n / L, a few
// ulps of the cell count: below 3e-12 cells at 4096 cells), and a pair a hair closer
// than exactly one cell width, one of them an ulp below a cell face, would otherwise be
// binned two cells apart (found by the brute-force tests on random boxes). Correct for any box:
// on axes with fewer than 3 cells the neighbouring cells are de-duplicated, and wall
// axes do not wrap. Supports incremental insert/remove (the event engine moves one
// particle at a time) as well as a full rebuild.
#include "pedesis/core/box.hpp"
#include "pedesis/core/clamped_int.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace pedesis {

template <int D> class CellList {
  public:
    static constexpr std::int32_t none = -1;
    // 4096 cells along an axis in 2D, 406 in 3D: at most 2^24 and 2^26 cells (64 and 256 MB)
    static constexpr int max_cells_along = D == 2 ? 4096 : 406;
    // How much wider than asked the cells are (see above), and the smaller margin by
    // which cells_to_reach rounds up: far above the binning's rounding, and small
    // enough that a reach of exactly min_cell still needs one cell.
    static constexpr double width_margin = 1e-10;
    static constexpr double reach_margin = 1e-11;

    CellList() = default;
    // With `periodic_multiple` m > 1, a periodic axis with at least m cells gets a
    // multiple of m (wider cells): the soft engine's neighbour list colours blocks of
    // cells with a period that must divide the count.
    CellList(const Box<D>& box, double min_cell, int periodic_multiple = 1) : box_(box) {
        std::size_t total = 1;
        for (int a = 0; a < D; ++a) {
            // the ratio is clamped before it becomes an int: a huge box, a tiny cutoff or
            // NaN from a crafted file must not overflow; the cap keeps the grid of a huge
            // sparse box within max_cells_along per axis (wider cells stay correct)
            int n =
                clamped_int(box.length(a) / (min_cell * (1.0 + width_margin)), 1, max_cells_along);
            if (box.periodic(a) && n >= periodic_multiple) n -= n % periodic_multiple;
            n_[a] = n;
            inv_w_[a] = n / box.length(a);
            stride_[a] = static_cast<std::int32_t>(total);
            total *= static_cast<std::size_t>(n);
        }
        head_.assign(total, none);
    }

    std::size_t cell_count() const { return head_.size(); }
    int cells_along(int a) const { return n_[a]; }
    double cell_width(int a) const { return box_.length(a) / n_[a]; }

    std::int32_t cell_index(const Vec<D>& r) const {
        std::int32_t idx = 0;
        for (int a = 0; a < D; ++a) idx += coord(r, a) * stride_[a];
        return idx;
    }

    void clear(std::size_t n_particles) {
        std::fill(head_.begin(), head_.end(), none);
        next_.assign(n_particles, none);
        cell_of_.assign(n_particles, none);
    }

    void build(const std::vector<Vec<D>>& pos) {
        clear(pos.size());
        for (std::size_t i = pos.size(); i-- > 0;) insert(static_cast<std::uint32_t>(i), pos[i]);
    }

    void insert(std::uint32_t i, const Vec<D>& r) {
        const std::int32_t c = cell_index(r);
        next_[i] = head_[c];
        head_[c] = static_cast<std::int32_t>(i);
        cell_of_[i] = c;
    }

    void remove(std::uint32_t i) {
        std::int32_t* link = &head_[cell_of_[i]];
        while (*link != static_cast<std::int32_t>(i)) link = &next_[*link];
        *link = next_[i];
        next_[i] = none;
        cell_of_[i] = none;
    }

    std::int32_t head(std::int32_t cell) const { return head_[cell]; }
    std::int32_t next(std::uint32_t i) const { return next_[i]; }
    std::int32_t cell_of(std::uint32_t i) const { return cell_of_[i]; }

    // Calls f(cell) once for every distinct cell adjacent to (or equal to) `cell`.
    template <class F> void for_each_neighbor_cell(std::int32_t cell, F&& f) const {
        for_each_cell_within(cell, 1, f);
    }

    // Calls f(cell) once for every distinct cell at most `m` cells from `cell` along each
    // axis (m >= 1). Periodic axes wrap; an axis with fewer than 2m + 1 cells is scanned
    // once, from `cell` on (the order of the m = 1 scan is that of a 3-cell stencil).
    template <class F> void for_each_cell_within(std::int32_t cell, int m, F&& f) const {
        // the usual 3-cell stencil gets offset tables of its own size (it runs for every
        // list rebuild of the event engine); reaches of up to 8 cells share wider ones
        if (m == 1)
            scan_cells<3>(cell, m, f);
        else
            scan_cells<17>(cell, m, f);
    }

  private:
    template <int most, class F> void scan_cells(std::int32_t cell, int m, F&& f) const {
        // the cell offsets along each axis, wrapped and scaled by the stride
        std::array<std::array<std::int32_t, most>, D> offs;
        std::array<int, D> count;
        for (int a = 0; a < D; ++a) {
            const int c = (cell / stride_[a]) % n_[a];
            const int n = n_[a];
            int first = 0, span = 0;
            if (box_.periodic(a)) {
                const bool whole = 2 * m + 1 > n || 2 * m + 1 > most;
                first = whole ? c : c - m;
                span = whole ? n : 2 * m + 1;
            } else {
                first = std::max(0, c - m);
                span = std::min(n - 1, c + m) - first + 1;
                if (span > most) {
                    first = 0;
                    span = n;
                }
            }
            if (span > most) {
                // a reach wider than 8 cells along a long axis: every cell once
                for (std::int32_t c2 = 0; c2 < static_cast<std::int32_t>(head_.size()); ++c2) f(c2);
                return;
            }
            count[a] = span;
            for (int k = 0; k < span; ++k) {
                int x = first + k;
                if (x < 0) x += n;
                if (x >= n) x -= n;
                offs[a][k] = x * stride_[a];
            }
        }
        std::array<int, D> k{};
        while (true) {
            std::int32_t idx = 0;
            for (int a = 0; a < D; ++a) idx += offs[a][k[a]];
            f(idx);
            int a = 0;
            while (a < D && ++k[a] == count[a]) k[a++] = 0;
            if (a == D) break;
        }
    }

  public:
    // Calls f(j) for every particle in the cells around position r.
    template <class F> void for_each_near(const Vec<D>& r, F&& f) const {
        for_each_within(r, 1, f);
    }
    // The same for the cells at most m cells away along each axis.
    template <class F> void for_each_within(const Vec<D>& r, int m, F&& f) const {
        for_each_cell_within(cell_index(r), m, [&](std::int32_t c) {
            for (std::int32_t j = head_[c]; j != none; j = next_[j])
                f(static_cast<std::uint32_t>(j));
        });
    }
    // The distance along one axis from a point at offset u in its cell (of width w) to the
    // cell d cells away, less `margin` (never below 0): a lower bound on how far any
    // particle binned there lies, where the margin exceeds the binning's rounding. The
    // scans that skip cells beyond a reach (for_each_reaching, NeighborList's build)
    // share it.
    static double gap_to_cell(double u, double w, int d, double margin) {
        const double g = d > 0 ? d * w - u : d < 0 ? u + (-d - 1) * w : 0.0;
        return d == 0 ? 0.0 : std::max(0.0, g - margin);
    }
    // for_each_within(r, 1, f) less the cells that come no closer to r than `reach` (at
    // a 3^3 stencil's corners, about a quarter of its cells): their particles are all
    // further, and the rest come in the same order. Needs cells at least `reach` wide
    // (cells_to_reach(reach) == 1), else it is for_each_within(r, cells_to_reach(reach)).
    template <class F> void for_each_reaching(const Vec<D>& r, double reach, F&& f) const {
        const int m = cells_to_reach(reach);
        // the gaps below take r's offset in its cell; a position off a periodic axis's
        // box (its cell found by wrapping) or not finite gets the whole stencil
        bool in_box = true;
        for (int a = 0; a < D; ++a)
            in_box = in_box && std::isfinite(r[a]) &&
                     (!box_.periodic(a) || (r[a] >= box_.lo(a) && r[a] < box_.hi(a)));
        if (m != 1 || !in_box) {
            for_each_within(r, m, f);
            return;
        }
        const std::int32_t cell = cell_index(r);
        // per axis, as scan_cells<3> visits them: the cells' offsets into head_ and the
        // squared distance from r to each, less a margin far above the rounding of r's
        // offset in its cell (0 where the axis is scanned whole: too few cells to tell
        // one side from the other)
        std::array<std::array<std::int32_t, 3>, D> offs;
        std::array<std::array<double, 3>, D> gap2;
        std::array<int, D> count;
        for (int a = 0; a < D; ++a) {
            const int c = (cell / stride_[a]) % n_[a];
            const int n = n_[a];
            const double w = cell_width(a);
            const double u = r[a] - (box_.lo(a) + c * w);
            const double margin = 1e-9 * box_.length(a);
            const bool whole = box_.periodic(a) && 3 > n;
            const int first = whole ? c : box_.periodic(a) ? c - 1 : std::max(0, c - 1);
            count[a] = whole ? n : box_.periodic(a) ? 3 : std::min(n - 1, c + 1) - first + 1;
            for (int k = 0; k < count[a]; ++k) {
                const int d = first + k - c; // -1, 0 or +1 unless whole
                const double g = whole ? 0.0 : gap_to_cell(u, w, d, margin);
                gap2[a][k] = g * g;
                int x = first + k;
                if (x < 0) x += n;
                if (x >= n) x -= n;
                offs[a][k] = x * stride_[a];
            }
        }
        const double reach2 = reach * reach;
        std::array<int, D> k{};
        while (true) {
            std::int32_t idx = 0;
            double g2 = 0.0;
            for (int a = 0; a < D; ++a) {
                idx += offs[a][k[a]];
                g2 += gap2[a][k[a]];
            }
            if (g2 < reach2)
                for (std::int32_t j = head_[idx]; j != none; j = next_[j])
                    f(static_cast<std::uint32_t>(j));
            int a = 0;
            while (a < D && ++k[a] == count[a]) k[a++] = 0;
            if (a == D) break;
        }
    }
    // Calls f(j) for the particles of every cell that meets the box `centre ± half` (per
    // axis; widened by a margin above the binning's rounding), each cell once: periodic
    // axes wrap (a span of the whole axis or more scans it once), wall axes are clipped.
    // The event engine's scans across sliding faces, whose reach is longer along x.
    template <class F> void for_each_in_box(const Vec<D>& centre, const Vec<D>& half, F&& f) const {
        std::array<int, D> first{}, count{};
        for (int a = 0; a < D; ++a) {
            const double margin = 1e-9 * box_.length(a);
            const double from = (centre[a] - half[a] - margin - box_.lo(a)) * inv_w_[a];
            const double to = (centre[a] + half[a] + margin - box_.lo(a)) * inv_w_[a];
            if (!(std::isfinite(from) && std::isfinite(to))) {
                first[a] = 0;
                count[a] = n_[a];
                continue;
            }
            int lo = clamped_int(std::floor(from), -(1 << 30), 1 << 30);
            int hi = clamped_int(std::floor(to), -(1 << 30), 1 << 30);
            if (!box_.periodic(a)) {
                lo = std::clamp(lo, 0, n_[a] - 1);
                hi = std::clamp(hi, 0, n_[a] - 1);
            }
            const long span = static_cast<long>(hi) - lo + 1;
            if (span >= n_[a]) {
                first[a] = 0;
                count[a] = n_[a];
            } else {
                first[a] = ((lo % n_[a]) + n_[a]) % n_[a];
                count[a] = static_cast<int>(span);
            }
        }
        std::array<int, D> k{};
        while (true) {
            std::int32_t idx = 0;
            for (int a = 0; a < D; ++a) {
                int x = first[a] + k[a];
                if (x >= n_[a]) x -= n_[a];
                idx += x * stride_[a];
            }
            for (std::int32_t j = head_[idx]; j != none; j = next_[j])
                f(static_cast<std::uint32_t>(j));
            int a = 0;
            while (a < D && ++k[a] == count[a]) k[a++] = 0;
            if (a == D) break;
        }
    }
    // Cells along each axis needed to reach distance `reach` from any point of a cell,
    // whatever the binning's rounding.
    int cells_to_reach(double reach) const {
        int m = 1;
        for (int a = 0; a < D; ++a)
            m = std::max(m, clamped_int(std::ceil(reach / cell_width(a) * (1.0 + reach_margin)), 1,
                                        1 << 30));
        return m;
    }

    // Exact membership and order, for checkpoints (scan order decides ties).
    template <class Out> void save(Out&& put) const {
        put(head_);
        put(next_);
        put(cell_of_);
    }
    template <class In> void load(In&& get) {
        const std::size_t cells = head_.size();
        get(head_);
        get(next_);
        get(cell_of_);
        const auto n = static_cast<std::int32_t>(next_.size());
        bool ok = head_.size() == cells && next_.size() == cell_of_.size();
        for (auto h : head_) ok = ok && h >= none && h < n;
        for (auto h : next_) ok = ok && h >= none && h < n;
        // none: a particle this list does not hold (the event engine's other size classes)
        for (auto c : cell_of_) ok = ok && c >= none && c < static_cast<std::int32_t>(cells);
        if (!ok) throw InputError("checkpoint: cell list does not match the box (corrupt file)");
    }

    std::size_t memory_bytes() const {
        return head_.capacity() * sizeof(std::int32_t) + next_.capacity() * sizeof(std::int32_t) +
               cell_of_.capacity() * sizeof(std::int32_t);
    }

  private:
    int coord(const Vec<D>& r, int a) const {
        // a position absurdly far outside the box (a blow-up) must not overflow the int;
        // any position within 2^30 cells keeps its true periodic image
        int c = clamped_int(std::floor((r[a] - box_.lo(a)) * inv_w_[a]), -(1 << 30), 1 << 30);
        if (box_.periodic(a)) {
            if (r[a] >= box_.lo(a) && r[a] < box_.hi(a)) {
                // inside the box, only rounding can give n (one ulp below L/2: (L - ulp)
                // n / L rounds to n); wrapping it to cell 0 would put a particle at +L/2
                // in the cell at -L/2, and a neighbour list that takes a cell's particles
                // to lie in it would miss its pairs (found by the lattice tests)
                c = std::clamp(c, 0, n_[a] - 1);
            } else {
                c %= n_[a];
                if (c < 0) c += n_[a];
            }
        } else {
            // positions on a wall (or a rounding error past it) belong to the edge cell
            if (c < 0) c = 0;
            if (c >= n_[a]) c = n_[a] - 1;
        }
        return c;
    }

    Box<D> box_;
    std::array<int, D> n_{};
    std::array<double, D> inv_w_{};
    std::array<std::int32_t, D> stride_{};
    std::vector<std::int32_t> head_;
    std::vector<std::int32_t> next_;
    std::vector<std::int32_t> cell_of_;
};

} // namespace pedesis
