#pragma once
// What a run under Lees-Edwards shear ([box] shear_rate, core/box.hpp) accumulates over
// its logged steps after step 0: the laboratory velocity along x binned in y (the
// velocity profile, velocity_profile.csv, which shows the linear flow) and the shear
// stress P_xy of every log row, whose mean gives the viscosity eta = -<P_xy> / rate with
// an error from 8 contiguous blocks of the run (docs/engines.md, "Shear flow").
#include "pedesis/core/box.hpp"
#include "pedesis/core/particles.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <ostream>
#include <vector>

namespace pedesis {

struct ShearRecord {
    // per bin of y: the sum of the laboratory v_x and the particles counted
    std::vector<double> velocity_sum, count;
    std::vector<double> shear_stress; // P_xy of each log row after step 0

    // Bins about one length unit wide, and at least 8.
    static std::size_t default_bins(double length_y) {
        return std::max<std::size_t>(8, static_cast<std::size_t>(std::floor(length_y)));
    }

    template <int D> void add_profile(const ParticleStore<D>& p, const Box<D>& box) {
        if (velocity_sum.empty()) {
            velocity_sum.assign(default_bins(box.length(1)), 0.0);
            count.assign(velocity_sum.size(), 0.0);
        }
        const auto bins = static_cast<double>(velocity_sum.size());
        for (std::size_t i = 0; i < p.size(); ++i) {
            const double u = (p.position[i][1] - box.lo(1)) / box.length(1) * bins;
            const auto b = static_cast<std::size_t>(std::clamp(std::floor(u), 0.0, bins - 1.0));
            velocity_sum[b] += box.lab_velocity(p.position[i], p.velocity[i])[0];
            count[b] += 1.0;
        }
    }

    // velocity_profile.csv: the bin centres y, the mean laboratory v_x there (nan where
    // no particle was counted), the particle samples counted.
    void write_profile(std::ostream& out, double lo_y, double length_y) const {
        out << "y,velocity_x,count\n";
        const auto bins = static_cast<double>(velocity_sum.size());
        for (std::size_t b = 0; b < velocity_sum.size(); ++b) {
            const double y = lo_y + (static_cast<double>(b) + 0.5) * length_y / bins;
            const double v = count[b] > 0.0 ? velocity_sum[b] / count[b] : std::nan("");
            out << fmt::format("{},{},{}\n", y, v, count[b]);
        }
    }

    // The mean of x and its error from `blocks` contiguous blocks (the standard error of
    // the block means); the error is null with fewer samples than blocks.
    static nlohmann::json mean_with_error(const std::vector<double>& x, std::size_t blocks = 8) {
        nlohmann::json j;
        double sum = 0.0;
        for (double v : x) sum += v;
        j["value"] = x.empty() ? nlohmann::json(nullptr) : nlohmann::json(sum / x.size());
        if (x.size() < blocks) {
            j["error"] = nullptr;
            return j;
        }
        std::vector<double> means(blocks, 0.0);
        for (std::size_t b = 0; b < blocks; ++b) {
            const std::size_t first = b * x.size() / blocks, last = (b + 1) * x.size() / blocks;
            for (std::size_t k = first; k < last; ++k) means[b] += x[k];
            means[b] /= static_cast<double>(last - first);
        }
        double mean = 0.0, var = 0.0;
        for (double m : means) mean += m / static_cast<double>(blocks);
        for (double m : means) var += (m - mean) * (m - mean);
        j["error"] = std::sqrt(var / static_cast<double>(blocks * (blocks - 1)));
        return j;
    }

    // summary.json's "shear": the rate, <P_xy> and eta = -<P_xy> / rate, with errors.
    nlohmann::json summary(double rate) const {
        const nlohmann::json stress = mean_with_error(shear_stress);
        nlohmann::json viscosity;
        for (const char* k : {"value", "error"})
            viscosity[k] =
                stress[k].is_null()
                    ? nlohmann::json(nullptr)
                    : nlohmann::json((k[0] == 'v' ? -1.0 : 1.0) * stress[k].get<double>() / rate);
        return {{"rate", rate}, {"shear_stress", stress}, {"viscosity", viscosity}};
    }
};

} // namespace pedesis
