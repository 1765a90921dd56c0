#pragma once
// Ctrl-C or a kill during a render: remember the signal so the render can stop between
// frames and clean up (an unfinished movie's temporary file), then end the process with
// that same signal, as the shell expects of an interrupted program.
#include <csignal>

namespace pedesis::render {

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

} // namespace pedesis::render
