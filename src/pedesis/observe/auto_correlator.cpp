#include "pedesis/observe/auto_correlator.hpp"

namespace pedesis {

using detail::MultipleTau;

std::vector<AutoCorrelator::Lag> AutoCorrelator::lags() const {
    std::vector<Lag> out;
    const auto channels = static_cast<double>(tau_.channels());
    for (const auto& s : tau_.lags())
        out.push_back({s.tau, s.quadratic / (static_cast<double>(s.count) * channels), s.count});
    return out;
}

AutoCorrelator AutoCorrelator::load(std::istream& in) {
    return AutoCorrelator(MultipleTau::load(in, MultipleTau::Kind::products));
}

} // namespace pedesis
