#pragma once
// A run's trajectory behind one interface, so the drawing code never knows whether
// the frames came from GSD, extended XYZ or the tutorial's JSON snapshots.
#include "pedesis/render/frame.hpp"

#include <array>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pedesis::render {

// What the run's config.toml adds to frame files that lack it: GSD frames of other
// programs store a step number but no time and no walls, and JSON stores neither walls
// nor species names.
struct RunFacts {
    std::optional<double> dt;
    std::optional<std::array<bool, 3>> periodic;
    std::vector<std::string> species_names; // in [[species]] order, that is by type index
};

class FrameSource {
  public:
    virtual ~FrameSource() = default;
    virtual std::size_t frames() const = 0;
    // Frame k (0-based); a fault is an InputError naming the file.
    virtual Frame frame(std::size_t k) = 0;
    // The file(s) read and their format, for messages: "runs/x/trajectory.gsd (GSD)".
    virtual std::string description() const = 0;
};

// GSD (hoomd schema). Time is step * dt when `facts` has dt; the walls are those of
// log/pedesis/periodic where the file has it (pedesis' own files), else of `facts`, else
// none (the schema's box is periodic).
std::unique_ptr<FrameSource> open_gsd_source(const std::filesystem::path& file,
                                             const RunFacts& facts);

// Extended XYZ. `allow_torn_tail` drops a torn last frame (a killed run's ".part" file).
std::unique_ptr<FrameSource> open_xyz_source(const std::filesystem::path& file,
                                             bool allow_torn_tail);

// Tutorial JSON, one file per frame in the order given.
std::unique_ptr<FrameSource> open_json_source(std::vector<std::filesystem::path> files,
                                              const RunFacts& facts);

} // namespace pedesis::render
