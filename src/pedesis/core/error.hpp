#pragma once
// One error type for everything a user can get wrong. The message always names
// the file, line, key or particle at fault; the CLI prints it and exits with 2.
#include <stdexcept>
#include <string>

namespace pedesis {

class InputError : public std::runtime_error {
  public:
    explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

// A run that cannot continue (blow-up, inelastic collapse). Outputs written so far
// stay valid; the CLI reports it and exits with 3.
class RunError : public std::runtime_error {
  public:
    explicit RunError(const std::string& what) : std::runtime_error(what) {}
};

inline constexpr int exit_input_error = 2;
inline constexpr int exit_run_error = 3;
// A run stopped by SIGTERM or SIGUSR1 (a scheduler's "time is up"), with its checkpoint
// and every output complete: resume it (EX_TEMPFAIL of sysexits.h, "try again later").
inline constexpr int exit_checkpointed = 75;

} // namespace pedesis
