// pedesis._write_frames: frames a script holds in memory (a pedesis.Recording) written as
// a GSD or extended-XYZ trajectory by the engines' own writers (io/trajectory_file.hpp),
// so that the file is the one `pedesis run` would write for the same states.
#include "bindings.hpp"
#include "box_object.hpp"
#include "errors.hpp"

#include "pedesis/core/box.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/core/particles.hpp"
#include "pedesis/io/trajectory_file.hpp"

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <optional>

namespace py = pybind11;

namespace pedesis::python {

namespace {

using Rows = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Images = py::array_t<std::int32_t, py::array::c_style | py::array::forcecast>;
using Types = py::array_t<std::uint16_t, py::array::c_style | py::array::forcecast>;
using Values = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Checks that `a` is n rows of `cols` values (one value per row when cols is 0).
template <class A>
A shaped(const py::dict& frame, const char* key, std::size_t n, int cols, std::size_t index) {
    A a = frame[key].cast<A>();
    const bool ok = cols == 0 ? a.ndim() == 1 && static_cast<std::size_t>(a.shape(0)) == n
                              : a.ndim() == 2 && static_cast<std::size_t>(a.shape(0)) == n &&
                                    a.shape(1) == cols;
    if (!ok)
        throw InputError(fmt::format("write_frames: frame {}: '{}' must hold {} rows of {} "
                                     "values",
                                     index, key, n, cols == 0 ? 1 : cols));
    return a;
}

template <int D> void write(TrajectoryFile<D>& file, const py::dict& frame, std::size_t index) {
    const std::size_t n = py::len(frame["type"]);
    const auto lengths = frame["box"].cast<std::vector<double>>();
    if (lengths.size() != static_cast<std::size_t>(D))
        throw InputError(fmt::format("write_frames: frame {}: box must hold {} lengths", index, D));
    const std::vector<bool> flags = box_periodic(py::object(frame["box"]), D);
    Vec<D> L{};
    std::array<bool, D> periodic{};
    for (int a = 0; a < D; ++a) {
        L[a] = lengths[static_cast<std::size_t>(a)];
        periodic[static_cast<std::size_t>(a)] = flags[static_cast<std::size_t>(a)];
        if (!(std::isfinite(L[a]) && L[a] > 0))
            throw InputError(fmt::format("write_frames: frame {}: box lengths must be "
                                         "positive and finite",
                                         index));
    }
    const Box<D> box(L, periodic);

    ParticleStore<D> p;
    p.resize(n);
    const auto position = shaped<Rows>(frame, "position", n, D, index).unchecked<2>();
    const auto type = shaped<Types>(frame, "type", n, 0, index).unchecked<1>();
    const auto radius = shaped<Values>(frame, "radius", n, 0, index).unchecked<1>();
    const auto mass = shaped<Values>(frame, "mass", n, 0, index).unchecked<1>();
    const auto names = frame["species"].cast<std::vector<std::string>>();
    p.species_table.resize(names.size());
    for (std::size_t s = 0; s < names.size(); ++s) p.species_table[s].name = names[s];
    std::optional<Rows> velocity;
    if (frame.contains("velocity") && !frame["velocity"].is_none())
        velocity = shaped<Rows>(frame, "velocity", n, D, index);
    for (std::size_t i = 0; i < n; ++i) {
        const auto t = static_cast<std::size_t>(type(static_cast<py::ssize_t>(i)));
        if (t >= names.size())
            throw InputError(fmt::format("write_frames: frame {}: particle {} has type {}, "
                                         "but there are {} species",
                                         index, i, t, names.size()));
        // radius and mass are per species in the writers: the table takes each
        // species' value from its particles
        p.species_table[t].radius = radius(static_cast<py::ssize_t>(i));
        p.species_table[t].mass = mass(static_cast<py::ssize_t>(i));
        p.species[i] = static_cast<std::uint16_t>(t);
        p.tag[i] = static_cast<std::uint32_t>(i);
        for (int a = 0; a < D; ++a) {
            p.position[i][a] = position(static_cast<py::ssize_t>(i), a);
            if (velocity) p.velocity[i][a] = velocity->at(static_cast<py::ssize_t>(i), a);
        }
    }
    std::vector<Vec<D>> directors;
    std::vector<std::array<std::int32_t, D>> images;
    Frame<D> f =
        frame_of(p, box, frame["time"].cast<double>(), frame["step"].cast<std::uint64_t>());
    if (frame.contains("director") && !frame["director"].is_none()) {
        const auto dir = shaped<Rows>(frame, "director", n, D, index).unchecked<2>();
        directors.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            for (int a = 0; a < D; ++a) directors[i][a] = dir(static_cast<py::ssize_t>(i), a);
        f.directors = &directors;
    }
    if (frame.contains("image") && !frame["image"].is_none()) {
        const auto img = shaped<Images>(frame, "image", n, D, index).unchecked<2>();
        images.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            for (int a = 0; a < D; ++a)
                images[i][static_cast<std::size_t>(a)] = img(static_cast<py::ssize_t>(i), a);
        f.images = &images;
    }
    file.append(f);
}

template <int D>
void write_all(const std::filesystem::path& path, const std::string& format,
               const py::list& frames) {
    TrajectoryFile<D> file(path, format);
    for (std::size_t k = 0; k < frames.size(); ++k) write<D>(file, frames[k].cast<py::dict>(), k);
    file.commit(); // only a complete file gets the final name
}

} // namespace

void bind_frames(py::module_& m) {
    m.def(
        "_write_frames",
        [](const std::filesystem::path& path, const std::string& format, const py::list& frames) {
            require_parent_directory(path, "write_frames");
            if (frames.empty()) throw InputError("write_frames: no frames to write");
            const auto first = frames[0].cast<py::dict>();
            const int dim = static_cast<int>(py::len(first["box"]));
            if (dim == 2)
                write_all<2>(path, format, frames);
            else if (dim == 3)
                write_all<3>(path, format, frames);
            else
                throw InputError(fmt::format("write_frames: box must hold 2 or 3 lengths"));
        },
        py::arg("path"), py::arg("format"), py::arg("frames"),
        "Writes frames (dicts as Simulation.frame() returns) as a GSD or XYZ trajectory.");
}

} // namespace pedesis::python
