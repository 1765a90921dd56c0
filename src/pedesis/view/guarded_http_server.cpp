#include "pedesis/view/guarded_http_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace pedesis::view {

namespace {

using Clock = std::chrono::steady_clock;

// A wait is cut into slices so that a stopping server is noticed within one.
constexpr std::chrono::milliseconds wait_slice{100};

enum class CutShort { no, line_too_long, headers_too_large, body_too_large, too_slow, garbled };
thread_local CutShort cut_short = CutShort::no;

// One connection's bytes, read through a buffer (cpp-httplib reads a request line and
// headers one byte at a time), with each request's allowance of bytes and time.
class LimitedStream final : public httplib::Stream {
  public:
    LimitedStream(int sock, const ConnectionLimits& limits, std::function<bool()> stopping)
        : sock_(sock), limits_(limits), stopping_(std::move(stopping)) {}

    // Waits for the first byte of the next request (or finds it buffered already).
    bool wait_for_request(std::chrono::milliseconds patience) {
        return buffered() > 0 || wait(POLLIN, Clock::now() + patience) > 0;
    }

    void begin_request() {
        cut_short = CutShort::no;
        const Clock::time_point now = Clock::now();
        read_deadline_ = now + limits_.request;
        write_deadline_ = read_deadline_ + limits_.response;
        header_bytes_ = 0;
        body_bytes_ = 0;
        blank_line_state_ = 0;
        line_ended_ = false;
        written_ = 0;
    }

    // Something of a request came, and nothing of an answer went out.
    bool unanswered() const { return header_bytes_ > 0 && written_ == 0; }

    bool is_readable() const override { return true; }
    bool is_writable() const override { return true; }

    ssize_t read(char* out, size_t size) override {
        if (size == 0) return 0;
        if (buffered() == 0 && !fill()) return -1;
        const std::size_t n = std::min(size, buffered());
        for (std::size_t i = 0; i < n; ++i) {
            if (in_headers()) {
                advance_blank_line(buffer_[begin_ + i]);
                line_ended_ = line_ended_ || buffer_[begin_ + i] == '\n';
                ++header_bytes_;
            } else {
                ++body_bytes_;
            }
        }
        if (in_headers() && header_bytes_ > limits_.header_bytes)
            return refuse(line_ended_ ? CutShort::headers_too_large : CutShort::line_too_long);
        // (a chunked body carries its framing: it is allowed a little room)
        if (body_bytes_ > limits_.body_bytes + 4096) return refuse(CutShort::body_too_large);
        std::copy_n(buffer_.data() + begin_, n, out);
        begin_ += n;
        return static_cast<ssize_t>(n);
    }

    ssize_t write(const char* data, size_t size) override {
        std::size_t sent = 0;
        while (sent < size) {
            if (wait(POLLOUT, write_deadline_) <= 0) return -1;
            const ssize_t n = ::send(sock_, data + sent, size - sent, MSG_NOSIGNAL);
            if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
            if (n <= 0) return -1;
            sent += static_cast<std::size_t>(n);
        }
        written_ += size;
        return static_cast<ssize_t>(size);
    }

    void get_remote_ip_and_port(std::string& ip, int& port) const override {
        address(::getpeername, ip, port);
    }
    void get_local_ip_and_port(std::string& ip, int& port) const override {
        address(::getsockname, ip, port);
    }
    socket_t socket() const override { return sock_; }

  private:
    std::size_t buffered() const { return end_ - begin_; }
    bool in_headers() const { return blank_line_state_ < 4; }

    // "\r\n\r\n" (or "\n\n") ends the headers.
    void advance_blank_line(char c) {
        if (!in_headers()) return;
        if (c == '\n')
            blank_line_state_ = blank_line_state_ >= 1 ? 4 : 1;
        else if (c != '\r')
            blank_line_state_ = 0;
    }

    ssize_t refuse(CutShort why) {
        cut_short = why;
        return -1;
    }

    bool fill() {
        const int ready = wait(POLLIN, read_deadline_);
        if (ready <= 0) {
            if (ready == 0 && !stopping_()) cut_short = CutShort::too_slow;
            return false;
        }
        ssize_t n;
        do n = ::recv(sock_, buffer_.data(), buffer_.size(), 0);
        while (n < 0 && errno == EINTR);
        if (n <= 0) return false;
        begin_ = 0;
        end_ = static_cast<std::size_t>(n);
        return true;
    }

    // >0 ready, 0 past the deadline or the server stopping, <0 an error
    int wait(short events, Clock::time_point deadline) const {
        for (;;) {
            if (stopping_()) return 0;
            const auto left =
                std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
            if (left.count() <= 0) return 0;
            pollfd p{sock_, events, 0};
            const int r = ::poll(&p, 1, static_cast<int>(std::min(left, wait_slice).count()));
            if (r < 0 && errno == EINTR) continue;
            if (r != 0) return r < 0 ? r : ((p.revents & (events | POLLHUP | POLLERR)) ? 1 : -1);
        }
    }

    template <class Query> void address(Query query, std::string& ip, int& port) const {
        sockaddr_storage a{};
        socklen_t len = sizeof a;
        ip.clear();
        port = 0;
        if (query(sock_, reinterpret_cast<sockaddr*>(&a), &len) != 0) return;
        char text[INET6_ADDRSTRLEN] = {};
        if (a.ss_family == AF_INET) {
            const auto* v4 = reinterpret_cast<const sockaddr_in*>(&a);
            ::inet_ntop(AF_INET, &v4->sin_addr, text, sizeof text);
            port = ntohs(v4->sin_port);
        } else if (a.ss_family == AF_INET6) {
            const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&a);
            ::inet_ntop(AF_INET6, &v6->sin6_addr, text, sizeof text);
            port = ntohs(v6->sin6_port);
        }
        ip = text;
    }

    int sock_;
    const ConnectionLimits& limits_;
    std::function<bool()> stopping_;
    std::array<char, 4096> buffer_{};
    std::size_t begin_ = 0, end_ = 0;
    Clock::time_point read_deadline_{}, write_deadline_{};
    std::size_t header_bytes_ = 0, body_bytes_ = 0;
    int blank_line_state_ = 0;
    bool line_ended_ = false; // the request line is whole
    std::size_t written_ = 0;
};

// Connections to threads: a thread for each, new threads made as they are taken up, up
// to a cap; past it, connections wait for the first free thread (each frees within its
// deadlines). The listening thread only queues a connection: a new thread is made by
// the worker that took the last idle place, so that accepting stays as fast as a plain
// queue (a slow accept loop overflows the listen queue, and a real client's connection
// then waits a second for its SYN to be sent again).
class GrowingThreadPool final : public httplib::TaskQueue {
  public:
    explicit GrowingThreadPool(std::size_t max_threads) : max_threads_(max_threads) {
        std::lock_guard lock(mutex_);
        for (std::size_t k = 0; k < std::min<std::size_t>(spare_threads, max_threads_); ++k)
            threads_.emplace_back([this] { work(); });
    }
    ~GrowingThreadPool() override { shutdown(); }

    void enqueue(std::function<void()> task) override {
        {
            std::lock_guard lock(mutex_);
            tasks_.push_back(std::move(task));
        }
        ready_.notify_one();
    }

    void shutdown() override {
        {
            std::lock_guard lock(mutex_);
            if (stopping_) return;
            stopping_ = true;
        }
        ready_.notify_all();
        // (threads are only added under the lock, and not once stopping)
        for (std::size_t k = 0;; ++k) {
            std::thread t;
            {
                std::lock_guard lock(mutex_);
                if (k == threads_.size()) break;
                t = std::move(threads_[k]);
            }
            t.join();
        }
    }

  private:
    static constexpr std::size_t spare_threads = 8;

    void work() {
        std::unique_lock lock(mutex_);
        for (;;) {
            ++idle_;
            ready_.wait(lock, [this] { return stopping_ || !tasks_.empty(); });
            --idle_;
            if (tasks_.empty()) return; // stopping, and nothing left to close
            std::function<void()> task = std::move(tasks_.front());
            tasks_.pop_front();
            if (idle_ < tasks_.size() + 1 && !stopping_ && threads_.size() < max_threads_)
                threads_.emplace_back([this] { work(); });
            lock.unlock();
            task();
            lock.lock();
        }
    }

    const std::size_t max_threads_;
    std::mutex mutex_;
    std::condition_variable ready_;
    std::deque<std::function<void()>> tasks_;
    std::vector<std::thread> threads_;
    std::size_t idle_ = 0;
    bool stopping_ = false;
};

// Closing a socket with unread bytes (the rest of a refused body or header) makes the
// kernel reset the connection, and the client may lose the answer sent just before. So
// the sending side is closed first, and what the client still sends is read and dropped,
// for a bounded time and amount, before the socket is.
void linger_and_close(int sock) {
    ::shutdown(sock, SHUT_WR);
    const auto until = Clock::now() + std::chrono::milliseconds(500);
    std::size_t dropped = 0;
    char sink[16384];
    while (dropped < (4u << 20) && Clock::now() < until) {
        pollfd p{sock, POLLIN, 0};
        if (::poll(&p, 1, 50) <= 0) {
            if (Clock::now() >= until) break;
            continue;
        }
        const ssize_t n = ::recv(sock, sink, sizeof sink, 0);
        if (n <= 0) break;
        dropped += static_cast<std::size_t>(n);
    }
    ::close(sock);
}

} // namespace

std::optional<CutShortAnswer> request_cut_short(const ConnectionLimits& limits) {
    switch (cut_short) {
    case CutShort::line_too_long:
        return CutShortAnswer{414, "URI Too Long", "the request line is longer than 8192 bytes"};
    case CutShort::headers_too_large:
        return CutShortAnswer{
            431, "Request Header Fields Too Large",
            fmt::format("the request's line and headers exceed {} bytes", limits.header_bytes)};
    case CutShort::body_too_large:
        return CutShortAnswer{
            413, "Payload Too Large",
            fmt::format("the request's body exceeds {} bytes", limits.body_bytes)};
    case CutShort::too_slow:
        return CutShortAnswer{
            408, "Request Timeout",
            fmt::format("the request did not arrive within {} ms", limits.request.count())};
    case CutShort::garbled:
        return CutShortAnswer{400, "Bad Request", "malformed HTTP request"};
    case CutShort::no:
        break;
    }
    return std::nullopt;
}

void close_after_answer() {
    if (cut_short == CutShort::no) cut_short = CutShort::garbled;
}

GuardedHttpServer::GuardedHttpServer(const ConnectionLimits& limits) : limits_(limits) {
    new_task_queue = [n = limits_.max_threads] { return new GrowingThreadPool(n); };
    set_payload_max_length(limits_.body_bytes);
}

void GuardedHttpServer::widen_listen_queue() {
    const socket_t sock = svr_sock_;
    if (sock != INVALID_SOCKET) ::listen(sock, 512); // (again on a listening socket: the queue)
}

bool GuardedHttpServer::stopping() const {
    // (stop() takes the listening socket away at once; is_running() stays true until
    // every connection's thread has ended)
    return svr_sock_ == INVALID_SOCKET;
}

bool GuardedHttpServer::process_and_close_socket(socket_t sock) {
    bool ok = true;
    try {
        LimitedStream stream(sock, limits_, [this] { return stopping(); });
        for (std::size_t served = 0; served < limits_.requests_per_connection; ++served) {
            if (!stream.wait_for_request(served == 0 ? limits_.first_request : limits_.keep_alive))
                break;
            stream.begin_request();
            bool closed = false;
            const bool last = served + 1 == limits_.requests_per_connection;
            ok = process_request(stream, last, closed, [](httplib::Request&) {});
            if (!ok && stream.unanswered()) {
                // cpp-httplib gave up on the request line without a word: say why
                if (cut_short == CutShort::no) cut_short = CutShort::garbled;
                const CutShortAnswer a = *request_cut_short(limits_);
                const std::string body = nlohmann::json{{"error", a.message}}.dump();
                const std::string answer =
                    fmt::format("HTTP/1.1 {} {}\r\nContent-Type: application/json\r\n"
                                "Content-Length: {}\r\nConnection: close\r\n\r\n{}",
                                a.status, a.reason, body.size(), body);
                stream.write(answer.data(), answer.size());
            }
            // (after a request cut short, what follows on the connection is its rest)
            if (!ok || closed || cut_short != CutShort::no) break;
        }
    } catch (...) {
        // whatever one connection does, the server (and the run around it) goes on
        ok = false;
    }
    linger_and_close(sock);
    return ok;
}

} // namespace pedesis::view
