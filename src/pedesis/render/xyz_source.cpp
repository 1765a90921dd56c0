#include "pedesis/io/xyz_reader.hpp"
#include "pedesis/render/frame_source.hpp"

#include <map>

namespace pedesis::render {

namespace {

namespace fs = std::filesystem;

// OVITO's radius for particles of a file without a radius column.
constexpr double default_radius = 0.5;

// pedesis writes a 2D run as a cell of unit height, not periodic in z, with every z and
// vz exactly zero; a 3D system never has all its centres on one plane.
bool looks_two_dimensional(const XyzFrame& x) {
    if (x.pbc[2]) return false;
    for (const auto& r : x.position)
        if (r[2] != 0.0) return false;
    for (const auto& v : x.velocity)
        if (v[2] != 0.0) return false;
    return true;
}

class XyzSource final : public FrameSource {
  public:
    XyzSource(const fs::path& file, bool allow_torn_tail) : reader_(file, allow_torn_tail) {}

    std::size_t frames() const override { return reader_.frames(); }

    std::string description() const override { return reader_.path().string() + " (extended XYZ)"; }

    Frame frame(std::size_t k) override {
        const XyzFrame x = reader_.frame(k);
        Frame f;
        f.dimension = looks_two_dimensional(x) ? 2 : 3;
        for (std::size_t a = 0; a < 3; ++a) {
            f.box_lo[a] = x.origin[a];
            f.box_length[a] = x.lattice[a];
        }
        if (f.dimension == 2) f.box_length[2] = 0.0;
        f.periodic = x.pbc;
        f.time = x.time;
        f.position = x.position;
        f.radius = x.radius.empty() ? std::vector<double>(x.size(), default_radius) : x.radius;
        f.velocity = x.velocity;
        if (!x.mass.empty()) f.scalars.emplace_back("mass", x.mass);
        if (!x.id.empty())
            f.scalars.emplace_back("id", std::vector<double>(x.id.begin(), x.id.end()));
        f.scalars.insert(f.scalars.end(), x.extra.begin(), x.extra.end());

        // Species indices by first appearance over the whole trajectory, so a species keeps
        // its colour in every frame.
        f.species.reserve(x.size());
        for (std::uint16_t s : x.species) {
            const std::string& name = x.species_names[s];
            auto it = index_.find(name);
            if (it == index_.end()) {
                it = index_.emplace(name, static_cast<std::uint32_t>(names_.size())).first;
                names_.push_back(name);
            }
            f.species.push_back(it->second);
        }
        f.species_names = names_;
        return f;
    }

  private:
    XyzReader reader_;
    std::map<std::string, std::uint32_t> index_;
    std::vector<std::string> names_;
};

} // namespace

std::unique_ptr<FrameSource> open_xyz_source(const fs::path& file, bool allow_torn_tail) {
    return std::make_unique<XyzSource>(file, allow_torn_tail);
}

} // namespace pedesis::render
