#pragma once
// The stage a command is in, named on standard error as it begins when the environment
// has PEDESIS_TRACE_STAGES=1: where a long set-up spends its time, and the hook by which
// the tests signal a command inside a chosen stage (tests/cli/cli_interrupt_stages_test).
namespace pedesis {

// Cheap when tracing is off (one cached flag): callable once per list rebuild or frame.
void enter_stage(const char* name);

} // namespace pedesis
