#pragma once
// `pedesis run CONFIG --out DIR --resume`: what DIR holds and where the run goes on from.
//   no run there (absent, empty, no config.toml): the run starts;
//   a run of another config (anything but its end: [run] time, steps,
//     collisions_per_particle; or [output] checkpoint_seconds, progress): InputError
//     naming the first key that differs;
//   a finished run of this config: nothing to do (a later end: it goes on from the final
//     checkpoint);
//   an unfinished one: it goes on from its newest checkpoint whose outputs were recorded
//     (the one a finished run's close kept, checkpoint.previous.bin, where a kill cut that
//     close short), its outputs cut back to that checkpoint's marks
//     (io/resume_record.hpp); with no checkpoint yet, the run starts again.
#include "pedesis/io/resume_record.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace pedesis {

struct ResumePlan {
    enum class Kind { start, resume, finished };
    Kind kind = Kind::start;
    std::filesystem::path checkpoint; // resume: the checkpoint to load
    std::vector<OutputMarks> marks;   // resume: the record of the directory's checkpoints
    std::string stopped_by;           // finished: the summary's stop condition
    std::string why;                  // a line for the console
};

// The stop condition of the finished run in `dir` (its summary.json's stopped_by), or ""
// where there is none: no summary, an unreadable one, or the summary of a run that was
// interrupted or closed by a script before a stop condition.
std::string finished_stop(const std::filesystem::path& dir);

// `config_text`: what the run would write as DIR/config.toml (run_directory_config).
// Leftover temporaries of a killed run (*.tmp.<pid>) are removed.
ResumePlan plan_resume(const std::filesystem::path& dir, const std::string& config_text);

// The first key whose value differs between two configs' texts, as "box.length (was 20,
// now 30)", ignoring the keys a resumed run may change; nullopt if none. `end_changed`
// says whether one of those differed.
std::optional<std::string> config_difference(const std::string& was, const std::string& now,
                                             bool& end_changed);

} // namespace pedesis
