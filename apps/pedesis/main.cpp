// pedesis command line: run, sweep, init, analyze, render, view, validate, bench. Input
// errors exit with 2, stopped runs with 3.
#include "analyze_command.hpp"
#include "bench_abp.hpp"
#include "bench_event.hpp"
#include "bench_stepped.hpp"
#include "init_command.hpp"
#include "mpi_world.hpp"
#include "run_command.hpp"
#include "subcommand_error.hpp"
#include "sweep_command.hpp"
#include "validate_command.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/simd_level.hpp"

#if PEDESIS_HAVE_GRAPHICS
#include "render_command.hpp"
#include "view_command.hpp"
#endif

#include <pedesis_version.hpp>

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <csignal>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

int main(int argc, char** argv) {
    // Past a file-size limit (ulimit -f) a write fails with EFBIG, and the run stops with
    // a message naming the file, its checkpoint intact, instead of dying by SIGXFSZ.
    std::signal(SIGXFSZ, SIG_IGN);
    CLI::App app{"pedesis: particle dynamics of gases and active matter"};
    pedesis::SimdLevel kernels;
    try { // PEDESIS_SIMD is checked once, before anything runs
        kernels = pedesis::simd_level();
    } catch (const std::invalid_argument& e) {
        fmt::print(stderr, "pedesis: error: {}\n", e.what());
        return pedesis::exit_input_error;
    }
    std::string this_cpu;
    for (const pedesis::SimdLevel l : pedesis::available_simd_levels())
        this_cpu += (this_cpu.empty() ? "" : ", ") + std::string(pedesis::simd_name(l));
    app.set_version_flag("--version", fmt::format("pedesis " PEDESIS_VERSION
                                                  " (commit " PEDESIS_COMMIT ")\nCPU kernels: {} "
                                                  "(this CPU runs: {}; PEDESIS_SIMD chooses)",
                                                  pedesis::simd_name(kernels), this_cpu));
    app.require_subcommand(1);
    pedesis::cli::add_run_command(app);
    pedesis::cli::add_sweep_command(app);
    pedesis::cli::add_init_command(app);
    pedesis::cli::add_analyze_command(app);
#if PEDESIS_HAVE_GRAPHICS // (a build for a bare GPU machine leaves them out: scripts/gpu_check.sh)
    pedesis::cli::add_render_command(app);
    pedesis::cli::add_view_command(app);
#endif
    pedesis::cli::add_validate_command(app);
    auto* bench =
        app.add_subcommand("bench", "Benchmark programs (print figures, never fail on speed)");
    bench->require_subcommand(1);
    pedesis::cli::add_bench_event(*bench);
    pedesis::cli::add_bench_abp(*bench);
    pedesis::cli::add_bench_stepped(*bench);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help and --version print as CLI11 has them; every fault is one line
        if (e.get_exit_code() == 0) return app.exit(e);
        fmt::print(stderr, "pedesis: error: {}\n",
                   pedesis::cli::parse_error_message(app, "pedesis", e));
        return pedesis::exit_input_error;
    } catch (const pedesis::InputError& e) {
        // every process of an MPI job reads the same input: one message, not P copies
        if (pedesis::cli::rank_for_messages() == 0)
            fmt::print(stderr, "pedesis: error: {}\n", e.what());
        return pedesis::exit_input_error;
    } catch (const pedesis::cli::SilentExit& e) {
        return e.code;
    } catch (const pedesis::RunError& e) {
        // a run divided among MPI processes stops on all with process 0's message
        if (pedesis::cli::rank_for_messages() == 0)
            fmt::print(stderr, "pedesis: run stopped: {}\n", e.what());
        return pedesis::exit_run_error;
    } catch (const std::logic_error& e) {
        // a broken invariant (a bounded loop gone past its bound, named in the message):
        // the run cannot go on, as with a RunError
        fmt::print(stderr, "pedesis: internal error: {}\n", e.what());
        return pedesis::exit_run_error;
    } catch (const std::exception& e) {
        fmt::print(stderr, "pedesis: internal error: {}\n", e.what());
        return 1;
    }
    return 0;
}
