// Issue 27: the viewer's server against a hostile web. Each attack is sent as raw bytes to
// a live server (`pedesis view`, and `pedesis run --view` with its steering), and each
// must get its 4xx with a one-line JSON error while the server goes on answering real
// requests at once and the run it serves ends with every file complete.
#include "cli/cli_support.hpp"
#include "support/raw_http.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <csignal>
#include <fstream>
#include <regex>
#include <thread>
#include <vector>

namespace pedesis::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// A Brownian run of harmonic disks, with a self-propulsion to steer.
std::string live_config(std::uint64_t steps) {
    return "dimension = 2\ndynamics = \"brownian\"\nseed = 5\n[box]\nlength = 20.0\n"
           "[[species]]\nname = \"A\"\ncount = 100\nradius = 0.5\n"
           "[[force]]\nname = \"harmonic\"\nk = 10.0\n"
           "[[force]]\nname = \"self_propulsion\"\nalpha = 1.0\n"
           "[[integrator]]\nname = \"brownian\"\nT = 0.1\ngamma = 1.0\n"
           "[[integrator]]\nname = \"brownian_rotation\"\nT = 0.1\ngamma = 1.0\n"
           "[run]\nsteps = " +
           std::to_string(steps) +
           "\ndt = 0.001\n[output]\nprogress = false\nformats = [\"gsd\"]\n"
           "snapshot_every = 100\ncheckpoint_every = 1000\nlog_every = 100\n";
}

// The JSON error of an answer, or "" where the body is not {"error": string}.
std::string error_of(const HttpAnswer& a) {
    const auto j = nlohmann::json::parse(a.body, nullptr, false);
    if (!j.is_object() || !j.contains("error") || !j["error"].is_string()) return "";
    return j["error"].get<std::string>();
}

class ViewAttacks : public ScratchDir {
  protected:
    void TearDown() override {
        if (pid_ > 0) {
            kill(pid_, SIGKILL);
            waitpid(pid_, nullptr, 0);
        }
        ScratchDir::TearDown();
    }

    // Starts `pedesis ARGS...` and waits until it prints its address; the port (and the
    // token, where the address has one).
    void start(const std::vector<std::string>& args) {
        console_ = dir / "console.txt";
        pid_ = start_pedesis(dir, console_, args);
        const std::regex address(R"(http://127\.0\.0\.1:(\d+)/(\?token=([0-9a-f]+))?)");
        const auto give_up = Clock::now() + std::chrono::seconds(120);
        while (Clock::now() < give_up) {
            std::smatch m;
            const std::string out = console();
            if (std::regex_search(out, m, address)) {
                port_ = std::stoi(m[1].str());
                token_ = m[3].str();
                return;
            }
            if (waitpid(pid_, nullptr, WNOHANG) == pid_) {
                pid_ = -1;
                FAIL() << "it ended before serving: " << out;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        FAIL() << "no address printed: " << console();
    }

    std::string console() {
        std::ifstream in(console_);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }

    // The server still answers a real request, within a second.
    void expect_serving(const std::string& after) {
        const HttpAnswer a = http_exchange(port_, http_request("GET", "/api/info", port_), 5.0);
        EXPECT_EQ(a.status, 200) << "after " << after << ": " << a.body;
        EXPECT_LT(a.seconds, 1.0) << "after " << after;
    }

    // `request` gets `status`, with a JSON error holding `fragment`.
    void expect_refused(const std::string& what, const std::string& request, int status,
                        const std::string& fragment) {
        const HttpAnswer a = http_exchange(port_, request);
        EXPECT_EQ(a.status, status) << what << ": " << a.headers << "\n" << a.body;
        EXPECT_NE(error_of(a).find(fragment), std::string::npos)
            << what << ": status " << a.status << ", '" << a.body << "' lacks '" << fragment << "'";
        EXPECT_EQ(a.headers.find("EXCEPTION_WHAT"), std::string::npos) << what;
        expect_serving(what);
    }

    std::size_t resident_bytes() {
        std::ifstream in("/proc/" + std::to_string(pid_) + "/status");
        for (std::string line; std::getline(in, line);)
            if (line.rfind("VmRSS:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
        return 0;
    }

    // A served run directory of a few frames.
    void serve_a_small_run() {
        write("small.toml", live_config(2000));
        const CliResult r = run_pedesis("run small.toml --out small", dir, 120);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        start({"view", "small", "--port", "0"});
    }

    // `pedesis run --view` of a live_config of `steps` steps.
    void start_live(std::uint64_t steps) {
        write("live.toml", live_config(steps));
        start({"run", "live.toml", "--out", "live", "--view", "--view-port", "0"});
    }

    // Waits up to `seconds` for the process to end; its wait status.
    int wait_for_end(int seconds) {
        int status = 0;
        const auto give_up = Clock::now() + std::chrono::seconds(seconds);
        while (waitpid(pid_, &status, WNOHANG) == 0 && Clock::now() < give_up)
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        pid_ = -1;
        return status;
    }

    // A change of `parameter` to `value` (JSON text) with the run's token.
    HttpAnswer change(const std::string& parameter, const std::string& value) {
        return http_exchange(port_, post_set(R"({"token":")" + token_ + R"(","parameter":")" +
                                             parameter + R"(","value":)" + value + "}"));
    }

    std::string post_set(const std::string& body, const std::string& extra = "") {
        return http_request("POST", "/api/set", port_, body, extra);
    }

    pid_t pid_ = -1;
    int port_ = 0;
    std::string token_;
    fs::path console_;
};

TEST_F(ViewAttacks, MalformedRequestsGetTheirStatusAndTheServerGoesOn) {
    ASSERT_NO_FATAL_FAILURE(serve_a_small_run());
    // (the report: GET /%FF aborted the process from the error handler)
    expect_refused("invalid UTF-8 in the path", http_request("GET", "/%FF", port_), 404,
                   "no such resource");
    expect_refused("raw invalid UTF-8 in the path", http_request("GET", "/\xff\xfe", port_), 404,
                   "no such resource");
    expect_refused("an unknown path", http_request("GET", "/etc/passwd", port_), 404,
                   "no such resource: /etc/passwd");
    expect_refused("a wrong method", http_request("POST", "/api/info", port_, "{}"), 405,
                   "GET only");
    expect_refused("DELETE of the page", http_request("DELETE", "/", port_), 405, "GET only");
    expect_refused("an address of 100 kB",
                   http_request("GET", "/api/info?" + std::string(100000, 'a'), port_), 414,
                   "longer than 8192 bytes");
    expect_refused("headers of 100 kB",
                   http_request("GET", "/api/info", port_, "",
                                "X-Padding: " + std::string(100000, 'b') + "\r\n"),
                   431, "headers exceed");
    std::string many;
    for (int k = 0; k < 5000; ++k) many += "X-" + std::to_string(k) + ": 1\r\n";
    expect_refused("5000 headers", http_request("GET", "/api/info", port_, "", many), 431,
                   "headers exceed");
    expect_refused("not HTTP", "\x16\x03\x01\x02\x01\x01\xfc\x03\x03 TLS?\r\n\r\n", 400,
                   "malformed");
    expect_refused("a frame past the end", http_request("GET", "/api/frame/99999/position", port_),
                   404, "past the end");
    expect_refused("a field the frames lack", http_request("GET", "/api/frame/0/<script>", port_),
                   404, "has no field");
    // what a page without the token may do: nothing (`pedesis view` has no steering)
    expect_refused("a change of a finished run", post_set(R"({"parameter":"T","value":1})"), 404,
                   "cannot be changed");
    // the run directory is as it was
    for (const char* name : {"log.csv", "trajectory.gsd", "checkpoint.bin", "summary.json"})
        EXPECT_TRUE(fs::exists(dir / "small" / name)) << name;
}

TEST_F(ViewAttacks, OtherHostsAndOriginsAreRefused) {
    ASSERT_NO_FATAL_FAILURE(serve_a_small_run());
    const std::string p = std::to_string(port_);
    auto with_host = [&](const std::string& host, const std::string& extra = "") {
        return "GET /api/info HTTP/1.1\r\nHost: " + host + "\r\n" + extra +
               "Connection: close\r\n\r\n";
    };
    // DNS rebinding: a name that resolves to 127.0.0.1 but is not this server's
    expect_refused("Host evil.example", with_host("evil.example:" + p), 403, "answers to");
    expect_refused("no Host", "GET /api/info HTTP/1.1\r\nConnection: close\r\n\r\n", 403,
                   "answers to");
    expect_refused("Host on another port", with_host("127.0.0.1:1"), 403, "answers to");
    EXPECT_EQ(http_exchange(port_, with_host("localhost:" + p)).status, 200);
    EXPECT_EQ(http_exchange(port_, with_host("LOCALHOST:" + p)).status, 200);
    expect_refused("a cross-origin read",
                   with_host("127.0.0.1:" + p, "Origin: http://evil.example\r\n"), 403,
                   "another origin");
    expect_refused("an image of another site",
                   with_host("127.0.0.1:" + p, "Sec-Fetch-Site: cross-site\r\n"
                                               "Sec-Fetch-Mode: no-cors\r\n"),
                   403, "another site");
    // a link from another site opens the page (and only the page)
    const HttpAnswer link =
        http_exchange(port_, "GET / HTTP/1.1\r\nHost: 127.0.0.1:" + p +
                                 "\r\nSec-Fetch-Site: cross-site\r\nSec-Fetch-Mode: navigate\r\n"
                                 "Connection: close\r\n\r\n");
    EXPECT_EQ(link.status, 200) << link.body;
    EXPECT_NE(link.headers.find("Content-Security-Policy: default-src 'none'"), std::string::npos)
        << link.headers;
}

TEST_F(ViewAttacks, LargeBodiesAreRefusedBeforeTheyAreRead) {
    ASSERT_NO_FATAL_FAILURE(serve_a_small_run());
    const std::size_t before = resident_bytes();
    // (the report: one 50 MB POST cost 200 MB, four at once 740 MB)
    std::vector<std::thread> senders;
    std::vector<int> statuses(4, 0);
    for (int k = 0; k < 4; ++k)
        senders.emplace_back([&, k] {
            RawConnection c(port_);
            c.send("POST /api/set HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port_) +
                   "\r\nContent-Type: application/json\r\nContent-Length: 50000000\r\n\r\n");
            const std::string chunk(1 << 20, ' ');
            for (int mb = 0; mb < 50 && c.send(chunk); ++mb) {
            }
            statuses[static_cast<std::size_t>(k)] = c.receive(5.0).status;
        });
    for (std::thread& t : senders) t.join();
    for (int s : statuses) EXPECT_EQ(s, 413);
    const std::size_t after = resident_bytes();
    EXPECT_LT(after, before + (32u << 20)) << "resident " << before << " -> " << after;
    // a chunked body has no length to refuse early: it is cut at the limit
    RawConnection c(port_);
    c.send("POST /api/set HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port_) +
           "\r\nTransfer-Encoding: chunked\r\n\r\n");
    const std::string chunk = "100000\r\n" + std::string(0x100000, 'x') + "\r\n";
    for (int k = 0; k < 8 && c.send(chunk); ++k) {
    }
    const HttpAnswer a = c.receive(5.0);
    EXPECT_EQ(a.status, 413) << a.body;
    expect_serving("large bodies");
}

TEST_F(ViewAttacks, IdleAndSlowConnectionsDoNotDelayARealRequest) {
    ASSERT_NO_FATAL_FAILURE(serve_a_small_run());
    {
        std::vector<RawConnection> idle;
        for (int k = 0; k < 200; ++k) idle.emplace_back(port_);
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        expect_serving("200 idle connections");
    }
    // 20 clients sending their headers a byte at a time
    std::vector<RawConnection> slow;
    for (int k = 0; k < 20; ++k) {
        slow.emplace_back(port_);
        slow.back().send("GET /api/info HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port_) +
                         "\r\n");
    }
    std::atomic<bool> dripping{true};
    std::thread drip([&] {
        const auto end = Clock::now() + std::chrono::seconds(10);
        while (dripping && Clock::now() < end) {
            for (RawConnection& c : slow) c.send("X");
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
        }
    });
    for (int k = 0; k < 5; ++k) {
        expect_serving("20 slow clients");
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    // and each slow one is cut off at the request's deadline, with 408
    const HttpAnswer cut = slow.front().receive(10.0);
    dripping = false;
    drip.join();
    EXPECT_EQ(cut.status, 408) << cut.body;
    EXPECT_NE(error_of(cut).find("did not arrive within"), std::string::npos) << cut.body;
}

// Every attack above, and the steering ones, against a run as it goes; then the run is
// stopped and its directory is complete.
TEST_F(ViewAttacks, ARunUnderAttackEndsWithEveryFileComplete) {
    ASSERT_NO_FATAL_FAILURE(start_live(100000000));
    ASSERT_FALSE(token_.empty()) << console();
    const std::string t = "\"token\":\"" + token_ + "\"";
    expect_refused("invalid UTF-8 in the path", http_request("GET", "/%FF", port_), 404,
                   "no such resource");
    expect_refused("invalid UTF-8 in the body",
                   post_set("{" + t + ",\"parameter\":\"\xff\xfe\",\"value\":1}"), 400,
                   "malformed JSON");
    expect_refused("an absurd temperature",
                   post_set("{" + t + R"(,"parameter":"temperature","value":1e308})"), 400,
                   "temperature must lie in [0, 100000]");
    expect_refused("an absurd activity",
                   post_set("{" + t + R"(,"parameter":"alpha","value":1.8e23})"), 400,
                   "alpha must lie in [-1000000, 1000000]");
    expect_refused("a change from another origin",
                   post_set("{" + t + R"(,"parameter":"temperature","value":0.2})",
                            "Origin: http://evil.example\r\n"),
                   403, "another origin");
    expect_refused("a change without the token",
                   post_set(R"({"parameter":"temperature","value":0.2})"), 403, "token");
    expect_refused("a body of 1 MB", post_set(std::string(1 << 20, ' ')), 413, "body exceeds");
    // the ranges are in the description the page reads
    const HttpAnswer info = http_exchange(port_, http_request("GET", "/api/info", port_));
    const auto j = nlohmann::json::parse(info.body, nullptr, false);
    ASSERT_TRUE(j.contains("steerable")) << info.body;
    for (const auto& p : j["steerable"])
        if (p["name"] == "temperature") {
            EXPECT_EQ(p["min"].get<double>(), 0.0);
            EXPECT_EQ(p["max"].get<double>(), 1e5);
        }
    const HttpAnswer queued = change("temperature", "0.2");
    EXPECT_EQ(queued.status, 202) << queued.body;
    // give the change a step to land, then stop the run as a user would
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    kill(pid_, SIGINT);
    const int status = wait_for_end(30);
    ASSERT_TRUE(WIFSIGNALED(status)) << console();
    EXPECT_EQ(WTERMSIG(status), SIGINT) << console();
    for (const char* name :
         {"log.csv", "trajectory.gsd", "checkpoint.bin", "summary.json", "steering.csv"})
        EXPECT_TRUE(fs::exists(dir / "live" / name)) << name << ": " << console();
    for (const auto& f : fs::directory_iterator(dir / "live"))
        EXPECT_EQ(f.path().string().find(".part"), std::string::npos) << f.path();
    EXPECT_NE(read("live/steering.csv").find(",temperature,0.2"), std::string::npos)
        << read("live/steering.csv");
}

// A change within its range may still blow a run up: the failure names the change, names
// only files that exist, and the record of the change is complete.
TEST_F(ViewAttacks, ABlowUpAfterAChangeNamesTheChange) {
    ASSERT_NO_FATAL_FAILURE(start_live(100000000));
    const HttpAnswer queued = change("alpha", "1000000");
    ASSERT_EQ(queued.status, 202) << queued.body;
    const int status = wait_for_end(60);
    ASSERT_TRUE(WIFEXITED(status)) << console();
    const std::string out = console();
    EXPECT_EQ(WEXITSTATUS(status), 3) << out;
    EXPECT_NE(out.find("after the change of alpha to 1000000 at step"), std::string::npos) << out;
    EXPECT_EQ(out.find("internal error"), std::string::npos) << out;
    if (out.find("checkpoint are in") != std::string::npos) {
        EXPECT_TRUE(fs::exists(dir / "live" / "checkpoint.bin")) << out;
    }
    EXPECT_TRUE(fs::exists(dir / "live" / "steering.csv")) << out;
}

// The record of changes is under its final name as soon as the run ends, while the page
// stays up (it stayed steering.csv.part until the process exited).
TEST_F(ViewAttacks, TheSteeringRecordIsCompleteWhenTheRunEnds) {
    ASSERT_NO_FATAL_FAILURE(start_live(20000));
    const HttpAnswer queued = change("temperature", "0.3");
    ASSERT_EQ(queued.status, 202) << queued.body;
    const auto give_up = Clock::now() + std::chrono::seconds(120);
    while (console().find("the run is done") == std::string::npos && Clock::now() < give_up)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_NE(console().find("the run is done"), std::string::npos) << console();
    EXPECT_TRUE(fs::exists(dir / "live" / "steering.csv")) << console();
    EXPECT_FALSE(fs::exists(dir / "live" / "steering.csv.part"));
    // the page may still ask; every change is refused now
    const HttpAnswer late = change("temperature", "0.4");
    EXPECT_EQ(late.status, 400);
    EXPECT_NE(error_of(late).find("has ended"), std::string::npos) << late.body;
}

TEST_F(ViewAttacks, AnEmptyHostIsRefused) {
    serve_a_small_run();
    const CliResult r = run_pedesis("view small --host '' --port 0", dir, 30);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--host must name an address"), std::string::npos) << r.output;
}

} // namespace
} // namespace pedesis::test
