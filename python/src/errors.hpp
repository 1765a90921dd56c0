#pragma once
// How C++ errors reach Python: InputError (bad parameters, malformed files) as
// pedesis.InputError, a ValueError; RunError (a run that cannot go on) as
// pedesis.RunError, a RuntimeError; a missing file as FileNotFoundError. The message is
// the C++ one, unchanged.
#include <pybind11/pybind11.h>

#include <filesystem>
#include <string>

namespace pedesis::python {

void register_errors(pybind11::module_& m);

// Raises FileNotFoundError naming `what` and the path unless the file exists.
void require_file(const std::filesystem::path& path, const std::string& what);
// Raises FileNotFoundError unless the directory a file is to be written into exists.
void require_parent_directory(const std::filesystem::path& path, const std::string& what);

// Called between steps while the GIL is released: takes it briefly and raises
// KeyboardInterrupt (or whatever a signal handler raised) if a signal came in.
void check_signals();

} // namespace pedesis::python
