#include "pedesis/io/config_table.hpp"

#include "pedesis/core/error.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace pedesis {

std::string read_config_file(const std::string& path) {
    // a directory opens as an empty file: read, it would pass for a config with no tables
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
        const std::filesystem::path inside = std::filesystem::path(path) / "config.toml";
        throw InputError(fmt::format(
            "{}: is a directory, not a config file{}", path,
            std::filesystem::is_regular_file(inside, ec)
                ? fmt::format(" (it holds the config of its run: give {})", inside.string())
                : std::string()));
    }
    std::ifstream in(path);
    if (!in) throw InputError(path + ": cannot open config file");
    std::stringstream buf;
    buf << in.rdbuf();
    return buf.str();
}

toml::table parse_toml_file(const std::string& path) {
    return parse_toml_text(read_config_file(path), path);
}

toml::table parse_toml_text(const std::string& text, const std::string& name) {
    try {
        return toml::parse(text, name);
    } catch (const toml::parse_error& e) {
        std::ostringstream m;
        m << name << ":" << e.source().begin.line << ":" << e.source().begin.column << ": "
          << e.description();
        throw InputError(m.str());
    }
}

ConfigTable::ConfigTable(const toml::table& table, std::string file, std::string prefix)
    : table_(&table), file_(std::move(file)), prefix_(std::move(prefix)) {}

bool ConfigTable::has(const std::string& key) const {
    return table_->contains(key);
}

bool ConfigTable::is_table(const std::string& key) const {
    const toml::node* n = table_->get(key);
    return n && n->is_table();
}

std::optional<std::size_t> ConfigTable::list_size(const std::string& key) const {
    const toml::node* n = table_->get(key);
    if (!n || !n->is_array()) return std::nullopt;
    return n->as_array()->size();
}

std::vector<std::string> ConfigTable::keys() const {
    std::vector<std::string> out;
    for (const auto& [k, v] : *table_) out.emplace_back(k.str());
    return out;
}

const toml::node* ConfigTable::node(const std::string& key) {
    used_.insert(key);
    return table_->get(key);
}

std::string ConfigTable::where(const std::string& key) const {
    std::ostringstream m;
    m << file_;
    const toml::node* n = table_->get(key);
    const auto& src = n ? n->source() : table_->source();
    if (src.begin.line > 0) m << ":" << src.begin.line << ":" << src.begin.column;
    m << ": key '" << full_key(key) << "'";
    return m.str();
}

std::string ConfigTable::location() const {
    const auto& src = table_->source();
    return src.begin.line > 0 ? fmt::format("{}:{}:{}", file_, src.begin.line, src.begin.column)
                              : file_;
}

void ConfigTable::fail(const std::string& key, const std::string& what) const {
    throw InputError(where(key) + ": " + what);
}

std::optional<double> ConfigTable::number(const std::string& key, bool allow_inf) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    double v;
    if (auto f = n->value_exact<double>())
        v = *f;
    else if (auto i = n->value_exact<std::int64_t>())
        v = static_cast<double>(*i);
    else
        fail(key, "expected a number");
    if (std::isnan(v)) fail(key, "is NaN; expected a number");
    if (std::isinf(v) && !(allow_inf && v > 0)) fail(key, "must be finite");
    return v;
}

double ConfigTable::number(const std::string& key, double fallback) {
    auto v = number(key);
    return v ? *v : fallback;
}

double ConfigTable::required_number(const std::string& key) {
    auto v = number(key);
    if (!v) fail(key, "is required");
    return *v;
}

std::optional<std::int64_t> ConfigTable::integer(const std::string& key) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    if (auto i = n->value_exact<std::int64_t>()) return *i;
    fail(key, "expected an integer");
}

std::optional<std::string> ConfigTable::string(const std::string& key) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    if (auto s = n->value_exact<std::string>()) return *s;
    fail(key, "expected a string");
}

std::optional<bool> ConfigTable::boolean(const std::string& key) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    if (auto b = n->value_exact<bool>()) return *b;
    fail(key, "expected true or false");
}

std::optional<std::vector<double>> ConfigTable::numbers(const std::string& key,
                                                        std::size_t expected_size) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    const toml::array* arr = n->as_array();
    if (!arr || arr->size() != expected_size)
        fail(key, "expected a list of " + std::to_string(expected_size) + " numbers");
    std::vector<double> out;
    for (const auto& e : *arr) {
        double v;
        if (auto f = e.value_exact<double>())
            v = *f;
        else if (auto i = e.value_exact<std::int64_t>())
            v = static_cast<double>(*i);
        else
            fail(key, "expected a list of numbers");
        if (!std::isfinite(v)) fail(key, "contains a non-finite number");
        out.push_back(v);
    }
    return out;
}

std::optional<std::vector<std::string>> ConfigTable::strings(const std::string& key,
                                                             std::size_t expected_size) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    if (auto s = n->value_exact<std::string>()) return std::vector<std::string>(expected_size, *s);
    const toml::array* arr = n->as_array();
    if (!arr || arr->size() != expected_size)
        fail(key, "expected a string or a list of " + std::to_string(expected_size) + " strings");
    std::vector<std::string> out;
    for (const auto& e : *arr) {
        auto s = e.value_exact<std::string>();
        if (!s) fail(key, "expected a list of strings");
        out.push_back(*s);
    }
    return out;
}

std::optional<ConfigTable> ConfigTable::table(const std::string& key) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    const toml::table* t = n->as_table();
    if (!t) fail(key, "expected a table");
    ConfigTable sub(*t, file_, full_key(key));
    sub.note_ = note_;
    return sub;
}

std::vector<ConfigTable> ConfigTable::tables(const std::string& key) {
    const toml::node* n = node(key);
    std::vector<ConfigTable> out;
    if (!n) return out;
    const toml::array* arr = n->as_array();
    if (!arr) fail(key, "expected an array of tables ([[" + full_key(key) + "]])");
    std::size_t k = 0;
    for (const auto& e : *arr) {
        const toml::table* t = e.as_table();
        if (!t) fail(key, "expected an array of tables ([[" + full_key(key) + "]])");
        out.emplace_back(*t, file_, full_key(key) + "[" + std::to_string(k++) + "]");
        out.back().note_ = note_;
    }
    return out;
}

void ConfigTable::finish() const {
    for (const auto& [k, v] : *table_) {
        const std::string key(k.str());
        if (!used_.count(key)) {
            std::ostringstream m;
            m << file_;
            if (v.source().begin.line > 0)
                m << ":" << v.source().begin.line << ":" << v.source().begin.column;
            const std::string note = note_ ? (*note_)(full_key(key)) : std::string();
            m << ": unknown key '" << full_key(key) << "'"
              << (note.empty() ? std::string(" (see docs/config.md for the keys)") : ": " + note);
            throw InputError(m.str());
        }
    }
}

} // namespace pedesis
