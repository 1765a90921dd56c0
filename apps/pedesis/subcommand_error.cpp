#include "subcommand_error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

namespace pedesis::cli {

namespace {

// The deepest command the parse got into, and its words: `pedesis analyze`.
std::pair<const CLI::App*, std::string> deepest_command(const CLI::App& root,
                                                        const std::string& program) {
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
    return {command, path};
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = up;
        }
    }
    return row[b.size()];
}

// "unknown option '--thread' of 'pedesis run' (did you mean --threads?)", for the first
// word of `words` that looks like an option and is none of the command's.
std::optional<std::string> unknown_option(const CLI::App& command, const std::string& path,
                                          const std::vector<std::string>& words) {
    std::vector<std::string> known;
    for (const CLI::Option* o : command.get_options()) {
        for (const std::string& l : o->get_lnames()) known.push_back("--" + l);
        for (const std::string& s : o->get_snames()) known.push_back("-" + s);
    }
    for (const std::string& word : words) {
        if (!word.starts_with("-") || word == "-" || word == "--") continue;
        const std::string name = word.substr(0, word.find('=')); // --thread=2
        if (std::find(known.begin(), known.end(), name) != known.end()) continue;
        std::string best;
        std::size_t best_distance = name.size();
        for (const std::string& k : known)
            if (const std::size_t d = edit_distance(name, k); d < best_distance) {
                best = k;
                best_distance = d;
            }
        if (!best.empty() && best_distance <= std::max<std::size_t>(2, name.size() / 3))
            return fmt::format("unknown option '{}' of '{}' (did you mean {}?)", name, path, best);
        std::string all;
        for (const std::string& k : known)
            if (k.starts_with("--")) all += (all.empty() ? "" : ", ") + k;
        return fmt::format("unknown option '{}' of '{}' (its options: {})", name, path, all);
    }
    return std::nullopt;
}

} // namespace

std::string parse_error_message(const CLI::App& root, const std::string& program,
                                const CLI::ParseError& error) {
    if (const auto message = subcommand_error(root, program)) return *message;
    const auto [command, path] = deepest_command(root, program);
    std::vector<std::string> words = command->remaining();
    for (const std::string& w : root.remaining(true)) words.push_back(w);
    if (const auto message = unknown_option(*command, path, words)) return *message;
    std::string what = error.what();
    std::replace(what.begin(), what.end(), '\n', ' '); // one line
    return fmt::format("{}: {} ({} --help lists what it takes)", path, what, path);
}

std::optional<std::string> subcommand_error(const CLI::App& root, const std::string& program) {
    const auto [command, path] = deepest_command(root, program);
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
