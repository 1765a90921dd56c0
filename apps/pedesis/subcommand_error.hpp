#pragma once
// What to say when the words of a command line name no subcommand: CLI11 says only "A
// subcommand is required", for a misspelt one as for a missing one.
#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace pedesis::cli {

// After a failed parse of `root` (named `program`): the message for the deepest command
// given whose next word is not one of its subcommands ("unknown subcommand 'struct' of
// 'pedesis analyze' (known: speed, thermo, ...)"), or for one given without any; nothing
// where the fault is another.
std::optional<std::string> subcommand_error(const CLI::App& root, const std::string& program);

// The one line (after "pedesis: error: ") for any failed parse of `root`: a subcommand
// fault as above; an unknown option with the command's closest known one ("unknown option
// '--thread' of 'pedesis run' (did you mean --threads?)"); else CLI11's message after the
// command it concerns.
std::string parse_error_message(const CLI::App& root, const std::string& program,
                                const CLI::ParseError& error);

} // namespace pedesis::cli
