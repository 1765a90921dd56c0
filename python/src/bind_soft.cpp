// pedesis.System, pedesis.Evolver, pedesis.Plugin (the base of HarmonicForce and the
// other terms, which pedesis/__init__.py builds from the catalogue) and random_init.
#include "bindings.hpp"
#include "box_object.hpp"
#include "errors.hpp"
#include "soft_model.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/tutorial_json.hpp"
#include "pedesis/setup/init_random.hpp"
#include "pedesis/soft/plugin_registry.hpp"

#include <fmt/format.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

namespace py = pybind11;

namespace pedesis::python {

namespace {

struct PySystem {
    double rcut = 0.0, pad = 0.5;
    std::uint64_t seed = 1;
    int dim = 0; // requested; 0: from the file
    std::unique_ptr<SystemModel> model;
    std::string source;

    SystemModel& get() {
        if (!model) throw InputError("System: it has no particles yet; call read_init(path) first");
        return *model;
    }
};

struct PyPlugin {
    PluginSpec spec;
    std::string label; // the Python class name, for messages
};

struct PyEvolver {
    py::object system; // keeps the System alive while its Evolver is
    std::unique_ptr<EvolverModel> model;
};

// A numpy view of N rows of `cols` values of type T at `data`, owned by `owner`.
template <class T> py::array view(T* data, std::size_t n, std::size_t cols, py::handle owner) {
    if (cols == 0) return py::array_t<T>({n}, {sizeof(T)}, data, owner);
    return py::array_t<T>({n, cols}, {cols * sizeof(T), sizeof(T)}, data, owner);
}

PluginParam python_param(const py::handle& value, const std::string& where) {
    PluginParam p;
    p.where = where;
    if (py::isinstance<py::dict>(value)) {
        for (const auto& [k, v] : value.cast<py::dict>()) {
            if (!py::isinstance<py::str>(k))
                throw InputError(where + ": species are named by strings");
            try {
                p.by_species.emplace_back(k.cast<std::string>(), v.cast<double>());
            } catch (const py::cast_error&) {
                throw InputError(where + " (species '" + k.cast<std::string>() +
                                 "'): must be a number");
            }
        }
        return p;
    }
    if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
        for (const auto& v : value) {
            try {
                p.components.push_back(v.cast<double>());
            } catch (const py::cast_error&) {
                throw InputError(where + ": a list of numbers (one per axis), got " +
                                 py::repr(value).cast<std::string>());
            }
        }
        if (p.components.empty()) throw InputError(where + ": give one number per axis");
        return p;
    }
    try {
        p.uniform = value.cast<double>();
    } catch (const py::cast_error&) {
        throw InputError(where + ": must be a number or a dict {species: number}, got " +
                         py::repr(value).cast<std::string>());
    }
    return p;
}

// pairs={("A", "B"): {"epsilon": 1.5, "sigma": 0.8}, ...}: a pair potential's per-pair
// values, as [[force.pairs]] gives them in a config.
std::vector<PairValues> python_pairs(const py::handle& value, const std::string& where) {
    if (!py::isinstance<py::dict>(value))
        throw InputError(where + ": must be a dict {(species, species): {parameter: number}}");
    std::vector<PairValues> out;
    for (const auto& [k, v] : value.cast<py::dict>()) {
        PairValues pv;
        pv.where = where + "[" + py::repr(k).cast<std::string>() + "]";
        try {
            const auto names = k.cast<std::pair<std::string, std::string>>();
            pv.a = names.first;
            pv.b = names.second;
            for (const auto& [key, x] : v.cast<py::dict>())
                pv.values[key.cast<std::string>()] = x.cast<double>();
        } catch (const py::cast_error&) {
            throw InputError(pv.where +
                             ": keys are (species, species), values {parameter: number}");
        }
        out.push_back(std::move(pv));
    }
    return out;
}

PluginKind kind_of(const std::string& kind) {
    if (kind == "force") return PluginKind::force;
    if (kind == "torque") return PluginKind::torque;
    if (kind == "integrator") return PluginKind::integrator;
    throw InputError("Plugin: kind must be force, torque or integrator, got '" + kind + "'");
}

void add_term(PyEvolver& e, const PyPlugin& p, PluginKind expected, const char* method) {
    if (p.spec.kind != expected)
        throw InputError(fmt::format("Evolver.{}: {} is {} {}; use Evolver.add_{}", method, p.label,
                                     p.spec.kind == PluginKind::integrator ? "an" : "a",
                                     kind_name(p.spec.kind), kind_name(p.spec.kind)));
    e.model->add(p.spec);
}

void evolver_run(PyEvolver& e, std::uint64_t steps, double dt, std::uint64_t every,
                 const py::object& callback) {
    RunHooks hooks;
    hooks.every = every;
    if (!callback.is_none()) {
        if (every == 0) throw InputError("Evolver.run: a callback needs every > 0 (steps)");
        hooks.between = [&callback](std::uint64_t step) {
            py::gil_scoped_acquire gil;
            callback(step);
        };
    }
    run_interruptible([&] { e.model->run(steps, dt, hooks); });
}

void random_init(double phi, double L, double rcut, const std::filesystem::path& outfile,
                 std::uint64_t seed, int dim, std::optional<double> Ly, std::optional<double> Lz,
                 double radius) {
    InitRandomOptions o;
    o.phi = phi;
    o.L = L;
    o.Ly = Ly;
    o.Lz = Lz;
    o.rcut = rcut;
    o.radius = radius;
    o.seed = seed;
    o.context = "random_init";
    o.option_prefix = "";
    require_parent_directory(outfile, "random_init");
    std::string text;
    if (dim == 2)
        text = to_tutorial_json(init_random<2>(o).frame()).dump();
    else if (dim == 3)
        text = to_tutorial_json(init_random<3>(o).frame()).dump();
    else
        throw InputError(fmt::format("random_init: dim must be 2 or 3, got {}", dim));
    write_file_atomically(outfile, [&](std::ostream& out) { out << text << "\n"; });
}

} // namespace

void bind_soft(py::module_& m) {
    py::class_<PySystem>(m, "System", R"doc(
A system of soft or active particles: the box, the particles and their directors.

System(rcut=0.0, pad=0.5, seed=1, dim=None), then read_init(path), as in the ABP
tutorial. rcut is the neighbour-list cutoff (0: the largest range of the terms added to
the Evolver), pad the list's skin: the list is rebuilt when a particle has moved pad/2
since the last build. seed keys every random stream (directors the file leaves out,
the integrators' noise): the same seed gives the same trajectory as `pedesis run` of
the same config.

positions, velocities, directors, forces, torques, images, tags and types are numpy
arrays that view the C++ memory (no copy), row i being the particle with tag i. Write
into them between steps (in a callback of Evolver.run, or between evolve calls):
positions outside the box are wrapped into it at the next step (images follow), and
the neighbour list notices any move by itself (it compares with the positions of its
last build). Views stay valid as long as the System lives.
)doc")
        .def(py::init([](double rcut, double pad, std::uint64_t seed, std::optional<int> dim) {
                 if (!(rcut >= 0.0 && std::isfinite(rcut)))
                     throw InputError(
                         fmt::format("System: rcut must be a finite number >= 0, got {}", rcut));
                 if (!(pad >= 0.0 && std::isfinite(pad)))
                     throw InputError(
                         fmt::format("System: pad must be a finite number >= 0, got {}", pad));
                 if (dim && *dim != 2 && *dim != 3)
                     throw InputError(fmt::format("System: dim must be 2 or 3, got {}", *dim));
                 auto s = std::make_unique<PySystem>();
                 s->rcut = rcut;
                 s->pad = pad;
                 s->seed = seed;
                 s->dim = dim.value_or(0);
                 return s;
             }),
             py::arg("rcut") = 0.0, py::arg("pad") = 0.5, py::arg("seed") = 1,
             py::arg("dim") = py::none())
        .def(
            "read_init",
            [](PySystem& s, const std::filesystem::path& path, std::optional<std::int64_t> frame) {
                if (s.model)
                    throw InputError("System.read_init: this System has particles already "
                                     "(views of its arrays would dangle); make a new System");
                require_file(path, "System.read_init");
                s.model = read_system(path, s.dim, s.seed, frame);
                s.source = path.string();
            },
            py::arg("path"), py::arg("frame") = py::none(), R"doc(
Reads an initial configuration, as [initial] file of a config does (docs/config.md):
the ABP tutorial's JSON (what pedesis.builder.random_init and `pedesis init random`
write: the box, and per particle "id" (0..N-1), "type", "r", optionally "n", "v",
"radius", "mass"), or a frame of a GSD file (HOOMD-blue's or pedesis' trajectory.gsd)
or of an extended XYZ file: `frame` (0-based, negative from the end) or else the last.
Each type becomes a species, named as the file names it (GSD, XYZ) or A, B, ... A
director the file leaves out is a random unit vector drawn from the seed. The dimension
is that of the file unless System(dim=...) says. Raises FileNotFoundError, or
InputError naming the particle and key.
)doc")
        .def_property_readonly(
            "dim", [](PySystem& s) { return s.get().dim(); }, "Dimension, 2 or 3.")
        .def_property_readonly(
            "N", [](PySystem& s) { return s.get().size(); }, "Number of particles.")
        .def("__len__", [](PySystem& s) { return s.model ? s.model->size() : 0; })
        .def_property_readonly(
            "box", [](PySystem& s) { return box_object(s.get().box(), s.get().periodic()); },
            "The box, a pedesis.Box: lengths [Lx, Ly(, Lz)] (it reads as that list) and "
            "periodic flags; the box is centred at the origin.")
        .def_property_readonly(
            "time", [](PySystem& s) { return s.get().time(); }, "Simulated time.")
        .def_property_readonly(
            "step", [](PySystem& s) { return s.get().step(); }, "Steps taken since the start.")
        .def_property_readonly(
            "seed", [](PySystem& s) { return s.seed; }, "The random seed.")
        .def_property_readonly(
            "species",
            [](PySystem& s) {
                py::list l;
                for (const auto& sp : s.get().species())
                    l.append(py::dict(py::arg("name") = sp.name, py::arg("radius") = sp.radius,
                                      py::arg("mass") = sp.mass));
                return l;
            },
            "The species table: [{'name', 'radius', 'mass'}, ...]; types index it.")
        .def_property_readonly(
            "positions",
            [](py::object self) {
                auto& s = self.cast<PySystem&>().get();
                return view(s.positions(), s.size(), static_cast<std::size_t>(s.dim()), self);
            },
            "(N, dim) view of the positions, wrapped into the box.")
        .def_property_readonly(
            "velocities",
            [](py::object self) {
                auto& s = self.cast<PySystem&>().get();
                return view(s.velocities(), s.size(), static_cast<std::size_t>(s.dim()), self);
            },
            "(N, dim) view of the velocities (overdamped integrators leave them as they are).")
        .def_property_readonly(
            "directors",
            [](py::object self) {
                auto& s = self.cast<PySystem&>().get();
                return view(s.directors(), s.size(), static_cast<std::size_t>(s.dim()), self);
            },
            "(N, dim) view of the unit polarity vectors n_i.")
        .def_property_readonly(
            "forces",
            [](py::object self) {
                auto& s = self.cast<PySystem&>().get();
                return view(s.forces(), s.size(), static_cast<std::size_t>(s.dim()), self);
            },
            "(N, dim) view of the total force of the last step.")
        .def_property_readonly(
            "torques",
            [](py::object self) {
                auto& s = self.cast<PySystem&>().get();
                return view(s.torques(), s.size(), s.dim() == 2 ? 0 : 3, self);
            },
            "View of the torques of the last step: (N,) about z in 2D, (N, 3) in 3D.")
        .def_property_readonly(
            "images",
            [](py::object self) {
                auto& s = self.cast<PySystem&>().get();
                return view(s.images(), s.size(), static_cast<std::size_t>(s.dim()), self);
            },
            "(N, dim) view of the periodic images crossed: unwrapped r = r + images * box.")
        .def_property_readonly(
            "tags",
            [](py::object self) {
                auto& s = self.cast<PySystem&>().get();
                return view(s.tags(), s.size(), 0, self);
            },
            "(N,) view of the particle ids; always 0..N-1 in order between steps.")
        .def_property_readonly(
            "types",
            [](py::object self) {
                auto& s = self.cast<PySystem&>().get();
                return view(s.types(), s.size(), 0, self);
            },
            "(N,) view of the species index of each particle (into System.species).")
        .def(
            "polar_order", [](PySystem& s) { return s.get().polar_order(); },
            "|sum n_i| / N: 0 for random directors, 1 when all point the same way.")
        .def(
            "kinetic_energy", [](PySystem& s) { return s.get().kinetic_energy(); },
            "sum m v^2 / 2 (meaningful with an inertial integrator).")
        .def(
            "write_vtp",
            [](PySystem& s, const std::filesystem::path& path) {
                require_parent_directory(path, "write_vtp");
                s.get().write_vtp(path);
            },
            py::arg("path"), "Writes a VTP (ParaView) snapshot, atomically.")
        .def(
            "write_json",
            [](PySystem& s, const std::filesystem::path& path) {
                require_parent_directory(path, "write_json");
                s.get().write_json(path);
            },
            py::arg("path"),
            "Writes the state in the tutorial's JSON layout (read_init reads it back), atomically.")
        .def("__repr__", [](PySystem& s) {
            if (!s.model)
                return fmt::format("<pedesis.System: empty, rcut={}, pad={}>", s.rcut, s.pad);
            return fmt::format("<pedesis.System: {}D, N={}, step {}, from {}>", s.model->dim(),
                               s.model->size(), s.model->step(), s.source);
        });

    py::class_<PyPlugin>(m, "Plugin", R"doc(
Base of the forces, torques and integrators (HarmonicForce, SelfPropulsion, PolarAlign,
BrownianIntegrator, ...). Plugin(kind, name, params, label) checks the parameters
against the engine's catalogue: unknown, missing or out-of-range ones raise InputError.
)doc")
        .def(py::init([](const std::string& kind, const std::string& name, const py::dict& params,
                         const std::string& label) {
                 std::map<std::string, PluginParam> given;
                 std::map<std::string, bool> flags;
                 std::vector<PairValues> pairs;
                 std::string mixing = "geometric";
                 std::map<std::string, std::string> choices;
                 for (const auto& [k, v] : params) {
                     const auto key = k.cast<std::string>();
                     if (key == "pairs")
                         pairs = python_pairs(v, label + ": pairs");
                     else if (key == "mixing")
                         mixing = v.cast<std::string>();
                     else if (py::isinstance<py::str>(v))
                         choices[key] = v.cast<std::string>();
                     else if (py::isinstance<py::bool_>(v))
                         flags[key] = v.cast<bool>();
                     else
                         given[key] = python_param(v, label + ": " + key);
                 }
                 auto p = std::make_unique<PyPlugin>();
                 p->spec = make_plugin_spec(kind_of(kind), name, std::move(given), label,
                                            std::move(flags), std::move(pairs), mixing,
                                            std::move(choices));
                 p->label = label;
                 return p;
             }),
             py::arg("kind"), py::arg("name"), py::arg("params"), py::arg("label"))
        .def_property_readonly(
            "kind", [](const PyPlugin& p) { return std::string(kind_name(p.spec.kind)); })
        .def_property_readonly(
            "name", [](const PyPlugin& p) { return p.spec.name; },
            "The name a config file gives it ([[force]] name = ...).")
        .def(
            "check_species",
            [](const PyPlugin& p, PySystem& s) {
                for (const auto& [key, value] : p.spec.params)
                    if (!value.by_species.empty()) plugin_parameter(p.spec, key, s.get().species());
            },
            "Raises InputError unless every per-species parameter names exactly the system's "
            "species.");

    py::class_<PyEvolver>(m, "Evolver", R"doc(
Advances a System: Evolver(system, sort_every=500). Register terms with add_force,
add_torque and add_integrator, then evolve(dt) one step at a time, as in the tutorial,
or run(steps, dt, every=k, callback=f), which stays in C++ for all the steps and calls
f(step) every k steps. A step: forces and torques reset and summed over the terms,
then each integrator. sort_every reorders the particles' storage along a space-filling
curve every so many steps for speed (0: never); the arrays Python sees are in tag order
whenever Python runs.
)doc")
        .def(py::init([](py::object system, std::uint64_t sort_every) {
                 auto& s = system.cast<PySystem&>();
                 auto e = std::make_unique<PyEvolver>();
                 e->model = make_evolver(s.get(), s.rcut, s.pad, s.seed, sort_every);
                 e->system = system;
                 return e;
             }),
             py::arg("system"), py::arg("sort_every") = 500)
        .def(
            "add_force",
            [](PyEvolver& e, const PyPlugin& p) { add_term(e, p, PluginKind::force, "add_force"); },
            py::arg("force"),
            "Registers a force (HarmonicForce, WcaForce, LjForce, SelfPropulsion).")
        .def(
            "add_torque",
            [](PyEvolver& e, const PyPlugin& p) {
                add_term(e, p, PluginKind::torque, "add_torque");
            },
            py::arg("torque"), "Registers a torque (PolarAlign).")
        .def(
            "add_integrator",
            [](PyEvolver& e, const PyPlugin& p) {
                add_term(e, p, PluginKind::integrator, "add_integrator");
            },
            py::arg("integrator"),
            "Registers an integrator (BrownianIntegrator, BrownianRotIntegrator, "
            "LangevinIntegrator, NVEIntegrator).")
        .def(
            "evolve", [](PyEvolver& e, double dt) { evolver_run(e, 1, dt, 0, py::none()); },
            py::arg("dt"), "Advances one step of length dt.")
        .def("run", &evolver_run, py::arg("steps"), py::arg("dt"), py::arg("every") = 0,
             py::arg("callback") = py::none(), R"doc(
Advances `steps` steps of length dt without returning to Python, except to call
callback(step) every `every` steps, at steps that are multiples of `every` (the arrays
are in tag order then, and what the callback writes into them is taken up); not at the
starting step: take a snapshot before calling run if you want one. The GIL is released; Ctrl-C (or any signal
handler that raises) stops the run at the next step boundary with the state intact,
and the exception propagates. A step that moves a particle further than pad (a
blow-up) or to NaN raises RunError naming the particle.
)doc")
        .def(
            "potential_energy", [](PyEvolver& e) { return e.model->potential_energy(); },
            "Potential energy of the pair forces at the current positions.")
        .def_property_readonly(
            "system", [](const PyEvolver& e) { return e.system; }, "The System it evolves.")
        .def_property_readonly(
            "list_builds", [](const PyEvolver& e) { return e.model->list_builds(); },
            "Neighbour-list builds so far.")
        .def_property_readonly(
            "terms", [](const PyEvolver& e) { return e.model->terms(); },
            "Names of the registered forces, torques and integrators, in that order.");

    m.def("_random_init", &random_init, py::arg("phi"), py::arg("L"), py::arg("rcut"),
          py::arg("outfile"), py::arg("seed"), py::arg("dim"), py::arg("Ly"), py::arg("Lz"),
          py::arg("radius"));

    py::list catalogue;
    for (const auto& info : plugin_catalogue()) {
        py::list params;
        for (const auto& p : info.params)
            params.append(py::dict(py::arg("key") = p.key, py::arg("required") = p.required,
                                   py::arg("per_species") = p.per_species,
                                   py::arg("per_axis") = p.per_axis,
                                   py::arg("meaning") = p.meaning));
        py::list flags;
        for (const auto& f : info.flags)
            flags.append(py::dict(py::arg("key") = f.key, py::arg("meaning") = f.meaning));
        py::list choices;
        for (const auto& c : info.choices) {
            py::list options;
            for (const char* o : c.options) options.append(o);
            choices.append(py::dict(py::arg("key") = c.key, py::arg("options") = options,
                                    py::arg("default") = c.fallback,
                                    py::arg("meaning") = c.meaning));
        }
        catalogue.append(py::dict(
            py::arg("kind") = kind_name(info.kind), py::arg("name") = info.name,
            py::arg("python_class") = info.python_class, py::arg("params") = params,
            py::arg("flags") = flags, py::arg("choices") = choices,
            py::arg("pair_potential") = info.pair_potential, py::arg("formula") = info.formula));
    }
    m.attr("_catalogue") = catalogue;
}

} // namespace pedesis::python
