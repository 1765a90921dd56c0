#include "pedesis/core/error.hpp"
#include "pedesis/io/gsd_reader.hpp"
#include "pedesis/render/frame_source.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pedesis::render {

namespace {

namespace fs = std::filesystem;

// The x axis turned by the unit quaternion (w, x, y, z): GsdWriter stores each director
// as the rotation that takes x onto it.
Vec3 rotated_x_axis(const std::array<double, 4>& q) {
    const double len2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    if (!(len2 > 0.0)) return {0.0, 0.0, 0.0};
    const double s = 2.0 / len2; // also normalises a quaternion stored in float32
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    return {1.0 - s * (y * y + z * z), s * (x * y + w * z), s * (x * z - w * y)};
}

class GsdSource final : public FrameSource {
  public:
    GsdSource(const fs::path& file, RunFacts facts) : reader_(file), facts_(std::move(facts)) {}

    std::size_t frames() const override { return static_cast<std::size_t>(reader_.frames()); }

    std::string description() const override { return reader_.path().string() + " (GSD)"; }

    Frame frame(std::size_t k) override {
        const GsdFrame g = reader_.frame(k);
        const std::string where = fmt::format("{}: frame {}", reader_.path().string(), k);
        Frame f;
        f.dimension = g.dimensions;
        // xy alone is a Lees-Edwards run's offset over L_y: pedesis keeps its positions in
        // the orthorhombic box, which is what is drawn
        if (g.box[4] != 0.0 || g.box[5] != 0.0)
            throw InputError(where + ": the box is tilted (xz or yz is not 0: triclinic); "
                                     "render draws orthorhombic boxes only");
        for (int a = 0; a < 3; ++a) {
            const auto i = static_cast<std::size_t>(a);
            f.box_length[i] = a < f.dimension ? g.box[i] : 0.0;
            f.box_lo[i] = -0.5 * f.box_length[i];
            if (a < f.dimension && !(f.box_length[i] > 0.0))
                throw InputError(fmt::format("{}: box length {} along axis {} must be positive",
                                             where, g.box[i], a));
        }
        // the file's own boundaries first (pedesis writes them), then the run's config
        f.periodic =
            g.periodic
                ? *g.periodic
                : facts_.periodic.value_or(std::array<bool, 3>{true, true, f.dimension == 3});
        f.step = g.step;
        if (g.time)
            f.time = *g.time;
        else if (facts_.dt)
            f.time = static_cast<double>(g.step) * *facts_.dt;

        f.position = g.position;
        f.radius.reserve(g.size());
        for (double d : g.diameter) f.radius.push_back(0.5 * d);
        f.species = g.type_id;
        f.species_names = g.types;
        if (g.velocity_stored) f.velocity = g.velocity;
        f.scalars.emplace_back("mass", g.mass);
        if (g.orientation_stored) {
            f.director.reserve(g.size());
            for (const auto& q : g.orientation) f.director.push_back(rotated_x_axis(q));
        }
        return f;
    }

  private:
    GsdReader reader_;
    RunFacts facts_;
};

} // namespace

std::unique_ptr<FrameSource> open_gsd_source(const fs::path& file, const RunFacts& facts) {
    return std::make_unique<GsdSource>(file, facts);
}

} // namespace pedesis::render
