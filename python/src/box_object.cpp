#include "box_object.hpp"

#include "pedesis/core/error.hpp"

#include <fmt/format.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace pedesis::python {

py::object box_object(const std::vector<double>& lengths, const std::vector<bool>& periodic) {
    return py::module_::import("pedesis.box").attr("Box")(lengths, periodic);
}

std::vector<bool> box_periodic(py::handle box, std::size_t dim) {
    if (!py::hasattr(box, "periodic")) return std::vector<bool>(dim, true);
    auto flags = box.attr("periodic").cast<std::vector<bool>>();
    if (flags.size() != dim)
        throw InputError(
            fmt::format("box: periodic holds {} flags for {} axes", flags.size(), dim));
    return flags;
}

} // namespace pedesis::python
