#pragma once
// The viewer's server (pedesis view, run --view) against any bytes a client sends: one
// server on a small run directory (an XYZ trajectory and a log) with steering hooks, for
// the whole process; each input is sent on a connection of its own as it is (request
// lines, headers, bodies, several requests in a row), the sending side then closed, and
// the answer read to the end. Whatever the input, the server must answer a real request
// afterwards; a crash or sanitizer report in its threads ends the process (a finding).
// "$PRT" in an input stands for the server's port (chosen at start), so that inputs can
// name the Host it answers to.
#include "fuzz_support.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/view/view_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>

namespace pedesis::fuzz {

// Sends `bytes` to 127.0.0.1:port, closes the sending side, and returns what came back
// within two seconds.
inline std::string exchange_bytes(int port, const std::string& bytes) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    std::string got;
    if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0) {
        std::size_t sent = 0;
        while (sent < bytes.size()) {
            const ssize_t n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
            if (n <= 0) break;
            sent += static_cast<std::size_t>(n);
        }
        ::shutdown(fd, SHUT_WR);
        for (int slices = 0; slices < 20; ++slices) {
            pollfd p{fd, POLLIN, 0};
            if (::poll(&p, 1, 100) <= 0) continue;
            char buffer[16384];
            const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
            if (n <= 0) break;
            got.append(buffer, static_cast<std::size_t>(n));
        }
    }
    ::close(fd);
    return got;
}

class FuzzedViewServer {
  public:
    static FuzzedViewServer& instance() {
        static FuzzedViewServer server;
        return server;
    }
    int port() const { return server_->port(); }

  private:
    FuzzedViewServer() {
        dir_ = std::filesystem::temp_directory_path() /
               ("pedesis_fuzz_view_" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir_);
        remove_at_exit(dir_);
        std::ofstream(dir_ / "trajectory.xyz")
            << "2\nLattice=\"4 0 0 0 4 0 0 0 4\" Properties=species:S:1:pos:R:3:radius:R:1 "
               "time=0\nA 1 1 0 0.5\nB 2 2 0 0.5\n2\nLattice=\"4 0 0 0 4 0 0 0 4\" "
               "Properties=species:S:1:pos:R:3:radius:R:1 time=1\nA 1.5 1 0 0.5\nB 2 2.5 0 "
               "0.5\n";
        std::ofstream(dir_ / "log.csv") << "time,T\n0,1\n1,1.5\n";
        view::ViewOptions o;
        o.run_dir = dir_;
        o.port = 0;
        o.require_page = false;
        o.steering = view::SteeringHooks{
            "0123456789abcdef0123456789abcdef",
            [] {
                return std::vector<view::SteerableValue>{{"temperature", 1.0, 0.0, 1e6}};
            },
            [](const std::string& parameter, double value) -> std::string {
                if (parameter != "temperature") return "unknown parameter";
                return value >= 0.0 && value <= 1e6 ? "" : "out of range";
            }};
        server_ = std::make_unique<view::ViewServer>(o);
        server_->start();
    }
    std::filesystem::path dir_;
    std::unique_ptr<view::ViewServer> server_;
};

inline void view_request_input(const std::uint8_t* data, std::size_t size) {
    FuzzedViewServer& server = FuzzedViewServer::instance();
    std::string bytes(reinterpret_cast<const char*>(data), size);
    const std::string port = std::to_string(server.port());
    for (std::size_t at = bytes.find("$PRT"); at != std::string::npos;
         at = bytes.find("$PRT", at + port.size()))
        bytes.replace(at, 4, port);
    (void)exchange_bytes(server.port(), bytes);
    const std::string answer = exchange_bytes(
        server.port(),
        "GET /api/info HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(server.port()) + "\r\n\r\n");
    if (answer.rfind("HTTP/1.1 200", 0) != 0)
        throw std::logic_error("the viewer's server stopped answering: " + answer.substr(0, 200));
}

} // namespace pedesis::fuzz
