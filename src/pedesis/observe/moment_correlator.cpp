#include "pedesis/observe/moment_correlator.hpp"

namespace pedesis {

using detail::MultipleTau;

std::vector<MomentCorrelator::Lag> MomentCorrelator::lags() const {
    std::vector<Lag> out;
    const auto channels = static_cast<double>(tau_.channels());
    for (const auto& s : tau_.lags()) {
        const double n = static_cast<double>(s.count) * channels;
        out.push_back({s.tau, s.quadratic / n, s.linear / n, s.count});
    }
    return out;
}

MomentCorrelator MomentCorrelator::load(std::istream& in) {
    return MomentCorrelator(MultipleTau::load(in, MultipleTau::Kind::increments));
}

} // namespace pedesis
