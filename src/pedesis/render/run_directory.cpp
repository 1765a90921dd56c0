#include "pedesis/render/run_directory.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/render/config_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <system_error>
#include <utility>

namespace pedesis::render {

namespace {

namespace fs = std::filesystem;

bool is_file(const fs::path& p) {
    std::error_code ec;
    return fs::is_regular_file(p, ec);
}

// snapshots/frame_NNNNNN.json in frame order (the numbers are zero-padded, so also in
// name order; sorting the numbers keeps a restarted run's frames in order past 999999).
std::vector<fs::path> json_snapshots(const fs::path& dir) {
    std::vector<std::pair<unsigned long long, fs::path>> found;
    std::error_code ec;
    const fs::path snapshots = dir / "snapshots";
    if (!fs::is_directory(snapshots, ec)) return {};
    static const std::regex name(R"(frame_(\d{1,18})\.json)"); // fits stoull
    for (const auto& entry : fs::directory_iterator(snapshots, ec)) {
        std::smatch m;
        const std::string file = entry.path().filename().string();
        if (entry.is_regular_file(ec) && std::regex_match(file, m, name))
            found.emplace_back(std::stoull(m[1].str()), entry.path());
    }
    std::sort(found.begin(), found.end());
    std::vector<fs::path> files;
    for (auto& f : found) files.push_back(std::move(f.second));
    return files;
}

fs::path part_of(const fs::path& p) {
    fs::path part = p;
    part += ".part";
    return part;
}

std::string unfinished_note(const fs::path& part) {
    return fmt::format("{} is the trajectory of an unfinished run (killed, or still running): "
                       "rendering the frames it holds",
                       part.string());
}

} // namespace

RunFacts read_run_facts(const fs::path& config_toml) {
    RunFacts facts;
    const auto parsed = parse_config_table(config_toml);
    if (!parsed) return facts;
    const toml::table& config = *parsed;
    const int dimension = config_dimension(config);
    if (const auto dt = config["run"]["dt"].value<double>(); dt && std::isfinite(*dt) && *dt > 0)
        facts.dt = *dt;

    // [box] boundary: one word for every axis, or one per axis; periodic when absent.
    const auto boundary = config["box"]["boundary"];
    std::vector<std::string> words;
    if (const auto word = boundary.value<std::string>()) {
        words.assign(static_cast<std::size_t>(dimension), *word);
    } else if (const toml::array* list = boundary.as_array()) {
        for (const auto& item : *list)
            if (const auto word = item.value<std::string>()) words.push_back(*word);
    } else if (!boundary) {
        words.assign(static_cast<std::size_t>(dimension), "periodic");
    }
    if (words.size() == static_cast<std::size_t>(dimension)) {
        std::array<bool, 3> periodic{true, true, true};
        bool known = true;
        for (std::size_t a = 0; a < words.size(); ++a) {
            known = known && (words[a] == "periodic" || words[a] == "wall");
            periodic[a] = words[a] == "periodic";
        }
        if (dimension == 2) periodic[2] = false;
        if (known) facts.periodic = periodic;
    }

    if (const toml::array* species = config["species"].as_array()) {
        for (const auto& item : *species) {
            const toml::table* s = item.as_table();
            const auto name = s ? (*s)["name"].value<std::string>() : std::nullopt;
            if (!name) { // a list with a gap would give later species the wrong names
                facts.species_names.clear();
                break;
            }
            facts.species_names.push_back(*name);
        }
    }
    return facts;
}

OpenedRun open_run_directory(const fs::path& dir, SourceKind kind) {
    std::error_code ec;
    if (!fs::exists(dir, ec)) throw InputError(dir.string() + ": no such run directory");
    if (!fs::is_directory(dir, ec))
        throw InputError(dir.string() + ": not a directory (render takes a run directory, the "
                                        "--out of pedesis run)");
    const RunFacts facts = read_run_facts(dir / "config.toml");
    const fs::path gsd = dir / "trajectory.gsd";
    const fs::path xyz = dir / "trajectory.xyz";

    OpenedRun run;
    run.scenery = read_scenery(dir / "config.toml");
    auto take_gsd = [&]() {
        if (is_file(gsd)) {
            run.source = open_gsd_source(gsd, facts);
        } else if (is_file(part_of(gsd))) {
            run.source = open_gsd_source(part_of(gsd), facts);
            run.notes.push_back(unfinished_note(part_of(gsd)));
        }
    };
    auto take_xyz = [&]() {
        if (is_file(xyz)) {
            run.source = open_xyz_source(xyz, false);
        } else if (is_file(part_of(xyz))) {
            run.source = open_xyz_source(part_of(xyz), true);
            run.notes.push_back(unfinished_note(part_of(xyz)));
        }
    };
    auto take_json = [&]() {
        auto files = json_snapshots(dir);
        if (!files.empty()) run.source = open_json_source(std::move(files), facts);
    };

    switch (kind) {
    case SourceKind::gsd:
        take_gsd();
        if (!run.source) throw InputError(gsd.string() + ": not found (--source gsd)");
        break;
    case SourceKind::xyz:
        take_xyz();
        if (!run.source) throw InputError(xyz.string() + ": not found (--source xyz)");
        break;
    case SourceKind::json:
        take_json();
        if (!run.source)
            throw InputError((dir / "snapshots").string() +
                             ": no frame_NNNNNN.json snapshots (--source json)");
        break;
    case SourceKind::automatic:
        take_gsd();
        if (!run.source) take_xyz();
        if (!run.source) take_json();
        if (!run.source)
            throw InputError(
                dir.string() +
                ": no trajectory to render: none of trajectory.gsd, trajectory.xyz or "
                "snapshots/frame_*.json is there (a run writes them when [output] formats "
                "includes \"gsd\", \"xyz\" or \"json\")");
        break;
    }
    if (run.source->frames() == 0)
        throw InputError(run.source->description() + ": the trajectory has no frames");
    return run;
}

} // namespace pedesis::render
