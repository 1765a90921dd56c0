#include "pedesis/soft/domain_decomposition.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/spatial/spatial_sort.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace pedesis {

namespace {

// A particle travels as plain numbers: tag, species, then position, velocity,
// director, image counts and force (D each) and torque. Tags (< 2^32) and species are
// exact in a double.
template <int D> constexpr std::size_t record_size = 2 + 5 * D + (D == 2 ? 1 : 3);

template <int D> void pack(const SoftState<D>& s, std::size_t i, std::vector<double>& out) {
    out.push_back(static_cast<double>(s.p.tag[i]));
    out.push_back(static_cast<double>(s.p.species[i]));
    for (const auto* v : {&s.p.position[i], &s.p.velocity[i], &s.director[i], &s.force[i]})
        out.insert(out.end(), v->c.begin(), v->c.end());
    for (int a = 0; a < D; ++a) out.push_back(static_cast<double>(s.image[i][a]));
    out.insert(out.end(), s.torque[i].c.begin(), s.torque[i].c.end());
}

template <int D> void unpack(const double* in, SoftState<D>& s, std::size_t i) {
    s.p.tag[i] = static_cast<std::uint32_t>(in[0]);
    s.p.species[i] = static_cast<std::uint16_t>(in[1]);
    in += 2;
    for (auto* v : {&s.p.position[i], &s.p.velocity[i], &s.director[i], &s.force[i]}) {
        std::copy(in, in + D, v->c.begin());
        in += D;
    }
    for (int a = 0; a < D; ++a) s.image[i][a] = static_cast<std::int32_t>(in[a]);
    in += D;
    std::copy(in, in + s.torque[i].c.size(), s.torque[i].c.begin());
}

// Appends the particles in `records` at the end of the state.
template <int D> void append(const std::vector<double>& records, SoftState<D>& s) {
    const std::size_t first = s.size();
    const std::size_t n = records.size() / record_size<D>;
    s.resize(first + n);
    for (std::size_t k = 0; k < n; ++k) unpack(records.data() + k * record_size<D>, s, first + k);
}

} // namespace

template <int D> std::array<int, D> domain_grid(int processes, const Box<D>& box, double range) {
    std::array<int, D> best{}, n{};
    double best_surface = std::numeric_limits<double>::infinity();
    // every n with n_0 n_1 ... = processes (an odometer over the divisors)
    auto consider = [&] {
        for (int a = 0; a < D; ++a)
            if (n[a] > 1 && box.length(a) / n[a] < range) return;
        double surface = 0.0;
        for (int a = 0; a < D; ++a) {
            double face = 1.0;
            for (int b = 0; b < D; ++b)
                if (b != a) face *= box.length(b) / n[b];
            if (n[a] > 1) surface += face;
        }
        if (surface <= best_surface * (1.0 + 1e-12)) {
            best_surface = surface;
            best = n;
        }
    };
    if constexpr (D == 2) {
        for (n[0] = 1; n[0] <= processes; ++n[0])
            if (processes % n[0] == 0) {
                n[1] = processes / n[0];
                consider();
            }
    } else {
        for (n[0] = 1; n[0] <= processes; ++n[0])
            if (processes % n[0] == 0)
                for (n[1] = 1; n[1] <= processes / n[0]; ++n[1])
                    if ((processes / n[0]) % n[1] == 0) {
                        n[2] = processes / n[0] / n[1];
                        consider();
                    }
    }
    if (best[0] == 0) {
        std::string lengths;
        for (int a = 0; a < D; ++a) lengths += fmt::format("{}{:g}", a ? " x " : "", box.length(a));
        throw InputError(fmt::format(
            "domain decomposition: {} processes cannot share a box of {}: every grid of {} "
            "domains has a domain thinner than the interaction range plus skin ({:g}) on some "
            "axis; run on fewer processes or in a larger box",
            processes, lengths, processes, range));
    }
    return best;
}

template <int D>
DomainDecomposition<D>::DomainDecomposition(Communicator& comm, const Box<D>& box, double range)
    : comm_(comm), box_(box), range_(range) {
    for (int a = 0; a < D; ++a)
        if (!box.periodic(a))
            throw InputError("domain decomposition needs a periodic box (axis " +
                             std::to_string(a) +
                             " is a wall): a walled box runs on one process; start it without "
                             "mpirun (a container wall in a periodic box runs on many)");
    grid_ = domain_grid<D>(comm.size(), box, range);
    int r = comm.rank();
    for (int a = 0; a < D; ++a) {
        mine_[a] = r % grid_[a];
        r /= grid_[a];
        width_[a] = box.length(a) / grid_[a];
    }
    // the processes of the domains next to this one, across faces, edges and corners
    partner_of_rank_.assign(static_cast<std::size_t>(comm.size()), -1);
    std::array<int, D> offset;
    offset.fill(-1);
    while (true) {
        std::array<int, D> c;
        for (int a = 0; a < D; ++a) c[a] = (mine_[a] + offset[a] + grid_[a]) % grid_[a];
        const int q = rank_of(c);
        if (q != comm.rank() && partner_of_rank_[static_cast<std::size_t>(q)] < 0) {
            partner_of_rank_[static_cast<std::size_t>(q)] = 0;
            partners_.push_back(q);
        }
        int a = 0;
        while (a < D && ++offset[a] == 2) offset[a++] = -1;
        if (a == D) break;
    }
    std::sort(partners_.begin(), partners_.end());
    for (std::size_t k = 0; k < partners_.size(); ++k)
        partner_of_rank_[static_cast<std::size_t>(partners_[k])] = static_cast<int>(k);
    ghost_send_.resize(partners_.size());
    send_.resize(partners_.size());
}

template <int D> std::array<int, D> DomainDecomposition<D>::coords_of(const Vec<D>& r) const {
    std::array<int, D> c;
    for (int a = 0; a < D; ++a) {
        const double L = box_.length(a);
        // the wrapped coordinate from the low face, in [0, L]
        double x = r[a] + 0.5 * L;
        x -= L * std::floor(x / L);
        c[a] = std::clamp(static_cast<int>(x / width_[a]), 0, grid_[a] - 1);
    }
    return c;
}

template <int D> int DomainDecomposition<D>::rank_of(const std::array<int, D>& c) const {
    int r = 0;
    for (int a = D - 1; a >= 0; --a) r = r * grid_[a] + c[a];
    return r;
}

template <int D> int DomainDecomposition<D>::domain_of(const Vec<D>& r) const {
    return rank_of(coords_of(r));
}

template <int D>
void DomainDecomposition<D>::ghost_destinations(const Vec<D>& r, std::vector<int>& out) const {
    // along each axis: this domain, and the neighbour across a face closer than range
    std::array<std::array<int, 3>, D> along;
    std::array<int, D> count;
    const std::array<int, D> c = coords_of(r);
    for (int a = 0; a < D; ++a) {
        count[a] = 1;
        along[a][0] = c[a];
        if (grid_[a] == 1) continue;
        const double L = box_.length(a);
        double x = r[a] + 0.5 * L;
        x -= L * std::floor(x / L);
        const double from_low = x - c[a] * width_[a];
        const double to_high = (c[a] + 1) * width_[a] - x;
        // Wrapping x and the face positions each round by an ulp of L: a particle a few
        // ulps inside range of a face could test as outside and its pairs go missing
        // (found by the brute-force tests). A ghost a hair too many costs nothing.
        const double reach = range_ + 1e-12 * (range_ + L);
        if (from_low < reach) along[a][count[a]++] = (c[a] + grid_[a] - 1) % grid_[a];
        if (to_high < reach) {
            const int up = (c[a] + 1) % grid_[a];
            if (count[a] == 1 || along[a][1] != up) along[a][count[a]++] = up;
        }
    }
    out.clear();
    std::array<int, D> k{};
    while (true) {
        std::array<int, D> d;
        for (int a = 0; a < D; ++a) d[a] = along[a][k[a]];
        const int q = rank_of(d);
        if (q != comm_.rank() && std::find(out.begin(), out.end(), q) == out.end())
            out.push_back(q);
        int a = 0;
        while (a < D && ++k[a] == count[a]) k[a++] = 0;
        if (a == D) break;
    }
}

template <int D> void DomainDecomposition<D>::scatter(SoftState<D>& s) const {
    std::vector<char> keep(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) keep[i] = domain_of(s.p.position[i]) == comm_.rank();
    s.keep_only(keep);
}

template <int D> void DomainDecomposition<D>::migrate(SoftState<D>& s) {
    // Between rebuilds no particle moves further than a domain is wide, so particles go
    // to partners, point to point; should one go further (all processes agree on that),
    // every process exchanges with every other.
    const std::size_t owned = s.owned();
    std::vector<char> keep(owned);
    std::vector<int> to(owned);
    bool far = false;
    for (std::size_t i = 0; i < owned; ++i) {
        to[i] = domain_of(s.p.position[i]);
        keep[i] = to[i] == comm_.rank();
        far = far || (!keep[i] && partner_of_rank_[static_cast<std::size_t>(to[i])] < 0);
    }
    far = any(far);
    std::vector<std::vector<double>> everyone(far ? static_cast<std::size_t>(comm_.size()) : 0);
    for (auto& b : send_) b.clear();
    for (std::size_t i = 0; i < owned; ++i)
        if (!keep[i])
            pack(s, i,
                 far ? everyone[static_cast<std::size_t>(to[i])]
                     : send_[static_cast<std::size_t>(
                           partner_of_rank_[static_cast<std::size_t>(to[i])])]);
    s.keep_only(keep);
    std::vector<std::size_t> counts;
    append(far ? comm_.exchange(everyone, counts) : comm_.exchange_with(partners_, send_, counts),
           s);
}

template <int D> void DomainDecomposition<D>::redistribute(SoftState<D>& s, double sort_cell) {
    migrate(s);
    if (sort_cell > 0.0) s.apply_order(space_filling_order(box_, s.p.position, s.p.tag, sort_cell));

    // ghosts
    for (auto& b : send_) b.clear();
    for (auto& g : ghost_send_) g.clear();
    std::vector<int> ranks;
    for (std::size_t i = 0; i < s.size(); ++i) {
        ghost_destinations(s.p.position[i], ranks);
        for (const int q : ranks) {
            // (a neighbouring domain's process: a partner)
            const auto k = static_cast<std::size_t>(partner_of_rank_[static_cast<std::size_t>(q)]);
            ghost_send_[k].push_back(static_cast<std::uint32_t>(i));
            pack(s, i, send_[k]);
        }
    }
    const std::size_t mine = s.size();
    std::vector<std::size_t> counts;
    append(comm_.exchange_with(partners_, send_, counts), s);
    s.ghosts = s.size() - mine;
}

template <int D> void DomainDecomposition<D>::settle_in_tag_order(SoftState<D>& s) {
    migrate(s);
    std::vector<std::uint32_t> order(s.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t a, std::uint32_t b) { return s.p.tag[a] < s.p.tag[b]; });
    s.apply_order(order);
}

template <int D> void DomainDecomposition<D>::refresh_ghosts(SoftState<D>& s) {
    for (std::size_t q = 0; q < send_.size(); ++q) {
        send_[q].clear();
        for (const std::uint32_t i : ghost_send_[q])
            for (const auto* v : {&s.p.position[i], &s.p.velocity[i], &s.director[i]})
                send_[q].insert(send_[q].end(), v->c.begin(), v->c.end());
    }
    std::vector<std::size_t> counts;
    const std::vector<double> in = comm_.exchange_with(partners_, send_, counts);
    if (in.size() != s.ghosts * 3 * D)
        throw std::logic_error("refresh_ghosts: the ghost lists of two processes disagree");
    const double* r = in.data();
    for (std::size_t i = s.owned(); i < s.size(); ++i)
        for (auto* v : {&s.p.position[i], &s.p.velocity[i], &s.director[i]}) {
            std::copy(r, r + D, v->c.begin());
            r += D;
        }
}

template <int D> void DomainDecomposition<D>::gather(const SoftState<D>& s, SoftState<D>& whole) {
    std::vector<double> mine;
    mine.reserve(s.owned() * record_size<D>);
    for (std::size_t i = 0; i < s.owned(); ++i) pack(s, i, mine);
    const std::vector<double> all = comm_.gather(mine);
    if (comm_.rank() != 0) return;
    const std::size_t n = all.size() / record_size<D>;
    whole.box = s.box;
    whole.p.species_table = s.p.species_table;
    whole.step = s.step;
    whole.time = s.time;
    whole.ghosts = 0;
    whole.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        const double* rec = all.data() + k * record_size<D>;
        const double tag = rec[0];
        if (!(tag >= 0.0 && tag < static_cast<double>(n)))
            throw std::logic_error("gather: tags are not 0..N-1");
        unpack(rec, whole, static_cast<std::size_t>(tag));
    }
}

template <int D> Box<D> DomainDecomposition<D>::local_box(double skin) const {
    Vec<D> lengths;
    std::array<bool, D> periodic;
    for (int a = 0; a < D; ++a) {
        const double extent = width_[a] + 2.0 * (range_ + 2.0 * skin);
        periodic[a] = !(grid_[a] >= 3 && extent < box_.length(a));
        lengths[a] = periodic[a] ? box_.length(a) : extent;
    }
    return Box<D>(lengths, periodic);
}

template <int D>
void DomainDecomposition<D>::local_positions(const std::vector<Vec<D>>& pos,
                                             std::vector<Vec<D>>& out, double skin) const {
    const Box<D> local = local_box(skin);
    Vec<D> centre{};
    std::array<bool, D> shifted{};
    for (int a = 0; a < D; ++a) {
        shifted[a] = !local.periodic(a);
        centre[a] = box_.lo(a) + (mine_[a] + 0.5) * width_[a];
    }
    out.resize(pos.size());
    const auto n = static_cast<std::int64_t>(pos.size());
#pragma omp parallel for schedule(static) if (n >= 4096)
    for (std::int64_t i = 0; i < n; ++i) {
        Vec<D> r = pos[i];
        for (int a = 0; a < D; ++a)
            if (shifted[a]) {
                const double L = box_.length(a);
                r[a] -= centre[a];
                r[a] -= L * std::nearbyint(r[a] / L);
            }
        out[i] = r;
    }
}

template <int D> bool DomainDecomposition<D>::any(bool mine) {
    return comm_.max(mine ? 1.0 : 0.0) > 0.0;
}

template std::array<int, 2> domain_grid<2>(int, const Box<2>&, double);
template std::array<int, 3> domain_grid<3>(int, const Box<3>&, double);
template class DomainDecomposition<2>;
template class DomainDecomposition<3>;

} // namespace pedesis
