#pragma once
// A client that sends a server exactly the bytes a test gives it, well formed or not
// (the viewer's server against hostile requests: tests/cli/cli_view_attacks_test.cpp).
// Every call has a deadline: a server that does not answer fails the test, never hangs it.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <string>

namespace pedesis::test {

struct HttpAnswer {
    int status = 0;      // 0: no answer (closed, or past the deadline)
    std::string headers; // the status line and headers as sent
    std::string body;
    double seconds = 0.0; // from the first byte sent to the end of the answer
};

// One connection to 127.0.0.1:port, closed when destroyed.
class RawConnection {
  public:
    explicit RawConnection(int port) {
        fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_port = htons(static_cast<std::uint16_t>(port));
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        if (::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
            ::close(fd_);
            fd_ = -1;
        }
    }
    ~RawConnection() {
        if (fd_ >= 0) ::close(fd_);
    }
    RawConnection(const RawConnection&) = delete;
    RawConnection& operator=(const RawConnection&) = delete;
    RawConnection(RawConnection&& o) noexcept : fd_(o.fd_) { o.fd_ = -1; }

    bool connected() const { return fd_ >= 0; }

    // false once the server has closed the connection or refuses more bytes
    bool send(const std::string& bytes) {
        std::size_t sent = 0;
        while (fd_ >= 0 && sent < bytes.size()) {
            const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
            if (n <= 0) return false;
            sent += static_cast<std::size_t>(n);
        }
        return fd_ >= 0;
    }

    // Reads one answer: headers, then Content-Length bytes of body (or up to the close).
    HttpAnswer receive(double timeout_s = 10.0) {
        using Clock = std::chrono::steady_clock;
        const auto start = Clock::now();
        const auto deadline = start + std::chrono::duration<double>(timeout_s);
        std::string got;
        std::size_t header_end = std::string::npos, wanted = std::string::npos;
        while (fd_ >= 0) {
            if (header_end == std::string::npos) {
                header_end = got.find("\r\n\r\n");
                if (header_end != std::string::npos) wanted = header_end + 4 + content_length(got);
            }
            if (wanted != std::string::npos && got.size() >= wanted) break;
            const auto left =
                std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
            if (left.count() <= 0) break;
            pollfd p{fd_, POLLIN, 0};
            if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
            char buffer[65536];
            const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
            if (n <= 0) break;
            got.append(buffer, static_cast<std::size_t>(n));
        }
        HttpAnswer a;
        a.seconds = std::chrono::duration<double>(Clock::now() - start).count();
        if (header_end == std::string::npos || got.rfind("HTTP/1.1 ", 0) != 0) return a;
        a.status = std::atoi(got.c_str() + 9);
        a.headers = got.substr(0, header_end);
        a.body = got.substr(header_end + 4);
        return a;
    }

    HttpAnswer exchange(const std::string& request, double timeout_s = 10.0) {
        send(request);
        return receive(timeout_s);
    }

  private:
    static std::size_t content_length(const std::string& head) {
        std::string lower = head;
        for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        const std::size_t at = lower.find("\r\ncontent-length:");
        return at == std::string::npos ? 0 : std::strtoull(lower.c_str() + at + 17, nullptr, 10);
    }

    int fd_ = -1;
};

// A request with the Host the server answers to; `extra` holds more header lines.
inline std::string http_request(const std::string& method, const std::string& path, int port,
                                const std::string& body = "", const std::string& extra = "") {
    std::string r = method + " " + path + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                    "\r\n" + extra;
    if (!body.empty() || method == "POST")
        r += "Content-Type: application/json\r\nContent-Length: " + std::to_string(body.size()) +
             "\r\n";
    return r + "Connection: close\r\n\r\n" + body;
}

inline HttpAnswer http_exchange(int port, const std::string& request, double timeout_s = 10.0) {
    RawConnection c(port);
    return c.exchange(request, timeout_s);
}

} // namespace pedesis::test
