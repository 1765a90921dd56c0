#pragma once
// Running a module of the pedesis Python package (python3 -m pedesis.MODULE ...) with
// Debian's interpreter, for the commands whose work is Python's: analyze and validate.
#include <string>
#include <vector>

namespace pedesis::cli {

// Runs `python3 -B -m pedesis.<module> <args>` with the package first on PYTHONPATH and
// `extra_env` (NAME=value entries) added, sharing stdout and stderr, and returns its exit
// status. A signal to pedesis (SIGINT, SIGTERM, SIGHUP) is passed on to the module;
// once it has ended, pedesis ends by the same signal, leaving no orphan. `command` names
// the pedesis command in messages. A missing interpreter or package is an InputError;
// a module killed by a signal is a runtime_error.
int run_python_module(const std::string& command, const std::string& module,
                      const std::vector<std::string>& args,
                      const std::vector<std::string>& extra_env = {});

} // namespace pedesis::cli
