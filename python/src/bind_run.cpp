// pedesis._Run: a run of any engine from a config file, driven by the one Simulation loop
// of the CLI (run/run.hpp). pedesis/simulation.py wraps it as pedesis.Simulation.
#include "bindings.hpp"
#include "box_object.hpp"
#include "errors.hpp"
#include "script_trigger.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/run/run.hpp"
#include "pedesis/run/steering.hpp"
#include "pedesis/setup/run_config.hpp"

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

namespace py = pybind11;

namespace pedesis::python {

namespace {

// Where a quiet run's console lines go.
class NullBuffer : public std::streambuf {
  protected:
    int overflow(int c) override { return c; }
};

struct PyRun {
    std::unique_ptr<NullBuffer> null_buffer;
    std::unique_ptr<std::ostream> null_stream;
    std::unique_ptr<Run> run;
    std::string config_path;
    std::filesystem::path out;
    std::unique_ptr<SteeringDesk> desk; // from the first set(), before run (destroyed first)
};

template <class T>
py::array_t<T> array(const std::vector<T>& v, std::size_t rows, std::size_t cols) {
    std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(rows)};
    if (cols > 1) shape.push_back(static_cast<py::ssize_t>(cols));
    py::array_t<T> a(shape);
    std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
}

py::dict frame_dict(const FrameArrays& f) {
    const std::size_t n = f.type.size();
    const auto d = static_cast<std::size_t>(f.dimension);
    // vectors keep their D components (the arrays hold 3, z = 0 in 2D)
    auto vectors = [&](const std::vector<double>& v) {
        std::vector<double> out(n * d);
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t a = 0; a < d; ++a) out[i * d + a] = v[3 * i + a];
        return array(out, n, d);
    };
    py::dict out;
    out["time"] = f.time;
    out["step"] = f.step;
    out["box"] =
        box_object(std::vector<double>(f.box.begin(), f.box.begin() + f.dimension),
                   std::vector<bool>(f.periodic.begin(), f.periodic.begin() + f.dimension));
    out["species"] = f.species;
    out["type"] = array(f.type, n, 1);
    out["position"] = vectors(f.position);
    out["velocity"] = vectors(f.velocity);
    out["radius"] = array(f.radius, n, 1);
    out["mass"] = array(f.mass, n, 1);
    std::vector<std::int32_t> image(n * d);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t a = 0; a < d; ++a) image[i * d + a] = f.image[3 * i + a];
    out["image"] = array(image, n, d);
    if (!f.director.empty()) out["director"] = vectors(f.director);
    return out;
}

} // namespace

void bind_run(py::module_& m) {
    py::class_<PyRun>(m, "_Run", "A run of any engine from a config (use pedesis.Simulation).")
        .def(py::init([](const std::filesystem::path& config, const std::filesystem::path& out,
                         std::optional<std::filesystem::path> restart, bool quiet) {
                 require_file(config, "Simulation.from_file");
                 if (restart) require_file(*restart, "Simulation.from_file: restart");
                 auto r = std::make_unique<PyRun>();
                 r->config_path = config.string();
                 r->out = out;
                 const RunConfig c = load_run_config(config.string());
                 RunOptions o;
                 o.config_path = config;
                 o.out_dir = out;
                 o.restart = restart;
                 std::ostream* console = &std::cout;
                 if (quiet) {
                     r->null_buffer = std::make_unique<NullBuffer>();
                     r->null_stream = std::make_unique<std::ostream>(r->null_buffer.get());
                     console = r->null_stream.get();
                 }
                 r->run = make_run(c, o, *console);
                 return r;
             }),
             py::arg("config"), py::arg("out"), py::arg("restart") = py::none(),
             py::arg("quiet") = false)
        .def_property_readonly("dimension", [](const PyRun& r) { return r.run->dimension(); })
        .def_property_readonly("step", [](const PyRun& r) { return r.run->step(); })
        .def_property_readonly("time", [](const PyRun& r) { return r.run->time(); })
        .def_property_readonly("has_steps", [](const PyRun& r) { return r.run->has_steps(); })
        .def_property_readonly("closed", [](const PyRun& r) { return r.run->closed(); })
        .def_property_readonly("stopped_by",
                               [](const PyRun& r) -> std::optional<std::string> {
                                   if (const char* s = r.run->stopped_by()) return std::string(s);
                                   return std::nullopt;
                               })
        .def(
            "advance",
            [](PyRun& r, std::optional<std::uint64_t> steps,
               std::optional<double> time) -> std::optional<std::string> {
                if (r.run->closed()) throw InputError("Simulation.run: the run is closed");
                std::uint64_t max_step = std::numeric_limits<std::uint64_t>::max();
                double max_time = std::numeric_limits<double>::infinity();
                if (steps) {
                    if (!r.run->has_steps())
                        throw InputError(
                            "Simulation.run: the event engine has no steps; give time instead");
                    max_step = r.run->step() + *steps;
                }
                if (time) {
                    if (!(std::isfinite(*time) && *time >= 0))
                        throw InputError("Simulation.run: time must be a finite number >= 0");
                    max_time = r.run->time() + *time;
                }
                const char* why = nullptr;
                run_interruptible([&] { why = r.run->advance(max_step, max_time); });
                if (why) return std::string(why);
                return std::nullopt;
            },
            py::arg("steps") = py::none(), py::arg("time") = py::none())
        .def(
            "close",
            [](PyRun& r, const std::string& ended_by) {
                r.run->close(ended_by.c_str());
                r.desk.reset(); // the record, under its final name
            },
            py::arg("ended_by"))
        .def(
            "set",
            [](PyRun& r, const std::string& parameter, double value) {
                if (r.run->closed()) throw InputError("Simulation.set: the run is closed");
                // the change applies between two steps, now, and is recorded as a change
                // from the page of `pedesis run --view` is (run/steering.hpp)
                if (!r.desk)
                    r.desk = std::make_unique<SteeringDesk>(
                        *r.run, r.out.empty() ? r.out : r.out / "steering.csv",
                        std::vector<SteeringChange>{});
                const std::string refused = r.desk->request(parameter, value);
                if (!refused.empty()) throw InputError("Simulation.set: " + refused);
                r.run->advance(r.run->step()); // opens the run directory if not yet
                r.desk->apply_due();
            },
            py::arg("parameter"), py::arg("value"))
        .def_property_readonly("steerable",
                               [](const PyRun& r) {
                                   py::dict d;
                                   for (const auto& [name, value] : r.run->steerable())
                                       d[py::str(name)] = value;
                                   return d;
                               })
        .def(
            "add_callback",
            [](PyRun& r, py::function fn, std::optional<std::uint64_t> steps,
               std::optional<double> time) {
                const Trigger t = make_trigger(steps, time, "callback", r.run->has_steps());
                r.run->add_operation(t, [fn] {
                    py::gil_scoped_acquire gil;
                    fn();
                });
            },
            py::arg("fn"), py::arg("steps") = py::none(), py::arg("time") = py::none())
        .def(
            "add_trajectory",
            [](PyRun& r, const std::filesystem::path& path, const std::string& format,
               std::optional<std::uint64_t> steps, std::optional<double> time) {
                require_parent_directory(path, "trajectory writer");
                const Trigger t = make_trigger(steps, time, "trajectory writer " + path.string(),
                                               r.run->has_steps());
                r.run->add_trajectory(path, format, t);
            },
            py::arg("path"), py::arg("format"), py::arg("steps") = py::none(),
            py::arg("time") = py::none())
        .def_property_readonly("log_names", [](const PyRun& r) { return r.run->log_names(); })
        .def_property_readonly("last_log_row", [](const PyRun& r) { return r.run->last_log_row(); })
        .def("frame", [](PyRun& r) { return frame_dict(r.run->frame()); });
}

} // namespace pedesis::python
