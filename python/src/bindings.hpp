#pragma once
#include <pybind11/pybind11.h>

namespace pedesis::python {
void bind_soft(pybind11::module_& m);
void bind_gas(pybind11::module_& m);
void bind_frames(pybind11::module_& m);
void bind_run(pybind11::module_& m);
void bind_analyze(pybind11::module_& m);
} // namespace pedesis::python
