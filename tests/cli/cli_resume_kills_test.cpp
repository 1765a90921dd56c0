// SIGKILL at random instants, then --resume until the run ends: the finished directory is
// byte for byte the one of a run never killed, for every engine (support/kill_and_resume.hpp;
// more kills in the validation label's resume_kills_long_test).
#include "support/kill_and_resume.hpp"

namespace pedesis::test {
namespace {

class ResumeKills : public ScratchDir {};

TEST_F(ResumeKills, EventRunsEndAsIfNeverKilled) {
    EXPECT_GE(kill_and_resume(dir, "event", 6).kills, 6);
}

TEST_F(ResumeKills, SteppedRunsEndAsIfNeverKilled) {
    EXPECT_GE(kill_and_resume(dir, "stepped", 6).kills, 6);
}

TEST_F(ResumeKills, SoftRunsEndAsIfNeverKilled) {
    EXPECT_GE(kill_and_resume(dir, "soft", 6).kills, 6);
}

} // namespace
} // namespace pedesis::test
