#include "pedesis/run/steering.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/interrupt.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace pedesis {

std::vector<SteeringChange> read_steering(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw InputError(fmt::format("{}: cannot read the steering record", file.string()));
    std::string line;
    std::vector<SteeringChange> out;
    std::size_t number = 1;
    if (!std::getline(in, line) || line != "step,time,parameter,value")
        throw InputError(
            fmt::format("{}:1: expected the header step,time,parameter,value", file.string()));
    while (std::getline(in, line)) {
        ++number;
        if (line.empty()) continue;
        std::istringstream row(line);
        std::string step, time, parameter, value;
        std::getline(row, step, ',');
        std::getline(row, time, ',');
        std::getline(row, parameter, ',');
        std::getline(row, value);
        SteeringChange c;
        try {
            std::size_t used = 0;
            c.step = std::stoull(step, &used);
            if (used != step.size() || step.front() == '-') throw std::invalid_argument("step");
            c.time = std::stod(time);
            c.value = std::stod(value, &used);
            if (used != value.size()) throw std::invalid_argument("value");
        } catch (const std::exception&) {
            throw InputError(fmt::format("{}:{}: expected step,time,parameter,value with numbers "
                                         "(got '{}')",
                                         file.string(), number, line));
        }
        c.parameter = parameter;
        if (!std::isfinite(c.value) || parameter.empty())
            throw InputError(fmt::format("{}:{}: a change needs a parameter and a finite value",
                                         file.string(), number));
        if (!out.empty() && c.step < out.back().step)
            throw InputError(fmt::format("{}:{}: steps must not decrease", file.string(), number));
        out.push_back(std::move(c));
    }
    return out;
}

std::pair<double, double> steering_range(const std::string& parameter, double start) {
    constexpr double widest = 1e6;
    if (parameter == "restitution" || parameter == "wall_restitution") return {0.0, 1.0};
    const double scale = start != 0.0 && std::isfinite(start) ? widest * std::abs(start) : widest;
    if (parameter == "temperature") return {0.0, scale};
    return {-scale, scale};
}

SteeringDesk::SteeringDesk(Run& run, std::filesystem::path record,
                           std::vector<SteeringChange> replay)
    : run_(run), record_path_(std::move(record)), replay_(std::move(replay)),
      values_(run.steerable()) {
    for (const auto& [name, start] : values_) ranges_.push_back(steering_range(name, start));
    for (const SteeringChange& c : replay_)
        if (std::none_of(values_.begin(), values_.end(),
                         [&](const auto& v) { return v.first == c.parameter; }))
            throw InputError(fmt::format("steering record: this run has no parameter '{}' to "
                                         "change",
                                         c.parameter));
    // a restart: what was changed before the checkpoint holds now
    while (next_replay_ < replay_.size() && due(replay_[next_replay_])) {
        apply(replay_[next_replay_]);
        ++next_replay_;
    }
}

SteeringDesk::~SteeringDesk() {
    try {
        write_record();
        if (record_) record_->commit();
    } catch (const std::exception&) {
        // (a destructor must not throw; the ".part" file keeps every whole row)
    }
}

void SteeringDesk::run_ended() {
    {
        std::lock_guard lock(mutex_);
        ended_ = true;
    }
    write_record();
    if (record_) record_->commit();
    record_.reset();
}

std::string SteeringDesk::request(const std::string& parameter, double value) {
    std::lock_guard lock(mutex_);
    if (ended_) return "the run has ended: nothing changes any more";
    const auto known = std::find_if(values_.begin(), values_.end(),
                                    [&](const auto& v) { return v.first == parameter; });
    if (known == values_.end()) {
        std::string names;
        for (const auto& v : values_) names += (names.empty() ? "" : ", ") + v.first;
        return fmt::format("unknown parameter '{}' (this run has: {})", parameter,
                           names.empty() ? "none" : names);
    }
    const auto [lo, hi] = ranges_[static_cast<std::size_t>(known - values_.begin())];
    if (!std::isfinite(value)) return "the value must be a finite number";
    if (!(value >= lo && value <= hi))
        return fmt::format("{} must lie in [{}, {}] (got {})", parameter, lo, hi, value);
    requests_.emplace_back(parameter, value);
    return "";
}

std::vector<SteerableParameter> SteeringDesk::parameters() const {
    std::lock_guard lock(mutex_);
    std::vector<SteerableParameter> out;
    for (std::size_t k = 0; k < values_.size(); ++k)
        out.push_back({values_[k].first, values_[k].second, ranges_[k].first, ranges_[k].second});
    return out;
}

std::string SteeringDesk::failure_note() const {
    if (!last_applied_) return "";
    const SteeringChange& c = *last_applied_;
    return fmt::format(" (after the change of {} to {} at step {}, t = {:.6g}; steering.csv "
                       "records every change)",
                       c.parameter, c.value, c.step, c.time);
}

void SteeringDesk::apply(const SteeringChange& c) {
    run_.steer(c.parameter, c.value);
    {
        std::lock_guard lock(mutex_);
        for (auto& v : values_)
            if (v.first == c.parameter) v.second = c.value;
    }
    last_applied_ = c;
    unwritten_ += fmt::format("{},{},{},{}\n", c.step, c.time, c.parameter, c.value);
}

void SteeringDesk::write_record() {
    if (record_path_.empty() || unwritten_.empty()) return;
    if (!record_) {
        // (first now: the run directory exists once the run has started)
        record_ = std::make_unique<AtomicAppendFile>(record_path_);
        record_->append("step,time,parameter,value\n");
    }
    record_->append(unwritten_);
    unwritten_.clear();
}

bool SteeringDesk::due(const SteeringChange& c) const {
    return run_.has_steps() ? c.step <= run_.step() : c.time <= run_.time();
}

void SteeringDesk::replay_until_done() {
    while (next_replay_ < replay_.size() && !run_.closed()) {
        const std::size_t k = next_replay_;
        const SteeringChange c = replay_[k];
        if (!due(c)) {
            const char* stopped =
                run_.has_steps() ? run_.advance(c.step)
                                 : run_.advance(std::numeric_limits<std::uint64_t>::max(), c.time);
            if (stopped) return; // the run ended first
            // a stepped run short of the step was interrupted; a run without steps that
            // stopped within rounding of the time (a trigger's) has reached it
            if (run_.has_steps() ? !due(c) : interrupt_requested()) return;
        }
        // (the every-step operation may have applied it inside advance already)
        if (next_replay_ == k) {
            apply(c);
            ++next_replay_;
            write_record();
        }
    }
}

void SteeringDesk::apply_due() {
    while (next_replay_ < replay_.size() && due(replay_[next_replay_])) {
        apply(replay_[next_replay_]);
        ++next_replay_;
    }
    std::deque<std::pair<std::string, double>> due;
    {
        std::lock_guard lock(mutex_);
        due.swap(requests_);
    }
    for (const auto& [parameter, value] : due) apply({run_.step(), run_.time(), parameter, value});
    write_record();
}

} // namespace pedesis
