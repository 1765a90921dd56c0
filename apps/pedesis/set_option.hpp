#pragma once
// `--set KEY=VALUE` of pedesis run and pedesis sweep (setup/config_overrides.hpp).
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace pedesis::cli {

inline void add_set_option(CLI::App& cmd, std::vector<std::string>& sets, const char* what) {
    cmd.add_option("--set", sets,
                   std::string("Change a key of ") + what +
                       ", repeatable: a dotted path and a TOML value, as run.steps=3000, "
                       "output.snapshot_every=100, species.0.count=50, 'dynamics=\"nve\"' "
                       "(docs/config.md)")
        ->allow_extra_args(false); // one value each: `--set a=1 cfg.toml` keeps the config
}

} // namespace pedesis::cli
