#include "pedesis/observe/quantities.hpp"

namespace pedesis {

namespace {
constexpr bool count = true;
constexpr bool may_be_infinite = true;
constexpr const char* hard = "event, stepped";
constexpr const char* all = "event, stepped, soft";
constexpr const char* soft = "soft";
constexpr const char* inertial = "stepped, event, langevin, nve, bussi, nose_hoover";
} // namespace

const std::vector<QuantityInfo>& quantity_catalogue() {
    static const std::vector<QuantityInfo> catalogue = {
        {"step", "1", "time steps so far", "stepped, soft", count},
        {"time", "time", "simulated time", all},
        {"collisions", "1", "pair collisions so far", hard, count},
        {"collisions_per_particle", "1", "pair collisions so far per particle", hard},
        {"wall_collisions", "1", "particle-wall collisions so far", hard, count},
        {"kinetic_energy", "energy", "total kinetic energy sum m v^2 / 2 (mobile particles)",
         inertial},
        {"kinetic_energy_<species>", "energy", "kinetic energy of one species", hard},
        {"energy_fraction", "1", "kinetic energy over its initial value", hard},
        {"temperature", "energy",
         "kinetic temperature 2 K / f, f the degrees of freedom (less the conserved momentum); "
         "under [box] shear_rate, of the peculiar velocities (the co-moving frame)",
         inertial},
        {"temperature_<species>", "energy", "kinetic temperature of one species", hard},
        {"potential_energy", "energy",
         "potential energy of the pair forces, walls and external fields; event and stepped: "
         "in [event]/[stepped] gravity, the weight times the height of each centre above the "
         "wall gravity points to, -sum m g.(r - r0)",
         "soft, event, stepped"},
        {"gravity_energy", "energy",
         "potential energy in the gravity force: sum of the weight times the height above the "
         "box's centre",
         soft},
        {"trap_energy", "energy", "potential energy in the harmonic traps", soft},
        {"wall_pressure_x", "energy / volume",
         "force per area the particles exert on the two walls normal to x (their mean), at the "
         "instant",
         "soft"},
        {"wall_pressure_y", "energy / volume", "the same on the walls normal to y", soft},
        {"wall_pressure_z", "energy / volume", "the same on the walls normal to z (3D)", soft},
        {"wall_pressure_sphere", "energy / volume",
         "outward force per area the particles exert on a spherical (2D: circular) container, "
         "at the instant",
         soft},
        {"wall_pressure_cylinder", "energy / volume",
         "outward force per area the particles exert on a cylindrical container's side, at the "
         "instant",
         soft},
        {"total_energy", "energy",
         "potential plus kinetic energy: constant in NVE up to the integrator's error (event "
         "and stepped: in gravity, constant in elastic runs to rounding)",
         "langevin, nve, bussi, nose_hoover, event, stepped"},
        {"injected_energy", "energy",
         "kinetic energy the white-noise driving ([event] driving) has added since t = 0",
         "event"},
        {"wall_work", "energy",
         "work the moving wall ([event.moving_wall]) has done on the particles since t = 0: the "
         "energy it injected (what the wall restitution takes of it is in the energy lost)",
         "event"},
        {"wall_position", "length",
         "coordinate of the moving wall's face ([event.moving_wall]) at the row's time", "event"},
        {"conserved_energy", "energy",
         "total_energy plus the energy of the thermostat's bath (bussi: minus the kinetic energy "
         "its rescales added; nose_hoover: the chain's kinetic and potential terms; nve with "
         "[barostat]: P V plus the barostat's kinetic energy): constant up to the integrator's "
         "error",
         "bussi, nose_hoover, nve with [barostat]"},
        {"pressure", "energy / volume",
         "pressure P; hard particles: averaged over the interval since the previous row "
         "(walls on walled axes, collision virial on periodic ones); soft: at the instant, "
         "pressure_ideal + pressure_virial + pressure_active",
         all},
        {"pressure_ideal", "energy / volume",
         "ideal-gas part: n T (hard: the interval's mean temperature; soft inertial: 2 K / (d V) "
         "in the centre-of-mass frame; overdamped: n T of the bath)",
         all},
        {"compressibility", "1", "Z = P / (n T) over the interval", hard},
        {"mean_free_time", "time", "N_mobile t / (2 collisions): mean time between collisions",
         hard, !count, may_be_infinite},
        {"list_rebuilds", "1", "neighbour-list builds so far", "event, soft", count},
        {"volume", "volume", "the box's volume (area in 2D), which [barostat] changes",
         "langevin, nve with [barostat]"},
        {"max_force", "energy / length",
         "largest force on a particle, max_i |F_i|: what [minimize] force_tolerance stops on",
         "minimize"},
        {"force_norm", "energy / length", "norm of the whole force vector, sqrt(sum_i |F_i|^2)",
         "minimize"},
        {"fire_dt", "time", "FIRE's adaptive time step", "minimize"},
        {"packing_fraction", "1", "volume fraction of the particles (growth runs)", "event"},
        {"growth_pressure", "1",
         "reduced pressure P V / (N T) over the last N collisions "
         "(growth runs)",
         "event"},
        {"v_rms", "length / time", "root-mean-square speed of the mobile particles", "stepped"},
        {"mean_speed", "length / time", "mean speed of the mobile particles", "stepped"},
        {"pressure_running", "energy / volume",
         "the notebook's pressure: everything the walls received since t = 0, over the whole "
         "time",
         "stepped"},
        {"polar_order", "1", "|sum n_i| / N: 0 for random directors, 1 when aligned", soft},
        {"msd", "length^2", "mean squared displacement since the start (unwrapped)", all},
        {"pressure_virial", "energy / volume", "pair virial sum r_ij . F_ij / (d V)", soft},
        {"pressure_active", "energy / volume",
         "swim pressure of the active forces, sum F_active,i . dr_i / (d V) (self_propulsion: "
         "F_active = alpha n_i; active_ou: gamma p_i)",
         soft},
        {"pressure_xx", "energy / volume",
         "pressure tensor, diagonal component along x, from the same parts as pressure "
         "(the mean of the diagonal components is pressure)",
         all},
        {"pressure_yy", "energy / volume", "pressure tensor, diagonal component along y", all},
        {"pressure_zz", "energy / volume", "pressure tensor, diagonal component along z (3D)", all},
        {"pressure_xy", "energy / volume",
         "pressure tensor, off-diagonal component xy: kinetic part plus pair or collision "
         "virial (walls push along their normal and add to the diagonal only); under [box] "
         "shear_rate the shear stress, -rate times the viscosity",
         all},
        {"pressure_xz", "energy / volume", "pressure tensor, off-diagonal component xz (3D)", all},
        {"pressure_yz", "energy / volume", "pressure tensor, off-diagonal component yz (3D)", all},
    };
    return catalogue;
}

const QuantityInfo* find_quantity(std::string_view column) {
    constexpr std::string_view placeholder = "<species>";
    for (const QuantityInfo& q : quantity_catalogue()) {
        const std::string_view name = q.name;
        if (name == column) return &q;
        const auto at = name.find(placeholder);
        if (at == std::string_view::npos) continue;
        const std::string_view head = name.substr(0, at);
        const std::string_view tail = name.substr(at + placeholder.size());
        if (column.size() > head.size() + tail.size() && column.starts_with(head) &&
            column.ends_with(tail))
            return &q;
    }
    return nullptr;
}

std::string quantity_names() {
    std::string s;
    for (const QuantityInfo& q : quantity_catalogue())
        s += std::string(s.empty() ? "" : ", ") + q.name;
    return s;
}

} // namespace pedesis
