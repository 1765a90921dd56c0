#include "pedesis/core/interrupt.hpp"

#include <cstring>
#include <unistd.h>

namespace pedesis {

namespace {

volatile std::sig_atomic_t received = 0;
// The guard's policy, and whether the stretch the process is in lets a signal end it.
volatile std::sig_atomic_t may_end_at_once = 0;
volatile std::sig_atomic_t end_at_once_here = 0;
// a file to remove when a signal ends the process at once (the run directory's lock)
char abrupt_path[4096] = {};
char abrupt_dir[4096] = {}; // and a directory to remove if then empty

// A second SIGINT while the first signal is being honoured ends the process at once: the
// way out, at the keyboard, of a close that takes too long (its files then stay .part,
// never passing for complete). A repeated SIGTERM, SIGHUP or SIGUSR1 does not: timeout,
// Slurm and mpirun send them to every process of a group, often twice within
// milliseconds, and the second must not cut short the clean stop the first began.
// A first signal outside a clean-stop window under OutsideCleanStops::end_process ends
// the process at once.
extern "C" void remember_signal(int sig) {
    if (received != 0 && sig != SIGINT) return;
    if (received != 0 || (may_end_at_once != 0 && end_at_once_here != 0)) {
        if (abrupt_path[0] != '\0') ::unlink(abrupt_path); // (async-signal-safe)
        if (abrupt_dir[0] != '\0') ::rmdir(abrupt_dir);
        std::signal(sig, SIG_DFL);
        std::raise(sig);
        return;
    }
    received = sig;
}

} // namespace

void remove_on_abrupt_end(const char* path, const char* empty_dir) {
    const auto keep = [](char(&into)[4096], const char* p) {
        into[0] = '\0';
        if (p && std::strlen(p) < sizeof into) std::memcpy(into, p, std::strlen(p) + 1);
    };
    keep(abrupt_path, path);
    keep(abrupt_dir, empty_dir);
}

int interrupt_signal() {
    return received;
}

InterruptGuard::InterruptGuard(OutsideCleanStops outside) {
    received = 0;
    may_end_at_once = outside == OutsideCleanStops::end_process ? 1 : 0;
    end_at_once_here = 1;
    struct sigaction action {};
    action.sa_handler = remember_signal;
    sigemptyset(&action.sa_mask);
    // A signal the caller ignores (nohup, a background job of a script) stays ignored.
    auto catch_unless_ignored = [&](int sig, struct sigaction& old) {
        ::sigaction(sig, &action, &old);
        if (old.sa_handler == SIG_IGN) ::sigaction(sig, &old, nullptr);
    };
    catch_unless_ignored(SIGINT, old_int_);
    catch_unless_ignored(SIGTERM, old_term_);
    catch_unless_ignored(SIGHUP, old_hup_);
    catch_unless_ignored(SIGUSR1, old_usr1_);
}

InterruptGuard::~InterruptGuard() {
    restore();
}

void InterruptGuard::restore() {
    if (restored_) return;
    ::sigaction(SIGINT, &old_int_, nullptr);
    ::sigaction(SIGTERM, &old_term_, nullptr);
    ::sigaction(SIGHUP, &old_hup_, nullptr);
    ::sigaction(SIGUSR1, &old_usr1_, nullptr);
    restored_ = true;
    may_end_at_once = 0;
    received = 0; // a signal is the business of the guard that caught it
}

int InterruptGuard::signal() const {
    return interrupt_signal();
}

void InterruptGuard::reraise() {
    const int sig = received;
    restore();
    if (sig != 0) ::raise(sig);
}

CleanStopWindow::CleanStopWindow() : outer_(end_at_once_here) {
    end_at_once_here = 0;
}

CleanStopWindow::~CleanStopWindow() {
    end_at_once_here = outer_;
}

SetUpStretch::SetUpStretch() : outer_(end_at_once_here) {
    end_at_once_here = 1;
}

SetUpStretch::~SetUpStretch() {
    end_at_once_here = outer_;
}

} // namespace pedesis
