#pragma once
// The HTTP server of `pedesis view`: the viewer page and, under /api, a run directory's
// frames (binary typed arrays, frame_arrays.hpp) and log. Read-only: it serves what the
// run directory holds when asked, so a run still being written shows its new frames.
//
//   GET /                      the page (index.html, viewer.js, viewer.css: page_files.hpp)
//   GET /api/info              JSON: dimension, box, frames, particles, species, fields
//   GET /api/frame/K/FIELD     bytes of FIELD of frame K (headers X-Pedesis-Time, -Step)
//   GET /api/log               JSON: log.csv's columns and rows (null for inf and nan)
//   POST /api/set              JSON {"token", "parameter", "value"}: change a running
//                              simulation (only with SteeringHooks): 202, or 403 for a
//                              wrong token, 400 for anything else wrong
//
// A frame past the end, a field the frames do not have, or an unknown path is a 404 with a
// JSON {"error": message}; so is every other refusal, with its own status (docs/view.md,
// "Statuses"). The server guards the run it serves: requests are bounded in size and
// time (guarded_http_server.hpp), only the addresses it listens on are served (a
// DNS-rebinding page gets 403), cross-site requests other than opening the page are
// refused, and nothing a client sends can stop the process.
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pedesis::view {

// What `pedesis run --view` lets the page change: the run's parameters and a way to ask
// for a change (run/steering.hpp's SteeringDesk, as plain functions: the server knows
// nothing of runs), guarded by a random token that only the printed address carries.
struct SteerableValue {
    std::string name;
    double value = 0.0;
    double min = 0.0, max = 0.0; // what a change may set it to
};

struct SteeringHooks {
    std::string token;
    std::function<std::vector<SteerableValue>()> parameters;
    std::function<std::string(const std::string&, double)> request; // "" when queued
};

struct ViewOptions {
    std::filesystem::path run_dir;
    std::string host = "127.0.0.1";
    int port = 8765; // 0: any free port
    // Serve a run directory that has no trajectory yet (`pedesis run --view`): the page
    // waits for the first frame. Otherwise a directory without one is an InputError.
    bool wait_for_frames = false;
    std::optional<SteeringHooks> steering;
    // Refuse to start without the page (a build without Node.js): the command does; a
    // client of the API alone (the fuzz target) need not.
    bool require_page = true;
};

class ViewServer {
  public:
    // Opens the run's trajectory and binds the port; InputError (naming the directory,
    // or the port and --port) if either fails, or if the host is empty.
    explicit ViewServer(const ViewOptions& options);
    ~ViewServer();
    ViewServer(const ViewServer&) = delete;
    ViewServer& operator=(const ViewServer&) = delete;

    int port() const;
    std::string url() const;
    // Serves on a thread of its own until the server is destroyed.
    void start();

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace pedesis::view
