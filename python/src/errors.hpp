#pragma once
// How C++ errors reach Python: InputError (bad parameters, malformed files) as
// pedesis.InputError, a ValueError; RunError (a run that cannot go on) as
// pedesis.RunError, a RuntimeError; a missing file as FileNotFoundError. The message is
// the C++ one, unchanged.
#include <pybind11/pybind11.h>

#include <filesystem>
#include <functional>
#include <string>

namespace pedesis::python {

void register_errors(pybind11::module_& m);

// Raises FileNotFoundError naming `what` and the path unless the file exists.
void require_file(const std::filesystem::path& path, const std::string& what);
// Raises FileNotFoundError unless the directory a file is to be written into exists.
void require_parent_directory(const std::filesystem::path& path, const std::string& what);

// Runs `work` with the GIL released and SIGINT, SIGTERM and SIGHUP caught
// (core/interrupt.hpp), so that the engines stop within a step of a signal with their
// state whole; then hands the signal to Python as if it had come now (Ctrl-C raises
// KeyboardInterrupt, and the run can go on or be closed).
void run_interruptible(const std::function<void()>& work);

} // namespace pedesis::python
