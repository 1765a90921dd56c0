// The compiled half of the `pedesis` Python package (pedesis/__init__.py is the other).
#include "bindings.hpp"
#include "errors.hpp"

PYBIND11_MODULE(_pedesis, m) {
    m.doc() = "pedesis' C++ engines; import pedesis, not this module.";
    pedesis::python::register_errors(m);
    pedesis::python::bind_soft(m);
    pedesis::python::bind_gas(m);
    pedesis::python::bind_frames(m);
    pedesis::python::bind_run(m);
    pedesis::python::bind_analyze(m);
}
