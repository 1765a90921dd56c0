// SIGKILL at random instants, then --resume until the run ends: the finished directory is
// byte for byte the one of a run never killed, for every engine (support/kill_and_resume.hpp;
// more kills in the validation label's resume_kills_long_test).
#include "support/kill_and_resume.hpp"

namespace pedesis::test {
namespace {

class ResumeKills : public ScratchDir {};

// The sanitizer build checks memory, not statistics: there each run is several times
// slower, and two kills per engine do.
#if defined(__SANITIZE_ADDRESS__)
constexpr int kills = 2;
#else
constexpr int kills = 6;
#endif

TEST_F(ResumeKills, EventRunsEndAsIfNeverKilled) {
    EXPECT_GE(kill_and_resume(dir, "event", kills).kills, kills);
}

TEST_F(ResumeKills, SteppedRunsEndAsIfNeverKilled) {
    EXPECT_GE(kill_and_resume(dir, "stepped", kills).kills, kills);
}

TEST_F(ResumeKills, SoftRunsEndAsIfNeverKilled) {
    EXPECT_GE(kill_and_resume(dir, "soft", kills).kills, kills);
}

} // namespace
} // namespace pedesis::test
