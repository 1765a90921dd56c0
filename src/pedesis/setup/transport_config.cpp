#include "pedesis/setup/transport_config.hpp"

#include "pedesis/core/error.hpp"

#include <cmath>

namespace pedesis {

namespace {

std::optional<double> positive_time(ConfigTable& t, const char* key) {
    const std::optional<double> v = t.number(key);
    if (v && !(*v > 0.0 && std::isfinite(*v)))
        throw InputError(t.where(key) + ": must be a positive time");
    return v;
}

} // namespace

void read_transport_config(ConfigTable& root, TransportConfig& c) {
    auto t = root.table("transport");
    if (!t) return;
    c.on = true;
    c.where = t->location() + ": table 'transport'";
    c.interval = positive_time(*t, "interval");
    c.diffusion_interval = positive_time(*t, "diffusion_interval");
    c.block_time = positive_time(*t, "block_time");
    if (const auto b = t->integer("blocks")) {
        if (*b < 1 || *b > 10000) throw InputError(t->where("blocks") + ": must be 1 to 10000");
        c.blocks = *b;
    }
    if (const auto p = t->integer("particles")) {
        if (*p < 1) throw InputError(t->where("particles") + ": must be at least 1");
        c.particles = *p;
    }
    if (const auto v = t->boolean("velocity_autocorrelation")) c.velocity_autocorrelation = *v;
    t->finish();
}

} // namespace pedesis
