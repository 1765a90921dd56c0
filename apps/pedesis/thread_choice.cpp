#include "thread_choice.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>
#include <thread>

namespace pedesis::cli {

namespace {

// Busy and total jiffies of all CPUs so far, from /proc/stat's first line.
bool cpu_times(double& busy, double& total) {
    std::ifstream in("/proc/stat");
    std::string label;
    if (!(in >> label) || label != "cpu") return false;
    double v[8] = {};
    for (double& x : v)
        if (!(in >> x)) return false;
    // user nice system idle iowait irq softirq steal
    const double idle = v[3] + v[4];
    total = 0.0;
    for (double x : v) total += x;
    busy = total - idle;
    return true;
}

// Cores other processes keep busy, from 100 ms of /proc/stat (0 if it cannot be read).
double busy_cores(int cores) {
    double b0, t0, b1, t1;
    if (!cpu_times(b0, t0)) return 0.0;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (!cpu_times(b1, t1) || !(t1 > t0)) return 0.0;
    return cores * (b1 - b0) / (t1 - t0);
}

} // namespace

int choose_threads(std::optional<int> requested, std::ostream& console) {
    if (requested) {
        omp_set_num_threads(*requested);
        return *requested;
    }
    if (std::getenv("OMP_NUM_THREADS")) return omp_get_max_threads(); // the user's choice
    const int cores = omp_get_num_procs();
    if (cores <= 1) return 1;
    // a core counts as busy from half a core's worth of load on
    const int busy = std::clamp(static_cast<int>(std::lround(busy_cores(cores))), 0, cores - 1);
    const int threads = cores - busy;
    omp_set_num_threads(threads);
    if (busy > 0)
        console << fmt::format("pedesis: note: {} of {} cores are busy with other work: running "
                               "on {} thread{} (--threads N chooses; results do not depend on "
                               "it)\n",
                               busy, cores, threads, threads == 1 ? "" : "s");
    return threads;
}

} // namespace pedesis::cli
