#pragma once
// Spatial domain decomposition of a soft / active system over the processes of a
// Communicator (MPI ranks): the periodic box is cut into a grid of equal rectangular
// domains, one per process, and each process integrates the particles in its domain.
//
// Positions stay in the coordinates of the whole box, wrapped as on one process, so the
// neighbour list, the minimum image and every force and torque term work unchanged.
// Each process also holds ghosts: copies of the particles of other domains that lie
// within `range` (the list cutoff plus skin) of its domain. They are chosen, and
// particles that left their domain migrate, whenever the neighbour list is rebuilt;
// between rebuilds no particle moves more than skin/2, so every pair within the cutoff
// that involves an owned particle is in the local list. Before each force computation
// the ghosts' positions, velocities and directors are refreshed from their owners.
// Forces on ghosts are discarded: each process sums the forces on its own particles
// over the half list, so force sums differ from one process's only in their order
// (round-off).
//
// A particle goes at most once to each process (its wrapped position serves every
// periodic image), so domains must be at least `range` wide: then a particle is a ghost
// only of the domains next to its own, across faces, edges and corners. Every exchange
// is point to point with those domains' processes (a few messages per step whatever the
// number of processes), and each process's neighbour list covers its own region
// (local_box), so that work and memory per process do not grow with their number.
#include "pedesis/core/communicator.hpp"
#include "pedesis/soft/soft_state.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace pedesis {

// The grid of domains for `processes` over a box: of all factorisations, the one whose
// domains have the least surface (the communication volume), among those whose domains
// are at least `range` wide on every axis. Ties go to more cuts along the later axes.
// Throws InputError when none is wide enough.
template <int D> std::array<int, D> domain_grid(int processes, const Box<D>& box, double range);

template <int D> class DomainDecomposition {
  public:
    // range: the list cutoff plus skin.
    DomainDecomposition(Communicator& comm, const Box<D>& box, double range);

    Communicator& comm() { return comm_; }
    const std::array<int, D>& grid() const { return grid_; }

    // Keeps, of a state every process holds whole (a fresh or restored run), the
    // particles of this process's domain, in their order; ghosts follow at the next
    // redistribute().
    void scatter(SoftState<D>& s) const;
    // Particles that left this domain go to their domain's process (any distance: a
    // particle may cross several domains), then the ghosts are chosen anew. With
    // sort_cell > 0 each process's particles are first ordered along a space-filling
    // curve of that spacing (spatial/spatial_sort.hpp), as the periodic sort of one process.
    void redistribute(SoftState<D>& s, double sort_cell = 0.0);
    // What scatter() makes of the whole state in tag order, which a checkpoint holds:
    // this process's particles (those that left its domain sent to theirs) in tag order,
    // no ghosts; the next redistribute() chooses them. A run that does this after each
    // checkpoint goes on from the state a restart from that checkpoint starts from, so
    // the two step alike, bit for bit (each process sums its forces in its storage order).
    void settle_in_tag_order(SoftState<D>& s);
    // Positions, velocities and directors of the ghosts, from their owners.
    void refresh_ghosts(SoftState<D>& s);
    // The whole state in tag order, on process 0 (`whole` is left alone elsewhere).
    void gather(const SoftState<D>& s, SoftState<D>& whole);

    // Whether any process says so.
    bool any(bool mine);

    // Where this process's neighbour list bins its particles, so that its cells cover
    // its own region, not the whole box: the domain widened by `range + 2 skin` (what a
    // ghost or a particle that left since the last build can reach) on each axis cut
    // into 3 or more domains where that stays within half the box, with walls there
    // (nothing lies beyond); elsewhere the whole periodic axis. (Cut into 2, an axis
    // stays periodic: a ghost may then be near both faces of the domain, through two
    // images.) Centred at the origin, as every Box; local_positions maps positions into it.
    Box<D> local_box(double skin) const;
    // Positions relative to the centre of this process's domain: on the walled axes of
    // local_box the periodic image nearest to it, elsewhere as they are.
    void local_positions(const std::vector<Vec<D>>& pos, std::vector<Vec<D>>& out,
                         double skin) const;

  private:
    // Particles that left this domain go to their domain's process; ghosts are dropped.
    void migrate(SoftState<D>& s);
    int domain_of(const Vec<D>& r) const;
    std::array<int, D> coords_of(const Vec<D>& r) const;
    int rank_of(const std::array<int, D>& c) const;
    void ghost_destinations(const Vec<D>& r, std::vector<int>& out) const;

    Communicator& comm_;
    Box<D> box_;
    double range_;
    std::array<int, D> grid_{};
    std::array<int, D> mine_{};     // this process's domain coordinates
    std::array<double, D> width_{}; // of a domain along each axis
    // The processes of the neighbouring domains (ascending), and each process's index
    // among them (-1: not a partner).
    std::vector<int> partners_;
    std::vector<int> partner_of_rank_;
    // Per partner, the owned particles (storage indices) it holds as ghosts, in order.
    std::vector<std::vector<std::uint32_t>> ghost_send_;
    std::vector<std::vector<double>> send_; // reused buffers
};

extern template class DomainDecomposition<2>;
extern template class DomainDecomposition<3>;

} // namespace pedesis
