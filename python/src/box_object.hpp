#pragma once
// The box as Python scripts see it: a pedesis.Box (python/pedesis/box.py), lengths and
// per-axis periodic flags, which still reads as the list of lengths that Gas.box and
// frame["box"] once were.
#include <pybind11/pybind11.h>

#include <vector>

namespace pedesis::python {

pybind11::object box_object(const std::vector<double>& lengths, const std::vector<bool>& periodic);

// The flags of a frame's "box": its `periodic` where it is a pedesis.Box, else (a plain
// list of lengths, as older scripts build frames) periodic on every one of `dim` axes.
std::vector<bool> box_periodic(pybind11::handle box, std::size_t dim);

} // namespace pedesis::python
