#include "pedesis/view/view_server.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/render/run_directory.hpp"
#include "pedesis/view/frame_arrays.hpp"
#include "pedesis/view/guarded_http_server.hpp"
#include "pedesis/view/page_files.hpp"
#include "pedesis/view/run_data.hpp"

#include <fmt/format.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <arpa/inet.h>

#include <cmath>
#include <cstdio>
#include <deque>
#include <fstream>
#include <iostream>
#include <mutex>
#include <regex>
#include <sstream>
#include <thread>
#include <utility>

namespace pedesis::view {

namespace {

// Frames the server keeps decoded: the page asks for several fields of one frame, and for
// the frames around its cursor.
constexpr std::size_t cached_frames = 8;

// Names, paths and messages from files and requests may hold any bytes: invalid UTF-8
// becomes U+FFFD instead of an exception.
std::string json_text(const nlohmann::json& j) {
    return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

void send_error(httplib::Response& res, int status, const std::string& message) {
    res.status = status;
    res.set_content(json_text(nlohmann::json{{"error", message}}), "application/json");
}

// What the page and the API answer to, and with which methods (for 405's Allow).
struct Route {
    const char* pattern;
    const char* method;
};
constexpr Route routes_served[] = {
    {R"(/api/info)", "GET"},
    {R"(/api/log)", "GET"},
    {R"(/api/set)", "POST"},
    {R"(/api/frame/(\d{1,18})/([^/]{1,200}))", "GET"},
    {R"(/(|index\.html|viewer\.js|viewer\.css|favicon\.ico))", "GET"},
};

// A request's path in a message: printable, and short.
std::string shown_path(const std::string& path) {
    constexpr std::size_t longest = 120;
    return path.size() <= longest ? path : path.substr(0, longest) + "...";
}

// "name" and port of a Host header ("name:port", "[v6]:port"); port 80 without one.
std::pair<std::string, std::string> split_host(const std::string& host) {
    const std::size_t colon = host.rfind(':');
    const std::size_t bracket = host.rfind(']');
    if (colon == std::string::npos || (bracket != std::string::npos && colon < bracket))
        return {host, "80"};
    return {host.substr(0, colon), host.substr(colon + 1)};
}

bool is_ip_literal(std::string name) {
    if (name.size() > 2 && name.front() == '[' && name.back() == ']')
        name = name.substr(1, name.size() - 2);
    unsigned char buffer[sizeof(in6_addr)];
    return ::inet_pton(AF_INET, name.c_str(), buffer) == 1 ||
           ::inet_pton(AF_INET6, name.c_str(), buffer) == 1;
}

std::string lower(std::string s) {
    for (char& c : s)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return s;
}

} // namespace

struct ViewServer::Impl {
    ViewOptions options;
    GuardedHttpServer server;
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
        for (const auto& [name, value, min, max] : options.steering->parameters())
            list.push_back({{"name", name}, {"value", value}, {"min", min}, {"max", max}});
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
        res.set_content(json_text(nlohmann::json{{"queued", parameter}, {"value", value}}),
                        "application/json");
    }

    void routes() {
        server.Get("/api/info", [this](const httplib::Request&, httplib::Response& res) {
            std::lock_guard lock(mutex);
            try {
                res.set_content(json_text(info()), "application/json");
            } catch (const InputError& e) {
                send_error(res, 422, e.what());
            }
        });
        server.Get("/api/log", [this](const httplib::Request&, httplib::Response& res) {
            res.set_content(json_text(read_log(options.run_dir)), "application/json");
        });
        server.Get(routes_served[3].pattern,
                   [this](const httplib::Request& req, httplib::Response& res) {
                       answer_frame(req, res);
                   });
        server.Post("/api/set", [this](const httplib::Request& req, httplib::Response& res) {
            answer_set(req, res);
        });
        server.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
            const std::string refused = refusal(req);
            if (refused.empty()) return httplib::Server::HandlerResponse::Unhandled;
            send_error(res, 403, refused);
            return httplib::Server::HandlerResponse::Handled;
        });
        server.set_error_handler([this](const httplib::Request& req, httplib::Response& res) {
            if (res.body.empty()) explain_status(req, res);
        });
        server.set_exception_handler(
            [](const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
                std::string what = "unknown";
                try {
                    std::rethrow_exception(error);
                } catch (const std::exception& e) {
                    what = e.what();
                } catch (...) {
                }
                send_error(res, 500, "internal error: " + what);
            });
        if (options.require_page && !page_file("index.html")) throw InputError(page_missing());
        // the page, from the binary (page_files.hpp)
        server.Get(
            routes_served[4].pattern, [](const httplib::Request& req, httplib::Response& res) {
                const std::string name = req.matches[1].str();
                const std::optional<PageFile> file = page_file(name.empty() ? "index.html" : name);
                if (!file)
                    return send_error(res, 404,
                                      name.empty() || name == "index.html"
                                          ? page_missing()
                                          : "this page has no " + name);
                res.set_header("Content-Security-Policy", std::string(page_security_policy()));
                res.set_content(file->bytes.data(), file->bytes.size(), file->content_type);
            });
    }

    // The addresses a request may name in its Host header: those the server was started
    // on. A page on any other name that resolves here (DNS rebinding) is refused.
    std::vector<std::string> own_hosts;
    bool any_address = false; // listening on 0.0.0.0 or ::

    void name_own_hosts() {
        const std::string p = std::to_string(port);
        const std::string& h = options.host;
        own_hosts = {"127.0.0.1:" + p, "localhost:" + p, "[::1]:" + p,
                     lower(h.find(':') != std::string::npos ? "[" + h + "]:" + p : h + ":" + p)};
        any_address = h == "0.0.0.0" || h == "::" || h == "[::]";
    }

    bool own_host(const std::string& host) const {
        const std::string wanted = lower(host);
        for (const std::string& h : own_hosts)
            if (wanted == h) return true;
        if (!any_address) return false;
        // listening everywhere: this machine's addresses (literals) and names
        const auto [name, p] = split_host(wanted);
        if (p != std::to_string(port)) return false;
        char machine[256] = {};
        ::gethostname(machine, sizeof machine - 1);
        return is_ip_literal(name) || name == "localhost" || name == lower(machine);
    }

    // Why a request is refused before it is routed, or "".
    std::string refusal(const httplib::Request& req) const {
        const std::string host = req.get_header_value("Host");
        if (!own_host(host))
            return fmt::format("this server answers to {} only, not to Host '{}'", own_hosts[0],
                               shown_path(host));
        // a page of another origin may open the viewer (a link), never read or change it
        const std::string origin = req.get_header_value("Origin");
        if (req.has_header("Origin") && lower(origin) != "http://" + lower(host))
            return fmt::format("requests from another origin ('{}') are refused",
                               shown_path(origin));
        const std::string site = req.get_header_value("Sec-Fetch-Site");
        const bool navigation = req.get_header_value("Sec-Fetch-Mode") == "navigate" &&
                                req.method == "GET" &&
                                (req.path == "/" || req.path == "/index.html");
        if ((site == "cross-site" || site == "same-site") && !navigation)
            return "requests from another site are refused (open the page itself)";
        return "";
    }

    // The message of a status the server library chose (a request it could not read, or
    // no route), and the status that says it where the library's is too vague.
    void explain_status(const httplib::Request& req, httplib::Response& res) const {
        const ConnectionLimits& limits = server.limits();
        if (const auto cut = request_cut_short(limits))
            return send_error(res, cut->status, cut->message);
        if (res.status == 404) {
            std::string allowed;
            for (const Route& r : routes_served)
                if (std::regex_match(req.path, std::regex(r.pattern)))
                    allowed += (allowed.empty() ? "" : ", ") + std::string(r.method);
            if (!allowed.empty()) {
                res.set_header("Allow", allowed);
                return send_error(res, 405,
                                  fmt::format("{} takes {} only, not {}", shown_path(req.path),
                                              allowed, shown_path(req.method)));
            }
            return send_error(res, 404, "no such resource: " + shown_path(req.path));
        }
        if (res.status == 413)
            return send_error(
                res, 413, fmt::format("the request's body exceeds {} bytes", limits.body_bytes));
        if (res.status == 414)
            return send_error(res, 414, "the request line is longer than 8192 bytes");
        if (res.status == 400) {
            close_after_answer();
            return send_error(res, 400, "malformed HTTP request");
        }
        send_error(res, res.status, fmt::format("HTTP status {}", res.status));
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
    if (options.host.empty())
        throw InputError("pedesis view: --host must name an address (127.0.0.1, this "
                         "machine's name, or 0.0.0.0 for every address)");
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
    impl_->server.widen_listen_queue();
    impl_->name_own_hosts();
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
        impl_->serving = std::thread([this] {
            // The server's end never takes a run down with it: say so and let it go on.
            try {
                impl_->server.listen_after_bind();
            } catch (const std::exception& e) {
                std::cerr << fmt::format("pedesis: the viewer's server stopped ({}); the run "
                                         "goes on\n",
                                         e.what());
            }
        });
}

} // namespace pedesis::view
