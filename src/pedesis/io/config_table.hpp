#pragma once
// Strict access to a TOML table: every key read is remembered, and finish() turns
// any key that nobody read into an error. Values are checked on the way out
// (type, finiteness) and every message names the file, line, column and key.
#include <toml++/toml.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace pedesis {

class ConfigTable {
  public:
    ConfigTable(const toml::table& table, std::string file, std::string prefix = "");

    bool has(const std::string& key) const;
    bool is_table(const std::string& key) const;
    // The length of the list at `key`, or nothing if the value is not a list.
    std::optional<std::size_t> list_size(const std::string& key) const;
    std::vector<std::string> keys() const; // every key of the table, in file order

    std::optional<double> number(const std::string& key, bool allow_inf = false);
    double number(const std::string& key, double fallback);
    double required_number(const std::string& key);
    std::optional<std::int64_t> integer(const std::string& key);
    std::optional<std::string> string(const std::string& key);
    std::optional<bool> boolean(const std::string& key);
    std::optional<std::vector<double>> numbers(const std::string& key, std::size_t expected_size);
    // A string, or a list of `expected_size` strings.
    std::optional<std::vector<std::string>> strings(const std::string& key,
                                                    std::size_t expected_size);

    std::optional<ConfigTable> table(const std::string& key);
    std::vector<ConfigTable> tables(const std::string& key); // array of tables [[key]]

    // Throws InputError on the first key that was never read.
    void finish() const;

    // What more to say of a key that no reader took, given its full key ("run.time"):
    // which engine takes it, say; empty for nothing. Tables read from this one (table(),
    // tables()) say the same.
    using UnknownKeyNote = std::function<std::string(const std::string& full_key)>;
    void explain_unknown_keys(UnknownKeyNote note) {
        note_ = std::make_shared<const UnknownKeyNote>(std::move(note));
    }

    // "file:line:column: key 'prefix.key'" for messages about a value.
    std::string where(const std::string& key) const;
    // "file:line:column" of the table itself, for messages about it as a whole.
    std::string location() const;
    const std::string& file() const { return file_; }
    std::string full_key(const std::string& key) const {
        return prefix_.empty() ? key : prefix_ + "." + key;
    }

  private:
    const toml::node* node(const std::string& key);
    [[noreturn]] void fail(const std::string& key, const std::string& what) const;

    const toml::table* table_;
    std::string file_;
    std::string prefix_;
    std::set<std::string> used_;
    std::shared_ptr<const UnknownKeyNote> note_;
};

// A config file's text; a directory or an unreadable file is an InputError naming it.
std::string read_config_file(const std::string& path);
// Parses a TOML file; malformed files give "file:line:column: message".
toml::table parse_toml_file(const std::string& path);
toml::table parse_toml_text(const std::string& text, const std::string& name);

} // namespace pedesis
