#include "pedesis/setup/config_overrides.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/stage.hpp"
#include "pedesis/io/config_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace pedesis {

namespace {

std::string names_of(const toml::array& tables) {
    std::string s;
    for (const toml::node& t : tables) {
        const toml::table* tt = t.as_table();
        const toml::node* name = tt ? tt->get("name") : nullptr;
        s += (s.empty() ? "" : ", ") +
             (name && name->is_string() ? name->value_or(std::string()) : std::string("?"));
    }
    return s;
}

std::vector<std::string> split(const std::string& text, char at) {
    std::vector<std::string> parts;
    for (std::size_t from = 0;;) {
        const std::size_t cut = text.find(at, from);
        parts.push_back(text.substr(from, cut == std::string::npos ? cut : cut - from));
        if (cut == std::string::npos) return parts;
        from = cut + 1;
    }
}

std::string join(const std::vector<std::string>& parts) {
    std::string s;
    for (const std::string& p : parts) s += (s.empty() ? "" : ".") + p;
    return s;
}

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return {};
    return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// A key TOML takes without quotes (the only ones a --set writes into the text).
bool bare_key(const std::string& k) {
    return !k.empty() && k.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                             "0123456789_-") == std::string::npos;
}

// The byte where a (1-based) column of toml++'s, counted in code points, begins.
std::size_t byte_of_column(const std::string& line, std::size_t column) {
    std::size_t b = 0;
    for (std::size_t c = 1; c < column && b < line.size(); ++c) {
        ++b;
        while (b < line.size() && (static_cast<unsigned char>(line[b]) & 0xC0) == 0x80) ++b;
    }
    return b;
}

struct SetArg {
    std::string arg; // "run.steps=3000", for messages
    std::string key;
    std::string value_text; // as it goes into the config's text
    toml::table holder;     // the value, as holder["v"]
};

SetArg split_set(const std::string& arg) {
    const std::string origin = "--set " + arg;
    const auto eq = arg.find('=');
    if (eq == std::string::npos || trim(arg.substr(0, eq)).empty())
        throw InputError(origin + ": expected KEY=VALUE, a dotted config key and a TOML value "
                                  "(--set run.steps=3000)");
    SetArg s;
    s.arg = arg;
    s.key = trim(arg.substr(0, eq));
    s.value_text = trim(arg.substr(eq + 1));
    if (s.value_text.find('\n') != std::string::npos)
        throw InputError(origin + ": the value must be on one line");
    return s;
}

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// What a bare word that is no TOML value was meant as: the type of the key it replaces
// (`old`, where the file has it) says; only for a string are quotes the fix.
std::string not_a_value(const SetArg& s, const toml::node* old, const std::string& path) {
    const std::string origin = "--set " + s.arg;
    const std::string v = s.value_text;
    if (lower(v) == "true" || lower(v) == "false")
        return fmt::format("{}: '{}' is not a TOML value; TOML's booleans are lower case: "
                           "--set {}={}",
                           origin, v, s.key, lower(v));
    const auto at = [&] {
        const auto& src = old->source().begin;
        return fmt::format("{}:{}:{}", path, src.line, src.column);
    };
    if (old && old->is_number())
        return fmt::format("{}: '{}' is not a number, and '{}' takes one ({} gives a number)",
                           origin, v, s.key, at());
    if (old && old->is_boolean())
        return fmt::format("{}: '{}' is neither true nor false, which '{}' takes ({} gives a "
                           "boolean)",
                           origin, v, s.key, at());
    return fmt::format("{}: '{}' is not a TOML value; a string needs quotes, and the shell needs "
                       "them kept: --set '{}=\"{}\"'",
                       origin, v, s.key, v);
}

// The value of `s`; `old` is the key's value in the file, if any, for the message.
void parse_value(SetArg& s, const toml::node* old, const std::string& path) {
    const std::string origin = "--set " + s.arg;
    try {
        s.holder = toml::parse("v = " + s.value_text, std::string_view("--set"));
    } catch (const toml::parse_error& e) {
        const bool word =
            !s.value_text.empty() && s.value_text.find_first_of("\"'[]{}") == std::string::npos;
        if (word) throw InputError(not_a_value(s, old, path));
        throw InputError(fmt::format("{}: '{}' is not a TOML value ({})", origin, s.value_text,
                                     e.description()));
    }
    if (s.holder.size() != 1 || !s.holder.contains("v"))
        throw InputError(origin + ": expected one TOML value after '='");
    // a comment after the value would swallow the rest of the line it is written into
    if (s.value_text.find('#') != std::string::npos) {
        std::ostringstream v;
        v << toml::toml_formatter(s.holder, toml::format_flags::none);
        s.value_text = trim(v.str().substr(v.str().find('=') + 1));
    }
}

} // namespace

ConfigSlot config_slot(toml::table& config, const std::string& key, const std::string& origin,
                       const std::string& base, bool create_tables) {
    // every part, empty ones too ("", "a.", "a..b" are refused)
    const std::vector<std::string> parts = split(key, '.');
    for (const std::string& p : parts)
        if (p.empty()) throw InputError(origin + " has an empty part");
    ConfigSlot slot;
    slot.table = &config;
    bool in_entry = false; // the table reached so far is an array's entry
    for (std::size_t k = 0; k + 1 < parts.size(); ++k) {
        const std::string path = slot.table_path + (slot.table_path.empty() ? "" : ".");
        toml::node* child = slot.table->get(parts[k]);
        if (!child && create_tables && slot.created.empty()) slot.in_entry = in_entry;
        if (!child && create_tables) {
            if (!bare_key(parts[k]))
                throw InputError(fmt::format("{}: '{}' is no table of {} (a new table's name is "
                                             "letters, digits, _ and -)",
                                             origin, parts[k], base));
            slot.table->insert_or_assign(parts[k], toml::table{});
            child = slot.table->get(parts[k]);
            slot.created.push_back(parts[k]);
        }
        if (!child) throw InputError(fmt::format("{}: {} has no [{}]", origin, base, parts[k]));
        if (toml::table* sub = child->as_table()) {
            slot.table = sub;
            slot.table_path = path + parts[k];
            slot.header.push_back(parts[k]);
            in_entry = false;
            continue;
        }
        toml::array* list = child->as_array();
        if (!list || !list->is_array_of_tables() || k + 1 >= parts.size())
            throw InputError(
                fmt::format("{}: '{}' of {} is a value, not a table", origin, parts[k], base));
        const std::string& pick = parts[++k];
        std::size_t found = list->size();
        for (std::size_t e = 0; e < list->size(); ++e) {
            const toml::node* name = (*list)[e].as_table()->get("name");
            if (name && name->value_or(std::string()) == pick) found = e;
        }
        const bool index = pick.find_first_not_of("0123456789") == std::string::npos;
        if (found == list->size() && index && pick.size() < 10 && std::stoul(pick) < list->size())
            found = std::stoul(pick);
        if (found == list->size() && index)
            throw InputError(fmt::format("{}: index {} of [[{}]] is out of range ({} has {} {}: "
                                         "0..{})",
                                         origin, pick, parts[k - 1], base, list->size(),
                                         list->size() == 1 ? "entry" : "entries",
                                         list->size() - 1));
        if (found == list->size())
            throw InputError(fmt::format("{}: {} has no [[{}]] named '{}' (it has: {}; or give "
                                         "an index)",
                                         origin, base, parts[k - 1], pick, names_of(*list)));
        if (k + 1 >= parts.size())
            throw InputError(
                fmt::format("{} names a [[{}]] entry, not one of its keys", origin, parts[k - 1]));
        slot.table = (*list)[found].as_table();
        slot.table_path = path + parts[k - 1] + "." + std::to_string(found);
        slot.header.push_back(parts[k - 1]);
        in_entry = true;
    }
    if (slot.created.empty()) slot.in_entry = in_entry;
    slot.key = parts.back();
    return slot;
}

namespace {

// Where in the file's text each set goes.
struct TextEdits {
    struct Replace {
        std::size_t line, column, end_line, end_column;
        std::string text, set;
    };
    struct Added {
        std::string text, set;
    };
    std::vector<Replace> replaced;
    std::map<std::size_t, std::vector<Added>> after_line; // 0: before the first line
    std::vector<std::pair<std::string, std::vector<Added>>> tables_at_end; // [header], lines
    std::map<std::string, std::size_t> table_at_end;                       // by path
};

// The line of a table's own [header] (0 where the file writes it otherwise: inline,
// dotted keys, or only through a sub-table's header).
std::size_t header_line(const toml::table& t, const std::vector<std::string>& header,
                        const std::vector<std::string>& file_lines) {
    const std::size_t line = t.source().begin.line;
    if (line == 0 || line > file_lines.size()) return 0;
    std::string h;
    for (const char ch : file_lines[line - 1])
        if (ch != ' ' && ch != '\t') h += ch;
    const std::string name = join(header);
    if (h.starts_with("[[" + name + "]]") || h.starts_with("[" + name + "]")) return line;
    return 0;
}

// Writes `text` over the value from (line, column) to (end_line, end_column), toml++'s
// source range; a value over several lines leaves them empty, so that the lines after
// keep their numbers.
void replace_value(std::vector<std::string>& lines, std::size_t line, std::size_t column,
                   std::size_t end_line, std::size_t end_column, const std::string& text) {
    std::string& first = lines[line - 1];
    const std::string rest =
        lines[end_line - 1].substr(byte_of_column(lines[end_line - 1], end_column));
    for (std::size_t l = line; l < end_line; ++l) lines[l].clear();
    first = first.substr(0, byte_of_column(first, column)) + text;
    if (end_line == line)
        first += rest;
    else
        lines[end_line - 1] = rest;
}

} // namespace

ConfigWithSets::ConfigWithSets(const std::string& path, const std::vector<std::string>& sets)
    : path_(path) {
    const std::string file_text = read_config_file(path);
    toml::table doc = parse_toml_text(file_text, path);
    std::vector<std::string> file_lines = split(file_text, '\n');
    if (!file_lines.empty() && file_lines.back().empty()) file_lines.pop_back();

    TextEdits edits;
    for (const std::string& arg : sets) {
        SetArg s = split_set(arg);
        const std::string origin = "--set " + arg;
        sets_text_ += (sets_text_.empty() ? "" : " ") + origin;
        const ConfigSlot slot = config_slot(doc, s.key, origin, path, true);
        const toml::node* old = slot.table->get(slot.key);
        parse_value(s, old, path);
        set_keys_[(slot.table_path.empty() ? "" : slot.table_path + ".") + slot.key] = origin;
        if (old && (old->is_table() || old->is_array_of_tables()))
            throw InputError(fmt::format("{}: '{}' is a table of {}; set its keys one by one "
                                         "({}.KEY=VALUE)",
                                         origin, s.key, path, s.key));
        if (old && old->source().begin.line == 0)
            throw InputError(origin + ": that key is set twice");
        if (old) {
            const auto& src = old->source();
            edits.replaced.push_back({src.begin.line, src.begin.column, src.end.line,
                                      src.end.column, s.value_text, origin});
        } else {
            if (!bare_key(slot.key))
                throw InputError(fmt::format("{}: '{}' is no key of {} (a key is letters, "
                                             "digits, _ and -)",
                                             origin, slot.key, path));
            const TextEdits::Added line{slot.key + " = " + s.value_text, origin};
            added_.push_back({slot.key, origin});
            const auto at_end = edits.table_at_end.find(slot.table_path);
            if (at_end != edits.table_at_end.end()) {
                edits.tables_at_end[at_end->second].second.push_back(line);
            } else if (!slot.created.empty()) {
                if (slot.in_entry)
                    throw InputError(fmt::format(
                        "{}: {} has no [{}] in that [[{}]] entry, and --set adds tables only "
                        "outside the [[...]] entries; write it in the file",
                        origin, path, slot.created.front(), slot.header.front()));
                edits.table_at_end[slot.table_path] = edits.tables_at_end.size();
                edits.tables_at_end.push_back({"[" + join(slot.header) + "]", {line}});
            } else if (slot.header.empty()) {
                edits.after_line[0].push_back(line);
            } else if (const std::size_t h = header_line(*slot.table, slot.header, file_lines)) {
                edits.after_line[h].push_back(line);
            } else {
                throw InputError(fmt::format("{}: {} writes [{}] without a [{}] header of its "
                                             "own; write the key in the file",
                                             origin, path, join(slot.header), join(slot.header)));
            }
        }
        slot.table->insert_or_assign(slot.key, *s.holder.get("v"));
    }

    // the file's lines with the values replaced, right to left within a line
    std::vector<std::string> out = file_lines;
    std::vector<Line> origin(out.size());
    for (std::size_t k = 0; k < out.size(); ++k) origin[k].file_line = k + 1;
    std::sort(edits.replaced.begin(), edits.replaced.end(), [](const auto& a, const auto& b) {
        return a.line != b.line ? a.line > b.line : a.column > b.column;
    });
    for (const TextEdits::Replace& r : edits.replaced) {
        replace_value(out, r.line, r.column, r.end_line, r.end_column, r.text);
        origin[r.line - 1].set = r.set;
        origin[r.line - 1].set_column = r.column;
    }
    std::ostringstream text;
    const auto add = [&](const std::string& line, const Line& where) {
        text << line << "\n";
        lines_.push_back(where);
    };
    for (std::size_t k = 0; k <= out.size(); ++k) {
        if (k > 0) add(out[k - 1], origin[k - 1]);
        if (const auto it = edits.after_line.find(k); it != edits.after_line.end())
            for (const TextEdits::Added& a : it->second) add(a.text, {0, a.set, 1});
    }
    for (const auto& [header, added] : edits.tables_at_end) {
        add(header, {0, added.front().set, 1});
        for (const TextEdits::Added& a : added) add(a.text, {0, a.set, 1});
    }
    text_ = text.str();
}

std::string ConfigWithSets::text_as_run() const {
    if (sets_text_.empty()) return text_;
    return fmt::format("# {} with {}\n", path_, sets_text_) + text_;
}

std::string ConfigWithSets::explain(const std::string& message) const {
    std::string out;
    const std::string mark = path_ + ":";
    std::size_t from = 0;
    for (std::size_t at; (at = message.find(mark, from)) != std::string::npos;) {
        out += message.substr(from, at - from);
        std::size_t p = at + mark.size();
        const auto number = [&] {
            const std::size_t b = p;
            while (p < message.size() && message[p] >= '0' && message[p] <= '9') ++p;
            return p > b && p - b < 10 ? std::stoul(message.substr(b, p - b)) : 0ul;
        };
        const std::size_t line = number();
        const bool colon = line > 0 && p < message.size() && message[p] == ':';
        if (colon) ++p;
        const std::size_t column = colon ? number() : 0;
        if (line == 0 || column == 0 || line > lines_.size()) {
            out += mark;
            from = at + mark.size();
            continue;
        }
        const Line& l = lines_[line - 1];
        if (l.file_line == 0 || (!l.set.empty() && column >= l.set_column))
            out += l.set;
        else
            out += fmt::format("{}:{}:{}", path_, l.file_line, column);
        from = p;
    }
    out += message.substr(from);
    // A key a --set added can clash with one of the file's (length and lengths, skin and
    // pad): the message is then placed at the file's key and names the added one only by
    // its name, so the --set that brought it is named too.
    const auto word_at = [&](std::size_t at, std::size_t n) {
        const auto part = [&](std::size_t k) {
            return k < out.size() && (std::isalnum(static_cast<unsigned char>(out[k])) ||
                                      out[k] == '_' || out[k] == '-');
        };
        return (at == 0 || !part(at - 1)) && !part(at + n);
    };
    if (out.find(mark) != std::string::npos)
        for (const Added& a : added_) {
            if (out.find(a.origin) != std::string::npos) continue;
            for (std::size_t at = out.find(a.key); at != std::string::npos;
                 at = out.find(a.key, at + 1))
                if (word_at(at, a.key.size())) {
                    out += fmt::format(" ({} is given by {})", a.key, a.origin);
                    break;
                }
        }
    return out;
}

std::string with_initial_file_anchored(const std::string& text,
                                       const std::filesystem::path& config_path) {
    toml::table doc;
    try {
        doc = toml::parse(text, config_path.string());
    } catch (const toml::parse_error&) {
        return text; // (read already: the run would have stopped at the fault)
    }
    const toml::node* file = doc["initial"]["file"].node();
    if (!file || !file->is_string() || file->source().begin.line == 0) return text;
    const std::filesystem::path p(file->value_or(std::string()));
    if (!p.is_relative()) return text;
    toml::table holder{
        {"v",
         std::filesystem::absolute(config_path.parent_path() / p).lexically_normal().string()}};
    std::ostringstream v;
    v << toml::toml_formatter(holder, toml::format_flags::none);
    std::vector<std::string> lines = split(text, '\n');
    const auto& src = file->source();
    replace_value(lines, src.begin.line, src.begin.column, src.end.line, src.end.column,
                  trim(v.str().substr(v.str().find('=') + 1)));
    std::string out;
    for (std::size_t k = 0; k < lines.size(); ++k) out += (k > 0 ? "\n" : "") + lines[k];
    return out;
}

RunConfig ConfigWithSets::read(bool scripted) const {
    enter_stage("reading the config");
    try {
        return parse_run_config(text_, path_, scripted);
    } catch (const InputError& e) {
        throw InputError(explain(e.what()));
    }
}

} // namespace pedesis
