#pragma once
// [transport]: the transport coefficients a run measures as it goes, the same way for
// every engine (docs/engines.md, "Transport coefficients"):
// - self-diffusion D from the mean square displacement of the followed particles'
//   unwrapped positions (and, if asked, the Green-Kubo integral of their velocity
//   autocorrelation), with the Yeh-Hummer correction in 3D;
// - shear viscosity from the off-diagonal Helfand moments G_ab = V ∫ P_ab dt, bulk
//   viscosity from G's trace / d less its mean growth, thermal conductivity from the
//   energy moment H = ∫ J_q dt (engines that give it);
// each an Einstein slope over the fit window of observe/transport_fit.hpp with its error
// from independent blocks. Samples come at fixed times; the engine's run stops at each.
#include "pedesis/core/sym_tensor.hpp"
#include "pedesis/core/vec.hpp"
#include "pedesis/observe/auto_correlator.hpp"
#include "pedesis/observe/theory.hpp"
#include "pedesis/observe/transport_fit.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pedesis {

template <int D> class TransportMeasurement {
  public:
    struct Plan {
        double start = 0.0;                // time of the first sample
        double interval = 0.0;             // between samples of the moments
        std::uint64_t diffusion_every = 1; // moment samples per sample of the positions
        double block_time = 0.0;
        std::size_t particles = 0; // followed for D (and the velocity autocorrelation)
        bool heat = true;          // the engine gives the energy moment H
        bool vacf = false;
        // The fit window is [20, 80] of this time (the Enskog mean free time: the fluxes
        // decorrelate within a few of it), if the blocks hold ten times its end; else
        // (0, or blocks too short) the block's [block_time / 40, block_time / 10].
        double time_scale = 0.0;
    };
    // What the run knows at the end: the coefficients' units and the references.
    struct Scales {
        double volume = 0.0;
        double temperature = 0.0;
        double cube_edge = 0.0; // the box's edge if cubic (Yeh-Hummer), else 0
        std::optional<theory::TransportCoefficients> enskog;
        std::string heat_missing; // why no thermal conductivity, if none
        std::string bulk_missing; // why no bulk viscosity, if none
    };

    // InputError (naming `where`) if a block holds fewer than 20 samples of a moment.
    TransportMeasurement(const Plan& plan, const std::string& where);

    const Plan& plan() const { return plan_; }
    std::uint64_t samples() const { return samples_; }
    // Whether the fit window is the block's (the run too short for [20, 80] time scales).
    bool window_limited() const;
    double next_time() const {
        return plan_.start + static_cast<double>(samples_) * plan_.interval;
    }
    bool positions_due() const { return plan_.particles && samples_ % plan_.diffusion_every == 0; }
    bool velocities_due() const { return plan_.particles && plan_.vacf; }

    // The sample at next_time(): the moments, and the followed particles' unwrapped
    // positions (if positions_due()) and velocities (if velocities_due()), else empty.
    void add(const SymTensor& G, const Vec<D>& H, const std::vector<Vec<D>>& unwrapped,
             const std::vector<Vec<D>>& velocities);

    // The same for an engine that gives the pressure tensor at the sample (times the
    // volume) and the heat flux (null: none) instead of their integrals: G and H are their
    // running sums times the interval (the Einstein form of Green-Kubo's integrals), kept
    // here.
    void add_flux(const SymTensor& volume_times_pressure, const Vec<D>* heat_flux,
                  const std::vector<Vec<D>>& unwrapped, const std::vector<Vec<D>>& velocities);

    // summary.json's "transport".
    nlohmann::json summary(const Scales& s) const;
    // transport.csv: quantity,lag,correlation,running_coefficient.
    void write_csv(const std::filesystem::path& path, const Scales& s) const;

    void save(std::ostream& out) const;
    static TransportMeasurement load(std::istream& in, const std::string& where);

  private:
    TransportMeasurement() = default;
    void set_windows();
    Plan plan_;
    std::uint64_t samples_ = 0;
    std::unique_ptr<EinsteinEstimator> shear_, bulk_, heat_, diffusion_;
    std::unique_ptr<AutoCorrelator> vacf_;
    std::vector<double> scratch_;
    SymTensor flux_integral_{}; // add_flux's running G
    Vec<D> heat_integral_{};    // and H
};

// The run's closing lines for summary.json's "transport": each coefficient with its error
// and Enskog's value beside it, then the fit window.
void print_transport(std::ostream& out, const nlohmann::json& transport);

extern template class TransportMeasurement<2>;
extern template class TransportMeasurement<3>;

} // namespace pedesis
