#pragma once
// Ctrl-C, a kill or a hang-up during a long command. The handler only remembers the
// signal; the engines poll interrupt_requested() between steps (the event engine every
// few thousand events) and return early, so that the command can end its files cleanly
// (complete, under their final names) and then end with that same signal, as the shell
// expects of an interrupted program.
#include <csignal>

namespace pedesis {

// The signal received while an InterruptGuard is in place, 0 if none (and 0 again once
// the guard is gone). Cheap enough to call once per step.
int interrupt_signal();
inline bool interrupt_requested() {
    return interrupt_signal() != 0;
}

class InterruptGuard {
  public:
    InterruptGuard();  // catches SIGINT, SIGTERM and SIGHUP
    ~InterruptGuard(); // puts the earlier handlers back
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

    // The signal received, 0 if none.
    int signal() const;
    // Puts the earlier handlers back and raises the signal received (if any); after an
    // interruption with the default handler, it does not return.
    void reraise();

  private:
    struct sigaction old_int_ {
    }, old_term_{}, old_hup_{};
    bool restored_ = false;
    void restore();
};

} // namespace pedesis
