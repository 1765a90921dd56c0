// The kill-and-resume test of cli_resume_kills_test with many more kills per engine.
#include "support/kill_and_resume.hpp"

namespace pedesis::test {
namespace {

class ResumeKillsLong : public ScratchDir {};

TEST_F(ResumeKillsLong, EventRuns) {
    EXPECT_GE(kill_and_resume(dir, "event", 80).kills, 80);
}

TEST_F(ResumeKillsLong, SteppedRuns) {
    EXPECT_GE(kill_and_resume(dir, "stepped", 80).kills, 80);
}

TEST_F(ResumeKillsLong, SoftRuns) {
    EXPECT_GE(kill_and_resume(dir, "soft", 80).kills, 80);
}

} // namespace
} // namespace pedesis::test
