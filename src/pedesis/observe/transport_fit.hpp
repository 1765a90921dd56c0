#pragma once
// From sampled moments and correlation functions to transport coefficients with errors.
//
// The fit-window rule (one rule for every coefficient, never tuned per case): the run is cut
// into independent blocks of block_time; a coefficient is the least-squares slope of the
// mean square increment against tau over the lags from tau_max / 4 to tau_max, with
// tau_max = block_time / 10, so that each block holds at least ten independent windows of
// the longest lag fitted (its mean square is then averaged well inside every block), and the
// window spans a factor of four in time (16 or 17 lags of the default multiple-tau grid
// once block_time holds 320 intervals). The value is the mean of the blocks' values, its error
// their standard error. The window must start past the moment's ballistic start: for a flux that
// decorrelates exponentially in a time tau_c the slope at t is low by e^(-t / tau_c) relative, so a
// block_time of 200 tau_c (window from 5 tau_c) leaves a bias under 1 %.
//
// Conventions: a coefficient is scale x slope / 2: the self-diffusion coefficient from the
// unwrapped coordinates of every particle (channels = d N, scale = 1: D = <dx_a^2> / (2 t)
// per axis); the shear viscosity from the off-diagonal Helfand moments (scale = 1 / (V T));
// thermal conductivity from the energy moments (scale = 1 / (V T^2)); the bulk viscosity
// with remove_drift (the moment of the pressure grows with the mean pressure).
//
// Drift removal (EinsteinEstimator): the moment's mean flux c is that of the whole run,
// c = (G(T) - G(0)) / T averaged over the channels, and each lag's mean square of G - c t
// follows from its mean square and mean, <(dG - c tau)^2> = ms - 2 c tau mean + c^2 tau^2,
// divided by 1 - tau / T: for a diffusing moment whose drift is estimated from the same
// run of length T, the expectation is 2 D tau (1 - tau / T) (a Brownian bridge), so the
// quotient is unbiased. Removing each block's own mean instead (mean_square - mean^2 per
// block) is biased low by the same factor with the block's length, about 14 % over the
// fit window.
#include "pedesis/observe/auto_correlator.hpp"
#include "pedesis/observe/moment_correlator.hpp"

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <vector>

namespace pedesis {

struct FitWindow {
    double from, to;
};

// [block_time / 40, block_time / 10]. Throws InputError unless block_time > 0 and finite.
FitWindow fit_window(double block_time);

// Least-squares slope (with intercept) of mean_square, or of mean_square - mean^2 with
// remove_drift, against tau over the lags with from <= tau <= to (ends widened by 1e-9
// relative, so that a lag on the boundary counts whatever the rounding); NaN with fewer than
// two such lags.
double einstein_slope(const std::vector<MomentCorrelator::Lag>& lags, FitWindow window,
                      bool remove_drift);

struct Estimate {
    double value, error;
    std::size_t blocks;
};

// Mean and standard error (sample standard deviation / sqrt(B)); error NaN when B < 2,
// value NaN when B = 0.
Estimate block_estimate(const std::vector<double>& per_block);

// Running Green-Kubo integral of a correlation function by the trapezoid rule from tau = 0,
// one value per lag (the AutoCorrelator's lags start at tau = 0, where the integral is 0; a
// list starting later counts its first value as constant from 0).
std::vector<double> running_integral(const std::vector<AutoCorrelator::Lag>& lags);

// One transport coefficient from one moment: a whole-run correlator for the curve and the
// fallback value, and a correlator restarted every block_time for the error. Blocks share
// their boundary sample (block b spans [b, b + 1] block_time) and only whole blocks count.
class EinsteinEstimator {
  public:
    struct Row {
        double tau;
        double mean_square; // the fitted quantity: minus mean^2 with remove_drift
        double running;     // scale x (centred slope of mean_square between neighbours) / 2
    };

    // block_time is rounded to a whole number of intervals and must hold at least 20
    // (InputError otherwise): the window then holds two lags or more.
    EinsteinEstimator(std::size_t channels, double interval, double block_time, double scale,
                      bool remove_drift);

    // The channels' running sums at the next sample time (samples `interval` apart).
    void add(const double* values);

    // Mean and standard error of the blocks' coefficients with two blocks or more; else the
    // whole run's coefficient, error NaN.
    Estimate estimate() const;
    // From the whole-run correlator; the running slope is the Einstein counterpart of a
    // Green-Kubo running integral: it levels off at the coefficient.
    std::vector<Row> rows() const;
    // fit_window(block_time) unless set: a run that knows its flux's time scale fits
    // there (run/transport_plan.cpp), within the block's [block_time/40, block_time/10].
    FitWindow window() const { return window_.to > 0.0 ? window_ : fit_window(block_time()); }
    void set_window(FitWindow w) { window_ = w; }

    double block_time() const { return static_cast<double>(block_steps_) * interval_; }
    // The coefficient of each whole block (with the whole run's drift, if removed).
    std::vector<double> block_values() const;
    // The whole run's mean flux per channel (0 before two samples).
    double drift() const;
    const MomentCorrelator& correlator() const { return whole_; }
    std::size_t memory_bytes() const;

    void save(std::ostream& out) const;
    // Throws InputError on a truncated, foreign or inconsistent stream.
    static EinsteinEstimator load(std::istream& in);

  private:
    double coefficient(const std::vector<MomentCorrelator::Lag>& lags) const;
    double fitted(const MomentCorrelator::Lag& lag) const;

    double interval_, scale_;
    bool remove_drift_;
    std::uint64_t block_steps_;
    MomentCorrelator whole_, block_;
    // each whole block's lags (about a hundred: kilobytes per block), fitted at the end
    // with the whole run's drift
    std::vector<std::vector<MomentCorrelator::Lag>> block_lags_;
    double first_mean_ = 0.0, last_mean_ = 0.0; // the channels' mean at the first and last sample
    FitWindow window_{0.0, 0.0};                // unset: fit_window(block_time)
};

} // namespace pedesis
