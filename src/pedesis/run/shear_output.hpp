#pragma once
// The end of a run under Lees-Edwards shear, alike for every engine: velocity_profile.csv
// and the printed viscosity -<P_xy>/rate from summary.json's "shear".
#include "pedesis/core/box.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/observe/shear_flow.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <ostream>
#include <string>

namespace pedesis {

template <int D>
void write_shear_results(const std::filesystem::path& out_dir, const ShearRecord& shear,
                         const Box<D>& box, const nlohmann::json& summary, std::ostream& console) {
    write_file_atomically(out_dir / "velocity_profile.csv", [&](std::ostream& out) {
        shear.write_profile(out, box.lo(1), box.length(1));
    });
    const nlohmann::json& eta = summary.at("shear").at("viscosity");
    if (eta.at("value").is_null()) return;
    console << fmt::format(
        "  shear viscosity -<P_xy>/rate = {:.6g}{}\n", eta["value"].template get<double>(),
        eta["error"].is_null() ? std::string()
                               : fmt::format(" +- {:.2g}", eta["error"].template get<double>()));
}

} // namespace pedesis
