#include "errors.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/interrupt.hpp"

namespace py = pybind11;

namespace pedesis::python {

void register_errors(py::module_& m) {
    auto input = py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
    input.doc() = "Bad input: a parameter out of range, a malformed file or config (the "
                  "message names the parameter, file, line or particle). A ValueError.";
    auto run = py::register_exception<RunError>(m, "RunError", PyExc_RuntimeError);
    run.doc() = "A run that cannot go on: a blow-up, a non-finite value, too many events in "
                "a step (the message names the particle and step). A RuntimeError.";
}

namespace {

[[noreturn]] void raise_file_not_found(const std::string& message, const std::string& path) {
    // FileNotFoundError(errno, strerror, filename), as open() raises it
    py::object error = py::reinterpret_borrow<py::object>(PyExc_FileNotFoundError);
    PyErr_SetObject(PyExc_FileNotFoundError, error(2, message, path).ptr());
    throw py::error_already_set();
}

} // namespace

void require_file(const std::filesystem::path& path, const std::string& what) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        raise_file_not_found(what + ": no such file: " + path.string(), path.string());
}

void require_parent_directory(const std::filesystem::path& path, const std::string& what) {
    const auto parent = path.parent_path();
    std::error_code ec;
    if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
        raise_file_not_found(what + ": no such directory: " + parent.string(), parent.string());
}

void run_interruptible(const std::function<void()>& work) {
    InterruptGuard guard;
    {
        py::gil_scoped_release release;
        work();
    }
    if (guard.signal() == 0) return;
    guard.reraise(); // to Python's own handler, which notes it (or ends the process)
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
}

} // namespace pedesis::python
