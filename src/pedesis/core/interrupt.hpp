#pragma once
// Ctrl-C, a kill or a hang-up during a long command. Inside a clean-stop window (the
// simulation loop and the close of its files) the handler only remembers the signal; the
// engines poll interrupt_requested() between steps (the event engine every few thousand
// events) and return early, so that the command can end its files cleanly (complete,
// under their final names) and then end with that same signal, as the shell expects of
// an interrupted program. Outside a window (parsing, reading an initial file, placing
// particles, the first list build: nothing there that a clean close could save) the
// command-line tool ends the process at once by the signal, so that no stage of set-up,
// however long, can keep it deaf; a host such as Python that decides for itself keeps
// the remembering behaviour everywhere.
#include <csignal>

namespace pedesis {

// The signal received while an InterruptGuard is in place, 0 if none (and 0 again once
// the guard is gone). Cheap enough to call once per step.
int interrupt_signal();

// A file that a signal ending the process at once removes first (the run directory's
// lock, so that a run killed in set-up leaves nothing behind), and a directory it then
// removes if empty (one the lock made); null: none.
void remove_on_abrupt_end(const char* path, const char* empty_dir);
inline bool interrupt_requested() {
    return interrupt_signal() != 0;
}

// What a caught signal does outside every CleanStopWindow.
enum class OutsideCleanStops {
    remember,   // as inside: the caller polls (the Python module)
    end_process // the default action of the signal, at once (the command-line tool)
};

class InterruptGuard {
  public:
    // catches SIGINT, SIGTERM, SIGHUP and SIGUSR1 (a scheduler's "checkpoint now")
    explicit InterruptGuard(OutsideCleanStops outside = OutsideCleanStops::remember);
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
    }, old_term_{}, old_hup_{}, old_usr1_{};
    bool restored_ = false;
    void restore();
};

// While one is alive, a caught signal is remembered for a clean stop at the next step
// boundary, whatever the guard does outside windows. A second SIGINT still ends the
// process at once: the way out of a close that takes too long; other repeated signals
// are ignored (interrupt.cpp).
class CleanStopWindow {
  public:
    CleanStopWindow();
    ~CleanStopWindow();
    CleanStopWindow(const CleanStopWindow&) = delete;
    CleanStopWindow& operator=(const CleanStopWindow&) = delete;

  private:
    int outer_;
};

// Set-up inside a window (a point of a sweep, made while the sweep keeps its table): while
// one is alive, a guard of OutsideCleanStops::end_process ends the process at once again,
// so that a long set-up cannot make it deaf. Under a remembering guard it changes nothing.
class SetUpStretch {
  public:
    SetUpStretch();
    ~SetUpStretch();
    SetUpStretch(const SetUpStretch&) = delete;
    SetUpStretch& operator=(const SetUpStretch&) = delete;

  private:
    int outer_;
};

} // namespace pedesis
