#include "pedesis/view/run_data.hpp"

#include "pedesis/render/scenery.hpp"
#include "pedesis/view/frame_arrays.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace pedesis::view {

namespace {

// Numbers only (read_scenery checked each one finite), and the shape as a word of ours:
// nothing of the config's own text reaches the page.
nlohmann::json scenery_json(const render::Scenery& scenery) {
    nlohmann::json containers = nlohmann::json::array();
    for (const render::Container& c : scenery.containers)
        containers.push_back(
            {{"shape", c.shape == render::ContainerShape::sphere ? "sphere" : "cylinder"},
             {"radius", c.radius},
             {"centre", c.centre},
             {"axis", c.axis}});
    nlohmann::json traps = nlohmann::json::array(), gravity = nlohmann::json::array();
    for (const render::Vec3& t : scenery.traps) traps.push_back(t);
    for (const render::Vec3& g : scenery.pulls) gravity.push_back(g);
    return {{"containers", containers}, {"traps", traps}, {"gravity", gravity}};
}

} // namespace

nlohmann::json run_info(render::FrameSource& source, const render::Frame& f,
                        const std::filesystem::path& run_dir) {
    nlohmann::json species = nlohmann::json::array();
    for (std::size_t s = 0; s < f.species_names.size(); ++s) {
        double radius = 0.0;
        for (std::size_t i = 0; i < f.size(); ++i)
            if (f.species[i] == s) {
                radius = f.radius[i];
                break;
            }
        species.push_back({{"name", f.species_names[s]}, {"radius", radius}});
    }
    nlohmann::json fields = {"position", "radius", "species"};
    if (frame_has(f, Field::director)) fields.push_back("director");
    const std::vector<std::string> colour_by = colour_fields(f);
    for (const std::string& c : colour_by)
        if (c != "radius") fields.push_back(c);
    std::filesystem::path dir = std::filesystem::absolute(run_dir).lexically_normal();
    if (dir.filename().empty()) dir = dir.parent_path(); // "runs/demo/"
    return {{"run", dir.filename().string()},
            {"source", source.description()},
            {"dimension", f.dimension},
            {"box_lo", f.box_lo},
            {"box_length", f.box_length},
            {"periodic", f.periodic},
            {"frames", source.frames()},
            {"particles", f.size()},
            {"species", species},
            {"fields", fields},
            {"colour_by", colour_by},
            {"scenery", scenery_json(render::read_scenery(run_dir / "config.toml"))}};
}

// log.csv as columns and rows of numbers ("inf" and "nan", which pandas writes and reads,
// become null: JSON has no such numbers).
nlohmann::json read_log(const std::filesystem::path& run_dir) {
    // a run still going writes log.csv.part, renamed at its end
    const std::filesystem::path done = run_dir / "log.csv";
    const std::filesystem::path file =
        std::filesystem::exists(done) ? done : run_dir / "log.csv.part";
    nlohmann::json out = {{"columns", nlohmann::json::array()}, {"rows", nlohmann::json::array()}};
    std::ifstream in(file);
    if (!in) return out;
    std::string line, cell;
    if (!std::getline(in, line)) return out;
    std::istringstream header(line);
    while (std::getline(header, cell, ',')) out["columns"].push_back(cell);
    const std::size_t columns = out["columns"].size();
    while (std::getline(in, line)) {
        std::istringstream row(line);
        nlohmann::json values = nlohmann::json::array();
        while (std::getline(row, cell, ',')) {
            char* end = nullptr;
            const double v = std::strtod(cell.c_str(), &end);
            if (end == cell.c_str() || !std::isfinite(v))
                values.push_back(nullptr);
            else
                values.push_back(v);
        }
        // a row being written (no newline yet, or cut short) is left for the next request
        if (values.size() == columns && !in.eof()) out["rows"].push_back(std::move(values));
    }
    return out;
}

} // namespace pedesis::view
