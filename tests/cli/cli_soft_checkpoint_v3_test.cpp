// Soft checkpoints of versions 3 (written before active_ou added its active velocities,
// version 4) and 4 (before Lees-Edwards shear added its block, version 5) still restore:
// a version-5 checkpoint of an unsheared run without active_ou is turned into the file an
// older pedesis wrote (the engine version, without the trailing shear block of two
// numbers for the offsets, the rate and three empty arrays and the [transport] flag that
// follows it, and for version 3 without the
// empty array of active velocities before it, envelope length and CRC redone), and the
// restart from it must continue the run bit for bit, as from the version-5 file. (The
// checkpoint pedesis writes now is of version 7: the blocks of versions 6 and 7, the
// integrators' states and the box of the list's build, are cut off first.)
#include "cli/cli_support.hpp"

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

namespace pedesis::test {
namespace {

std::string abp_config(int steps) {
    return "dimension = 2\ndynamics = \"brownian\"\nseed = 8\n[initial]\nmin_distance = 1.0\n"
           "[box]\nlengths = [20.0, 20.0]\n[[species]]\nname = \"A\"\ncount = 100\n"
           "radius = 0.5\n[[force]]\nname = \"wca\"\nepsilon = 1.0\n"
           "[[force]]\nname = \"self_propulsion\"\nalpha = 1.0\n"
           "[[integrator]]\nname = \"brownian\"\nT = 0.1\ngamma = 1.0\n"
           "[[integrator]]\nname = \"brownian_rotation\"\nT = 0.5\ngamma = 1.0\n"
           "[run]\nsteps = " +
           std::to_string(steps) +
           "\ndt = 0.002\n[output]\nlog_every = 50\ncheckpoint_every = 200\n";
}

// The envelope (checkpoint_file.hpp): 8 bytes magic, 8 bytes payload length, payload,
// CRC-32 of the payload and then of the first 16 bytes.
std::string as_version(const std::string& file, std::uint32_t older) {
    std::uint64_t n = 0;
    std::memcpy(&n, file.data() + 8, 8);
    EXPECT_EQ(file.size(), 20 + n);
    std::string payload = file.substr(16, n);
    std::uint32_t version = 0;
    std::memcpy(&version, payload.data() + 8, 4); // after the engine's 8-byte magic
    EXPECT_EQ(version, 7u);
    std::memcpy(payload.data() + 8, &older, 4);
    // version 6's block: the integrators' count, then each one's name and numbers (none
    // for these two); version 7's: the box of the list's last build (this box, 20 x 20)
    std::string later;
    const auto count = [&later](std::uint64_t x) {
        later.append(reinterpret_cast<const char*>(&x), 8);
    };
    count(2);
    for (const std::string name : {"brownian", "brownian_rotation"}) {
        count(name.size());
        later += name;
        count(0);
    }
    count(2);
    for (const double length : {20.0, 20.0})
        later.append(reinterpret_cast<const char*>(&length), 8);
    EXPECT_EQ(payload.substr(payload.size() - later.size()), later);
    payload.resize(payload.size() - later.size());
    // the shear block: rate, offset, the list's offset (all 0), three empty arrays; then
    // the [transport] flag (0)
    std::string shear(49, '\0');
    EXPECT_EQ(payload.substr(payload.size() - 49), shear)
        << "the run should be unsheared, without [transport]";
    payload.resize(payload.size() - 49);
    if (older == 3) {
        std::uint64_t empty = 1;
        std::memcpy(&empty, payload.data() + payload.size() - 8, 8);
        EXPECT_EQ(empty, 0u) << "the last array (active velocities) should be empty";
        payload.resize(payload.size() - 8);
    }
    std::string head = file.substr(0, 16);
    const std::uint64_t shorter = payload.size();
    std::memcpy(head.data() + 8, &shorter, 8);
    uLong crc = crc32(0L, reinterpret_cast<const Bytef*>(payload.data()),
                      static_cast<uInt>(payload.size()));
    crc = crc32(crc, reinterpret_cast<const Bytef*>(head.data()), 16);
    const auto crc32bits = static_cast<std::uint32_t>(crc);
    std::string out = head + payload;
    out.append(reinterpret_cast<const char*>(&crc32bits), 4);
    return out;
}

class SoftCheckpointVersion3 : public ScratchDir {};

TEST_F(SoftCheckpointVersion3, RestoresAndContinuesBitForBit) {
    write("full.toml", abp_config(400));
    write("half.toml", abp_config(200));
    ASSERT_EQ(run_pedesis("run full.toml --out full", dir, 120).exit_code, 0);
    ASSERT_EQ(run_pedesis("run half.toml --out half", dir, 120).exit_code, 0);
    for (std::uint32_t older : {3u, 4u}) {
        const std::string old = "old" + std::to_string(older);
        write(old + ".bin", as_version(read("half/checkpoint.bin"), older));
        const CliResult cont =
            run_pedesis("run full.toml --out " + old + " --restart " + old + ".bin", dir, 120);
        ASSERT_EQ(cont.exit_code, 0) << cont.output;
        const std::string full = read("full/log.csv"), rest = read(old + "/log.csv");
        const std::string rows = rest.substr(rest.find('\n') + 1);
        ASSERT_GT(rows.size(), 20u);
        EXPECT_NE(full.find(rows), std::string::npos) << "version " << older << ", continued:\n"
                                                      << rest << "\nfull:\n"
                                                      << full;
    }
}

} // namespace
} // namespace pedesis::test
