#include "pedesis/run/sweep.hpp"

#include "pedesis/run/resume.hpp"
#include "pedesis/run/run_directory.hpp"
#include "pedesis/run/run_directory_lock.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/config_table.hpp"
#include "pedesis/run/run.hpp"
#include "pedesis/setup/config_overrides.hpp"
#include "pedesis/setup/run_config.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

namespace pedesis {

namespace fs = std::filesystem;

namespace {

std::string where(const toml::node& n, const std::string& file) {
    const auto& s = n.source();
    return fmt::format("{}:{}:{}", file, s.begin.line, s.begin.column);
}

// Sets `value` at the key: a number where the base has a float may be given as an
// integer; any other change of type is refused.
void set_value(toml::table& config, const std::string& key, const toml::node& value,
               const std::string& at, const std::string& base) {
    const ConfigSlot slot = config_slot(config, key, at + ": [vary] key '" + key + "'",
                                        "the base config " + base, false);
    toml::table* table = slot.table;
    const std::string& last = slot.key;
    const toml::node* old = table->get(last);
    if (old && old->is_floating_point() && value.is_integer()) {
        table->insert_or_assign(last, static_cast<double>(*value.value<std::int64_t>()));
        return;
    }
    if (old && old->type() != value.type()) {
        std::ostringstream m;
        m << at << ": [vary] key '" << key << "': " << base << " holds a value of type "
          << old->type() << " there, the sweep gives " << value.type();
        throw InputError(m.str());
    }
    if (old && (old->is_table() || old->is_array()))
        throw InputError(at + ": [vary] key '" + key + "' names a table or an array, not a value");
    table->insert_or_assign(last, value);
}

// As the sweep file wrote it, near enough: numbers in their shortest exact form (0.9,
// not toml++'s 0.90000000000000002), strings without quotes.
std::string value_text(const toml::node& value) {
    if (const auto d = value.as_floating_point()) return fmt::format("{}", d->get());
    if (const auto i = value.as_integer()) return fmt::format("{}", i->get());
    if (const auto b = value.as_boolean()) return b->get() ? "true" : "false";
    return value.value_or(std::string());
}

// A file the config names relative to itself stays the same file when the point's config
// is written elsewhere.
void anchor_initial_file(toml::table& config, const fs::path& base) {
    toml::table* initial = config["initial"].as_table();
    if (!initial) return;
    toml::node* file = initial->get("file");
    if (!file || !file->is_string()) return;
    fs::path p = file->value_or(std::string());
    if (p.is_relative())
        initial->insert_or_assign("file", fs::absolute(base.parent_path() / p).string());
}

} // namespace

Sweep load_sweep(const std::string& path, const std::optional<fs::path>& out,
                 const std::vector<std::string>& sets) {
    const toml::table doc = parse_toml_file(path);
    ConfigTable root(doc, path);
    Sweep s;
    s.file = path;
    const auto base = root.string("base");
    if (!base)
        throw InputError(path + ": needs base = \"CONFIG.toml\", the config every point varies");
    s.base = fs::path(*base).is_relative() ? fs::path(path).parent_path() / *base : fs::path(*base);
    if (const auto o = root.string("out"))
        s.out = *o;
    else
        s.out = fs::path("runs") / fs::path(path).stem();
    if (out) s.out = *out;
    const toml::table* vary = doc["vary"].as_table();
    root.table("vary"); // read: its keys are config paths, checked below
    if (!vary || vary->empty())
        throw InputError(path + ": needs a [vary] table: config keys and the values each takes");
    root.finish();

    std::error_code ec;
    if (!fs::is_regular_file(s.base, ec))
        throw InputError(root.where("base") + ": no such config file: " + s.base.string());
    std::optional<ConfigWithSets> with_sets;
    if (!sets.empty()) with_sets.emplace(s.base.string(), sets);
    const toml::table base_config = [&] {
        if (!with_sets) return parse_toml_file(s.base.string());
        try {
            return parse_toml_text(with_sets->text(), s.base.string());
        } catch (const InputError& e) {
            throw InputError(with_sets->explain(e.what()));
        }
    }();

    // toml++ keeps a table's keys sorted; the sweep keeps the file's order
    std::vector<std::pair<std::string, const toml::node*>> entries;
    for (const auto& [key, node] : *vary) entries.emplace_back(std::string(key.str()), &node);
    std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
        const auto &p = a.second->source().begin, &q = b.second->source().begin;
        return p.line != q.line ? p.line < q.line : p.column < q.column;
    });
    std::vector<std::vector<const toml::node*>> values;
    for (const auto& [key, node_ptr] : entries) {
        const toml::node& node = *node_ptr;
        const std::string at = where(node, path);
        const toml::array* list = node.as_array();
        if (!list || list->empty())
            throw InputError(at + ": [vary] '" + key + "' must be a non-empty list of values");
        std::vector<const toml::node*> v;
        for (const toml::node& x : *list) {
            if (!(x.is_number() || x.is_string() || x.is_boolean()))
                throw InputError(where(x, path) + ": [vary] '" + key +
                                 "': a value must be a number, a string or a boolean");
            v.push_back(&x);
        }
        s.keys.push_back(key);
        values.push_back(std::move(v));
    }
    std::size_t total = 1;
    for (const auto& v : values) {
        if (total > 10000 / v.size())
            throw InputError(path + ": [vary] makes more than 10000 points (one run directory "
                                    "each); split the sweep");
        total *= v.size();
    }

    for (std::size_t i = 0; i < total; ++i) {
        SweepPoint p;
        p.index = i;
        p.name = fmt::format("point_{:03d}", i);
        p.config = s.out / "configs" / (p.name + ".toml");
        p.dir = s.out / p.name;
        p.console = s.out / "logs" / (p.name + ".txt");
        toml::table config = base_config;
        anchor_initial_file(config, s.base);
        std::size_t rest = i;
        std::vector<std::size_t> pick(values.size());
        for (std::size_t k = values.size(); k-- > 0;) { // the last key varies fastest
            pick[k] = rest % values[k].size();
            rest /= values[k].size();
        }
        std::string header =
            fmt::format("# {} of the sweep {}: {}{}", p.name, path, s.base.string(),
                        with_sets ? " with " + with_sets->sets_text() : std::string());
        for (std::size_t k = 0; k < values.size(); ++k) {
            const toml::node& v = *values[k][pick[k]];
            set_value(config, s.keys[k], v, where(v, path), s.base.string());
            p.values.push_back(value_text(v));
            header += fmt::format(", {} = {}", s.keys[k], p.values.back());
        }
        std::ostringstream text;
        text << header << "\n" << toml::toml_formatter(config) << "\n";
        p.config_text = text.str();
        // checked now, as `pedesis run` would: a bad point stops the sweep before any run
        parse_run_config(p.config_text, p.config.string(), false);
        s.points.push_back(std::move(p));
    }
    return s;
}

bool point_done(const SweepPoint& point) {
    return !finished_stop(point.dir).empty();
}

namespace {

PointOutcome failed(const SweepPoint& point, const char* kind, const std::string& message,
                    std::ostream& lines, std::ostream& console) {
    lines << "pedesis: " << kind << ": " << message << "\n";
    write_file_atomically(failure_note(point), [&](std::ostream& out) { out << message << "\n"; });
    console << fmt::format("pedesis sweep: {} failed: {}\n", point.name, message);
    return PointOutcome::failed;
}

} // namespace

fs::path failure_note(const SweepPoint& point) {
    fs::path p = point.console;
    return p.replace_extension(".failed");
}

PointOutcome run_point(const SweepPoint& point, std::ostream& console, bool resume) {
    std::error_code ec;
    fs::create_directories(point.config.parent_path(), ec);
    fs::create_directories(point.console.parent_path(), ec);
    fs::remove(failure_note(point), ec);
    write_file_atomically(point.config, [&](std::ostream& out) { out << point.config_text; });
    std::ofstream lines(point.console);
    RunOptions o;
    o.config_path = point.config;
    o.out_dir = point.dir;
    try {
        const RunDirectoryLock lock(point.dir);
        if (resume) {
            const ResumePlan plan = plan_resume(point.dir, run_directory_config(point.config, {}));
            lines << "pedesis: " << plan.why << "\n";
            if (plan.kind == ResumePlan::Kind::finished) return PointOutcome::done;
            if (plan.kind == ResumePlan::Kind::resume) {
                o.restart = plan.checkpoint;
                o.resume_marks = plan.marks;
            }
        }
        const std::unique_ptr<Run> run = make_run(load_run_config(point.config.string()), o, lines);
        run->run();
        return run->stopped_by() ? PointOutcome::done : PointOutcome::interrupted;
    } catch (const RunError& e) {
        return failed(point, "run stopped", e.what(), lines, console);
    } catch (const InputError& e) {
        // what only the run finds (a placement that does not fit, an unreadable file):
        // this point fails, the others go on, and no process of an MPI job is left behind
        return failed(point, "error", e.what(), lines, console);
    }
}

namespace {

void flatten(const nlohmann::json& j, const std::string& prefix,
             std::map<std::string, std::string>& out) {
    for (const auto& [k, v] : j.items()) {
        const std::string key = prefix.empty() ? k : prefix + "." + k;
        // timings differ from run to run: the table holds what a rerun reproduces
        if (key == "wall_seconds" || key == "particle_steps_per_second" ||
            key == "stepping_seconds" || key == "mpi")
            continue;
        if (v.is_object())
            flatten(v, key, out);
        else if (v.is_number() || v.is_boolean() || v.is_null())
            out[key] = v.is_null() ? "" : v.dump();
        else if (v.is_string())
            out[key] = v.get<std::string>();
    }
}

std::string csv_cell(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

} // namespace

void write_sweep_table(const Sweep& sweep) {
    std::vector<std::map<std::string, std::string>> rows(sweep.points.size());
    std::vector<std::string> status(sweep.points.size(), "not run");
    std::vector<std::string> columns;
    for (const SweepPoint& p : sweep.points) {
        std::ifstream in(p.dir / "summary.json");
        std::error_code ec;
        if (fs::exists(failure_note(p), ec)) {
            status[p.index] = "failed";
        } else if (in) {
            const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
            if (j.is_object()) {
                flatten(j, "", rows[p.index]);
                status[p.index] = point_done(p) ? "done" : "interrupted";
            }
        }
        for (const auto& [k, v] : rows[p.index])
            if (std::find(columns.begin(), columns.end(), k) == columns.end()) columns.push_back(k);
    }
    std::sort(columns.begin(), columns.end());
    write_file_atomically(sweep.out / "sweep.csv", [&](std::ostream& out) {
        out << "point,name";
        for (const auto& k : sweep.keys) out << "," << csv_cell(k);
        out << ",status";
        for (const auto& c : columns) out << "," << csv_cell(c);
        out << "\n";
        for (const SweepPoint& p : sweep.points) {
            out << p.index << "," << p.name;
            for (const auto& v : p.values) out << "," << csv_cell(v);
            out << "," << status[p.index];
            for (const auto& c : columns) {
                const auto it = rows[p.index].find(c);
                out << "," << (it == rows[p.index].end() ? "" : csv_cell(it->second));
            }
            out << "\n";
        }
    });
}

} // namespace pedesis
