// Slow compression crystallises: 2000 spheres grown (diameter +0.01 per unit time at
// T = 1) to packing fraction 0.56, inside the fluid-solid coexistence region's solid
// side (freezing 0.494, melting 0.545), start as a compressed fluid on the fluid branch
// (Carnahan-Starling Z = 19.9) and then nucleate: the reduced pressure falls to the
// crystal branch (Speedy's FCC equation of state: Z = 12.1 at 0.56; a polycrystal with
// grain boundaries sits a little above). A fluid that never crystallised would stay near
// 19.9, so the test asks Z < 15 over t = 600-800 after Z > 17 just after growth.
// About 30 s: label `validation`.
#include "pedesis/event/event_engine.hpp"
#include "support/growing_gas.hpp"

#include <gtest/gtest.h>

using namespace pedesis;
using namespace pedesis::test;

namespace {

// Z = PV/(NkT) over [e.time(), until] from the collision virial (elastic: K constant).
double reduced_pressure(EventEngine<3>& e, double until) {
    const double t0 = e.time(), w0 = virial_trace(e.counters());
    StopLimits lim;
    lim.time = until;
    e.run(lim);
    return 1.0 + (virial_trace(e.counters()) - w0) / (2.0 * e.kinetic_energy() * (e.time() - t0));
}

} // namespace

TEST(GrowthCrystallisation, SlowCompressionToPointFiftySixFreezes) {
    auto e = growing_gas(2000, 0.08, 11, 0.01, 0.56);
    StopLimits lim;
    lim.time = 1000.0;
    ASSERT_EQ(e.run(lim), StopReason::grown);
    EXPECT_NEAR(e.packing_fraction(), 0.56, 1e-9);
    const double fluid = reduced_pressure(e, e.time() + 20.0);
    EXPECT_GT(fluid, 17.0) << "just after growth the system should still be a dense fluid";
    reduced_pressure(e, 600.0);
    const double late = reduced_pressure(e, 800.0);
    EXPECT_LT(late, 15.0) << "Z = " << late << ": no crystal (fluid branch 19.9, FCC 12.1)";
    EXPECT_GT(late, 11.5) << "Z = " << late << " below the perfect FCC crystal's 12.1";
}
