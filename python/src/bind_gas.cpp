// pedesis.Gas: the event-driven and time-stepped hard-particle engines from Python.
#include "bindings.hpp"
#include "box_object.hpp"
#include "errors.hpp"
#include "gas_model.hpp"
#include "script_trigger.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/sym_tensor.hpp"

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <memory>

namespace py = pybind11;

namespace pedesis::python {

namespace {

struct PyGas {
    std::unique_ptr<GasModel> model;
    std::string source;
};

py::array_t<double> rows(const std::vector<double>& v, std::size_t n, int dim) {
    py::array_t<double> a({n, static_cast<std::size_t>(dim)});
    std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
}

template <class F> py::array_t<double> per_particle(const GasModel& g, F value) {
    const auto types = g.types();
    py::array_t<double> a(types.size());
    auto* out = a.mutable_data();
    for (std::size_t i = 0; i < types.size(); ++i) out[i] = value(g.species()[types[i]]);
    return a;
}

// The state now, laid out as Simulation.frame() gives it (pedesis.Recording keeps these).
py::dict frame(const GasModel& g) {
    const std::size_t n = g.size();
    const int d = g.dim();
    py::dict out;
    out["time"] = g.time();
    // (as the engines' frames count: the event engine has no steps, its collisions stand in)
    out["step"] = g.dynamics() == "event" ? g.pair_collisions() : g.steps();
    out["box"] = box_object(g.box(), g.periodic());
    std::vector<std::string> names;
    for (const auto& sp : g.species()) names.push_back(sp.name);
    out["species"] = names;
    const auto t = g.types();
    py::array_t<std::uint16_t> types(n);
    std::copy(t.begin(), t.end(), types.mutable_data());
    out["type"] = types;
    out["position"] = rows(g.positions(), n, d);
    out["velocity"] = rows(g.velocities(), n, d);
    out["radius"] = per_particle(g, [](const Species& s) { return s.radius; });
    out["mass"] = per_particle(g, [](const Species& s) { return s.mass; });
    return out;
}

std::unique_ptr<PyGas> make(const RunConfig& c, const std::string& source) {
    auto g = std::make_unique<PyGas>();
    g->model = make_gas(c);
    g->source = source;
    return g;
}

// Gas(text) given a file's name instead of its text: the TOML parser would report its
// first character, so say what was meant. One line that ends in .toml, or that names a
// file and is not a config.
InputError path_given(const std::string& path) {
    return InputError(fmt::format("Gas(...) takes the config's text; to read a file use "
                                  "pedesis.Gas.from_file('{}')",
                                  path));
}

std::unique_ptr<PyGas> from_text(const std::string& text) {
    const auto first = text.find_first_not_of(" \t\r\n");
    const auto last = text.find_last_not_of(" \t\r\n");
    const std::string line = first == std::string::npos ? "" : text.substr(first, last - first + 1);
    const bool one_line = !line.empty() && line.find('\n') == std::string::npos;
    if (one_line && line.find('=') == std::string::npos && line.size() > 5 &&
        line.compare(line.size() - 5, 5, ".toml") == 0)
        throw path_given(line);
    RunConfig c;
    try {
        c = parse_run_config(text, "<Gas config>", true);
    } catch (const InputError&) {
        std::error_code ec;
        if (one_line && std::filesystem::is_regular_file(line, ec)) throw path_given(line);
        throw;
    }
    return make(c, "<Gas config>");
}

} // namespace

void bind_gas(py::module_& m) {
    py::class_<PyGas>(m, "Gas", R"doc(
A gas of hard disks (2D) or spheres (3D) on the exact event-driven engine
(dynamics = "event") or the time-stepped one (dynamics = "stepped").

Gas(config) takes the text of a run config in TOML, Gas.from_file(path) a config file:
the same [box], [[species]], [initial], [event] and [stepped] sections `pedesis run`
reads (docs/config.md), with the same checks; [run] and [output] are not needed here
(the stop conditions are run()'s arguments). Measured quantities are numpy arrays,
copies in tag order.
)doc")
        .def(py::init(&from_text), py::arg("config"))
        // (a pathlib.Path is no text: the same pointer to from_file)
        .def(py::init([](const std::filesystem::path& path) -> std::unique_ptr<PyGas> {
                 throw path_given(path.string());
             }),
             py::arg("config"))
        .def_static(
            "from_file",
            [](const std::filesystem::path& path) {
                require_file(path, "Gas.from_file");
                return make(load_run_config(path.string(), true), path.string());
            },
            py::arg("path"), "A gas from a run config file (TOML), as `pedesis run` reads it.")
        .def(
            "run",
            [](PyGas& g, std::optional<double> time, std::optional<double> collisions_per_particle,
               std::optional<std::uint64_t> steps) {
                if (!time && !collisions_per_particle && !steps)
                    throw InputError("Gas.run: give time, collisions_per_particle or steps");
                if (time && !std::isfinite(*time))
                    throw InputError(fmt::format("Gas.run: time must be finite, got {}", *time));
                if (collisions_per_particle &&
                    !(std::isfinite(*collisions_per_particle) && *collisions_per_particle >= 0.0))
                    throw InputError(fmt::format(
                        "Gas.run: collisions_per_particle must be a finite number >= 0, got {}",
                        *collisions_per_particle));
                GasLimits l{time, collisions_per_particle, steps};
                std::string why;
                run_interruptible([&] { why = g.model->run(l); });
                return why;
            },
            py::arg("time") = py::none(), py::arg("collisions_per_particle") = py::none(),
            py::arg("steps") = py::none(), R"doc(
Advances until the simulated time reaches `time`, the pair collisions since t = 0
reach collisions_per_particle * N, or (stepped engine) `steps` more steps were taken,
whichever comes first; returns which, by the names summary.json's "stopped_by" uses:
"time", "collisions_per_particle", "steps", "no more events" (nothing moves), or
"grown" (Lubachevsky-Stillinger growth has ended). The result is a pedesis.StopName,
which also equals the earlier names "no_events" and "energy" (deprecated: a
DeprecationWarning). The GIL is released; Ctrl-C stops at the next step (stepped) or
within a few thousand collisions (event), with the gas in a valid state.
)doc")
        .def_property_readonly(
            "dynamics", [](const PyGas& g) { return g.model->dynamics(); },
            "\"event\" or \"stepped\".")
        .def_property_readonly(
            "dim", [](const PyGas& g) { return g.model->dim(); }, "Dimension, 2 or 3.")
        .def_property_readonly(
            "N", [](const PyGas& g) { return g.model->size(); }, "Number of particles.")
        .def("__len__", [](const PyGas& g) { return g.model->size(); })
        .def_property_readonly(
            "box", [](const PyGas& g) { return box_object(g.model->box(), g.model->periodic()); },
            "The box (a pedesis.Box): lengths, and periodic per axis (False: walls); it reads as "
            "the list of lengths. The box is centred at the origin.")
        .def_property_readonly(
            "time", [](const PyGas& g) { return g.model->time(); }, "Simulated time.")
        .def_property_readonly(
            "steps", [](const PyGas& g) { return g.model->steps(); },
            "Steps taken (stepped engine; 0 for event).")
        .def_property_readonly(
            "collisions", [](const PyGas& g) { return g.model->pair_collisions(); },
            "Pair collisions since t = 0.")
        .def_property_readonly(
            "wall_collisions", [](const PyGas& g) { return g.model->wall_collisions(); },
            "Particle-wall collisions since t = 0.")
        .def_property_readonly(
            "species",
            [](const PyGas& g) {
                py::list l;
                for (const auto& sp : g.model->species())
                    l.append(py::dict(py::arg("name") = sp.name, py::arg("radius") = sp.radius,
                                      py::arg("mass") = sp.mass));
                return l;
            },
            "The species table: [{'name', 'radius', 'mass'}, ...]; types index it.")
        .def_property_readonly(
            "positions",
            [](const PyGas& g) {
                return rows(g.model->positions(), g.model->size(), g.model->dim());
            },
            "(N, dim) positions at the current time (a copy).")
        .def_property_readonly(
            "velocities",
            [](const PyGas& g) {
                return rows(g.model->velocities(), g.model->size(), g.model->dim());
            },
            "(N, dim) velocities (a copy).")
        .def_property_readonly(
            "speeds",
            [](const PyGas& g) {
                const auto v = g.model->velocities();
                const int d = g.model->dim();
                py::array_t<double> a(g.model->size());
                auto* out = a.mutable_data();
                for (std::size_t i = 0; i < g.model->size(); ++i) {
                    double s = 0.0;
                    for (int k = 0; k < d; ++k) s += v[i * d + k] * v[i * d + k];
                    out[i] = std::sqrt(s);
                }
                return a;
            },
            "(N,) speeds |v|.")
        .def_property_readonly(
            "types",
            [](const PyGas& g) {
                const auto t = g.model->types();
                py::array_t<std::uint16_t> a(t.size());
                std::copy(t.begin(), t.end(), a.mutable_data());
                return a;
            },
            "(N,) species index of each particle.")
        .def_property_readonly(
            "masses",
            [](const PyGas& g) {
                return per_particle(*g.model, [](const Species& s) { return s.mass; });
            },
            "(N,) masses (inf for fixed obstacles).")
        .def_property_readonly(
            "radii",
            [](const PyGas& g) {
                return per_particle(*g.model, [](const Species& s) { return s.radius; });
            },
            "(N,) radii.")
        .def(
            "kinetic_energy", [](const PyGas& g) { return g.model->kinetic_energy(); },
            "sum m v^2 / 2 over the mobile particles.")
        .def(
            "temperature", [](const PyGas& g) { return g.model->temperature(); },
            R"doc(
Kinetic temperature 2 K / f, with K taken in the centre-of-mass frame along the
momentum components the dynamics conserves and f the degrees of freedom (see
degrees_of_freedom()); as log.csv's temperature column.
)doc")
        .def(
            "degrees_of_freedom", [](const PyGas& g) { return g.model->degrees_of_freedom(); },
            R"doc(
Kinetic degrees of freedom f = d N_mobile - c, with c the momentum components the
dynamics conserves: d in a fully periodic box without fixed obstacles, one per periodic
axis with walls on the others, 0 with walls on every axis or a fixed obstacle.
)doc")
        .def(
            "pressure",
            [](PyGas& g, bool tensor) -> py::object {
                const SymTensor t = g.model->pressure_tensor();
                const int d = g.model->dim();
                if (!tensor) {
                    double trace = 0.0;
                    for (int a = 0; a < d; ++a) trace += t[static_cast<std::size_t>(a)];
                    return py::float_(trace / d);
                }
                py::array_t<double> m({d, d});
                auto w = m.mutable_unchecked<2>();
                for (int a = 0; a < d; ++a)
                    for (int b = 0; b < d; ++b)
                        w(a, b) = t[static_cast<std::size_t>(sym_slot(a, b))];
                return m;
            },
            py::arg("tensor") = false, R"doc(
Pressure since the previous call (or t = 0), log.csv's definition: the mean of the
pressure tensor's diagonal, or with tensor=True the d x d tensor itself (numpy array).
A walled axis's diagonal component is the momentum delivered to its walls per unit time
and wall area (seed 003's definition); every other component is the virial
<sum m u_a u_b> / V + sum J n_a r_b / (V dt), u the velocities in the centre-of-mass
frame along conserved axes, averaged over both ends of the interval.
)doc")
        .def(
            "frame", [](const PyGas& g) { return frame(*g.model); },
            R"doc(
The state now as a dict of numpy arrays in tag order, laid out as Simulation.frame():
time, step (the event engine: pair collisions), box (a pedesis.Box), species (names),
type, position, velocity, radius, mass.
)doc")
        .def(
            "_add_recording",
            [](PyGas& g, py::function fn, std::optional<std::uint64_t> steps,
               std::optional<double> time) {
                const Trigger t =
                    make_trigger(steps, time, "Gas.record", g.model->dynamics() == "stepped");
                GasModel* model = g.model.get();
                // run() copies its operations with the GIL released: a shared_ptr's copies
                // leave fn's reference count alone, and the last one takes the GIL to drop it
                std::shared_ptr<py::function> held(new py::function(std::move(fn)),
                                                   [](py::function* f) {
                                                       py::gil_scoped_acquire gil;
                                                       delete f;
                                                   });
                // fn receives the frame, so it needs no reference to the Gas (which
                // holds fn: a cycle Python's collector cannot see through C++)
                g.model->add_operation(t, [held, model] {
                    py::gil_scoped_acquire gil;
                    (*held)(frame(*model));
                });
            },
            py::arg("fn"), py::arg("steps") = py::none(), py::arg("time") = py::none())
        .def("__repr__", [](const PyGas& g) {
            return fmt::format("<pedesis.Gas: {} {}D, N={}, t={:g}, from {}>", g.model->dynamics(),
                               g.model->dim(), g.model->size(), g.model->time(), g.source);
        });
}

} // namespace pedesis::python
