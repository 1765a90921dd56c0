#pragma once
// Runs the real pedesis binary in a scratch directory and captures what a user sees.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace pedesis::test {

struct CliResult {
    int exit_code = -1;
    std::string output; // stdout and stderr together
};

// Runs a shell command line in `cwd`, stdout and stderr together.
inline CliResult shell(const std::string& command, const std::filesystem::path& cwd) {
    const std::string cmd = "cd '" + cwd.string() + "' && " + command + " 2>&1";
    CliResult r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf;
    while (fgets(buf.data(), buf.size(), pipe)) r.output += buf.data();
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

// With timeout_s > 0 the run is killed after that many seconds (exit code 137): a hang
// fails the test instead of stalling the suite.
inline CliResult run_pedesis(const std::string& args, const std::filesystem::path& cwd,
                             int timeout_s = 0) {
    const std::string limit =
        timeout_s > 0 ? "timeout -s KILL " + std::to_string(timeout_s) + " " : std::string();
    return shell(limit + "'" + PEDESIS_BINARY + "' " + args, cwd);
}

// Starts `pedesis ARGS...` in `cwd` without waiting, stdout and stderr into `console`,
// with `env` ("NAME=value") added to its environment; the caller waits for the pid.
inline pid_t start_pedesis(const std::filesystem::path& cwd, const std::filesystem::path& console,
                           const std::vector<std::string>& args,
                           const std::vector<std::string>& env = {}) {
    const pid_t pid = fork();
    if (pid != 0) return pid;
    if (chdir(cwd.c_str()) != 0) _exit(120);
    const int fd = open(console.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    for (const std::string& e : env) putenv(const_cast<char*>(e.c_str()));
    std::vector<char*> argv{const_cast<char*>(PEDESIS_BINARY)};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(PEDESIS_BINARY, argv.data());
    _exit(127);
}

class ScratchDir : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = std::filesystem::temp_directory_path() /
              (std::string("pedesis_cli_") + info->test_suite_name() + "_" + info->name());
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
    }
    void TearDown() override {
        if (!HasFailure()) std::filesystem::remove_all(dir);
    }
    // Runs `config` as bad.toml and expects exit code 2 with every fragment in the message,
    // no internal error, and no output file that looks complete.
    void expect_rejected(const std::string& config, std::initializer_list<std::string> fragments) {
        write("bad.toml", config);
        const CliResult r = run_pedesis("run bad.toml --out out", dir);
        EXPECT_EQ(r.exit_code, 2) << r.output;
        for (const auto& f : fragments)
            EXPECT_NE(r.output.find(f), std::string::npos)
                << "missing '" << f << "' in: " << r.output;
        EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "out" / "log.csv"));
        EXPECT_FALSE(std::filesystem::exists(dir / "out" / "trajectory.xyz"));
        EXPECT_FALSE(std::filesystem::exists(dir / "out" / "summary.json"));
    }
    void write(const std::string& name, const std::string& text) {
        std::ofstream(dir / name) << text;
    }
    std::string read(const std::string& name) {
        std::ifstream in(dir / name);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }
    std::filesystem::path dir;
};

// A CSV file with one header line (log.csv): the column names in order, and each
// column's cells by name.
struct CsvColumns {
    std::vector<std::string> names;
    std::map<std::string, std::vector<std::string>> cells;
    std::vector<double> numbers(const std::string& name) const {
        std::vector<double> v;
        for (const auto& c : cells.at(name)) v.push_back(std::stod(c));
        return v;
    }
};

inline CsvColumns csv_columns(const std::string& csv) {
    std::istringstream in(csv);
    std::string line, cell;
    std::getline(in, line);
    CsvColumns out;
    std::istringstream head(line);
    while (std::getline(head, cell, ',')) out.names.push_back(cell);
    while (std::getline(in, line)) {
        std::istringstream row(line);
        for (std::size_t k = 0; std::getline(row, cell, ','); ++k)
            out.cells[out.names.at(k)].push_back(cell);
    }
    return out;
}

// A small valid config; tests replace pieces of it to make it invalid.
inline std::string small_config(const std::string& extra_species = "",
                                const std::string& box = "length = 20.0",
                                const std::string& run = "time = 2.0") {
    return "dimension = 2\nseed = 3\n[box]\n" + box + "\nboundary = \"wall\"\n" +
           "[[species]]\nname = \"A\"\ncount = 50\nradius = 0.5\nmass = 1.0\n" + extra_species +
           "[run]\n" + run + "\n[output]\nlog_interval = 0.5\nprogress = false\n";
}

// A soft config on `init.json` (written by pedesis init random in `dir`), and a sweep of
// it whose second point names a file that does not exist: the run of that point fails
// (exit 3 at the end), the other runs.
inline std::string sweep_with_a_failing_point(const std::filesystem::path& dir) {
    const CliResult init =
        run_pedesis("init random --phi 0.1 --L 20 --rcut 1.0 -o init.json", dir, 60);
    EXPECT_EQ(init.exit_code, 0) << init.output;
    std::ofstream(dir / "soft.toml")
        << "dimension = 2\ndynamics = \"brownian\"\nseed = 1\n[initial]\nfile = "
           "\"init.json\"\n[[force]]\nname = \"harmonic\"\nk = 10.0\n[[integrator]]\n"
           "name = \"brownian\"\nT = 0.1\ngamma = 1.0\n[run]\nsteps = 50\ndt = 0.01\n"
           "[output]\nprogress = false\nformats = []\n";
    return "base = \"soft.toml\"\n[vary]\n\"initial.file\" = [\"" + (dir / "init.json").string() +
           "\", \"missing.json\"]\n";
}

} // namespace pedesis::test
