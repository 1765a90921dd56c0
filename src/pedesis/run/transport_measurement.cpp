#include "pedesis/run/transport_measurement.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/binary_stream.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <ostream>

namespace pedesis {

namespace {

constexpr std::uint64_t transport_magic = 0x54524f5053415254ull; // "TRASPORT"
// 2: add_flux's running heat integral (1 is read with none)
constexpr std::uint32_t transport_version = 2;
constexpr std::size_t min_block_samples = 20;

// The shear viscosity's channels: the off-diagonal moments (xy; xy, xz, yz) and the
// normal-stress differences (G_xx - G_yy) / 2 (3D also (G_yy - G_zz) / 2), which in an
// isotropic fluid have the same Einstein coefficient V T eta (the traceless part of the
// stress; Daivis & Evans, J. Chem. Phys. 100, 541 (1994)): d (d - 1) / 2 + d - 1 of them.
template <int D> constexpr int shear_channels() {
    return D * (D - 1) / 2 + D - 1;
}

nlohmann::json number_or_null(double x) {
    return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
}

nlohmann::json coefficient(const Estimate& e, double scale) {
    return {{"value", number_or_null(e.value * scale)}, {"error", number_or_null(e.error * scale)}};
}

nlohmann::json missing(const std::string& why) {
    return {{"value", nullptr}, {"error", nullptr}, {"why", why}};
}

void put_optional(std::ostream& out, const std::unique_ptr<EinsteinEstimator>& e) {
    binary::put<std::uint8_t>(out, e != nullptr);
    if (e) e->save(out);
}

std::unique_ptr<EinsteinEstimator> get_optional(std::istream& in) {
    std::uint8_t has = 0;
    binary::get(in, has);
    if (has > 1) throw InputError("transport: corrupt state");
    return has ? std::make_unique<EinsteinEstimator>(EinsteinEstimator::load(in)) : nullptr;
}

} // namespace

template <int D>
TransportMeasurement<D>::TransportMeasurement(const Plan& plan, const std::string& where)
    : plan_(plan) {
    const double diffusion_interval = plan.interval * static_cast<double>(plan.diffusion_every);
    // a run's samples are its length over the interval: bounded, so that a tiny interval
    // is an error now rather than a run that never ends
    if (!(plan.interval > 0.0) || plan.block_time / plan.interval > 1e8)
        throw InputError(fmt::format("{}: interval {:g} gives more than 10^8 samples a block "
                                     "of {:g}: raise interval",
                                     where, plan.interval, plan.block_time));
    const double needed = static_cast<double>(min_block_samples) *
                          (plan.particles ? diffusion_interval : plan.interval);
    if (!(plan.block_time >= needed * (1.0 - 1e-9)))
        throw InputError(fmt::format(
            "{}: a block of {:g} holds fewer than {} samples ({:.4g} apart): lengthen the run or "
            "block_time, or shorten interval{}",
            where, plan.block_time, min_block_samples,
            plan.particles ? diffusion_interval : plan.interval,
            plan.particles ? " and diffusion_interval" : ""));
    shear_ = std::make_unique<EinsteinEstimator>(shear_channels<D>(), plan.interval,
                                                 plan.block_time, 1.0, false);
    bulk_ = std::make_unique<EinsteinEstimator>(1, plan.interval, plan.block_time, 1.0, true);
    if (plan.heat)
        heat_ = std::make_unique<EinsteinEstimator>(D, plan.interval, plan.block_time, 1.0, false);
    if (plan.particles) {
        diffusion_ = std::make_unique<EinsteinEstimator>(D * plan.particles, diffusion_interval,
                                                         plan.block_time, 1.0, false);
        if (plan.vacf) vacf_ = std::make_unique<AutoCorrelator>(D * plan.particles, plan.interval);
    }
    set_windows();
}

template <int D> bool TransportMeasurement<D>::window_limited() const {
    const double end = 80.0 * plan_.time_scale;
    return !(end > 0.0 && 10.0 * end <= plan_.block_time);
}

template <int D> void TransportMeasurement<D>::set_windows() {
    if (window_limited()) return; // the estimators' own: the block's
    const FitWindow w{20.0 * plan_.time_scale, 80.0 * plan_.time_scale};
    for (auto* e : {shear_.get(), bulk_.get(), heat_.get(), diffusion_.get()})
        if (e) e->set_window(w);
}

template <int D>
void TransportMeasurement<D>::add(const SymTensor& G, const Vec<D>& H,
                                  const std::vector<Vec<D>>& unwrapped,
                                  const std::vector<Vec<D>>& velocities) {
    double shear[shear_channels<D>()];
    int k = 0;
    for (int a = 0; a < D; ++a)
        for (int b = a + 1; b < D; ++b) shear[k++] = G[sym_slot(a, b)];
    for (int a = 0; a + 1 < D; ++a) shear[k++] = 0.5 * (G[a] - G[a + 1]);
    shear_->add(shear);
    const double mean_diagonal = sym_trace<D>(G) / D;
    bulk_->add(&mean_diagonal);
    if (heat_) {
        double h[D];
        for (int a = 0; a < D; ++a) h[a] = H[a];
        heat_->add(h);
    }
    const auto flatten = [&](const std::vector<Vec<D>>& v) {
        scratch_.resize(D * v.size());
        for (std::size_t i = 0; i < v.size(); ++i)
            for (int a = 0; a < D; ++a) scratch_[D * i + a] = v[i][a];
        return scratch_.data();
    };
    if (positions_due()) {
        if (unwrapped.size() != plan_.particles)
            throw std::logic_error("TransportMeasurement: positions of the wrong particles");
        diffusion_->add(flatten(unwrapped));
    }
    if (velocities_due()) {
        if (velocities.size() != plan_.particles)
            throw std::logic_error("TransportMeasurement: velocities of the wrong particles");
        vacf_->add(flatten(velocities));
    }
    ++samples_;
}

template <int D>
void TransportMeasurement<D>::add_flux(const SymTensor& volume_times_pressure,
                                       const Vec<D>* heat_flux,
                                       const std::vector<Vec<D>>& unwrapped,
                                       const std::vector<Vec<D>>& velocities) {
    for (int c = 0; c < 6; ++c) flux_integral_[c] += volume_times_pressure[c] * plan_.interval;
    if (heat_flux) heat_integral_ += *heat_flux * plan_.interval;
    add(flux_integral_, heat_integral_, unwrapped, velocities);
}

template <int D> nlohmann::json TransportMeasurement<D>::summary(const Scales& s) const {
    const double VT = s.volume * s.temperature;
    nlohmann::json j;
    const Estimate shear = shear_->estimate();
    j["shear_viscosity"] = coefficient(shear, 1.0 / VT);
    j["bulk_viscosity"] =
        s.bulk_missing.empty() ? coefficient(bulk_->estimate(), 1.0 / VT) : missing(s.bulk_missing);
    if (heat_)
        j["thermal_conductivity"] = coefficient(heat_->estimate(), 1.0 / (VT * s.temperature));
    else
        j["thermal_conductivity"] = missing(s.heat_missing);
    if (diffusion_) {
        const Estimate d = diffusion_->estimate();
        j["diffusion"] = coefficient(d, 1.0);
        if (D == 3) {
            if (s.cube_edge > 0.0) {
                // D_inf = D + c / eta, c = xi T / (6 pi L): errors added in quadrature
                const double eta = shear.value / VT, eta_error = shear.error / VT;
                const double c = 2.837297 * s.temperature / (6.0 * std::numbers::pi * s.cube_edge);
                const double value = theory::yeh_hummer(d.value, s.temperature, eta, s.cube_edge);
                const double error = std::hypot(d.error, c * eta_error / (eta * eta));
                j["diffusion_infinite"] = {{"value", number_or_null(eta > 0 ? value : NAN)},
                                           {"error", number_or_null(eta > 0 ? error : NAN)}};
            } else {
                j["diffusion_infinite"] = missing("the Yeh-Hummer correction is for cubic boxes");
            }
        }
        if (vacf_) {
            const auto lags = vacf_->lags();
            const auto integral = running_integral(lags);
            // the integral's mean over the fit window (the plateau of Green-Kubo's D)
            const FitWindow w = diffusion_->window();
            double sum = 0.0;
            int n = 0;
            for (std::size_t i = 0; i < lags.size(); ++i)
                if (lags[i].tau >= w.from && lags[i].tau <= w.to) {
                    sum += integral[i];
                    ++n;
                }
            j["diffusion_velocity_autocorrelation"] = {{"value", number_or_null(n ? sum / n : NAN)},
                                                       {"error", nullptr}};
        }
    } else {
        j["diffusion"] = missing("no particle followed ([transport] particles)");
    }
    const FitWindow w = shear_->window();
    j["fit_window"] = {{"from", w.from}, {"to", w.to}};
    // [20, 80] mean free times, or the block's own when the blocks are too short for it
    j["fit_window_rule"] = window_limited() ? "block" : "mean_free_time";
    j["time_scale"] = plan_.time_scale;
    j["blocks"] = shear.blocks;
    j["block_time"] = shear_->block_time();
    j["interval"] = plan_.interval;
    j["diffusion_interval"] = plan_.interval * static_cast<double>(plan_.diffusion_every);
    j["particles"] = plan_.particles;
    j["samples"] = samples_;
    j["temperature"] = s.temperature;
    if (s.enskog)
        j["enskog"] = {{"diffusion", s.enskog->diffusion},
                       {"shear_viscosity", s.enskog->shear_viscosity},
                       {"bulk_viscosity", s.enskog->bulk_viscosity},
                       {"thermal_conductivity", s.enskog->thermal_conductivity}};
    return j;
}

template <int D>
void TransportMeasurement<D>::write_csv(const std::filesystem::path& path, const Scales& s) const {
    const double VT = s.volume * s.temperature;
    write_file_atomically(path, [&](std::ostream& out) {
        out << "quantity,lag,correlation,running_coefficient\n";
        const auto rows = [&](const char* name, const EinsteinEstimator& e,
                              double correlation_scale, double scale) {
            for (const auto& r : e.rows())
                out << fmt::format("{},{:.10g},{:.10g},{:.10g}\n", name, r.tau,
                                   r.mean_square * correlation_scale, r.running * scale);
        };
        if (diffusion_) rows("diffusion", *diffusion_, D, 1.0);
        rows("shear_viscosity", *shear_, 1.0, 1.0 / VT);
        if (s.bulk_missing.empty()) rows("bulk_viscosity", *bulk_, 1.0, 1.0 / VT);
        if (heat_) rows("thermal_conductivity", *heat_, 1.0, 1.0 / (VT * s.temperature));
        if (vacf_) {
            const auto lags = vacf_->lags();
            const auto integral = running_integral(lags);
            for (std::size_t i = 0; i < lags.size(); ++i)
                out << fmt::format("velocity_autocorrelation,{:.10g},{:.10g},{:.10g}\n",
                                   lags[i].tau, D * lags[i].correlation, integral[i]);
        }
    });
}

template <int D> void TransportMeasurement<D>::save(std::ostream& out) const {
    binary::put(out, transport_magic);
    binary::put(out, transport_version);
    binary::put(out, plan_.start);
    binary::put(out, plan_.interval);
    binary::put(out, plan_.diffusion_every);
    binary::put(out, plan_.block_time);
    binary::put<std::uint64_t>(out, plan_.particles);
    binary::put<std::uint8_t>(out, plan_.heat);
    binary::put<std::uint8_t>(out, plan_.vacf);
    binary::put(out, plan_.time_scale);
    binary::put(out, samples_);
    binary::put(out, flux_integral_);
    binary::put(out, heat_integral_);
    shear_->save(out);
    bulk_->save(out);
    put_optional(out, heat_);
    put_optional(out, diffusion_);
    binary::put<std::uint8_t>(out, vacf_ != nullptr);
    if (vacf_) vacf_->save(out);
}

template <int D>
TransportMeasurement<D> TransportMeasurement<D>::load(std::istream& in, const std::string& where) {
    std::uint64_t magic = 0, particles = 0;
    std::uint32_t version = 0;
    std::uint8_t heat = 0, vacf = 0;
    binary::get(in, magic);
    binary::get(in, version);
    if (magic != transport_magic || version < 1 || version > transport_version)
        throw InputError("transport: not a transport measurement of this version");
    TransportMeasurement m;
    binary::get(in, m.plan_.start);
    binary::get(in, m.plan_.interval);
    binary::get(in, m.plan_.diffusion_every);
    binary::get(in, m.plan_.block_time);
    binary::get(in, particles);
    binary::get(in, heat);
    binary::get(in, vacf);
    binary::get(in, m.plan_.time_scale);
    binary::get(in, m.samples_);
    binary::get(in, m.flux_integral_);
    if (version >= 2) binary::get(in, m.heat_integral_);
    m.plan_.particles = particles;
    m.plan_.heat = heat != 0;
    m.plan_.vacf = vacf != 0;
    m.shear_ = std::make_unique<EinsteinEstimator>(EinsteinEstimator::load(in));
    m.bulk_ = std::make_unique<EinsteinEstimator>(EinsteinEstimator::load(in));
    m.heat_ = get_optional(in);
    m.diffusion_ = get_optional(in);
    std::uint8_t has_vacf = 0;
    binary::get(in, has_vacf);
    if (has_vacf) m.vacf_ = std::make_unique<AutoCorrelator>(AutoCorrelator::load(in));
    // the parts must be those the plan makes, with its sizes
    const bool consistent =
        heat <= 1 && vacf <= 1 && has_vacf <= 1 && std::isfinite(m.plan_.start) &&
        std::isfinite(m.plan_.time_scale) && m.plan_.time_scale >= 0.0 && m.plan_.interval > 0.0 &&
        m.plan_.diffusion_every >= 1 && m.shear_->correlator().channels() == shear_channels<D>() &&
        m.shear_->correlator().samples() == m.samples_ && m.bulk_->correlator().channels() == 1 &&
        (m.heat_ != nullptr) == m.plan_.heat &&
        (!m.heat_ || m.heat_->correlator().channels() == D) &&
        (m.diffusion_ != nullptr) == (particles > 0) &&
        (!m.diffusion_ || m.diffusion_->correlator().channels() == D * particles) &&
        (m.vacf_ != nullptr) == (particles > 0 && m.plan_.vacf) &&
        (!m.vacf_ || m.vacf_->channels() == D * particles);
    if (!consistent) throw InputError(where + ": transport: corrupt state in the checkpoint");
    return m;
}

void print_transport(std::ostream& out, const nlohmann::json& t) {
    static const std::pair<const char*, const char*> rows[] = {
        {"diffusion", "diffusion D"},
        {"diffusion_infinite", "D (Yeh-Hummer)"},
        {"diffusion_velocity_autocorrelation", "D (Green-Kubo)"},
        {"shear_viscosity", "shear viscosity"},
        {"bulk_viscosity", "bulk viscosity"},
        {"thermal_conductivity", "heat conductivity"}};
    for (const auto& [key, label] : rows) {
        if (!t.contains(key)) continue;
        const auto& c = t[key];
        std::string line;
        if (c["value"].is_null())
            line = c.contains("why") ? "not measured: " + c["why"].get<std::string>()
                                     : std::string("not measured");
        else if (c["error"].is_null())
            line =
                fmt::format("{:.5g} (no error: fewer than two blocks)", c["value"].get<double>());
        else
            line =
                fmt::format("{:.5g} +- {:.2g}", c["value"].get<double>(), c["error"].get<double>());
        if (t.contains("enskog") && t["enskog"].contains(key))
            line += fmt::format("  (Enskog {:.5g})", t["enskog"][key].get<double>());
        out << fmt::format("  {:<18} {}\n", label, line);
    }
    out << fmt::format("  transport fit      lags {:.4g} to {:.4g} in {} blocks of {:.4g} "
                       "(transport.csv)\n",
                       t["fit_window"]["from"].get<double>(), t["fit_window"]["to"].get<double>(),
                       t["blocks"].get<std::size_t>(), t["block_time"].get<double>());
}

template class TransportMeasurement<2>;
template class TransportMeasurement<3>;

} // namespace pedesis
