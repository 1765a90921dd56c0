#include "pedesis/run/simulation.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/interrupt.hpp"
#include "pedesis/core/stage.hpp"
#include "pedesis/observe/quantities.hpp"
#include "pedesis/run/run_directory.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <stdexcept>

namespace pedesis {

template <int D>
Simulation<D>::Simulation(RunEngine<D>& engine, Schedule schedule, OutputChoice outputs,
                          const RunOptions& options)
    : engine_(engine), schedule_(std::move(schedule)), outputs_(std::move(outputs)),
      options_(options) {
    if (!in_directory() && (schedule_.frames.active() || schedule_.checkpoint.active()))
        throw std::logic_error("Simulation: frames and checkpoints need a run directory");
    logged_ = engine_.log_columns();
    const std::vector<std::string>& logged = logged_;
    for (const std::string& name : logged) {
        const QuantityInfo* q = find_quantity(name);
        if (!q)
            throw std::logic_error("log column '" + name + "' is not in the quantity catalogue");
        may_be_infinite_.push_back(q->may_be_infinite);
        is_count_.push_back(q->count);
    }
    std::vector<std::string> chosen = outputs_.quantities.empty() ? logged : outputs_.quantities;
    for (const std::string& name : chosen) {
        const auto it = std::find(logged.begin(), logged.end(), name);
        if (it == logged.end()) {
            std::string known;
            for (const std::string& l : logged) known += (known.empty() ? "" : ", ") + l;
            const std::string where = outputs_.quantities_where.empty()
                                          ? options_.config_path.string() + ": [log] quantities"
                                          : outputs_.quantities_where;
            throw InputError(where + ": '" + name +
                             "' is not measured by this run (it measures: " + known + ")");
        }
        columns_.push_back(static_cast<std::size_t>(it - logged.begin()));
        chosen_.push_back(name);
    }
}

template <int D> void Simulation<D>::open() {
    if (opened_) return;
    opened_ = true;
    if (in_directory())
        on_process_zero(options_.comm, [&] {
            if (options_.resume_marks) {
                reopen_outputs();
                return;
            }
            const auto& dir = options_.out_dir;
            const std::vector<const char*> stale = engine_.stale_results();
            prepare_run_directory(dir, options_.config_path, options_.config_text, stale,
                                  options_.restart ? RunStart::restarted : RunStart::fresh);
            log_ = std::make_unique<AtomicAppendFile>(dir / "log.csv");
            std::string header;
            for (std::size_t c : columns_) header += (header.empty() ? "" : ",") + logged_[c];
            log_->append(header + "\n");
            frames_ = std::make_unique<FrameWriters<D>>(dir, outputs_.formats);
        });

    const bool fresh = !options_.restart;
    engine_.start(fresh);
    // a restarted run writes nothing at its start: the run it continues did
    if (fresh && in_directory()) {
        write_log_row();
        write_frame();
    }
    for (Trigger* t : {&schedule_.log, &schedule_.frames, &schedule_.checkpoint})
        t->schedule(engine_.step(), engine_.time());
    for (Operation& op : operations_) op.trigger.schedule(engine_.step(), engine_.time());
    last_checkpoint_wall_ = std::chrono::steady_clock::now();
}

template <int D> void Simulation<D>::reopen_outputs() {
    const auto& dir = options_.out_dir;
    const std::vector<OutputMarks>& all = *options_.resume_marks;
    const auto m = std::find_if(all.begin(), all.end(), [&](const OutputMarks& x) {
        return marks_at(x, engine_.step(), engine_.time());
    });
    if (m == all.end() || m->frames.frames != engine_.frames())
        throw InputError(fmt::format(
            "{}: no marks of the checkpoint {} (t = {:.17g}, step {}), so its outputs cannot be "
            "cut back to it; start the run again without --resume",
            (dir / checkpoint_record_file).string(), options_.restart->string(), engine_.time(),
            engine_.step()));
    prepare_run_directory(dir, options_.config_path, options_.config_text, engine_.stale_results(),
                          RunStart::resumed);
    log_ = std::make_unique<AtomicAppendFile>(dir / "log.csv", m->log_bytes);
    frames_ = std::make_unique<FrameWriters<D>>(dir, outputs_.formats, m->frames);
    marks_ = {*m};
}

template <int D> void Simulation<D>::write_checkpoint(bool final) {
    enter_stage("writing a checkpoint");
    const auto& dir = options_.out_dir;
    on_process_zero(options_.comm, [&] {
        // every row and frame the marks count on the disk before the marks, and the marks
        // before the checkpoint
        log_->sync();
        frames_->sync();
        OutputMarks m;
        m.step = engine_.step();
        m.time = engine_.time();
        m.log_bytes = log_->bytes();
        m.frames = frames_->marks(engine_.frames());
        m.final = final;
        if (!marks_.empty() && marks_at(marks_.back(), m.step, m.time)) marks_.pop_back();
        if (marks_.size() > 1) marks_.erase(marks_.begin());
        marks_.push_back(m);
        write_checkpoint_record(dir / checkpoint_record_file, marks_);
    });
    engine_.save_checkpoint(dir / "checkpoint.bin");
    last_checkpoint_wall_ = std::chrono::steady_clock::now();
}

template <int D> void Simulation<D>::add_operation(Trigger trigger, std::function<void()> act) {
    if (opened_) trigger.schedule(engine_.step(), engine_.time());
    operations_.push_back({trigger, std::move(act)});
}

template <int D> const char* Simulation<D>::advance(std::uint64_t max_step, double max_time) {
    if (closed_) throw std::logic_error("Simulation::advance after close");
    const CleanStopWindow window; // a signal from here on stops at a step boundary
    enter_stage("running");
    // a time limit within rounding of the clock is reached (a stepped clock is k dt)
    const auto reached = [&] {
        return engine_.step() >= max_step ||
               engine_.time() >= max_time - 1e-9 * std::max(1.0, std::abs(max_time));
    };
    try {
        open();
        // a signal (core/interrupt.hpp) ends the loop at the engine's next return, with
        // the state whole: the caller decides whether to close the run or go on
        while (!stopped_by_ && !reached() && !engine_.interrupted()) {
            std::uint64_t until_step = max_step;
            double until_time = max_time;
            for (const Trigger* t : {&schedule_.log, &schedule_.frames, &schedule_.checkpoint}) {
                until_step = std::min(until_step, t->next_step());
                until_time = std::min(until_time, t->next_time());
            }
            for (const Operation& op : operations_) {
                until_step = std::min(until_step, op.trigger.next_step());
                until_time = std::min(until_time, op.trigger.next_time());
            }
            const Advance a = engine_.advance(until_step, until_time);
            stopped_by_ = a.stopped_by;
            const std::uint64_t step = engine_.step();
            const double time = engine_.time();
            // the end of the run always has a log row; its frame and checkpoint come at close
            if (schedule_.log.due(step, time) || stopped_by_ || a.log_now) {
                write_log_row();
                schedule_.log.schedule(step, time);
            }
            if (stopped_by_) break;
            if (schedule_.frames.due(step, time)) {
                write_frame();
                schedule_.frames.schedule(step, time);
            }
            bool clock_due = options_.checkpoint_seconds > 0.0 && in_directory() &&
                             std::chrono::steady_clock::now() - last_checkpoint_wall_ >=
                                 std::chrono::duration<double>(options_.checkpoint_seconds);
            // the processes of a run write a checkpoint together: when the first is due
            if (options_.checkpoint_seconds > 0.0 && options_.comm && options_.comm->size() > 1)
                clock_due = options_.comm->max(clock_due ? 1.0 : 0.0) > 0.0;
            if (schedule_.checkpoint.due(step, time) || clock_due) {
                write_checkpoint(false);
                schedule_.checkpoint.schedule(step, time);
            }
            for (Operation& op : operations_)
                if (op.trigger.due(step, time)) {
                    op.act();
                    op.trigger.schedule(step, time);
                }
        }
    } catch (const RunError& e) {
        fail(e);
    }
    // (any other exception, an interrupt or a callback's error, leaves a good state)
    return stopped_by_;
}

template <int D> void Simulation<D>::close(const char* ended_by) {
    const CleanStopWindow window; // the close completes; a second SIGINT cuts it short
    open();
    if (closed_) return;
    closed_ = true;
    if (!in_directory()) return;
    const auto& dir = options_.out_dir;
    const bool finished = stopped_by_ != nullptr;
    // An unfinished run's checkpoint comes before the row and frame that show where it
    // stopped: --resume continues the state the run had there and cuts those two away,
    // as a run that never stopped has neither. A finished run's close keeps the checkpoint
    // before it until the close is complete (previous_checkpoint_file): a run killed
    // inside the close continues from there.
    if (!finished)
        write_checkpoint(false);
    else
        on_process_zero(options_.comm, [&] { keep_previous_checkpoint(dir); });
    // the end of the run always has a log row (summary.json's "final" is that row)
    if (rows_this_run_ == 0 || last_row_step_ != engine_.step() || last_row_time_ != engine_.time())
        try {
            write_log_row();
        } catch (const RunError& e) {
            fail(e);
        }
    if (frames_this_run_ == 0 || last_frame_step_ != engine_.step() ||
        last_frame_time_ != engine_.time())
        write_frame();
    if (finished) write_checkpoint(true);
    on_process_zero(options_.comm, [&] { close_files(); });
    nlohmann::json summary = engine_.summary(stopped_by_ ? stopped_by_ : ended_by);
    summary["stopped_by"] = stopped_by_ ? stopped_by_ : ended_by;
    // every quantity the engine measures, by its catalogue name (observe/quantities.hpp);
    // +inf and NaN are null in JSON
    nlohmann::json& final_row = summary["final"];
    for (std::size_t c = 0; c < logged_.size(); ++c) {
        if (is_count_[c])
            final_row[logged_[c]] = static_cast<std::uint64_t>(values_.at(c));
        else
            final_row[logged_[c]] = values_.at(c);
    }
    // the engine's own files first: summary.json is the last file of a run, the sign that
    // it ended (--resume)
    engine_.finish(summary);
    on_process_zero(options_.comm, [&] {
        write_file_atomically(dir / "summary.json",
                              [&](std::ostream& out) { out << summary.dump(2) << "\n"; });
        if (!finished) return;
        std::error_code ec;
        std::filesystem::remove(dir / previous_checkpoint_file, ec);
        write_checkpoint_record(dir / checkpoint_record_file, {marks_.back()});
    });
}

template <int D> void Simulation<D>::run() {
    advance();
    close(engine_.interrupted() ? "interrupted" : "");
}

// Every value with 10 significant digits (counts as integers): "inf" and "nan" as
// pandas and numpy read them.
template <int D> void Simulation<D>::write_log_row() {
    values_.clear();
    engine_.measure(values_);
    // every measured value, shown or not: a NaN anywhere means the state is broken
    for (std::size_t c = 0; c < logged_.size(); ++c) {
        const double v = values_.at(c);
        if (std::isnan(v) || (std::isinf(v) && !may_be_infinite_[c]))
            throw RunError(fmt::format("at step {} (t = {:.6g}) the logged quantity '{}' is {}: "
                                       "the state is no longer finite, and the run stops",
                                       engine_.step(), engine_.time(), logged_[c], v));
    }
    last_row_.clear();
    for (std::size_t c : columns_) last_row_.push_back(values_.at(c));
    ++rows_this_run_;
    last_row_step_ = engine_.step();
    last_row_time_ = engine_.time();
    if (!in_directory()) return;
    on_process_zero(options_.comm, [&] {
        fmt::memory_buffer row;
        for (std::size_t k = 0; k < columns_.size(); ++k) {
            if (k) row.push_back(',');
            const double v = values_.at(columns_[k]);
            if (is_count_[columns_[k]])
                fmt::format_to(std::back_inserter(row), "{}", static_cast<std::uint64_t>(v));
            else
                fmt::format_to(std::back_inserter(row), "{:.10g}", v);
        }
        row.push_back('\n');
        log_->append(fmt::to_string(row));
    });
}

template <int D> void Simulation<D>::write_frame() {
    enter_stage("writing a frame");
    // (every process makes the engine's call: under a Communicator it gathers the state)
    const Frame<D> frame = engine_.frame();
    on_process_zero(options_.comm, [&] { frames_->write(frame, engine_.frames()); });
    engine_.frame_written();
    ++frames_this_run_;
    last_frame_step_ = engine_.step();
    last_frame_time_ = engine_.time();
}

template <int D> void Simulation<D>::close_files() {
    if (log_) log_->commit();
    if (frames_) frames_->commit();
}

template <int D> void Simulation<D>::fail(const RunError& e) {
    // the state is broken: keep what was written while it was good
    closed_ = true;
    close_files();
    throw RunError(std::string(e.what()) + failure_note());
}

template <int D> std::string Simulation<D>::failure_note() const {
    if (!in_directory()) return "";
    if (frames_this_run_ == 0) {
        // (a failure at step 0 of a fresh run: nothing good was written but the log)
        if (!options_.restart)
            return fmt::format(" (no snapshot or checkpoint was written by this run; the log "
                               "is in {})",
                               options_.out_dir.string());
        return fmt::format(" (no snapshot was written by this run; the last good state is the "
                           "checkpoint it started from, {}; the log is in {})",
                           options_.restart->string(), options_.out_dir.string());
    }
    // name only files that exist: a run that fails before its first checkpoint has none
    const bool checkpoint = std::filesystem::exists(options_.out_dir / "checkpoint.bin");
    return fmt::format(" (the last good snapshot is frame {} at t = {:.6g}; {} {})",
                       engine_.frames() - 1, last_frame_time_,
                       checkpoint ? "it, the log and the last checkpoint are in"
                                  : "it and the log are in",
                       options_.out_dir.string() +
                           (checkpoint ? "" : "; no checkpoint was written before the failure"));
}

template class Simulation<2>;
template class Simulation<3>;

} // namespace pedesis
