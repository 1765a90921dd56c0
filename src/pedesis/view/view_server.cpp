#include "pedesis/view/view_server.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/render/run_directory.hpp"
#include "pedesis/view/frame_arrays.hpp"
#include "pedesis/view/page_files.hpp"
#include "pedesis/view/run_data.hpp"

#include <fmt/format.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <deque>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>
#include <utility>

namespace pedesis::view {

namespace {

// Frames the server keeps decoded: the page asks for several fields of one frame, and for
// the frames around its cursor.
constexpr std::size_t cached_frames = 8;

void send_error(httplib::Response& res, int status, const std::string& message) {
    res.status = status;
    res.set_content(nlohmann::json{{"error", message}}.dump(), "application/json");
}

} // namespace

struct ViewServer::Impl {
    ViewOptions options;
    httplib::Server server;
    std::thread serving;
    int port = 0;
    std::mutex mutex; // the frame source and cache (the server answers on several threads)
    std::unique_ptr<render::FrameSource> source;
    std::deque<std::pair<std::size_t, render::Frame>> cache;

    const render::Frame& frame(std::size_t k) {
        for (const auto& [index, f] : cache)
            if (index == k) return f;
        if (cache.size() == cached_frames) cache.pop_front();
        cache.emplace_back(k, source->frame(k));
        return cache.back().second;
    }

    // A run still going adds frames (and commits its ".part" file under the final name
    // at the end): the page asks for the description every two seconds, and the run
    // directory is opened anew each time, so that new frames show.
    nlohmann::json info() {
        render::OpenedRun run;
        try {
            run = render::open_run_directory(options.run_dir, render::SourceKind::automatic);
        } catch (const InputError& e) {
            // caught mid-write (a frame half written): what was read before stands
            if (source) return with_steering(run_info(*source, frame(0), options.run_dir));
            if (!options.wait_for_frames) throw;
            // a run that has not written its first frame yet
            return with_steering(nlohmann::json{{"frames", 0}, {"waiting", e.what()}});
        }
        if (!source || run.source->frames() != source->frames() ||
            run.source->description() != source->description()) {
            source = std::move(run.source);
            cache.clear();
        }
        return with_steering(run_info(*source, frame(0), options.run_dir));
    }

    nlohmann::json with_steering(nlohmann::json info) const {
        if (!options.steering) return info;
        nlohmann::json& list = info["steerable"];
        list = nlohmann::json::array();
        for (const auto& [name, value] : options.steering->parameters())
            list.push_back({{"name", name}, {"value", value}});
        return info;
    }

    void answer_set(const httplib::Request& req, httplib::Response& res) {
        if (!options.steering)
            return send_error(res, 404,
                              "this run cannot be changed: start it with pedesis run --view");
        nlohmann::json body;
        try {
            body = nlohmann::json::parse(req.body);
        } catch (const nlohmann::json::exception& e) {
            return send_error(res, 400, fmt::format("malformed JSON: {}", e.what()));
        }
        if (!body.is_object() || !body.contains("token") || !body["token"].is_string() ||
            body["token"].get<std::string>() != options.steering->token)
            return send_error(res, 403, "wrong or missing token: use the address pedesis printed");
        if (!body.contains("parameter") || !body["parameter"].is_string())
            return send_error(res, 400, "\"parameter\" must be a string");
        if (!body.contains("value") || !body["value"].is_number())
            return send_error(res, 400, "\"value\" must be a finite number");
        const std::string parameter = body["parameter"].get<std::string>();
        const double value = body["value"].get<double>();
        const std::string refused = options.steering->request(parameter, value);
        if (!refused.empty()) return send_error(res, 400, refused);
        res.status = 202;
        res.set_content(nlohmann::json{{"queued", parameter}, {"value", value}}.dump(),
                        "application/json");
    }

    void routes() {
        server.Get("/api/info", [this](const httplib::Request&, httplib::Response& res) {
            std::lock_guard lock(mutex);
            try {
                res.set_content(info().dump(), "application/json");
            } catch (const InputError& e) {
                send_error(res, 422, e.what());
            }
        });
        server.Get("/api/log", [this](const httplib::Request&, httplib::Response& res) {
            res.set_content(read_log(options.run_dir).dump(), "application/json");
        });
        server.Get(R"(/api/frame/(\d{1,18})/([^/]{1,200}))",
                   [this](const httplib::Request& req, httplib::Response& res) {
                       answer_frame(req, res);
                   });
        server.Post("/api/set", [this](const httplib::Request& req, httplib::Response& res) {
            answer_set(req, res);
        });
        server.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
            if (res.body.empty())
                send_error(res, res.status, fmt::format("no such resource: {}", req.path));
        });
        if (!page_file("index.html")) throw InputError(page_missing());
        // the page, from the binary (page_files.hpp)
        server.Get(R"(/(|index\.html|viewer\.js|viewer\.css))",
                   [](const httplib::Request& req, httplib::Response& res) {
                       const std::string name = req.matches[1].str();
                       const PageFile file = *page_file(name.empty() ? "index.html" : name);
                       res.set_content(file.bytes.data(), file.bytes.size(), file.content_type);
                   });
    }

    // A structural field (position, radius, species, director) or a number to colour by
    // (frame_arrays.hpp), by name.
    void answer_frame(const httplib::Request& req, httplib::Response& res) {
        const std::string name = req.matches[2].str();
        const std::optional<Field> field = field_named(name);
        const std::size_t k = std::stoull(req.matches[1].str());
        std::lock_guard lock(mutex);
        try {
            // a trajectory still being written grows: ask the file, not a count from before
            if (!source || k >= source->frames())
                return send_error(res, 404,
                                  fmt::format("frame {} is past the end: the run has {} frames", k,
                                              source ? source->frames() : 0));
            const render::Frame& f = frame(k);
            std::optional<std::string> bytes;
            if (field && frame_has(f, *field))
                bytes = frame_bytes(f, *field);
            else if (!field)
                bytes = colour_field_bytes(f, name);
            if (!bytes) {
                std::string known = "position, radius, species";
                if (frame_has(f, Field::director)) known += ", director";
                for (const std::string& c : colour_fields(f))
                    if (c != "radius") known += ", " + c;
                return send_error(
                    res, 404,
                    fmt::format("frame {} has no field '{}' (it has: {})", k, name, known));
            }
            res.set_header("X-Pedesis-Time", f.time ? fmt::format("{}", *f.time) : "");
            res.set_header("X-Pedesis-Step", f.step ? std::to_string(*f.step) : "");
            res.set_header("Access-Control-Expose-Headers", "X-Pedesis-Time, X-Pedesis-Step");
            res.set_content(*bytes, "application/octet-stream");
        } catch (const InputError& e) {
            send_error(res, 422, e.what());
        }
    }
};

ViewServer::ViewServer(const ViewOptions& options) : impl_(std::make_unique<Impl>()) {
    impl_->options = options;
    if (!options.wait_for_frames)
        impl_->source =
            render::open_run_directory(options.run_dir, render::SourceKind::automatic).source;
    impl_->routes();
    impl_->port =
        options.port == 0
            ? impl_->server.bind_to_any_port(options.host)
            : (impl_->server.bind_to_port(options.host, options.port) ? options.port : -1);
    if (impl_->port < 0)
        throw InputError(fmt::format("pedesis view: cannot listen on {}:{} (in use, or not an "
                                     "address of this machine); choose another with --port",
                                     options.host, options.port));
}

ViewServer::~ViewServer() {
    if (impl_->serving.joinable()) {
        impl_->server.stop();
        impl_->serving.join();
    }
}

int ViewServer::port() const {
    return impl_->port;
}

std::string ViewServer::url() const {
    const std::string& h = impl_->options.host;
    return fmt::format("http://{}:{}/", h.find(':') != std::string::npos ? "[" + h + "]" : h,
                       impl_->port);
}

void ViewServer::start() {
    if (!impl_->serving.joinable())
        impl_->serving = std::thread([this] { impl_->server.listen_after_bind(); });
}

} // namespace pedesis::view
