// The CUDA kernels of the soft/active engine and the device state they work on
// (device_system.hpp). One thread per particle throughout: the neighbour list is full
// (each pair twice), so every thread sums its own force and torque and nothing needs an
// atomic. The physics is the CPU engine's own: the pair evaluators of
// soft/pair_potentials.hpp, the Philox stream keyed by (seed, stream, tag, step) with the
// same Box-Muller and sin/cos (core/sincos.hpp), the integrators' per-species tables.
#include "pedesis/core/sincos.hpp"
#include "pedesis/core/sphere_rotation.hpp"
#include "pedesis/core/sym_tensor.hpp"
#include "pedesis/gpu/device_system.hpp"

#include <Random123/philox.h>
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_reduce.cuh>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace pedesis::gpu {

namespace {

void check(cudaError_t e, const char* what) {
    if (e != cudaSuccess)
        throw std::runtime_error(std::string("CUDA: ") + what + ": " + cudaGetErrorString(e));
}

constexpr int block_size = 128;
unsigned blocks(std::size_t n) {
    return static_cast<unsigned>((n + block_size - 1) / block_size);
}

// The streams of core/rng.hpp's RngStream.
constexpr std::uint32_t stream_orientation = 3, stream_thermostat = 4;

// A device buffer of T; grows, never shrinks.
template <class T> struct Buffer {
    T* p = nullptr;
    std::size_t n = 0;
    void reserve(std::size_t count) {
        if (count <= n) return;
        if (p) cudaFree(p);
        p = nullptr;
        check(cudaMalloc(&p, std::max<std::size_t>(count, 1) * sizeof(T)), "cudaMalloc");
        n = count;
    }
    ~Buffer() {
        if (p) cudaFree(p);
    }
    std::size_t bytes() const { return n * sizeof(T); }
};

// The box (every axis periodic) and the grid of cells, as the kernels need them.
struct Geometry {
    double L[3], half[3], inv_width[3];
    int cells[3];
};

template <int D> struct Vd { double c[D]; };

template <int D> __device__ inline Vd<D> load(const double* a, std::size_t i) {
    Vd<D> v;
    for (int k = 0; k < D; ++k) v.c[k] = a[i * D + k];
    return v;
}
template <int D> __device__ inline void store(double* a, std::size_t i, const Vd<D>& v) {
    for (int k = 0; k < D; ++k) a[i * D + k] = v.c[k];
}

// Box::minimum_image, for displacements within (-1.5 L, 1.5 L)
template <int D> __device__ inline Vd<D> minimum_image(Vd<D> d, const Geometry& g) {
    for (int a = 0; a < D; ++a) {
        if (d.c[a] > g.half[a])
            d.c[a] -= g.L[a];
        else if (d.c[a] < -g.half[a])
            d.c[a] += g.L[a];
    }
    return d;
}

template <int D> __device__ inline double norm2(const Vd<D>& v) {
    double s = 0.0;
    for (int a = 0; a < D; ++a) s += v.c[a] * v.c[a];
    return s;
}

// Cell coordinates of a position (anywhere: a pre-step may leave it a skin outside).
template <int D> __device__ inline void cell_of(const double* r, const Geometry& g, int* c) {
    for (int a = 0; a < D; ++a) {
        const double x = (r[a] + g.half[a]) * g.inv_width[a];
        int k = isfinite(x) ? static_cast<int>(floor(fmax(fmin(x, 1e9), -1e9))) : 0;
        k %= g.cells[a];
        if (k < 0) k += g.cells[a];
        c[a] = k;
    }
}

template <int D> __device__ inline std::uint32_t linear_cell(const int* c, const Geometry& g) {
    std::uint32_t l = static_cast<std::uint32_t>(c[D - 1]);
    for (int a = D - 2; a >= 0; --a) l = l * static_cast<std::uint32_t>(g.cells[a]) + c[a];
    return l;
}

// The neighbour cells of cell c (each once, also for two cells along an axis) as ranks.
template <int D> struct Stencil {
    std::uint32_t rank[D == 2 ? 9 : 27];
    int size = 0;
};
template <int D>
__device__ inline Stencil<D> stencil(const int* c, const Geometry& g, const std::uint32_t* rank) {
    Stencil<D> s;
    const int span[3] = {g.cells[0] >= 3 ? 3 : g.cells[0], g.cells[1] >= 3 ? 3 : g.cells[1],
                         D == 3 ? (g.cells[2] >= 3 ? 3 : g.cells[2]) : 1};
    for (int z = 0; z < (D == 3 ? span[2] : 1); ++z)
        for (int y = 0; y < span[1]; ++y)
            for (int x = 0; x < span[0]; ++x) {
                const int off[3] = {x, y, z};
                int nb[3];
                for (int a = 0; a < D; ++a) {
                    // three cells: c-1, c, c+1; fewer: every cell of the axis
                    const int k = g.cells[a] >= 3 ? c[a] + off[a] - 1 : off[a];
                    nb[a] = (k + g.cells[a]) % g.cells[a];
                }
                s.rank[s.size++] = rank[linear_cell<D>(nb, g)];
            }
    return s;
}

// ---- binning: keys, sort, cell bounds, gathers ----

template <int D>
__global__ void k_cell_keys(const double* pos, std::size_t n, Geometry g, const std::uint32_t* rank,
                            std::uint32_t* keys, std::uint32_t* order) {
    const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
    if (i >= n) return;
    int c[3];
    cell_of<D>(pos + i * D, g, c);
    keys[i] = rank[linear_cell<D>(c, g)];
    order[i] = static_cast<std::uint32_t>(i);
}

__global__ void k_cell_bounds(const std::uint32_t* keys, std::size_t n, std::uint32_t* start,
                              std::uint32_t* end) {
    const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
    if (i >= n) return;
    const std::uint32_t k = keys[i];
    if (i == 0 || keys[i - 1] != k) start[k] = static_cast<std::uint32_t>(i);
    if (i + 1 == n || keys[i + 1] != k) end[k] = static_cast<std::uint32_t>(i + 1);
}

// out[i] = in[order[i]] for records of `width` elements
template <class T>
__global__ void k_gather(const T* in, T* out, const std::uint32_t* order, std::size_t n,
                         int width) {
    const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
    if (i >= n) return;
    const std::size_t from = order[i];
    for (int k = 0; k < width; ++k) out[i * width + k] = in[from * width + k];
}

// ---- the neighbour list: full, column-major (entry k of particle i at k n + i) ----

template <int D>
__global__ void k_neighbours(const double* pos, std::size_t n, Geometry g,
                             const std::uint32_t* rank, const std::uint32_t* start,
                             const std::uint32_t* end, double r_list2, std::uint32_t* list,
                             std::uint32_t* count, std::uint32_t capacity, std::uint32_t* needed) {
    const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
    if (i >= n) return;
    const Vd<D> ri = load<D>(pos, i);
    int c[3];
    cell_of<D>(ri.c, g, c);
    const Stencil<D> s = stencil<D>(c, g, rank);
    std::uint32_t m = 0;
    for (int q = 0; q < s.size; ++q) {
        const std::uint32_t e = end[s.rank[q]];
        for (std::uint32_t j = start[s.rank[q]]; j < e; ++j) {
            if (j == i) continue;
            Vd<D> d = load<D>(pos, j);
            for (int a = 0; a < D; ++a) d.c[a] = ri.c[a] - d.c[a];
            if (norm2(minimum_image(d, g)) < r_list2) {
                if (m < capacity) list[m * n + i] = j;
                ++m;
            }
        }
    }
    count[i] = m;
    if (m > capacity) atomicMax(needed, m);
}

// ---- forces and torques ----

// no pair force (a run of self-propulsion and alignment alone)
struct NoPair {};

struct ForceTables {
    const double* radius;
    const SpeciesCoefficients* coef;
    std::size_t species;
    double J, align2;
};

template <int D, class Pair, bool Uniform, bool Align, bool Propel>
__global__ void k_forces(const double* pos, const double* dir, const std::uint16_t* sp,
                         std::size_t n, Geometry g, const std::uint32_t* list,
                         const std::uint32_t* count, const Pair* pairs, ForceTables t,
                         double* force, double* torque) {
    const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
    if (i >= n) return;
    const Vd<D> ri = load<D>(pos, i);
    const std::uint16_t si = sp[i];
    const double rad_i = t.radius[Uniform ? 0 : si];
    const Pair* row = pairs + (Uniform ? 0 : si * t.species);
    Vd<D> f{}, sum_n{};
    const std::uint32_t m = count[i];
    for (std::uint32_t k = 0; k < m; ++k) {
        const std::uint32_t j = list[k * n + i];
        Vd<D> d = load<D>(pos, j);
        for (int a = 0; a < D; ++a) d.c[a] = ri.c[a] - d.c[a];
        d = minimum_image(d, g);
        const double r2 = norm2(d);
        if constexpr (!std::is_same_v<Pair, NoPair>) {
            double f_over_r, energy;
            const std::uint16_t sj = Uniform ? 0 : sp[j];
            const double rsum = rad_i + (Uniform ? rad_i : t.radius[sj]);
            if (row[Uniform ? 0 : sj].eval(r2, rsum, f_over_r, energy))
                for (int a = 0; a < D; ++a) f.c[a] += f_over_r * d.c[a];
        }
        if (Align && r2 <= t.align2) {
            const Vd<D> nj = load<D>(dir, j);
            for (int a = 0; a < D; ++a) sum_n.c[a] += nj.c[a];
        }
    }
    const Vd<D> ni = load<D>(dir, i);
    if (Propel)
        for (int a = 0; a < D; ++a) f.c[a] += t.coef[si].alpha * ni.c[a];
    store<D>(force, i, f);
    // tau = J n_i x sum n_j (a pseudo-scalar in 2D)
    if constexpr (D == 2) {
        torque[i] = Align ? t.J * (ni.c[0] * sum_n.c[1] - ni.c[1] * sum_n.c[0]) : 0.0;
    } else {
        double tq[3] = {0.0, 0.0, 0.0};
        if (Align) {
            tq[0] = t.J * (ni.c[1] * sum_n.c[2] - ni.c[2] * sum_n.c[1]);
            tq[1] = t.J * (ni.c[2] * sum_n.c[0] - ni.c[0] * sum_n.c[2]);
            tq[2] = t.J * (ni.c[0] * sum_n.c[1] - ni.c[1] * sum_n.c[0]);
        }
        for (int a = 0; a < 3; ++a) torque[i * 3 + a] = tq[a];
    }
}

// Energy, virial and virial tensor, each pair half to each of its particles, over a cell
// list of its own (order: the sorted indices, cell bounds by rank). The tensor's slot c
// (sym_tensor.hpp) of sorted particle s is at tensor[c n + s].
template <int D, class Pair, bool Uniform>
__global__ void k_totals(const double* pos, const std::uint16_t* sp, std::size_t n, Geometry g,
                         const std::uint32_t* rank, const std::uint32_t* order,
                         const std::uint32_t* start, const std::uint32_t* end, double r_cut2,
                         const Pair* pairs, ForceTables t, double* energy, double* virial,
                         double* tensor) {
    const std::size_t s = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
    if (s >= n) return;
    const std::uint32_t i = order[s];
    const Vd<D> ri = load<D>(pos, i);
    int c[3];
    cell_of<D>(ri.c, g, c);
    const Stencil<D> st = stencil<D>(c, g, rank);
    const std::uint16_t si = sp[i];
    double e = 0.0, w = 0.0, wt[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    for (int q = 0; q < st.size; ++q)
        for (std::uint32_t k = start[st.rank[q]]; k < end[st.rank[q]]; ++k) {
            const std::uint32_t j = order[k];
            if (j == i) continue;
            Vd<D> d = load<D>(pos, j);
            for (int a = 0; a < D; ++a) d.c[a] = ri.c[a] - d.c[a];
            d = minimum_image(d, g);
            const double r2 = norm2(d);
            if (!(r2 < r_cut2)) continue;
            const std::uint16_t sj = Uniform ? 0 : sp[j];
            const double rsum = t.radius[Uniform ? 0 : si] + t.radius[sj];
            double f_over_r, u;
            if (pairs[Uniform ? 0 : si * t.species + sj].eval(r2, rsum, f_over_r, u)) {
                e += 0.5 * u;
                w += 0.5 * f_over_r * r2;
                for (int a = 0; a < D; ++a)
                    for (int b = a; b < D; ++b)
                        wt[sym_slot(a, b)] += 0.5 * f_over_r * d.c[a] * d.c[b];
            }
        }
    energy[s] = e;
    virial[s] = w;
    for (int c = 0; c < 6; ++c) tensor[c * n + s] = wt[c];
}

// ---- integrators ----

// Per Philox block p of (seed, stream, tag, step): two uniforms as CounterRng::uniform,
// then Box-Muller as detail::batch_normals: z[2p] = r cos, z[2p+1] = r sin.
template <int Per>
__device__ inline void normals(std::uint64_t seed, std::uint32_t stream, std::uint32_t tag,
                               std::uint32_t step, double* z) {
    r123::Philox4x32 philox;
    const r123::Philox4x32::key_type key = {
        {static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)}};
    for (int p = 0; p < (Per + 1) / 2; ++p) {
        const r123::Philox4x32::ctr_type ctr = {{tag, step, stream, static_cast<std::uint32_t>(p)}};
        const r123::Philox4x32::ctr_type out = philox(ctr, key);
        auto uniform = [](std::uint32_t hi, std::uint32_t lo) {
            const std::uint64_t bits = ((static_cast<std::uint64_t>(hi) << 32) | lo) >> 11;
            return (static_cast<double>(bits) + 1.0) * 0x1.0p-53;
        };
        const double u1 = uniform(out.v[0], out.v[1]), u2 = uniform(out.v[2], out.v[3]);
        const double r = sqrt(-2.0 * log(u1));
        double s, c;
        detail::sincos_turns(u2, s, c);
        z[2 * p] = r * c;
        if (2 * p + 1 < Per) z[2 * p + 1] = r * s;
    }
}

struct StepArgs {
    std::size_t n;
    Geometry g;
    const SpeciesCoefficients* coef;
    std::uint64_t seed, rotation_seed;
    std::uint32_t step;
    double inv_dt, max_move2, rebuild2;
    bool noisy, rot_noisy;
    Mover mover;
    bool rotation;
};

// Zeroed before each pre- or post-step.
struct Status {
    std::uint32_t rebuild;            // a particle moved more than half the skin since the build
    std::uint32_t bad_move;           // any blown-up move
    std::uint32_t bad_tag_complement; // UINT32_MAX - the lowest tag of a blown-up move
    std::uint32_t pad;
};

template <int D>
__device__ inline void after_move(const StepArgs& a, std::size_t i, const Vd<D>& r,
                                  const double* ref, const std::uint32_t* tag, double move2,
                                  bool checked, Status* status) {
    if (checked && !(move2 <= a.max_move2)) {
        atomicMax(&status->bad_tag_complement, 0xffffffffu - tag[i]);
        status->bad_move = 1;
    }
    Vd<D> d = load<D>(ref, i);
    for (int k = 0; k < D; ++k) d.c[k] = r.c[k] - d.c[k];
    if (!(norm2(minimum_image(d, a.g)) <= a.rebuild2)) status->rebuild = 1;
}

// pre-step: langevin's B A O A, nve's kick and drift
template <int D>
__global__ void k_prestep(StepArgs a, double* pos, double* vel, const double* force,
                          const double* ref, const std::uint32_t* tag, const std::uint16_t* sp,
                          Status* status) {
    const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
    if (i >= a.n) return;
    const SpeciesCoefficients c = a.coef[sp[i]];
    Vd<D> v = load<D>(vel, i), r = load<D>(pos, i);
    const Vd<D> f = load<D>(force, i);
    Vd<D> move;
    if (a.mover == Mover::langevin) {
        for (int k = 0; k < D; ++k) v.c[k] += c.half_kick * f.c[k];
        for (int k = 0; k < D; ++k) move.c[k] = c.half_drift * v.c[k];
        for (int k = 0; k < D; ++k) v.c[k] *= c.damp;
        if (a.noisy) {
            double z[D];
            normals<D>(a.seed, stream_thermostat, tag[i], a.step, z);
            for (int k = 0; k < D; ++k) v.c[k] += c.noise * z[k];
        }
        for (int k = 0; k < D; ++k) move.c[k] += c.half_drift * v.c[k];
    } else {
        for (int k = 0; k < D; ++k) v.c[k] += c.half_kick * f.c[k];
        for (int k = 0; k < D; ++k) move.c[k] = c.half_drift * v.c[k];
    }
    for (int k = 0; k < D; ++k) r.c[k] += move.c[k];
    store<D>(pos, i, r);
    store<D>(vel, i, v);
    after_move<D>(a, i, r, ref, tag, norm2(move), true, status);
}

// post-step: brownian's move, langevin's and nve's last half kick, brownian_rotation,
// then the periodic wrap
template <int D>
__global__ void k_poststep(StepArgs a, double* pos, double* vel, double* dir, const double* force,
                           const double* torque, std::int32_t* image, const double* ref,
                           const std::uint32_t* tag, const std::uint16_t* sp, Status* status) {
    const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
    if (i >= a.n) return;
    const SpeciesCoefficients c = a.coef[sp[i]];
    Vd<D> r = load<D>(pos, i);
    const Vd<D> f = load<D>(force, i);
    double move2 = 0.0;
    if (a.mover == Mover::brownian) {
        Vd<D> move;
        for (int k = 0; k < D; ++k) move.c[k] = c.drift * f.c[k];
        if (a.noisy) {
            double z[D];
            normals<D>(a.seed, stream_thermostat, tag[i], a.step, z);
            for (int k = 0; k < D; ++k) move.c[k] += c.kick * z[k];
        }
        move2 = norm2(move);
        Vd<D> v;
        for (int k = 0; k < D; ++k) {
            r.c[k] += move.c[k];
            v.c[k] = move.c[k] * a.inv_dt;
        }
        store<D>(vel, i, v);
    } else if (a.mover != Mover::none) {
        Vd<D> v = load<D>(vel, i);
        for (int k = 0; k < D; ++k) v.c[k] += c.half_kick * f.c[k];
        store<D>(vel, i, v);
    }
    if (a.rotation) {
        Vd<D> d = load<D>(dir, i);
        if constexpr (D == 2) {
            double angle = c.rot_drift * torque[i];
            if (a.rot_noisy && c.rot_kick > 0.0) {
                double z[1];
                normals<1>(a.rotation_seed, stream_orientation, tag[i], a.step, z);
                angle += c.rot_kick * z[0];
            }
            double sn, cs;
            if (fabs(angle) <= 0.25 * detail::pi)
                detail::sincos_kernel(angle, sn, cs);
            else {
                sn = sin(angle);
                cs = cos(angle);
            }
            const double d0 = d.c[0], d1 = d.c[1];
            d.c[0] = cs * d0 - sn * d1;
            d.c[1] = sn * d0 + cs * d1;
        } else {
            double w[3];
            for (int k = 0; k < 3; ++k) w[k] = c.rot_drift * torque[i * 3 + k];
            if (a.rot_noisy && c.rot_kick > 0.0) {
                double z[3];
                normals<3>(a.rotation_seed, stream_orientation, tag[i], a.step, z);
                const double amplitude = c.rot_kick * sphere_kick_scale(c.rot_kick);
                for (int k = 0; k < 3; ++k) w[k] += amplitude * z[k];
            }
            rotate_on_sphere(w, d.c); // as the CPU's step
        }
        store<D>(dir, i, d);
    }
    // Box::wrap into [-L/2, L/2), counting images
    for (int k = 0; k < D; ++k) {
        double x = r.c[k];
        if (x >= -a.g.half[k] && x < a.g.half[k]) continue;
        double shift = floor((x + a.g.half[k]) / a.g.L[k]);
        x -= shift * a.g.L[k];
        if (x >= a.g.half[k]) {
            x -= a.g.L[k];
            shift += 1.0;
        }
        if (x < -a.g.half[k]) {
            x += a.g.L[k];
            shift -= 1.0;
        }
        if (x >= a.g.half[k]) x = -a.g.half[k];
        r.c[k] = x;
        if (isfinite(shift)) image[i * D + k] += static_cast<std::int32_t>(shift);
    }
    store<D>(pos, i, r);
    after_move<D>(a, i, r, ref, tag, move2, a.mover == Mover::brownian, status);
}

// Ranks of the cells along a Morton (Z-order) curve: sorting particles by the rank of
// their cell puts each cell's particles together and neighbouring cells close by.
std::vector<std::uint32_t> morton_ranks(const int* cells, int dim) {
    std::size_t total = 1;
    for (int a = 0; a < dim; ++a) total *= static_cast<std::size_t>(cells[a]);
    std::vector<std::uint64_t> code(total);
    for (std::size_t l = 0; l < total; ++l) {
        std::size_t rest = l;
        std::uint64_t m = 0;
        for (int a = 0; a < dim; ++a) {
            const std::uint64_t c = rest % static_cast<std::size_t>(cells[a]);
            rest /= static_cast<std::size_t>(cells[a]);
            for (int b = 0; b < 64 / dim; ++b) m |= ((c >> b) & 1u) << (b * dim + a);
        }
        code[l] = m;
    }
    std::vector<std::uint32_t> by_code(total);
    std::iota(by_code.begin(), by_code.end(), 0u);
    std::sort(by_code.begin(), by_code.end(),
              [&](std::uint32_t x, std::uint32_t y) { return code[x] < code[y]; });
    std::vector<std::uint32_t> rank(total);
    for (std::size_t k = 0; k < total; ++k) rank[by_code[k]] = static_cast<std::uint32_t>(k);
    return rank;
}

} // namespace

struct DeviceSystem::Impl {
    Model m;
    std::size_t n = 0;
    int D = 2;
    int torque_width = 1;
    Geometry grid{}; // cells at least r_cut + skin wide (the list's, and the totals')
    Buffer<std::uint32_t> rank;
    std::size_t cells = 0;
    Buffer<double> pos, vel, dir, force, torque, ref, scratch;
    Buffer<std::int32_t> image;
    Buffer<std::uint32_t> tag, keys, keys_alt, order, order_alt, cell_start, cell_end, list, count;
    Buffer<std::uint16_t> species;
    Buffer<unsigned char> sort_temp;
    Buffer<double> energy, virial, tensor, sums;
    Buffer<HarmonicPair> harmonic;
    Buffer<WcaPair> wca;
    Buffer<LjPair> lj;
    Buffer<double> radius;
    Buffer<SpeciesCoefficients> coef;
    Buffer<Status> status;
    Buffer<std::uint32_t> needed;
    Status* host_status = nullptr;
    std::uint32_t capacity = 0;
    bool has_list = false;
    bool need_rebuild = true;
    bool uniform = true;
    StepCoefficients c;
    std::vector<SpeciesCoefficients> uploaded;
    int key_bits = 1;

    explicit Impl(const Model& model) : m(model), n(model.particles), D(model.dim) {
        if (D != 2 && D != 3) throw std::invalid_argument("gpu: dimension must be 2 or 3");
        torque_width = D == 2 ? 1 : 3;
        make_grid(m.r_cut + m.skin, grid, rank, cells);
        const std::size_t nn = std::max<std::size_t>(n, 1);
        pos.reserve(nn * D);
        vel.reserve(nn * D);
        dir.reserve(nn * D);
        force.reserve(nn * D);
        torque.reserve(nn * torque_width);
        ref.reserve(nn * D);
        scratch.reserve(nn * 3);
        image.reserve(nn * D);
        tag.reserve(nn);
        species.reserve(nn);
        keys.reserve(nn);
        keys_alt.reserve(nn);
        order.reserve(nn);
        order_alt.reserve(nn);
        cell_start.reserve(cells);
        cell_end.reserve(cells);
        count.reserve(nn);
        while ((std::size_t{1} << key_bits) < cells) ++key_bits;
        std::size_t temp = 0;
        cub::DoubleBuffer<std::uint32_t> k(keys.p, keys_alt.p), v(order.p, order_alt.p);
        check(
            cub::DeviceRadixSort::SortPairs(nullptr, temp, k, v, static_cast<int>(nn), 0, key_bits),
            "sort size");
        sort_temp.reserve(temp);
        // the list's first capacity: 1.5 times the mean number within r_cut + skin; a build
        // that finds more (a dense cluster) grows it
        double volume = 1.0;
        for (int a = 0; a < D; ++a) volume *= m.box[a];
        const double rl = m.r_cut + m.skin;
        const double sphere = D == 2 ? detail::pi * rl * rl : 4.0 / 3.0 * detail::pi * rl * rl * rl;
        capacity = static_cast<std::uint32_t>(
            std::min(1.5 * sphere * static_cast<double>(n) / volume + 8.0, 4096.0));
        list.reserve(nn * capacity);
        radius.reserve(m.species);
        check(cudaMemcpy(radius.p, m.radius.data(), m.species * sizeof(double),
                         cudaMemcpyHostToDevice),
              "radii");
        uniform = true;
        for (double r : m.radius) uniform = uniform && r == m.radius[0];
        auto upload_pairs = [&](auto& buffer, const auto& table) {
            buffer.reserve(table.size());
            for (const auto& p : table) uniform = uniform && p == table[0];
            check(cudaMemcpy(buffer.p, table.data(), table.size() * sizeof(table[0]),
                             cudaMemcpyHostToDevice),
                  "pair table");
        };
        if (m.pair == PairKind::harmonic) upload_pairs(harmonic, m.harmonic);
        if (m.pair == PairKind::wca) upload_pairs(wca, m.wca);
        if (m.pair == PairKind::lj) upload_pairs(lj, m.lj);
        coef.reserve(m.species);
        status.reserve(1);
        needed.reserve(1);
        sums.reserve(8);
        check(cudaHostAlloc(&host_status, sizeof(Status), cudaHostAllocDefault), "pinned status");
    }
    ~Impl() {
        if (host_status) cudaFreeHost(host_status);
    }

    // Cells at least `width` wide on every axis, and not many more than particles (a
    // sparse box would otherwise ask for a huge grid of empty cells).
    void make_grid(double width, Geometry& g, Buffer<std::uint32_t>& ranks, std::size_t& total) {
        for (int a = 0; a < 3; ++a) {
            g.L[a] = a < D ? m.box[a] : 1.0;
            g.half[a] = 0.5 * g.L[a];
            g.cells[a] = 1;
        }
        for (int a = 0; a < D; ++a)
            g.cells[a] = static_cast<int>(std::clamp(std::floor(g.L[a] / width), 1.0, 1e6));
        auto product = [&] {
            std::size_t p = 1;
            for (int a = 0; a < D; ++a) p *= static_cast<std::size_t>(g.cells[a]);
            return p;
        };
        const std::size_t most = std::max<std::size_t>(2 * n, 4096);
        while (product() > most) {
            int widest = 0;
            for (int a = 1; a < D; ++a)
                if (g.cells[a] > g.cells[widest]) widest = a;
            g.cells[widest] = (g.cells[widest] + 1) / 2;
        }
        for (int a = 0; a < 3; ++a) g.inv_width[a] = g.cells[a] / g.L[a];
        total = product();
        const std::vector<std::uint32_t> r = morton_ranks(g.cells, D);
        ranks.reserve(r.size());
        check(
            cudaMemcpy(ranks.p, r.data(), r.size() * sizeof(std::uint32_t), cudaMemcpyHostToDevice),
            "cell ranks");
    }

    // keys, order (sorted) and cell bounds of positions p on grid g
    void bin(const double* p, const Geometry& g, const Buffer<std::uint32_t>& ranks,
             std::size_t total, cub::DoubleBuffer<std::uint32_t>& k,
             cub::DoubleBuffer<std::uint32_t>& v) {
        if (D == 2)
            k_cell_keys<2><<<blocks(n), block_size>>>(p, n, g, ranks.p, k.Current(), v.Current());
        else
            k_cell_keys<3><<<blocks(n), block_size>>>(p, n, g, ranks.p, k.Current(), v.Current());
        std::size_t temp = sort_temp.n;
        check(cub::DeviceRadixSort::SortPairs(sort_temp.p, temp, k, v, static_cast<int>(n), 0,
                                              key_bits),
              "sort");
        check(cudaMemsetAsync(cell_start.p, 0, total * sizeof(std::uint32_t)), "memset");
        check(cudaMemsetAsync(cell_end.p, 0, total * sizeof(std::uint32_t)), "memset");
        k_cell_bounds<<<blocks(n), block_size>>>(k.Current(), n, cell_start.p, cell_end.p);
    }

    template <class T> void permute(Buffer<T>& a, int width, const std::uint32_t* by) {
        T* tmp = reinterpret_cast<T*>(scratch.p);
        k_gather<T><<<blocks(n), block_size>>>(a.p, tmp, by, n, width);
        check(cudaMemcpyAsync(a.p, tmp, n * width * sizeof(T), cudaMemcpyDeviceToDevice), "gather");
    }

    // Sorts the particles by cell of `source` (the positions, or a checkpoint's build
    // positions in ref) and builds the list from it.
    void build(bool from_reference) {
        if (n == 0) {
            has_list = true;
            need_rebuild = false;
            return;
        }
        cub::DoubleBuffer<std::uint32_t> k(keys.p, keys_alt.p), v(order.p, order_alt.p);
        bin(from_reference ? ref.p : pos.p, grid, rank, cells, k, v);
        const std::uint32_t* by = v.Current();
        permute(pos, D, by);
        permute(vel, D, by);
        permute(dir, D, by);
        permute(force, D, by);
        permute(torque, torque_width, by);
        permute(image, D, by);
        permute(tag, 1, by);
        permute(species, 1, by);
        if (from_reference)
            permute(ref, D, by);
        else
            check(cudaMemcpyAsync(ref.p, pos.p, n * D * sizeof(double), cudaMemcpyDeviceToDevice),
                  "reference");
        const double rl = m.r_cut + m.skin;
        // a bounded retry: the second pass has room for the most any particle found
        for (int attempt = 0; attempt < 2; ++attempt) {
            check(cudaMemsetAsync(needed.p, 0, sizeof(std::uint32_t)), "memset");
            if (D == 2)
                k_neighbours<2><<<blocks(n), block_size>>>(ref.p, n, grid, rank.p, cell_start.p,
                                                           cell_end.p, rl * rl, list.p, count.p,
                                                           capacity, needed.p);
            else
                k_neighbours<3><<<blocks(n), block_size>>>(ref.p, n, grid, rank.p, cell_start.p,
                                                           cell_end.p, rl * rl, list.p, count.p,
                                                           capacity, needed.p);
            std::uint32_t most = 0;
            check(cudaMemcpy(&most, needed.p, sizeof most, cudaMemcpyDeviceToHost), "list build");
            if (most == 0) break;
            if (attempt == 1)
                throw std::logic_error("gpu: the neighbour list outgrew its second pass");
            capacity = most + most / 4 + 4;
            list.reserve(n * capacity);
        }
        has_list = true;
        need_rebuild = false;
    }

    StepArgs args(std::uint32_t step) const {
        StepArgs a{};
        a.n = n;
        a.g = grid;
        a.coef = coef.p;
        a.seed = m.seed;
        a.rotation_seed = m.rotation_seed;
        a.step = step;
        a.inv_dt = 1.0 / c.dt;
        a.max_move2 = c.max_move * c.max_move;
        a.rebuild2 = 0.25 * m.skin * m.skin;
        a.noisy = c.noisy;
        a.rot_noisy = c.rot_noisy;
        a.mover = m.mover;
        a.rotation = m.rotation;
        return a;
    }

    StepStatus read_status() {
        check(cudaMemcpyAsync(host_status, status.p, sizeof(Status), cudaMemcpyDeviceToHost),
              "status");
        check(cudaStreamSynchronize(nullptr), "step");
        need_rebuild = need_rebuild || host_status->rebuild != 0;
        return {host_status->bad_move != 0, 0xffffffffu - host_status->bad_tag_complement};
    }

    void reset_status() { check(cudaMemsetAsync(status.p, 0, sizeof(Status)), "status"); }

    template <int Dim, class Pair, bool Uniform> void forces_with(const Pair* pairs) {
        const ForceTables t{radius.p, coef.p, m.species, c.J, m.align_range * m.align_range};
        auto launch = [&](auto align, auto propel) {
            k_forces<Dim, Pair, Uniform, decltype(align)::value, decltype(propel)::value>
                <<<blocks(n), block_size>>>(pos.p, dir.p, species.p, n, grid, list.p, count.p,
                                            pairs, t, force.p, torque.p);
        };
        using T = std::true_type;
        using F = std::false_type;
        if (m.align && m.propulsion)
            launch(T{}, T{});
        else if (m.align)
            launch(T{}, F{});
        else if (m.propulsion)
            launch(F{}, T{});
        else
            launch(F{}, F{});
    }

    template <int Dim> void forces_dim() {
        switch (m.pair) {
        case PairKind::harmonic:
            return uniform ? forces_with<Dim, HarmonicPair, true>(harmonic.p)
                           : forces_with<Dim, HarmonicPair, false>(harmonic.p);
        case PairKind::wca:
            return uniform ? forces_with<Dim, WcaPair, true>(wca.p)
                           : forces_with<Dim, WcaPair, false>(wca.p);
        case PairKind::lj:
            return uniform ? forces_with<Dim, LjPair, true>(lj.p)
                           : forces_with<Dim, LjPair, false>(lj.p);
        case PairKind::none:
            return forces_with<Dim, NoPair, true>(nullptr);
        }
    }

    template <int Dim, class Pair> void totals_with(const Pair* pairs, std::uint32_t* by) {
        const ForceTables t{radius.p, coef.p, m.species, c.J, 0.0};
        const double rc2 = m.r_cut * m.r_cut;
        if (uniform)
            k_totals<Dim, Pair, true><<<blocks(n), block_size>>>(
                pos.p, species.p, n, grid, rank.p, by, cell_start.p, cell_end.p, rc2, pairs, t,
                energy.p, virial.p, tensor.p);
        else
            k_totals<Dim, Pair, false><<<blocks(n), block_size>>>(
                pos.p, species.p, n, grid, rank.p, by, cell_start.p, cell_end.p, rc2, pairs, t,
                energy.p, virial.p, tensor.p);
    }

    template <int Dim> void totals_dim(std::uint32_t* by) {
        switch (m.pair) {
        case PairKind::harmonic:
            return totals_with<Dim>(harmonic.p, by);
        case PairKind::wca:
            return totals_with<Dim>(wca.p, by);
        case PairKind::lj:
            return totals_with<Dim>(lj.p, by);
        case PairKind::none:
            return;
        }
    }
};

bool cuda_built() {
    return true;
}

std::string unavailable_reason() {
    int devices = 0;
    const cudaError_t e = cudaGetDeviceCount(&devices);
    if (e != cudaSuccess)
        return std::string("no usable CUDA device (") + cudaGetErrorString(e) + ")";
    if (devices == 0) return "no CUDA device found";
    return {};
}

std::string device_description() {
    int device = 0;
    cudaDeviceProp p{};
    if (cudaGetDevice(&device) != cudaSuccess || cudaGetDeviceProperties(&p, device) != cudaSuccess)
        return "no CUDA device";
    int runtime = 0;
    cudaRuntimeGetVersion(&runtime);
    return std::string(p.name) + ", compute capability " + std::to_string(p.major) + "." +
           std::to_string(p.minor) + ", " + std::to_string(p.multiProcessorCount) +
           " multiprocessors, " + std::to_string(p.totalGlobalMem >> 20) + " MiB, CUDA runtime " +
           std::to_string(runtime / 1000) + "." + std::to_string(runtime % 1000 / 10);
}

DeviceSystem::DeviceSystem(const Model& model) : impl_(std::make_unique<Impl>(model)) {}
DeviceSystem::~DeviceSystem() = default;

void DeviceSystem::upload(const HostArrays& a, const double* reference) {
    Impl& s = *impl_;
    const std::size_t n = s.n, D = static_cast<std::size_t>(s.D);
    auto put = [](void* to, const void* from, std::size_t bytes) {
        check(cudaMemcpy(to, from, bytes, cudaMemcpyHostToDevice), "upload");
    };
    put(s.pos.p, a.position, n * D * sizeof(double));
    put(s.vel.p, a.velocity, n * D * sizeof(double));
    put(s.dir.p, a.director, n * D * sizeof(double));
    put(s.force.p, a.force, n * D * sizeof(double));
    put(s.torque.p, a.torque, n * s.torque_width * sizeof(double));
    put(s.image.p, a.image, n * D * sizeof(std::int32_t));
    put(s.tag.p, a.tag, n * sizeof(std::uint32_t));
    put(s.species.p, a.species, n * sizeof(std::uint16_t));
    s.has_list = false;
    s.need_rebuild = true;
    if (reference) {
        put(s.ref.p, reference, n * D * sizeof(double));
        s.build(true);
    }
}

void DeviceSystem::download(const HostArrays& a) const {
    const Impl& s = *impl_;
    const std::size_t n = s.n, D = static_cast<std::size_t>(s.D);
    auto get = [](void* to, const void* from, std::size_t bytes) {
        check(cudaMemcpy(to, from, bytes, cudaMemcpyDeviceToHost), "download");
    };
    get(a.position, s.pos.p, n * D * sizeof(double));
    get(a.velocity, s.vel.p, n * D * sizeof(double));
    get(a.director, s.dir.p, n * D * sizeof(double));
    get(a.force, s.force.p, n * D * sizeof(double));
    get(a.torque, s.torque.p, n * s.torque_width * sizeof(double));
    get(a.image, s.image.p, n * D * sizeof(std::int32_t));
    get(a.tag, s.tag.p, n * sizeof(std::uint32_t));
    get(a.species, s.species.p, n * sizeof(std::uint16_t));
}

bool DeviceSystem::download_reference(double* reference) const {
    const Impl& s = *impl_;
    if (!s.has_list) return false;
    check(cudaMemcpy(reference, s.ref.p, s.n * s.D * sizeof(double), cudaMemcpyDeviceToHost),
          "download");
    return true;
}

void DeviceSystem::set_coefficients(const StepCoefficients& c) {
    Impl& s = *impl_;
    if (c.species.size() != s.m.species)
        throw std::invalid_argument("gpu: coefficients for another number of species");
    s.c = c;
    if (s.uploaded != c.species) {
        check(cudaMemcpy(s.coef.p, c.species.data(), c.species.size() * sizeof(SpeciesCoefficients),
                         cudaMemcpyHostToDevice),
              "coefficients");
        s.uploaded = c.species;
    }
}

StepStatus DeviceSystem::prestep(std::uint32_t step) {
    Impl& s = *impl_;
    if (s.n == 0 || (s.m.mover != Mover::langevin && s.m.mover != Mover::nve)) return {};
    if (!s.has_list) s.build(false); // the reference the moves are measured from
    s.reset_status();
    const StepArgs a = s.args(step);
    if (s.D == 2)
        k_prestep<2><<<blocks(s.n), block_size>>>(a, s.pos.p, s.vel.p, s.force.p, s.ref.p, s.tag.p,
                                                  s.species.p, s.status.p);
    else
        k_prestep<3><<<blocks(s.n), block_size>>>(a, s.pos.p, s.vel.p, s.force.p, s.ref.p, s.tag.p,
                                                  s.species.p, s.status.p);
    return s.read_status();
}

bool DeviceSystem::compute_forces() {
    Impl& s = *impl_;
    const bool rebuild = !s.has_list || s.need_rebuild;
    if (rebuild) s.build(false);
    if (s.n == 0) return rebuild;
    if (s.D == 2)
        s.forces_dim<2>();
    else
        s.forces_dim<3>();
    check(cudaGetLastError(), "forces");
    return rebuild;
}

StepStatus DeviceSystem::poststep(std::uint32_t step) {
    Impl& s = *impl_;
    if (s.n == 0) return {};
    s.reset_status();
    const StepArgs a = s.args(step);
    if (s.D == 2)
        k_poststep<2><<<blocks(s.n), block_size>>>(a, s.pos.p, s.vel.p, s.dir.p, s.force.p,
                                                   s.torque.p, s.image.p, s.ref.p, s.tag.p,
                                                   s.species.p, s.status.p);
    else
        k_poststep<3><<<blocks(s.n), block_size>>>(a, s.pos.p, s.vel.p, s.dir.p, s.force.p,
                                                   s.torque.p, s.image.p, s.ref.p, s.tag.p,
                                                   s.species.p, s.status.p);
    // the next forces are measured from here: only moves since the build count
    s.need_rebuild = false;
    return s.read_status();
}

Totals DeviceSystem::totals() {
    Impl& s = *impl_;
    if (s.m.pair == PairKind::none || s.n == 0) return {};
    s.energy.reserve(s.n);
    s.virial.reserve(s.n);
    s.tensor.reserve(6 * s.n);
    cub::DoubleBuffer<std::uint32_t> k(s.keys.p, s.keys_alt.p), v(s.order.p, s.order_alt.p);
    s.bin(s.pos.p, s.grid, s.rank, s.cells, k, v);
    if (s.D == 2)
        s.totals_dim<2>(v.Current());
    else
        s.totals_dim<3>(v.Current());
    std::size_t temp = s.sort_temp.n, needed_temp = 0;
    check(cub::DeviceReduce::Sum(nullptr, needed_temp, s.energy.p, s.sums.p, static_cast<int>(s.n)),
          "reduce size");
    if (needed_temp > temp) s.sort_temp.reserve(needed_temp);
    temp = s.sort_temp.n;
    check(cub::DeviceReduce::Sum(s.sort_temp.p, temp, s.energy.p, s.sums.p, static_cast<int>(s.n)),
          "reduce");
    check(cub::DeviceReduce::Sum(s.sort_temp.p, temp, s.virial.p, s.sums.p + 1,
                                 static_cast<int>(s.n)),
          "reduce");
    for (int c = 0; c < 6; ++c)
        check(cub::DeviceReduce::Sum(s.sort_temp.p, temp, s.tensor.p + c * s.n, s.sums.p + 2 + c,
                                     static_cast<int>(s.n)),
              "reduce");
    double out[8];
    check(cudaMemcpy(out, s.sums.p, sizeof out, cudaMemcpyDeviceToHost), "totals");
    Totals t{out[0], out[1], {}};
    for (int c = 0; c < 6; ++c) t.virial_tensor[c] = out[2 + c];
    return t;
}

std::size_t DeviceSystem::device_bytes() const {
    const Impl& s = *impl_;
    return s.pos.bytes() + s.vel.bytes() + s.dir.bytes() + s.force.bytes() + s.torque.bytes() +
           s.ref.bytes() + s.scratch.bytes() + s.image.bytes() + s.tag.bytes() + s.keys.bytes() +
           s.keys_alt.bytes() + s.order.bytes() + s.order_alt.bytes() + s.cell_start.bytes() +
           s.cell_end.bytes() + s.list.bytes() + s.count.bytes() + s.species.bytes() +
           s.sort_temp.bytes() + s.energy.bytes() + s.virial.bytes() + s.tensor.bytes() +
           s.rank.bytes();
}

} // namespace pedesis::gpu
