#include "pedesis/observe/speed_histogram.hpp"

#include "pedesis/io/binary_stream.hpp"
#include "pedesis/observe/theory.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ostream>

namespace pedesis {

template <int D> void SpeedHistogram::add(const ParticleStore<D>& p) {
    // The range is fixed at the first sample: 4.5 thermal speeds or 1.2 x the fastest.
    if (samples_ == 0) {
        std::vector<double> kin(per_species_.size(), 0.0), vmax(per_species_.size(), 0.0);
        std::vector<std::size_t> n(per_species_.size(), 0);
        for (std::size_t i = 0; i < p.size(); ++i) {
            if (std::isinf(p.mass(i))) continue;
            const double v2 = norm2(p.velocity[i]);
            kin[p.species[i]] += v2;
            vmax[p.species[i]] = std::max(vmax[p.species[i]], std::sqrt(v2));
            ++n[p.species[i]];
        }
        for (std::size_t s = 0; s < per_species_.size(); ++s) {
            const double thermal = n[s] ? std::sqrt(kin[s] / (D * static_cast<double>(n[s]))) : 0.0;
            double top = std::max(4.5 * thermal, 1.2 * vmax[s]);
            if (!(top > 0.0)) top = 1.0;
            per_species_[s].v_max = top;
            per_species_[s].count.assign(static_cast<std::size_t>(bins_), 0);
        }
    }
    for (std::size_t i = 0; i < p.size(); ++i) {
        const double m = p.mass(i);
        if (std::isinf(m)) continue;
        Bins& b = per_species_[p.species[i]];
        const double v2 = norm2(p.velocity[i]);
        const double v = std::sqrt(v2);
        const auto k = static_cast<std::size_t>(v / b.v_max * bins_);
        if (k < b.count.size()) ++b.count[k];
        ++b.total;
        b.sum_v2_times_m += m * v2;
        ++b.mobile;
    }
    ++samples_;
}

void SpeedHistogram::write_csv(std::ostream& out, int dim, const std::vector<std::string>& names,
                               const std::vector<double>& masses) const {
    out << "species,v_lo,v_hi,density,theory,temperature\n";
    for (std::size_t s = 0; s < per_species_.size(); ++s) {
        const Bins& b = per_species_[s];
        if (b.total == 0) continue;
        const double T = b.sum_v2_times_m / (dim * static_cast<double>(b.mobile));
        const double w = b.v_max / bins_;
        for (std::size_t k = 0; k < b.count.size(); ++k) {
            const double lo = w * static_cast<double>(k), hi = lo + w;
            const double density =
                static_cast<double>(b.count[k]) / (static_cast<double>(b.total) * w);
            // bin average of the theoretical density, so coarse bins compare fairly
            const double theory = (theory::speed_cdf(dim, hi, T, masses[s]) -
                                   theory::speed_cdf(dim, lo, T, masses[s])) /
                                  w;
            out << fmt::format("{},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g}\n", names[s], lo, hi,
                               density, theory, T);
        }
    }
}

void SpeedHistogram::save(std::ostream& out) const {
    binary::put(out, bins_);
    binary::put(out, samples_);
    binary::put<std::uint64_t>(out, per_species_.size());
    for (const Bins& b : per_species_) {
        binary::put(out, b.v_max);
        binary::put(out, b.count);
        binary::put(out, b.total);
        binary::put(out, b.sum_v2_times_m);
        binary::put(out, b.mobile);
    }
}

void SpeedHistogram::load(std::istream& in) {
    std::uint64_t n = 0;
    binary::get(in, bins_);
    binary::get(in, samples_);
    binary::get(in, n);
    if (n > 65535) throw InputError("checkpoint: corrupt histogram");
    per_species_.resize(n);
    for (Bins& b : per_species_) {
        binary::get(in, b.v_max);
        binary::get(in, b.count);
        binary::get(in, b.total);
        binary::get(in, b.sum_v2_times_m);
        binary::get(in, b.mobile);
    }
}

template void SpeedHistogram::add(const ParticleStore<2>&);
template void SpeedHistogram::add(const ParticleStore<3>&);

} // namespace pedesis
