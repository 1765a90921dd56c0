#include "subcommand_error.hpp"

#include <fmt/format.h>

#include <vector>

namespace pedesis::cli {

std::optional<std::string> subcommand_error(const CLI::App& root, const std::string& program) {
    // the chain of commands the parse got into: `pedesis analyze`
    const CLI::App* command = &root;
    std::string path = program;
    for (bool deeper = true; deeper;) {
        deeper = false;
        for (const CLI::App* sub : command->get_subcommands([](const CLI::App*) { return true; }))
            if (sub->parsed() > 0) {
                command = sub;
                path += " " + sub->get_name();
                deeper = true;
                break;
            }
    }
    const std::vector<const CLI::App*> subs =
        command->get_subcommands([](const CLI::App* s) { return !s->get_group().empty(); });
    if (subs.empty()) return std::nullopt;
    std::string known;
    for (const CLI::App* s : subs) known += (known.empty() ? "" : ", ") + s->get_name();
    for (const std::string& word : command->remaining()) {
        if (word.starts_with("-")) continue; // an option (CLI11 names it itself)
        return fmt::format("unknown subcommand '{}' of '{}' (known: {})", word, path, known);
    }
    if (command->get_require_subcommand_min() == 0) return std::nullopt;
    return fmt::format("'{}' needs a subcommand (known: {}; {} --help says what each does)", path,
                       known, path);
}

} // namespace pedesis::cli
