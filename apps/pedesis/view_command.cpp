#include "view_command.hpp"

#include "pedesis/view/export_page.hpp"
#include "pedesis/view/view_server.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <unistd.h>

namespace pedesis::cli {

namespace {
struct ViewArgs {
    std::string run_dir;
    std::string host = "127.0.0.1";
    int port = 8765;
    bool open = false;
    std::string export_to;
    std::size_t every = 1;
};

bool is_loopback(const std::string& host) {
    return host == "127.0.0.1" || host == "localhost" || host == "::1";
}
} // namespace

void add_view_command(CLI::App& app) {
    auto a = std::make_shared<ViewArgs>();
    auto* cmd = app.add_subcommand(
        "view",
        "Show a run directory in the browser: particles, playback, log plots (docs/view.md)");
    cmd->add_option("run_dir", a->run_dir, "Run directory")->required();
    cmd->add_option("--port", a->port, "Port to listen on (0: any free port)")
        ->check(CLI::Range(0, 65535));
    cmd->add_option("--host", a->host,
                    "Address to listen on (default 127.0.0.1: this machine only)");
    cmd->add_flag("--open", a->open, "Open the page in the default browser (xdg-open)");
    auto* exporting = cmd->add_option(
        "--export", a->export_to,
        "Write one self-contained HTML file (page and frames inside, opens offline) and exit");
    cmd->add_option("--every", a->every, "With --export: keep every k-th frame (and the last)")
        ->check(CLI::Range(std::size_t{1}, std::size_t{1000000}))
        ->needs(exporting);
    cmd->callback([a] {
        if (!a->export_to.empty()) {
            view::ExportOptions e;
            e.run_dir = a->run_dir;
            e.output = a->export_to;
            e.every = a->every;
            view::export_page(e);
            std::cout << fmt::format("pedesis view: wrote {} ({:.1f} MB)\n", a->export_to,
                                     static_cast<double>(std::filesystem::file_size(a->export_to)) /
                                         (1 << 20));
            return;
        }
        view::ViewOptions o;
        o.run_dir = a->run_dir;
        o.host = a->host;
        o.port = a->port;
        view::ViewServer server(o);
        if (!is_loopback(a->host))
            std::cerr << fmt::format(
                "pedesis view: warning: listening on {}: anyone who can reach this machine "
                "can read this run\n",
                a->host);
        std::cout << fmt::format("pedesis view: {} at {}  (Ctrl-C to stop)\n", a->run_dir,
                                 server.url())
                  << std::flush;
        if (a->open) {
            const std::string command =
                fmt::format("xdg-open '{}' >/dev/null 2>&1 &", server.url());
            if (std::system(command.c_str()) != 0)
                std::cerr << "pedesis view: could not start a browser; open the address above\n";
        }
        server.start();
        // Nothing here to close cleanly: SIGINT, SIGTERM and SIGHUP keep their default
        // action and end the process at once, however busy the server is.
        for (;;) ::pause();
    });
}

} // namespace pedesis::cli
