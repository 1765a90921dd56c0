#pragma once
// LAMMPS' in.lj at 4000 atoms as a pedesis config: the cli and validation tests' system.
#include <cstdint>
#include <string>

namespace pedesis::test {

inline const std::string inlj_data_dir = std::string(PEDESIS_SOURCE_DIR) + "/tests/data/inlj";

inline std::string inlj(const std::string& start, double skin, std::uint64_t steps,
                        std::uint64_t log_every) {
    return "dimension = 3\ndynamics = \"nve\"\nseed = 87287\n"
           "[box]\nlength = 16.795961913825074\n"
           "[[species]]\nname = \"A\"\ncount = 4000\nradius = 0.5\n" +
           start +
           "[[force]]\nname = \"lj\"\nepsilon = 1.0\nsigma = 1.0\ncutoff = 2.5\n"
           "[[integrator]]\nname = \"nve\"\n"
           "[neighbor_list]\nskin = " +
           std::to_string(skin) + "\n[run]\nsteps = " + std::to_string(steps) +
           "\ndt = 0.005\n[output]\nlog_every = " + std::to_string(log_every) +
           "\nformats = []\nprogress = false\n";
}

} // namespace pedesis::test
