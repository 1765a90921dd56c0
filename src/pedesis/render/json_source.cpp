#include "pedesis/core/error.hpp"
#include "pedesis/io/tutorial_json.hpp"
#include "pedesis/render/frame_source.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <iterator>

namespace pedesis::render {

namespace {

namespace fs = std::filesystem;

// The tutorial's particle radius, for files (pymd's own) that leave it out.
constexpr double default_radius = 1.0;

struct Peek {
    int dimension = 2;
    std::optional<double> time;
};

// The dimension (a box with Lz, or three-component positions) and the time: what
// read_tutorial_json does not return. A file that does not parse is left to it, which
// reports the line and column.
Peek peek(const fs::path& file) {
    Peek p;
    std::ifstream in(file, std::ios::binary);
    const std::string text(std::istreambuf_iterator<char>(in), {});
    const auto doc = nlohmann::json::parse(text, nullptr, false);
    if (doc.is_discarded() || !doc.is_object() || !doc.contains("system")) return p;
    const auto& system = doc["system"];
    if (!system.is_object()) return p;
    if (system.contains("time") && system["time"].is_number())
        p.time = system["time"].get<double>();
    if (system.contains("box") && system["box"].is_object() && system["box"].contains("Lz"))
        p.dimension = 3;
    else if (system.contains("particles") && system["particles"].is_array() &&
             !system["particles"].empty() && system["particles"][0].is_object() &&
             system["particles"][0].contains("r") && system["particles"][0]["r"].is_array() &&
             system["particles"][0]["r"].size() == 3)
        p.dimension = 3;
    return p;
}

// pedesis names the species of a file without [[species]] A, B, ... by type.
std::string default_species_name(std::size_t type) {
    return type < 26 ? std::string(1, static_cast<char>('A' + type))
                     : "type " + std::to_string(type);
}

template <int D> Frame to_frame(const fs::path& file, const Peek& peeked, const RunFacts& facts) {
    const ParticleFile<D> pf = read_tutorial_json<D>(file);
    if (!pf.box)
        throw InputError(file.string() + ": no \"box\" in \"system\" (render needs the box)");
    Frame f;
    f.dimension = D;
    for (int a = 0; a < D; ++a) {
        f.box_length[static_cast<std::size_t>(a)] = (*pf.box)[a];
        f.box_lo[static_cast<std::size_t>(a)] = -0.5 * (*pf.box)[a];
    }
    f.periodic = facts.periodic.value_or(std::array<bool, 3>{true, true, D == 3});
    f.time = peeked.time;

    const bool all_v = std::all_of(pf.particles.begin(), pf.particles.end(),
                                   [](const auto& q) { return q.v.has_value(); });
    const bool all_n = std::all_of(pf.particles.begin(), pf.particles.end(),
                                   [](const auto& q) { return q.n.has_value(); });
    auto as_3d = [](const Vec<D>& v) {
        Vec3 out{};
        for (int a = 0; a < D; ++a) out[static_cast<std::size_t>(a)] = v[a];
        return out;
    };
    std::size_t types = 0;
    for (const auto& q : pf.particles) {
        f.position.push_back(as_3d(q.r));
        f.radius.push_back(q.radius.value_or(default_radius));
        f.species.push_back(static_cast<std::uint32_t>(q.type));
        types = std::max(types, static_cast<std::size_t>(q.type) + 1);
        if (all_v) f.velocity.push_back(as_3d(*q.v));
        if (all_n) f.director.push_back(as_3d(*q.n));
    }
    f.species_names = facts.species_names;
    for (std::size_t t = f.species_names.size(); t < types; ++t)
        f.species_names.push_back(default_species_name(t));
    return f;
}

class JsonSource final : public FrameSource {
  public:
    JsonSource(std::vector<fs::path> files, RunFacts facts)
        : files_(std::move(files)), facts_(std::move(facts)) {}

    std::size_t frames() const override { return files_.size(); }

    std::string description() const override {
        return (files_.front().parent_path() / "frame_*.json").string() + " (tutorial JSON)";
    }

    Frame frame(std::size_t k) override {
        const fs::path& file = files_.at(k);
        const Peek p = peek(file);
        return p.dimension == 3 ? to_frame<3>(file, p, facts_) : to_frame<2>(file, p, facts_);
    }

  private:
    std::vector<fs::path> files_;
    RunFacts facts_;
};

} // namespace

std::unique_ptr<FrameSource> open_json_source(std::vector<fs::path> files, const RunFacts& facts) {
    return std::make_unique<JsonSource>(std::move(files), facts);
}

} // namespace pedesis::render
