#pragma once
// Config keys named by dotted paths, set from outside the file: a sweep's [vary] keys and
// the command line's `--set KEY=VALUE` (pedesis run, pedesis sweep). A path names tables
// by name and arrays of tables ([[force]], [[integrator]], [[species]]) by their entry's
// `name` or index: "run.steps", "force.harmonic.k", "species.0.count".
#include "pedesis/setup/run_config.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace pedesis {

// Where a dotted key lands in a config: the table that holds its last part, and that part.
struct ConfigSlot {
    toml::table* table = nullptr;
    std::string key;
    std::string table_path;           // the table's path, entries by index: "species.0"
    std::vector<std::string> header;  // its [header] in TOML: {"species"}, {"output"}
    std::vector<std::string> created; // tables made for the key, outermost first
    bool in_entry = false;            // the deepest table that existed is an array's entry
};

// Finds the slot of `key`; `origin` begins every message ("sweep.toml:3:1: [vary] key
// 'a.b'", "--set a.b=1") and `base` names the config. Missing tables are created where
// `create_tables`, else refused.
ConfigSlot config_slot(toml::table& config, const std::string& key, const std::string& origin,
                       const std::string& base, bool create_tables);

// A config file with `--set KEY=VALUE` applied (VALUE as TOML writes it: 3000, 0.001,
// "brownian", [1, 2]), each set written into the file's text where the key is (or after
// its table's header, or in a table added at the end), so that every other line keeps its
// number and a message about the file still names the user's line.
class ConfigWithSets {
  public:
    ConfigWithSets(const std::string& path, const std::vector<std::string>& sets);

    // What the config reader takes (messages from it through explain()).
    const std::string& text() const { return text_; }
    // The run directory's config.toml: the text under a comment naming the sets.
    std::string text_as_run() const;
    // "--set run.steps=1 --set ...", for the comment lines of a sweep's point configs.
    const std::string& sets_text() const { return sets_text_; }
    // The message with every "path:line:column" of the text turned into the file's line,
    // or into the --set that wrote that value.
    std::string explain(const std::string& message) const;
    // The config, checked as load_run_config checks a file; messages through explain().
    RunConfig read(bool scripted = false) const;
    // The --set that gave each key, by its path with entries by index ("run.time",
    // "species.0.count"): "--set run.time=10".
    const std::map<std::string, std::string>& set_keys() const { return set_keys_; }

  private:
    struct Line {
        std::size_t file_line = 0;  // 0: a line a --set added
        std::string set;            // the --set that added it, or replaced a value on it
        std::size_t set_column = 0; // where that value begins (code points, 1-based)
    };
    std::string path_;
    std::string text_;
    std::string sets_text_;
    std::vector<Line> lines_; // per line of text_
    struct Added {
        std::string key;    // its last part: "lengths"
        std::string origin; // "--set box.lengths=[1.0]"
    };
    std::vector<Added> added_; // the keys the file did not have
    std::map<std::string, std::string> set_keys_;
};

// The config's text with a relative [initial] file written as the absolute path it names
// (relative to `config_path`), in place: the same config read from any other directory,
// as a run directory's config.toml is. Every other byte is kept.
std::string with_initial_file_anchored(const std::string& text,
                                       const std::filesystem::path& config_path);

} // namespace pedesis
