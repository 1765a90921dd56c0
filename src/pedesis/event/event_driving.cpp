// The event engine's external drives: uniform gravity's set-up, the Andersen thermostat
// and the white-noise driving of granular gases (van Noije & Ernst, Granular Matter 1, 57
// (1998)). The stochastic events are a Poisson process each: their random numbers are
// keyed by the seed and the event's number alone (core/rng.hpp), so a restored engine
// draws what the uninterrupted one would have.
#include "pedesis/core/error.hpp"
#include "pedesis/event/event_engine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pedesis {

namespace {
// Event k's random numbers: the first gives the wait before it, the rest its choices.
CounterRng draws(std::uint64_t seed, RngStream stream, std::uint64_t k) {
    return CounterRng(seed, stream, static_cast<std::uint32_t>(k >> 32),
                      static_cast<std::uint32_t>(k));
}
} // namespace

// Gravity along walled axes only: along a periodic one the particles would fall for ever
// (no stationary state). Growth, shear and fixed obstacles would need flights that are
// not parabolas relative to each other, and are refused.
template <int D> void EventEngine<D>::start_gravity() {
    for (int a = 0; a < D; ++a) gravity_[a] = params_.gravity[a];
    falling_ = false;
    for (int a = 0; a < D; ++a) {
        if (gravity_[a] == 0.0) continue;
        falling_ = true;
        if (box_.periodic(a))
            throw InputError(fmt::format(
                "event.gravity: component {:g} along axis {} which is periodic: particles "
                "would fall for ever (no stationary state); make that axis a wall "
                "([box] boundary) or give 0",
                gravity_[a], a));
    }
    if (!falling_) return;
    if (box_.sheared())
        throw InputError("event.gravity: not with Lees-Edwards shear ([box] shear_rate)");
    if (params_.growth_rate > 0.0 || growth_.growing)
        throw InputError("event.gravity: not with growth (event.growth_rate)");
    for (double im : inv_mass_)
        if (im == 0.0)
            throw InputError("event.gravity: fixed obstacles (mass = inf) do not fall, and "
                             "the pair flights relative to them are not straight; not with "
                             "gravity");
    pair_times_ = nullptr; // the batch kernel knows straight flights only
}

template <int D> void EventEngine<D>::start_driving() {
    mobile_.clear();
    for (std::uint32_t i = 0; i < size(); ++i)
        if (inv_mass_[f_[i].species] > 0.0) mobile_.push_back(i);
    const bool andersen = params_.andersen_rate > 0.0, kicks = params_.driving_rate > 0.0;
    if (andersen || kicks) {
        const char* what = andersen ? "event.thermostat = \"andersen\"" : "event.driving";
        if (box_.sheared()) throw InputError(std::string(what) + ": not with Lees-Edwards shear");
        if (params_.growth_rate > 0.0 || growth_.growing)
            throw InputError(std::string(what) + ": not with growth (event.growth_rate)");
        if (mobile_.size() < (kicks ? 2u : 1u))
            throw InputError(std::string(what) + ": needs at least " + (kicks ? "two" : "one") +
                             " mobile particle" + (kicks ? "s" : ""));
    }
    const double n = static_cast<double>(mobile_.size());
    // a restored engine keeps its schedule; a drive the config no longer has stops
    if (!andersen)
        next_andersen_ = never_time;
    else if (next_andersen_ == never_time)
        next_andersen_ = next_stochastic_time(RngStream::andersen, driving_.andersen_events,
                                              params_.andersen_rate * n);
    if (!kicks)
        next_kick_ = never_time;
    else if (next_kick_ == never_time)
        next_kick_ = next_stochastic_time(RngStream::white_noise, driving_.kicks,
                                          0.5 * params_.driving_rate * n);
}

template <int D>
double EventEngine<D>::next_stochastic_time(RngStream stream, std::uint64_t k, double rate) const {
    CounterRng rng = draws(params_.seed, stream, k);
    return now_ - std::log(rng.uniform()) / rate; // (uniform in (0, 1]: a finite wait)
}

template <int D> std::uint32_t EventEngine<D>::random_mobile(CounterRng& rng) const {
    const auto n = static_cast<double>(mobile_.size());
    const auto k = static_cast<std::size_t>(rng.uniform() * n);
    return mobile_[std::min(k, mobile_.size() - 1)];
}

template <int D> double EventEngine<D>::set_velocity(std::uint32_t i, const Vec<D>& v) {
    const double change = 0.5 * mass_of(f_[i].species) * (norm2(v) - norm2(f_[i].v));
    f_[i].v = v;
    ++f_[i].count; // events predicted with i as partner are stale
    kinetic_ += change;
    return change;
}

template <int D> void EventEngine<D>::stochastic_event() {
    if (next_andersen_ <= next_kick_)
        andersen_event();
    else
        kick_event();
    if (kinetic_ < 0.5 * kinetic_exact_) resum_kinetic_energy();
}

template <int D> void EventEngine<D>::andersen_event() {
    const std::uint64_t k = driving_.andersen_events;
    CounterRng rng = draws(params_.seed, RngStream::andersen, k);
    rng.uniform(); // (the wait before this event)
    const std::uint32_t i = random_mobile(rng);
    advance(i);
    const double sd = std::sqrt(params_.andersen_temperature * inv_mass_[f_[i].species]);
    Vec<D> v;
    for (int a = 0; a < D; ++a) v[a] = sd * rng.normal();
    driving_.andersen_energy += set_velocity(i, v);
    ++driving_.andersen_events;
    next_andersen_ = next_stochastic_time(
        RngStream::andersen, k + 1, params_.andersen_rate * static_cast<double>(mobile_.size()));
    queue_.update(i, predict(i));
}

// Two different mobile particles, at random, get opposite momentum kicks.
template <int D> void EventEngine<D>::kick_event() {
    const std::uint64_t k = driving_.kicks;
    CounterRng rng = draws(params_.seed, RngStream::white_noise, k);
    rng.uniform(); // (the wait before this event)
    const std::size_t n = mobile_.size();
    const auto first = static_cast<std::size_t>(rng.uniform() * static_cast<double>(n));
    auto second = static_cast<std::size_t>(rng.uniform() * static_cast<double>(n - 1));
    const std::size_t a_index = std::min(first, n - 1);
    second = std::min(second, n - 2);
    if (second >= a_index) ++second;
    const std::uint32_t i = mobile_[a_index], j = mobile_[second];
    advance(i);
    advance(j);
    const double im_i = inv_mass_[f_[i].species], im_j = inv_mass_[f_[j].species];
    const double scale = std::sqrt(params_.driving_strength / (im_i * im_j));
    Vec<D> dp;
    for (int a = 0; a < D; ++a) dp[a] = scale * rng.normal();
    const Vec<D> vi = f_[i].v + dp * im_i, vj = f_[j].v - dp * im_j;
    driving_.injected_energy += set_velocity(i, vi) + set_velocity(j, vj);
    ++driving_.kicks;
    next_kick_ = next_stochastic_time(RngStream::white_noise, k + 1,
                                      0.5 * params_.driving_rate * static_cast<double>(n));
    queue_.update(i, predict(i));
    queue_.update(j, predict(j));
}

#define PEDESIS_EVENT_DRIVING(D)                                                                   \
    template void EventEngine<D>::start_gravity();                                                 \
    template void EventEngine<D>::start_driving();                                                 \
    template void EventEngine<D>::stochastic_event();                                              \
    template void EventEngine<D>::andersen_event();                                                \
    template void EventEngine<D>::kick_event();                                                    \
    template double EventEngine<D>::next_stochastic_time(RngStream, std::uint64_t, double) const;  \
    template std::uint32_t EventEngine<D>::random_mobile(CounterRng&) const;                       \
    template double EventEngine<D>::set_velocity(std::uint32_t, const Vec<D>&);

PEDESIS_EVENT_DRIVING(2)
PEDESIS_EVENT_DRIVING(3)

} // namespace pedesis
