#pragma once
// cpp-httplib's server with the limits a server inside a long run needs against any web
// page the user opens and any process on the machine (docs/view.md, "Security").
//
// cpp-httplib 0.11 reads a request's line and headers without a bound on their size or
// on the time they take, and serves from a fixed pool of a few threads: one idle or slow
// connection per thread starves every real request, and one endless header line grows
// without bound. Here each connection is read through a stream that allows a request a
// number of bytes and a deadline, and connections are served by a pool that grows (up to
// a cap) when every thread is busy, so that slow clients hold threads of their own for a
// few seconds at most and never the one a real request gets.
#include <httplib.h>

#include <chrono>
#include <cstddef>
#include <optional>
#include <string>

namespace pedesis::view {

struct ConnectionLimits {
    std::chrono::milliseconds first_request{1000}; // a new connection that says nothing
    std::chrono::milliseconds keep_alive{5000};    // between two requests of a connection
    std::chrono::milliseconds request{3000};       // a whole request, from its first byte
    std::chrono::milliseconds response{60000};     // writing one answer
    std::size_t header_bytes = 16384;              // the request line and the headers
    std::size_t body_bytes = 65536;
    std::size_t requests_per_connection = 100;
    std::size_t max_threads = 1000; // about the descriptors a process may hold (1024)
};

// Why the request this thread was reading was cut short, as a status and a message (414,
// 431, 413, 408), or none. Where cpp-httplib answers such a request itself (with 400), the
// error handler uses this instead; where it gives up without answering (a request line
// cut short), the server answers with it.
struct CutShortAnswer {
    int status;
    const char* reason; // the status line's phrase
    std::string message;
};
std::optional<CutShortAnswer> request_cut_short(const ConnectionLimits& limits);

// From the error handler, for a request that could not be read as HTTP: the connection
// closes after the answer (what follows it on the connection is no request either).
void close_after_answer();

class GuardedHttpServer : public httplib::Server {
  public:
    explicit GuardedHttpServer(const ConnectionLimits& limits = {});

    const ConnectionLimits& limits() const { return limits_; }

    // After binding: room for 512 connections not yet accepted (cpp-httplib listens with
    // 5, and a burst of connections past that drops SYNs, a real client's among them,
    // which then wait a second to be sent again).
    void widen_listen_queue();

  private:
    // (a private virtual of httplib::Server: overriding it replaces the library's
    // keep-alive loop over plain socket reads)
    bool process_and_close_socket(socket_t sock) override;
    bool stopping() const;

    ConnectionLimits limits_;
};

} // namespace pedesis::view
