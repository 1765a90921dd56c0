#pragma once
// A parameter sweep: a base run config and a table of config keys to vary, one run
// directory per point of their Cartesian product, and one table of every point's summary.
// Any engine: the points are ordinary runs (run/run.hpp). Who runs which point (all of
// them, every P-th under MPI, one shard of a job array) is the caller's choice; a point
// is done once its run directory holds a summary.json of a finished run, so a stopped
// sweep resumes by skipping those.
//
//   base = "abp_mips.toml"            # relative to the sweep file
//   out = "runs/mips_sweep"           # optional: runs/<sweep file name>
//   [vary]
//   "force.self_propulsion.alpha" = [0.5, 1.0, 2.0]
//   "box.length" = [80.9, 100.0]
//
// A key is a path into the base config: tables by name, and arrays of tables ([[force]],
// [[integrator]], [[species]]) by the entry's `name` or by its index.
#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace pedesis {

struct SweepPoint {
    std::size_t index = 0;
    std::vector<std::string> values; // per varied key, as TOML writes the value
    std::string name;                // point_007
    std::string config_text;         // the base config with this point's values
    std::filesystem::path config;    // where config_text is written: OUT/configs/NAME.toml
    std::filesystem::path dir;       // the point's run directory: OUT/NAME
    std::filesystem::path console;   // what its run prints: OUT/logs/NAME.txt
};

struct Sweep {
    std::string file;               // the sweep file
    std::filesystem::path base;     // the base config
    std::filesystem::path out;      // the sweep's directory
    std::vector<std::string> keys;  // the varied keys, in the file's order
    std::vector<SweepPoint> points; // the first key varies slowest
};

// Reads the sweep file and builds every point's config, each checked as `pedesis run`
// checks a config: any fault is an InputError naming the sweep file and key, or the point
// and the config's key, before any file is written. `out` overrides the file's `out`;
// `sets` (--set KEY=VALUE, setup/config_overrides.hpp) change the base config of every point.
Sweep load_sweep(const std::string& path, const std::optional<std::filesystem::path>& out,
                 const std::vector<std::string>& sets = {});

// Whether the point's run directory holds the summary of a finished run (not of an
// interrupted one).
bool point_done(const SweepPoint& point);

enum class PointOutcome { done, failed, interrupted };

// Runs one point (its config written to point.config, its console lines to
// point.console) in this process; a run that fails (RunError, or an InputError that only
// the run finds) is reported on `console`, its message kept in failure_note(point), and
// returned, not thrown. A caught signal
// (core/interrupt.hpp) ends the run early.
// With `resume`, an unfinished run in the point's directory goes on in place from its
// checkpoint (run/resume.hpp), as `pedesis run --resume`. The point's directory is locked
// while it runs (run/run_directory_lock.hpp).
PointOutcome run_point(const SweepPoint& point, std::ostream& console, bool resume = false);

// OUT/logs/NAME.failed: the message of a point whose run failed (removed when it reruns).
std::filesystem::path failure_note(const SweepPoint& point);

// OUT/sweep.csv: one row per point: its index, name, the varied values, its status (done,
// interrupted, failed, not run) and the numbers of its summary.json, flattened with dots
// (final.pressure, species.A.temperature, ...), without the wall-clock timings, so that
// the table of a sweep does not depend on how or where its points ran.
void write_sweep_table(const Sweep& sweep);

} // namespace pedesis
