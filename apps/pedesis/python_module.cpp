// python3 -m pedesis.MODULE, started and waited for by pedesis (python_module.hpp).
#include "python_module.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/interrupt.hpp"

#include <fmt/core.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include <csignal>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace pedesis::cli {

namespace {

namespace fs = std::filesystem;

// An environment variable overrides the path built in at compile time, so an installed
// binary or a moved source tree still finds its interpreter and package.
std::string configured_path(const char* variable, const char* built_in) {
    const char* v = std::getenv(variable);
    return v && *v ? std::string(v) : std::string(built_in);
}

std::string python_interpreter(const std::string& command) {
    const std::string python = configured_path("PEDESIS_PYTHON", PEDESIS_ANALYZE_PYTHON);
    if (::access(python.c_str(), X_OK) != 0)
        throw InputError(
            fmt::format("{}: no Python interpreter at {}: this command needs Debian's python3 with "
                        "python3-numpy, python3-scipy and python3-matplotlib (apt-get install "
                        "python3-matplotlib python3-scipy), or set PEDESIS_PYTHON",
                        command, python));
    return python;
}

// The folder holding the pedesis package (build/python; the source tree's python/ in a
// build without the compiled module, whose pure-Python parts work all the same).
std::string package_path(const std::string& command, const std::string& module) {
    const std::string dir = configured_path("PEDESIS_PYTHONPATH", PEDESIS_ANALYZE_PYTHONPATH);
    std::error_code ec;
    if (!fs::is_regular_file(fs::path(dir) / "pedesis" / module / "__main__.py", ec))
        throw InputError(
            fmt::format("{}: the pedesis Python package is not in {} (no pedesis/{} there); set "
                        "PEDESIS_PYTHONPATH to the build's python folder",
                        command, dir, module));
    return dir;
}

// This process's environment with `dir` first on PYTHONPATH (a user's own entries stay).
std::vector<std::string> environment_with_package(const std::string& dir,
                                                  const std::vector<std::string>& extra) {
    std::vector<std::string> env;
    std::string path = "PYTHONPATH=" + dir;
    for (char** e = environ; *e; ++e) {
        const std::string entry(*e);
        if (entry.rfind("PYTHONPATH=", 0) == 0) {
            if (entry.size() > 11) path.append(":").append(entry, 11, std::string::npos);
        } else {
            env.push_back(entry);
        }
    }
    env.push_back(path);
    env.insert(env.end(), extra.begin(), extra.end());
    return env;
}

// Runs argv[0] with the arguments and returns its wait status, passing a signal to
// pedesis on to it (module files are written, then renamed, so none is left half
// written).
int run_process(const std::string& command, const std::vector<std::string>& args,
                const std::vector<std::string>& env, const InterruptGuard& guard) {
    std::vector<char*> argv, envp;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    for (const std::string& e : env) envp.push_back(const_cast<char*>(e.c_str()));
    envp.push_back(nullptr);
    // what this process printed must come out before the child's lines
    std::cout.flush();
    std::fflush(stdout);
    pid_t pid = 0;
    const int err = ::posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), envp.data());
    if (err != 0)
        throw InputError(
            fmt::format("{}: cannot start {}: {}", command, args[0], std::strerror(err)));
    int status = 0;
    bool passed_on = false;
    // polled, so that a signal between two looks cannot be missed by a blocking wait
    for (;;) {
        const pid_t done = ::waitpid(pid, &status, WNOHANG);
        if (done == pid) return status;
        if (done < 0 && errno != EINTR)
            throw std::runtime_error(
                fmt::format("{}: waiting for {}: {}", command, args[0], std::strerror(errno)));
        if (guard.signal() != 0 && !passed_on) {
            ::kill(pid, guard.signal());
            passed_on = true;
        }
        ::usleep(10000);
    }
}

} // namespace

int run_python_module(const std::string& command, const std::string& module,
                      const std::vector<std::string>& args,
                      const std::vector<std::string>& extra_env) {
    const std::string package = package_path(command, module);
    std::vector<std::string> argv{python_interpreter(command),
                                  "-B", // no __pycache__ in the source tree
                                  "-m", fmt::format("pedesis.{}", module)};
    argv.insert(argv.end(), args.begin(), args.end());
    InterruptGuard guard;
    const int status =
        run_process(command, argv, environment_with_package(package, extra_env), guard);
    if (guard.signal() != 0) guard.reraise();
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    throw std::runtime_error(fmt::format("{}: python3 -m pedesis.{} was killed by signal {}",
                                         command, module,
                                         WIFSIGNALED(status) ? WTERMSIG(status) : -1));
}

} // namespace pedesis::cli
