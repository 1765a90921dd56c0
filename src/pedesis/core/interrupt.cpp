#include "pedesis/core/interrupt.hpp"

namespace pedesis {

namespace {

volatile std::sig_atomic_t received = 0;
// The guard's policy, and whether the stretch the process is in lets a signal end it.
volatile std::sig_atomic_t may_end_at_once = 0;
volatile std::sig_atomic_t end_at_once_here = 0;

// A second signal while the first is being honoured ends the process at once: the way out
// of a close that takes too long (its files then stay .part, never passing for complete).
// So does a first one outside a clean-stop window under OutsideCleanStops::end_process.
extern "C" void remember_signal(int sig) {
    if (received != 0 || (may_end_at_once != 0 && end_at_once_here != 0)) {
        std::signal(sig, SIG_DFL);
        std::raise(sig);
        return;
    }
    received = sig;
}

} // namespace

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
}

InterruptGuard::~InterruptGuard() {
    restore();
}

void InterruptGuard::restore() {
    if (restored_) return;
    ::sigaction(SIGINT, &old_int_, nullptr);
    ::sigaction(SIGTERM, &old_term_, nullptr);
    ::sigaction(SIGHUP, &old_hup_, nullptr);
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
