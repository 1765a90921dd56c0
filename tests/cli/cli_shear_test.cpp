// Lees-Edwards shear through `pedesis run` ([box] shear_rate, the soft engine):
// - an ideal gas under a Langevin thermostat takes the exact stationary moments of SLLOD
//   with friction gamma (m = 1): <v_y^2> = T, <v_x v_y> = -rate T / (2 gamma),
//   <v_x^2> = T (1 + rate^2 / (2 gamma^2)); so the peculiar temperature is
//   T (1 + rate^2 / (2 d gamma^2)), P_xy = -n rate T / (2 gamma), eta = n T / (2 gamma),
//   and the laboratory velocity profile is rate * y;
// - a WCA fluid flows linearly, has P_xy < 0, a viscosity that agrees at two rates
//   (Newtonian at these rates), and in its steady state the viscous heating -rate <P_xy> V
//   equals what the thermostat takes out, gamma d N (<T> - T_bath) (exact for SLLOD
//   with Langevin friction);
// - a restart continues bit for bit, shear_rate = 0 is the run without the key, frames
//   record the offset (GSD tilt xy = offset / L_y, read back by python3-gsd) and the
//   laboratory velocities, and bad shear configs are refused with one message.
#include "cli/cli_support.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

namespace pedesis::test {
namespace {

#ifdef PEDESIS_PYTHON
const char* const python = PEDESIS_PYTHON;
#else
const char* const python = "/usr/bin/python3"; // Debian's, which has python3-gsd
#endif

std::string fluid_config(int dim, double length, int count, double rate, double gamma, int steps,
                         const std::string& extra = "") {
    std::ostringstream c;
    c.precision(17);
    c << "dimension = " << dim << "\ndynamics = \"langevin\"\nseed = 3\n[box]\nlength = " << length
      << "\nshear_rate = " << rate << "\n[[species]]\nname = \"A\"\ncount = " << count
      << "\nradius = 0.5\n[initial]\nmin_distance = 0.85\nvelocities = \"maxwell_boltzmann\"\n"
         "temperature = 1.0\n[[force]]\nname = \"wca\"\nepsilon = 1.0\nsigma = 1.0\n"
         "[[integrator]]\nname = \"langevin\"\nT = 1.0\ngamma = "
      << gamma << "\n[neighbor_list]\nskin = 0.4\n[run]\nsteps = " << steps
      << "\ndt = 0.004\n[output]\nlog_every = 25\nprogress = false\n"
      << extra;
    return c.str();
}

// The mean of a log column over the rows at time >= from.
double mean_after(const CsvColumns& log, const std::string& column, double from) {
    const auto t = log.numbers("time"), v = log.numbers(column);
    double sum = 0.0;
    int n = 0;
    for (std::size_t k = 0; k < t.size(); ++k)
        if (t[k] >= from) {
            sum += v[k];
            ++n;
        }
    return sum / n;
}

class Shear : public ScratchDir {
  protected:
    nlohmann::json summary(const std::string& run) {
        return nlohmann::json::parse(read(run + "/summary.json"));
    }
    // The largest |v_x - rate y| over the profile's bins (each must have samples).
    double profile_deviation(const std::string& run, double rate) {
        const CsvColumns p = csv_columns(read(run + "/velocity_profile.csv"));
        EXPECT_EQ(p.names, (std::vector<std::string>{"y", "velocity_x", "count"}));
        const auto y = p.numbers("y"), v = p.numbers("velocity_x"), n = p.numbers("count");
        EXPECT_GE(y.size(), 8u);
        double worst = 0.0;
        for (std::size_t k = 0; k < y.size(); ++k) {
            EXPECT_GT(n[k], 0.0) << "bin " << k;
            worst = std::max(worst, std::abs(v[k] - rate * y[k]));
        }
        return worst;
    }
    CliResult run_python(const std::string& code) {
        write("check.py", code);
        return shell(std::string(python) + " check.py", dir);
    }
};

// 400 free particles in 2D, rate 0.5, gamma 1, T 1, n = 1, t = 150: the moments' run
// means have statistical errors near 0.3% (T, P_xx, P_yy) and 0.003 (P_xy); the bounds
// are 3 to 5 of them, and the shear's effects (+6% on T, +12.5% on P_xx, P_xy = -0.25)
// far outside them.
TEST_F(Shear, AnIdealLangevinGasHasTheExactSllodMoments) {
    write("gas.toml", "dimension = 2\ndynamics = \"langevin\"\nseed = 11\n[box]\nlength = 20.0\n"
                      "shear_rate = 0.5\n[[species]]\nname = \"A\"\ncount = 400\nradius = 0.5\n"
                      "[initial]\nvelocities = \"maxwell_boltzmann\"\ntemperature = 1.0\n"
                      "[[integrator]]\nname = \"langevin\"\nT = 1.0\ngamma = 1.0\n"
                      "[neighbor_list]\nskin = 0.5\n[run]\nsteps = 15000\ndt = 0.01\n"
                      "[output]\nlog_every = 10\nprogress = false\n");
    const CliResult r = run_pedesis("run gas.toml --out gas", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const CsvColumns log = csv_columns(read("gas/log.csv"));
    const double rate = 0.5, gamma = 1.0, T = 1.0, n = 1.0;
    EXPECT_NEAR(mean_after(log, "temperature", 5.0),
                T * (1.0 + rate * rate / (4.0 * gamma * gamma)), 0.01);
    EXPECT_NEAR(mean_after(log, "pressure_yy", 5.0), n * T, 0.015);
    EXPECT_NEAR(mean_after(log, "pressure_xx", 5.0),
                n * T * (1.0 + rate * rate / (2.0 * gamma * gamma)), 0.015);
    EXPECT_NEAR(mean_after(log, "pressure_xy", 5.0), -n * rate * T / (2.0 * gamma), 0.012);
    const nlohmann::json s = summary("gas").at("shear");
    EXPECT_EQ(s.at("rate").get<double>(), rate);
    const double eta = s.at("viscosity").at("value").get<double>();
    const double error = s.at("viscosity").at("error").get<double>();
    EXPECT_NEAR(eta, n * T / (2.0 * gamma), 0.025) << "error " << error;
    EXPECT_GT(error, 0.0);
    EXPECT_LT(error, 0.03);
    EXPECT_NEAR(s.at("shear_stress").at("value").get<double>(), -rate * eta, 1e-12);
    // 20 bins of 1, about 30,000 samples each, correlated over 1 / gamma: the bins' means
    // of v_x - rate y scatter by about 0.03
    EXPECT_LT(profile_deviation("gas", rate), 0.15);
}

// 500 WCA particles at density 0.8 in 3D, gamma 1, at rates 0.5 and 1 (t = 60 each).
TEST_F(Shear, AWcaFluidFlowsLinearlyAndBalancesItsViscousHeat) {
    const double L = std::cbrt(500 / 0.8), n = 0.8, gamma = 1.0;
    double eta[2], error[2];
    for (int k = 0; k < 2; ++k) {
        const double rate = k == 0 ? 0.5 : 1.0;
        const std::string name = k == 0 ? "slow" : "fast";
        write(name + ".toml", fluid_config(3, L, 500, rate, gamma, 15000));
        const CliResult r = run_pedesis("run " + name + ".toml --out " + name, dir, 200);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        const CsvColumns log = csv_columns(read(name + "/log.csv"));
        const double pxy = mean_after(log, "pressure_xy", 4.0);
        const double T = mean_after(log, "temperature", 4.0);
        EXPECT_LT(pxy, 0.0) << name;
        // heating per particle -rate P_xy / n against cooling gamma d (T - 1): about 2.5%
        // apart from the run's noise (the stress's 2-3% error)
        const double heating = -rate * pxy / n, cooling = gamma * 3.0 * (T - 1.0);
        EXPECT_NEAR(heating / cooling, 1.0, 0.08)
            << name << ": heating " << heating << ", cooling " << cooling << ", T " << T;
        EXPECT_LT(profile_deviation(name, rate), 0.1 * rate * 0.5 * L) << name;
        const nlohmann::json s = summary(name).at("shear");
        eta[k] = s.at("viscosity").at("value").get<double>();
        error[k] = s.at("viscosity").at("error").get<double>();
        EXPECT_GT(eta[k], 10.0 * error[k]) << name;
    }
    // Newtonian between the two rates (the stress doubles with the rate) within the
    // runs' errors (a few per cent each) and a little shear thinning
    EXPECT_NEAR(eta[1] / eta[0], 1.0, 0.12)
        << eta[0] << " +- " << error[0] << ", " << eta[1] << " +- " << error[1];
}

// 2D WCA at rate 1 with Langevin noise and storage sorts: 400 steps in one go against 200,
// a checkpoint, and 200 more (list rebuilds and face crossings on both sides).
TEST_F(Shear, ARestartContinuesBitForBit) {
    const double L = std::sqrt(300 / 0.7);
    const std::string out = "snapshot_every = 200\nformats = [\"json\", \"gsd\"]\n";
    const std::string nl = "[neighbor_list]\nskin = 0.4\nsort_every = 50\n";
    std::string full = fluid_config(2, L, 300, 1.0, 0.5, 400, out);
    full = std::regex_replace(full, std::regex("\\[neighbor_list\\]\nskin = 0.4\n"), nl);
    write("full.toml", full);
    write("half.toml", std::regex_replace(full, std::regex("steps = 400"), "steps = 200"));
    ASSERT_EQ(run_pedesis("run full.toml --out full", dir, 60).exit_code, 0);
    const CliResult half = run_pedesis("run half.toml --out half", dir, 60);
    ASSERT_EQ(half.exit_code, 0) << half.output;
    const CliResult cont =
        run_pedesis("run full.toml --out cont --restart half/checkpoint.bin", dir, 60);
    ASSERT_EQ(cont.exit_code, 0) << cont.output;
    const std::string a = read("full/snapshots/frame_000002.json");
    ASSERT_FALSE(a.empty());
    EXPECT_TRUE(a == read("cont/snapshots/frame_000002.json")) << "the frames at step 400 differ";
    const std::string la = read("full/log.csv"), lb = read("cont/log.csv");
    EXPECT_NE(la.find(lb.substr(lb.find('\n') + 1)), std::string::npos) << lb;
    EXPECT_EQ(read("full/velocity_profile.csv"), read("cont/velocity_profile.csv"));
    EXPECT_EQ(summary("full").at("shear"), summary("cont").at("shear"));
    // the offset had slid across the box and the particles across the faces
    EXPECT_NE(a.find("\"shear_offset\""), std::string::npos);
    // a restart at another rate is refused
    write("other.toml", std::regex_replace(full, std::regex("shear_rate = 1"), "shear_rate = 0.5"));
    const CliResult other =
        run_pedesis("run other.toml --out other --restart half/checkpoint.bin", dir, 60);
    EXPECT_EQ(other.exit_code, 2) << other.output;
    EXPECT_NE(other.output.find("does not match the checkpoint's"), std::string::npos)
        << other.output;
}

// An existing example with and without `shear_rate = 0`: the same trajectory and log.
TEST_F(Shear, ZeroRateIsTheRunWithoutShear) {
    const std::string example = std::string(PEDESIS_SOURCE_DIR) + "/examples/kob_andersen.toml";
    const std::string common = " --set run.steps=300 --set output.snapshot_every=100 "
                               "--set output.log_every=50 --set output.progress=false "
                               "--set 'output.formats=[\"gsd\", \"xyz\"]'";
    ASSERT_EQ(run_pedesis("run '" + example + "' --out plain" + common, dir, 120).exit_code, 0);
    const CliResult zero =
        run_pedesis("run '" + example + "' --out zero --set box.shear_rate=0" + common, dir, 120);
    ASSERT_EQ(zero.exit_code, 0) << zero.output;
    for (const char* f : {"trajectory.gsd", "trajectory.xyz", "log.csv"}) {
        const std::string a = read(std::string("plain/") + f);
        ASSERT_FALSE(a.empty()) << f;
        EXPECT_TRUE(a == read(std::string("zero/") + f)) << f << " differs";
    }
    EXPECT_FALSE(summary("zero").contains("shear"));
    EXPECT_FALSE(std::filesystem::exists(dir / "zero/velocity_profile.csv"));
}

// GSD's tilt xy = offset / L_y (HOOMD's image above at x + xy L_y), read back by
// python3-gsd in 2D and 3D, with the laboratory velocities of the JSON frame; XYZ names
// the offset in its comment line.
TEST_F(Shear, FramesRecordTheOffsetAndTheLaboratoryVelocities) {
    for (int dim : {2, 3}) {
        const std::string name = dim == 2 ? "d2" : "d3";
        const double L = dim == 2 ? 12.0 : 7.0;
        const int count = dim == 2 ? 100 : 240;
        // 250 steps of 0.004 at rate 0.7: offset 0.7 L t (mod L, into [-L/2, L/2))
        write(name + ".toml",
              fluid_config(dim, L, count, 0.7, 0.5, 250,
                           "snapshot_every = 250\nformats = [\"gsd\", \"json\", \"xyz\"]\n"));
        const CliResult r = run_pedesis("run " + name + ".toml --out " + name, dir, 60);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        const double t = 1.0;
        double offset = std::fmod(0.7 * L * t, L);
        if (offset >= 0.5 * L) offset -= L;
        const auto frame =
            nlohmann::json::parse(read(name + "/snapshots/frame_000001.json")).at("system");
        EXPECT_NEAR(frame.at("box").at("shear_offset").get<double>(), offset, 1e-9);
        std::ostringstream v;
        v.precision(17);
        for (const auto& p : frame.at("particles"))
            v << "(" << p.at("v")[0].get<double>() << ", " << p.at("r")[1].get<double>() << "),";
        std::ostringstream code;
        code.precision(17);
        code << "import gsd.hoomd, numpy\n"
             << "t = gsd.hoomd.open('" << name << "/trajectory.gsd')\n"
             << "f = t[len(t) - 1]\n"
             << "box = list(f.configuration.box)\n"
             << "L = " << L << "\n"
             << "assert abs(box[3] - " << offset / L << ") < 1e-6, box\n"
             << "assert box[4] == 0 and box[5] == 0, box\n"
             << "assert abs(box[0] - L) < 1e-5 and abs(box[1] - L) < 1e-5, box\n"
             << "lab = [" << v.str() << "]  # the JSON's laboratory v_x and y, by tag\n"
             << "for k, (vx, y) in enumerate(lab):\n"
             << "    assert abs(f.particles.velocity[k][0] - vx) < 1e-5 * (1 + abs(vx)), (k, vx)\n"
             << "# laboratory velocities follow the flow: v_x against y has slope near 0.7\n"
             << "slope = numpy.polyfit([y for vx, y in lab], [vx for vx, y in lab], 1)[0]\n"
             << "assert 0.5 < slope < 0.9, slope\n"
             << "print('ok')\n";
        const CliResult py = run_python(code.str());
        ASSERT_EQ(py.exit_code, 0) << py.output;
        EXPECT_NE(py.output.find("ok"), std::string::npos) << py.output;
        const std::string xyz = read(name + "/trajectory.xyz");
        EXPECT_NE(xyz.find("shear_rate=0.7 shear_offset="), std::string::npos);
    }
}

TEST_F(Shear, BadShearIsRefusedWithOneMessage) {
    const std::string good = fluid_config(2, 12.0, 100, 0.5, 0.5, 100);
    auto with = [&](const std::string& from, const std::string& to) {
        return std::regex_replace(good, std::regex(from), to);
    };
    expect_rejected(with("shear_rate = 0.5", "shear_rate = -0.5"), {"shear_rate", ">= 0"});
    expect_rejected(with("shear_rate = 0.5", "shear_rate = nan"), {"shear_rate", "NaN"});
    expect_rejected(
        with("shear_rate = 0.5", "shear_rate = 0.5\nboundary = [\"periodic\", \"wall\"]"),
        {"shear_rate", "periodic x", "axis y is a wall"});
    expect_rejected(
        with("shear_rate = 0.5", "shear_rate = 0.5\nboundary = [\"wall\", \"periodic\"]"),
        {"shear_rate", "axis x is a wall"});
    // (the event and stepped engines' shear: cli_event_shear_test, cli_stepped_shear_test)
    // the streaming at the faces, rate L_y dt / 2 = 40 * 12 * 0.004 / 2 = 0.96 a step,
    // is more than half the skin
    expect_rejected(with("shear_rate = 0.5", "shear_rate = 40"),
                    {"shear_rate", "half the neighbour list's skin", "lower dt"});
    expect_rejected(with("dt = 0.004", "dt = 0.004\ndevice = \"gpu\""),
                    {"device = \"gpu\" does not run Lees–Edwards shear"});
}

} // namespace
} // namespace pedesis::test
