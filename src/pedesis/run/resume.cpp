#include "pedesis/run/resume.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/run/run_directory.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string_view>

namespace pedesis {

namespace {

namespace fs = std::filesystem;

// The keys a resumed run may change: where it ends, and how it reports (which changes
// nothing in the directory, and does not make a finished run go on).
constexpr std::array<std::string_view, 3> end_keys = {"run.time", "run.steps",
                                                      "run.collisions_per_particle"};
constexpr std::array<std::string_view, 2> report_keys = {"output.checkpoint_seconds",
                                                         "output.progress"};

std::string text_of(const toml::node& n) {
    std::ostringstream out;
    if (const auto* t = n.as_table())
        out << *t;
    else if (const auto* a = n.as_array())
        out << *a;
    else
        n.visit([&](const auto& v) { out << v; });
    return out.str();
}

std::string shown(const toml::node* n) {
    if (!n) return "not set";
    std::string s = text_of(*n);
    if (s.size() > 60) s = s.substr(0, 57) + "...";
    return s;
}

struct Differ {
    bool end_changed = false;

    // the first difference under `key`, depth first in the order of `was`, then `now`
    std::optional<std::string> compare(const std::string& key, const toml::node* was,
                                       const toml::node* now) {
        const bool end = std::find(end_keys.begin(), end_keys.end(), key) != end_keys.end();
        const bool report =
            std::find(report_keys.begin(), report_keys.end(), key) != report_keys.end();
        if (was && now && was->is_table() && now->is_table()) {
            const toml::table& a = *was->as_table();
            const toml::table& b = *now->as_table();
            std::vector<std::string> names;
            for (const auto& [k, v] : a) names.emplace_back(k.str());
            for (const auto& [k, v] : b)
                if (!a.contains(k.str())) names.emplace_back(k.str());
            for (const std::string& k : names)
                if (auto d = compare(key.empty() ? k : key + "." + k, a.get(k), b.get(k))) return d;
            return std::nullopt;
        }
        if (was && now && was->is_array() && now->is_array() &&
            was->as_array()->size() == now->as_array()->size()) {
            const toml::array& a = *was->as_array();
            const toml::array& b = *now->as_array();
            for (std::size_t i = 0; i < a.size(); ++i)
                if (auto d = compare(fmt::format("{}[{}]", key, i), a.get(i), b.get(i))) return d;
            return std::nullopt;
        }
        const bool same =
            was && now && was->type() == now->type() && text_of(*was) == text_of(*now);
        if (same || report) return std::nullopt;
        if (end) {
            end_changed = true;
            return std::nullopt;
        }
        return fmt::format("{} (was {}, now {})", key, shown(was), shown(now));
    }
};

std::string read_text(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

// Files a killed writer left: "NAME.tmp.PID" (io/atomic_file.cpp, io/checkpoint_file.cpp).
void remove_temporaries(const fs::path& dir) {
    std::error_code ec;
    for (const fs::path& d : {dir, dir / "snapshots"}) {
        if (!fs::is_directory(d, ec)) continue;
        std::vector<fs::path> left;
        for (const auto& e : fs::directory_iterator(d, ec))
            if (e.path().filename().string().find(".tmp.") != std::string::npos &&
                e.is_regular_file(ec))
                left.push_back(e.path());
        for (const fs::path& p : left) fs::remove(p, ec);
    }
}

} // namespace

std::optional<std::string> config_difference(const std::string& was, const std::string& now,
                                             bool& end_changed) {
    toml::table a, b;
    try {
        a = toml::parse(was, std::string_view("the run directory's config.toml"));
    } catch (const toml::parse_error& e) {
        return fmt::format("its config.toml does not parse ({})", e.description());
    }
    b = toml::parse(now, std::string_view("the config"));
    Differ d;
    auto diff = d.compare("", &a, &b);
    end_changed = d.end_changed;
    return diff;
}

std::string finished_stop(const fs::path& dir) {
    const fs::path summary = dir / "summary.json";
    std::error_code ec;
    if (!fs::is_regular_file(summary, ec) || fs::file_size(summary, ec) > (64u << 20)) return "";
    try {
        const nlohmann::json j = nlohmann::json::parse(read_text(summary));
        if (!j.is_object() || !j.contains("stopped_by") || !j["stopped_by"].is_string()) return "";
        const std::string why = j["stopped_by"].get<std::string>();
        return why == "interrupted" || why == "script" ? "" : why;
    } catch (const nlohmann::json::exception&) {
        return "";
    }
}

ResumePlan plan_resume(const fs::path& dir, const std::string& config_text) {
    ResumePlan plan;
    std::error_code ec;
    const fs::path config = dir / "config.toml";
    if (!fs::is_regular_file(config, ec)) {
        remove_temporaries(dir);
        plan.why = fmt::format("{} holds no run yet: starting it", dir.string());
        return plan;
    }
    bool end_changed = false;
    if (const auto diff = config_difference(read_text(config), config_text, end_changed))
        throw InputError(fmt::format(
            "{}: holds a run of another config: {}; --resume continues a run only with the "
            "config it ran (its end may change: [run] time, steps, collisions_per_particle); "
            "give another --out for a new run",
            dir.string(), *diff));
    remove_temporaries(dir);
    const fs::path previous = dir / previous_checkpoint_file;
    const fs::path checkpoint = dir / "checkpoint.bin";
    const std::string stop = finished_stop(dir);
    const bool finished = !stop.empty() && !fs::exists(previous, ec);
    if (finished && !end_changed) {
        plan.kind = ResumePlan::Kind::finished;
        plan.stopped_by = stop;
        plan.why = fmt::format("{} holds a finished run of this config (stopped by {}): nothing "
                               "to do",
                               dir.string(), stop);
        return plan;
    }
    if (fs::exists(previous, ec))
        plan.checkpoint = previous;
    else if (fs::exists(checkpoint, ec))
        plan.checkpoint = checkpoint;
    if (plan.checkpoint.empty()) {
        plan.why =
            fmt::format("{} holds no checkpoint of its run: starting it again", dir.string());
        return plan;
    }
    const fs::path record = dir / checkpoint_record_file;
    if (!fs::exists(record, ec))
        throw InputError(fmt::format(
            "{}: has a checkpoint but no {} (the lengths of its outputs at the checkpoint), so "
            "it cannot continue in place: it was written by a pedesis before --resume, or by "
            "--restart into it; continue with --restart {} --out NEW",
            dir.string(), checkpoint_record_file, plan.checkpoint.string()));
    plan.marks = read_checkpoint_record(record);
    plan.kind = ResumePlan::Kind::resume;
    plan.why = fmt::format("resuming {} from {}", dir.string(), plan.checkpoint.string());
    return plan;
}

} // namespace pedesis
