#include "pedesis/render/interrupt_guard.hpp"

namespace pedesis::render {

namespace {

volatile std::sig_atomic_t received = 0;

extern "C" void remember_signal(int sig) {
    received = sig;
}

} // namespace

InterruptGuard::InterruptGuard() {
    received = 0;
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
}

int InterruptGuard::signal() const {
    return received;
}

void InterruptGuard::reraise() {
    const int sig = received;
    restore();
    if (sig != 0) ::raise(sig);
}

} // namespace pedesis::render
